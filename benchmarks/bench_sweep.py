"""Speed and accuracy of the misalignment sweep.

Prints (1) the time of the full map - every tooth x 360 rotations x both flanks, all four
clearance measures - for ``renzo-1967`` at 1°, and (2) the speed/accuracy table: coarse
grid and tolerance against the time of the full map and the error of its minima against a
brute-force evaluation of the exact flank (``hub_flank_model``) on a dense grid.

Run: ``python benchmarks/bench_sweep.py [--quick] [--against OLD_TREE]``. Times are the
best of several runs of CPU time of this process (the machine is shared; wall time is
printed beside it). ``--against DIR`` times the same maps with another checkout
(``DIR/src``), each in a subprocess (``bench_speed.py``'s map rows).
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
from bench_speed import MAP, python_row

from gearcoupling.clearance import sweep
from gearcoupling.clearance.flank_table import flank_table
from gearcoupling.clearance.kernel import minimise
from gearcoupling.clearance.reference import brute_force
from gearcoupling.geometry.sleeve import sleeve_model
from gearcoupling.spec import load_spec


def timed(fn, repeats):
    cpu, wall = [], []
    for _ in range(repeats):
        c, w = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - w)
    return min(cpu), min(wall)


def checkout_maps(checkout: Path, repeats: int, **env: str) -> tuple[float, float]:
    """Best CPU seconds of the periodic and the per-tooth map of renzo-1967 at 1° with
    ``checkout``'s kernel, in subprocesses."""
    maps = [python_row(MAP.format(spec="renzo-1967", periodic=p, repeats=k), **env)(checkout)
            for p, k in ((True, repeats), (False, 1))]
    return min(maps[0]), min(maps[1])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer repeats and reference angles")
    ap.add_argument("--against", metavar="DIR", help="also time the kernel of this checkout")
    ap.add_argument("--maps-only", action="store_true", help="skip the accuracy table")
    args = ap.parse_args(argv)
    repeats = 3 if args.quick else 7
    spec = load_spec("renzo-1967")
    angles = np.arange(360.0)
    mis_deg = 1.0
    c0 = time.process_time()
    flank_table(spec)
    print(f"flank table (renzo-1967): {time.process_time() - c0:.4f} s CPU, "
          f"interpolation error {flank_table(spec).max_error_mm:.2e} mm")
    sweep(spec, mis_deg, angles, tolerance_mm=1e-6)  # warm caches
    cpu, wall = timed(lambda: sweep(spec, mis_deg, angles, tolerance_mm=1e-6), repeats)
    n = 2 * spec.tooth.teeth * angles.size
    print(f"\nfull map renzo-1967 at {mis_deg}°: {spec.tooth.teeth} teeth x {angles.size} "
          f"angles x 2 flanks = {n} minima x 4 measures, tolerance 1e-6 mm")
    print(f"  periodic (default): {cpu * 1e3:.1f} ms CPU ({wall * 1e3:.1f} ms wall)")
    cpu, wall = timed(lambda: sweep(spec, mis_deg, angles, tolerance_mm=1e-6, periodic=False),
                      max(1, repeats // 3))
    print(f"  per tooth (periodic=False, {n} evaluations): {cpu * 1e3:.1f} ms CPU "
          f"({wall * 1e3:.1f} ms wall)")
    if args.against:
        old, old_pt = checkout_maps(Path(args.against), repeats)
        print(f"  {args.against}: periodic {old * 1e3:.1f} ms CPU, per tooth "
              f"{old_pt * 1e3:.1f} ms CPU (same run, subprocess)")
    other = load_spec("industrial-m2")
    sweep(other, 0.75, angles, tolerance_mm=1e-6)
    cpu, wall = timed(lambda: sweep(other, 0.75, angles, tolerance_mm=1e-6), repeats)
    print(f"  industrial-m2 at 0.75° (38 teeth, ~3420 distinct turning angles): "
          f"{cpu * 1e3:.1f} ms CPU ({wall * 1e3:.1f} ms wall)")

    if args.maps_only:
        return
    # reference: brute force on the exact flank at sample turning angles
    thetas = np.radians([0.0, 8.0, 37.0, 90.0, 133.0, 165.4, 251.0, 300.0])
    if args.quick:
        thetas = thetas[[1, 5]]
    n_ref = thetas.size
    mis = math.radians(mis_deg)
    c0 = time.process_time()
    ref = np.array([[brute_force(spec, mis, th, normal) for normal in (False, True)]
                    for th in thetas])  # (n_ref, 2)
    t_ref = (time.process_time() - c0) / n_ref
    print(f"\nbrute force (gearcoupling.clearance.reference: 401 x 121 exact flank points per "
          f"plane grid, polished): {t_ref:.2f} s CPU per turning angle, both gaps "
          f"({t_ref * 900 / 60:.0f} min for the 900 distinct angles of the map)")
    print("\nspeed/accuracy (full map time; error = kernel minus brute force over "
          f"{n_ref} turning angles, both gaps; negative = kernel found a lower point)")
    fine = sweep(spec, mis_deg, angles, tolerance_mm=1e-10, grid=33)
    print("map err: largest difference over the whole map (all four measures) from a run "
          "at grid 33, tolerance 1e-10 mm")
    print(f"{'grid':>5} {'tol mm':>8} {'map ms':>8} {'max err mm':>11} {'min err mm':>11}"
          f" {'map err mm':>11}")
    table = flank_table(spec)
    sm = sleeve_model(spec)
    names = ("clearance_mm", "normal_clearance_mm", "pitch_clearance_mm",
             "pitch_normal_clearance_mm")
    for grid in (5, 9, 17, 33):
        for tol in (1e-4, 1e-6, 1e-8):
            cpu, _ = timed(lambda grid=grid, tol=tol: sweep(spec, mis_deg, angles,
                                                             tolerance_mm=tol, grid=grid),
                           max(1, repeats // 2))
            res = minimise(table, sm, mis, thetas, pitch_radius=spec.tooth.pitch_radius,
                           tolerance_mm=tol, grid=grid)
            got = np.stack([res["circumferential"].value_mm, res["normal"].value_mm], axis=1)
            err = got - ref
            run = sweep(spec, mis_deg, angles, tolerance_mm=tol, grid=grid)
            map_err = max(float(np.max(np.abs(getattr(run, k) - getattr(fine, k))))
                          for k in names)
            print(f"{grid:>5} {tol:>8.0e} {cpu * 1e3:>8.1f} {err.max():>11.2e} "
                  f"{err.min():>11.2e} {map_err:>11.2e}")

if __name__ == "__main__":
    main()
