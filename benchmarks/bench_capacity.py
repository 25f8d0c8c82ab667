"""Cost of the default capacity: solves and CPU per template and misalignment, optionally
against another checkout (the answers' largest change with it).

Run: ``python benchmarks/bench_capacity.py [--angles 0.5 1 2 3] [--against OLD_CHECKOUT]``.

Each row is ``gc.capacity(gc.load_spec(NAME), ANGLE)`` under ``time.process_time`` in a
fresh process per checkout (one warm-up capacity first: compiled kernels, flank tables).
With ``--against`` the other checkout's ``src`` runs the same rows; printed: solves, CPU,
the capacity and the face-end torque of both, and the largest relative changes.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

ROWS = """
import json, sys, time
import gearcoupling as gc
angles = json.loads(sys.argv[1])
gc.capacity(gc.load_spec("industrial-m2"), 1.0)
rows = []
for name in gc.template_names():
    spec = gc.load_spec(name)
    for a in angles:
        t = time.process_time()
        c = gc.capacity(spec, a)
        rows.append([name, a, c.solves, time.process_time() - t, c.capacity_Nm,
                     c.face_end_torque_Nm])
print(json.dumps(rows))
"""


def rows(src: Path, angles: list[float]) -> list[list]:
    env = {**os.environ, "PYTHONPATH": str(src)}
    out = subprocess.run([sys.executable, "-c", ROWS, json.dumps(angles)], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.splitlines()[-1])


def num(v) -> str:
    return "—" if v is None else f"{v:.4g}"


def change(a, b) -> float:
    if a is None or b is None:
        return 0.0 if a == b else float("inf")
    return abs(b / a - 1.0) if a else abs(b - a)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--angles", nargs="*", type=float, default=[0.5, 1.0, 2.0, 3.0])
    ap.add_argument("--against", type=Path, metavar="OLD_CHECKOUT")
    a = ap.parse_args(argv)
    new = rows(Path(__file__).resolve().parents[1] / "src", a.angles)
    old = rows(a.against / "src", a.angles) if a.against else new
    print("| spec | angle ° | solves | CPU s | capacity N·m | face-end torque N·m |")
    print("|---|---|---|---|---|---|")
    for (name, ang, s, cpu, cap, fe), (_, _, s0, cpu0, cap0, fe0) in zip(new, old, strict=True):
        if a.against:
            print(f"| {name} | {ang:g} | {s0} → {s} | {cpu0:.2f} → {cpu:.2f} | {cap0:.6g} → "
                  f"{cap:.6g} | {num(fe0)} → {num(fe)} |")
        else:
            print(f"| {name} | {ang:g} | {s} | {cpu:.2f} | {cap:.6g} | {num(fe)} |")
    print(f"\nsolves {sum(r[2] for r in old)} → {sum(r[2] for r in new)}, CPU "
          f"{sum(r[3] for r in old):.1f} → {sum(r[3] for r in new):.1f} s, largest per angle "
          f"{max(r[3] for r in new):.2f} s")
    if a.against:
        pairs = list(zip(old, new, strict=True))
        print(f"largest change: capacity {max(change(o[4], n[4]) for o, n in pairs):.2e}, "
              f"face-end torque {max(change(o[5], n[5]) for o, n in pairs):.2e}")


if __name__ == "__main__":
    main()
