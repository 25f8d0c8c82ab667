"""Speed and accuracy of the ``surface`` load model (issue 10): the grid trade.

For renzo-1967 at a misalignment and torque, one pose (rotation 0) is solved on a ladder of
fine grids (cells along the face x across the depth); each row prints the CPU and wall
time of the pose, the largest tooth load, the wind-up, the largest peak pressure (grid
dependent where a flank end cuts the patch: it grows like 1/sqrt(cell)), the interior
pressure and the edge intensity p sqrt(cell) (both grid independent), the patch length,
and their differences from the finest grid.

Run: ``python benchmarks/bench_surface.py [--misalignment 1] [--torque 2000] [--quick]``.
The machine is shared: times are the best of ``--repeats`` runs.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

from gearcoupling.load.api import tooth_compliance
from gearcoupling.load.surface import DEFAULT_GRID, solve_surface
from gearcoupling.spec import load_spec
from gearcoupling.sweep import sweep

LADDER = ((16, 12), (24, 16), (32, 24), (48, 32), (64, 48), (96, 64), (128, 96))


def timed(fn, repeats):
    best = (np.inf, np.inf, None)
    for _ in range(repeats):
        c, w = time.process_time(), time.perf_counter()
        out = fn()
        cpu, wall = time.process_time() - c, time.perf_counter() - w
        if cpu < best[0]:
            best = (cpu, wall, out)
    return best


def measures(res):
    W = res["normal_force_N"][:, 0]
    k = int(np.argmax(W))
    return {
        "W_max": float(W[k]),
        "windup_urad": float(res["windup_rad"][0]) * 1e6,
        "p_max": float(np.max(res["max_pressure_MPa"][:, 0])),
        "p_int": float(np.max(res["interior_pressure_MPa"][:, 0])),
        "edge_I": float(np.max(res["edge_intensity_MPa_sqrt_mm"][:, 0])),
        "length": float(res["patch_length_mm"][k, 0]),
        "loaded": int(np.count_nonzero(W)),
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spec", default="renzo-1967")
    ap.add_argument("--misalignment", type=float, default=1.0)
    ap.add_argument("--torque", type=float, default=2000.0, help="N·m")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="stop at the 96 x 64 grid")
    ap.add_argument("--rigid", action="store_true", help="rigid teeth (no bending compliance)")
    args = ap.parse_args(argv)
    spec = load_spec(args.spec)
    sw = sweep(spec, args.misalignment, [0.0])
    ladder = LADDER[:-1] if args.quick else LADDER
    comp = None if args.rigid else tooth_compliance(spec)
    rows = []
    for grid in ladder:
        reps = 1 if grid[0] * grid[1] > 64 * 48 else args.repeats
        cpu, wall, res = timed(lambda g=grid: solve_surface(spec, sw, torque_Nm=args.torque,
                                                            grid=g, compliance=comp), reps)
        rows.append((grid, cpu, wall, measures(res)))
    ref = rows[-1][3]
    print(f"{args.spec}, misalignment {args.misalignment}°, torque {args.torque} N·m, "
          f"rotation 0, {'rigid teeth' if args.rigid else 'cantilever tooth compliance'}; "
          f"default grid {DEFAULT_GRID}")
    print("| grid (face x depth) | CPU s | wall s | teeth loaded | max tooth load N | "
          "wind-up µrad | p_max MPa | interior p MPa | edge p·√h MPa·√mm | "
          "patch length mm |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for grid, cpu, wall, m in rows:
        def rel(key, m=m):
            return f"{m[key]:.4g} ({(m[key] / ref[key] - 1) * 100:+.2f} %)"
        print(f"| {grid[0]} x {grid[1]} | {cpu:.2f} | {wall:.2f} | {m['loaded']} | "
              f"{rel('W_max')} | {rel('windup_urad')} | {rel('p_max')} | {rel('p_int')} | "
              f"{rel('edge_I')} | {rel('length')} |")


if __name__ == "__main__":
    main()
