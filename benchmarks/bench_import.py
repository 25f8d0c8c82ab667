"""Time of ``import gearcoupling``.

Runs fresh interpreters ``--repeats`` times each for ``import numpy`` (the floor: every
kernel needs it) and ``import gearcoupling``, and prints the medians and the difference,
then the largest cumulative entries of ``python -X importtime -c "import gearcoupling"``.

Run: ``python benchmarks/bench_import.py [--repeats 9]``. The machine is shared: compare
medians, not single runs.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time


def wall(code: str, repeats: int) -> tuple[float, float]:
    """Median wall time and median CPU time (user + system) of ``python -c code``."""
    walls, cpus = [], []
    for _ in range(repeats):
        c0, t0 = os.times(), time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        c1 = os.times()
        walls.append(time.perf_counter() - t0)
        cpus.append(c1.children_user + c1.children_system - c0.children_user
                    - c0.children_system)
    return statistics.median(walls), statistics.median(cpus)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=9)
    args = ap.parse_args()
    base = wall("pass", args.repeats)
    np_ = wall("import numpy", args.repeats)
    gc = wall("import gearcoupling", args.repeats)
    print(f"fresh interpreters, medians of {args.repeats} runs: wall s / CPU s")
    for label, (w, c) in (("python -c pass", base), ("import numpy", np_),
                          ("import gearcoupling", gc)):
        print(f"  {label:20s} {w:6.3f} / {c:6.3f}   (+{w - base[0]:.3f} / "
              f"+{c - base[1]:.3f} over the bare interpreter)")
    print(f"  gearcoupling over numpy: +{gc[0] - np_[0]:.3f} s wall, "
          f"+{gc[1] - np_[1]:.3f} s CPU")
    out = subprocess.run([sys.executable, "-X", "importtime", "-c", "import gearcoupling"],
                         capture_output=True, text=True, check=True).stderr.splitlines()
    rows = []
    for line in out[1:]:
        _, cum, name = (part.strip() for part in line.split(":", 1)[1].split("|"))
        rows.append((int(cum), name))
    print("\nlargest cumulative imports (-X importtime, one run, microseconds):")
    for cum, name in sorted(rows, reverse=True)[:12]:
        print(f"  {cum:9d}  {name}")


if __name__ == "__main__":
    main()
