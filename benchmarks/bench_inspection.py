"""Inspection speed and accuracy: a 1-million-point scan, registered and reported.

Run: ``python benchmarks/bench_inspection.py [POINTS ...]`` (default 1e5 and 1e6). For each
size it builds a synthetic renzo-1967 hub scan (points on the exact flanks of all 50 teeth,
index errors of +20 um on tooth 3 and -12 um on tooth 17, +10 um thickness, 1 um noise,
random rigid placement), writes it as an ``.xyz`` text file, and times reading the file
and ``compare_part`` (coarse + fine registration, per-point deviations from the exact
flank table, per tooth/flank fits), median of 3 runs. Then, at 1e5 points, the accuracy
knobs: ``fit_points`` (registration subsample) and the flank table ``grid`` against the
recovered index error, thickness and crown height (largest C_beta deviation over all
flanks; the scan has the nominal crown). Markdown tables on stdout.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import gearcoupling as gc
from gearcoupling.inspection import compare_part, load_points
from inspection_synth import label_map, random_placement, synthetic_hub

INDEX = {3: 0.020, 17: -0.012}
THICK = 0.010


def scan(spec, points, seed=3):
    per_flank = max(10, int(points) // (2 * spec.tooth.teeth))
    pts = synthetic_hub(spec, per_flank=per_flank, index_mm=INDEX, thickness_mm=THICK,
                        noise_mm=0.001, seed=seed)
    return random_placement(pts, seed=seed)


def errors(rep, Rp, N):
    labels, flipped = label_map(rep, Rp, N)
    sgn = -1.0 if flipped else 1.0
    fpk = rep.flank["cw"]["Fpk_mm"]
    others = np.delete(fpk, [labels[k] for k in INDEX])
    e_index = max(abs(fpk[labels[k]] - np.median(others) - sgn * v) for k, v in INDEX.items())
    e_thick = abs(rep.part["thickness_dev_mean_mm"] - THICK)
    e_crown = max(float(np.max(np.abs(rep.flank[f]["C_beta_dev_mm"]))) for f in ("cw", "ccw"))
    return 1e3 * e_index, 1e3 * e_thick, 1e3 * e_crown


def main(sizes):
    spec = gc.load_spec("renzo-1967")
    N = spec.tooth.teeth
    print("| points | read .xyz (s) | compare_part (s) | total (s) | registration rms (um) |"
          " index error (um) | thickness error (um) | C_beta error (um) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            pts, Rp = scan(spec, n)
            path = Path(tmp) / "scan.xyz"
            np.savetxt(path, pts, fmt="%.6f")
            t_read, t_cmp = [], []
            for _ in range(3):
                t0 = time.perf_counter()
                loaded = load_points(path)
                t1 = time.perf_counter()
                rep = compare_part(spec, loaded)
                t2 = time.perf_counter()
                t_read.append(t1 - t0)
                t_cmp.append(t2 - t1)
            ei, et, ec = errors(rep, Rp, N)
            r, c = float(np.median(t_read)), float(np.median(t_cmp))
            print(f"| {len(pts):,} | {r:.2f} | {c:.2f} | {r + c:.2f} | "
                  f"{1e3 * rep.registration.rms_mm:.2f} | {ei:.2f} | {et:.2f} | {ec:.2f} |")
    pts, Rp = scan(spec, 1e5)
    print("\n| fit_points | grid (z, r) | table error (mm) | time (s) | index error (um) |"
          " thickness error (um) | C_beta error (um) |")
    print("|---:|---|---:|---:|---:|---:|---:|")
    for fit, grid in ((2_000, (61, 41)), (20_000, (61, 41)), (100_000, (61, 41)),
                      (20_000, (11, 8)), (20_000, (21, 15)), (20_000, (101, 61))):
        t0 = time.perf_counter()
        rep = compare_part(spec, pts, fit_points=fit, grid=grid)
        dt = time.perf_counter() - t0
        ei, et, ec = errors(rep, Rp, N)
        print(f"| {fit:,} | {grid} | {rep.table_error_mm:.1e} | {dt:.2f} | {ei:.2f} | "
              f"{et:.2f} | {ec:.2f} |")


if __name__ == "__main__":
    main([float(a) for a in sys.argv[1:]] or [1e5, 1e6])
