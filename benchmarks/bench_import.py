"""Time of ``import gearcoupling`` (issue 14 item 8: target <= 0.15 s).

Runs fresh interpreters ``--repeats`` times each for ``import numpy`` (the floor: every
kernel needs it) and ``import gearcoupling``, and prints the medians and the difference,
then the largest cumulative entries of ``python -X importtime -c "import gearcoupling"``.

Run: ``python benchmarks/bench_import.py [--repeats 9]``. The machine is shared: compare
medians, not single runs.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time


def wall(code: str, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=9)
    args = ap.parse_args()
    base = wall("pass", args.repeats)
    np_ = wall("import numpy", args.repeats)
    gc = wall("import gearcoupling", args.repeats)
    print(f"median wall time of a fresh interpreter ({args.repeats} runs each):")
    print(f"  python -c pass                  {base:.3f} s")
    print(f"  python -c 'import numpy'        {np_:.3f} s  (+{np_ - base:.3f} s)")
    print(f"  python -c 'import gearcoupling' {gc:.3f} s  (+{gc - base:.3f} s over the "
          f"interpreter, +{gc - np_:.3f} s over numpy)")
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
