"""The design report: what it costs per section and what its accuracy knobs buy.

Run: ``python benchmarks/bench_report.py [TEMPLATE]`` (default renzo-1967). Prints

- the default report's wall time per section, and the time ``--pdf`` adds (headless
  chromium opening and printing the page, the 3D view as its still picture);
- for ``angles`` (rotations over a turn of the sweep and the loads): the smallest backlash,
  the largest tooth load, q and the largest root stress the report states, and the time;
- for ``capacity_count``: the capacity curve's largest gap to a curve of 49 points
  (the verdict's capacity is computed at the misalignment itself, not read off the curve);
- for ``check_angles``: the smallest mesh gap over the turn and the check's time.

The 3D view is left out of the knob rows (its cost is in the first table).
"""

from __future__ import annotations

import sys
import tempfile
import time

import numpy as np

import gearcoupling as gc
from gearcoupling.interference import check_interference
from gearcoupling.outputs import compare_capacity, comparison_range


def default_report(spec) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        res = gc.report(spec, tmp)
        t0 = time.perf_counter()
        gc.report(spec, tmp, pdf=True)
        pdf = time.perf_counter() - t0 - res.wall_seconds
    print(f"\n{spec.name}: default report {res.wall_seconds:.1f} s ({res.verdict_text})")
    print("| section | seconds |\n|---|---|")
    for name, s in res.seconds.items():
        print(f"| {name} | {s:.2f} |")
    print(f"| --pdf adds (about) | {pdf:.1f} |")


def angles_knob(spec) -> None:
    print("\n| angles | smallest backlash (µm) | largest tooth load (N) | q | largest root "
          "stress (MPa) | seconds |\n|---|---|---|---|---|---|")
    mis = spec.design_misalignment_deg
    for n in (36, 90, 180, 360, 720):
        t0 = time.perf_counter()
        sw = gc.sweep(spec, mis, np.arange(n) * 360.0 / n, tolerance_mm=1e-7)
        res = gc.load_from_sweep(sw)
        dt = time.perf_counter() - t0
        print(f"| {n} | {1e3 * float(np.min(sw.backlash_mm)):.3f} | "
              f"{float(np.max(res.tangential_force_N)):.1f} | {res.q():.4f} | "
              f"{float(np.max(res.root_stress_MPa)):.2f} | {dt:.2f} |")


def capacity_knob(spec) -> None:
    mis, _ = comparison_range([spec], 49)
    fine = compare_capacity([spec], mis).curves[spec.name]
    ref = np.array([c.capacity_Nm for c in fine])
    print("\n| capacity_count | largest gap to the 49-point curve (%) | where (deg) | largest "
          "gap beyond 0.2° (%) | seconds |\n|---|---|---|---|---|")
    for n in (7, 13, 25):
        t0 = time.perf_counter()
        m, _ = comparison_range([spec], n)
        curve = compare_capacity([spec], m).curves[spec.name]
        dt = time.perf_counter() - t0
        drawn = np.interp(mis, m, [c.capacity_Nm for c in curve])
        gap = np.abs(drawn - ref) / ref
        k = int(np.argmax(gap))
        beyond = float(np.max(gap[mis > 0.2]))
        print(f"| {n} | {100 * float(gap[k]):.1f} | {mis[k]:.2f} | {100 * beyond:.1f} | "
              f"{dt:.2f} |")


def check_knob(spec) -> None:
    print("\n| check_angles | smallest mesh gap (mm) | seconds |\n|---|---|---|")
    for n in (12, 36, 72):
        t0 = time.perf_counter()
        res = check_interference(spec, spec.design_misalignment_deg, np.arange(n) * 360.0 / n)
        print(f"| {n} | {float(np.min(res.min_gap_mm)):.5f} | {time.perf_counter() - t0:.2f} |")


if __name__ == "__main__":
    spec = gc.load_spec(sys.argv[1] if len(sys.argv) > 1 else "renzo-1967")
    default_report(spec)
    angles_knob(spec)
    capacity_knob(spec)
    check_knob(spec)
