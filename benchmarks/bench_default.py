"""The default load model and springs against the validated ones: ``surface`` with the FE
tooth table (``stiffness = "fe"``).

Run: ``python benchmarks/bench_default.py [--random 30] [--seed 2026] [--angles 0.5 1 2 3]
[--no-compute] [--jobs N]``.

On the data set of ``bench_springs.py`` (the templates and seeded random specs; FE tables
from its cache, computed where missing unless ``--no-compute``), at each misalignment: the
capacity without options (``gc.capacity(spec, angle)``: the default model and springs)
against the same with ``stiffness = "fe"``, and the largest tooth load over a tooth pitch
at a torque (the spec's, else half the FE capacity at 1°) likewise. Printed: one row per
spec and angle, the error range over all, and the CPU time of a default capacity.
``--jobs N`` compares N specs at a time in worker processes (the rows in the data set's
order; the CPU time is each worker's own).
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_springs import dataset_specs, fe_table

import gearcoupling as gc
from gearcoupling.errors import GearCouplingError


def with_springs(spec: gc.CouplingSpec, springs: str) -> gc.CouplingSpec:
    return replace(spec, load=replace(spec.load, stiffness=springs))


def largest_load(spec: gc.CouplingSpec, angle: float, torque_Nm: float) -> float:
    pitch = np.linspace(0.0, 360.0 / spec.tooth.teeth, 8, endpoint=False)
    return float(gc.load(spec, angle, pitch, torque_Nm=torque_Nm).tangential_force_N.max())


def compare(spec: gc.CouplingSpec, angles) -> list[tuple]:
    """Rows ``(angle, capacity default, capacity fe, load default, load fe, cpu s)``."""
    fe = with_springs(spec, "fe")
    T = spec.load.torque_Nm
    if T is None:
        c1 = gc.capacity(fe, 1.0).capacity_Nm
        T = 0.5 * c1 if c1 else 1e-3 * spec.tooth.pitch_radius
    rows = []
    for angle in angles:
        t0 = time.process_time()
        mine = gc.capacity(spec, angle)
        cpu = time.process_time() - t0
        ref = gc.capacity(fe, angle)
        rows.append((angle, mine.capacity_Nm, ref.capacity_Nm, largest_load(spec, angle, T),
                     largest_load(fe, angle, T), cpu, T))
    return rows


def compare_spec(spec: gc.CouplingSpec, angles, compute: bool) -> list[tuple] | str | None:
    """:func:`compare`'s rows, None without an FE table, or the refusal's text."""
    try:
        if fe_table(spec, compute) is None:
            return None
        return compare(spec, angles)
    except GearCouplingError as err:
        return str(err)


def results(work: list[tuple], jobs: int):
    """:func:`compare_spec` of each item of ``work`` in order, ``jobs`` at a time."""
    if jobs <= 1:
        yield from (compare_spec(*w) for w in work)
        return
    with multiprocessing.get_context("fork").Pool(jobs) as pool:
        yield from pool.imap(_compare_args, work)


def _compare_args(w: tuple):
    return compare_spec(*w)


def pct(a, b) -> str:
    return "—" if a is None or b is None else f"{100 * (a / b - 1):+.1f} %"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--random", type=int, default=30)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--angles", nargs="*", type=float, default=[0.5, 1.0, 2.0, 3.0])
    ap.add_argument("--no-compute", action="store_true")
    ap.add_argument("--jobs", type=int, default=1)
    a = ap.parse_args()
    specs = dataset_specs(a.random, a.seed)
    work = [(spec, a.angles, not a.no_compute) for spec in specs]
    print("| spec | angle ° | capacity default · fe N·m | error | torque N·m | largest "
          "load default · fe N | error | default capacity CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    cap_err, load_err, cpus = [], [], []
    for spec, rows in zip(specs, results(work, a.jobs), strict=True):
        if rows is None:
            continue
        if isinstance(rows, str):
            print(f"| {spec.name} | refused: {rows} |")
            continue
        for angle, c, cf, p, pf, cpu, T in rows:
            print(f"| {spec.name} | {angle:g} | {c or 0:.4g} · {cf or 0:.4g} | {pct(c, cf)} | "
                  f"{T:.4g} | {p:.4g} · {pf:.4g} | {pct(p, pf)} | {cpu:.2f} |")
            if c and cf:
                cap_err.append(c / cf - 1)
            load_err.append(p / pf - 1)
            cpus.append(cpu)
    for label, e in (("capacity", cap_err), ("largest tooth load", load_err)):
        e = np.asarray(e)
        if e.size:
            print(f"\n{label}: {e.size} cases, error {100 * e.min():+.1f} … "
                  f"{100 * e.max():+.1f} %, within 5 %: {np.mean(np.abs(e) <= 0.05):.0%}")
    if cpus:
        print(f"default capacity: CPU {np.median(cpus):.2f} s median, {np.max(cpus):.2f} s "
              "largest per angle")


if __name__ == "__main__":
    main()
