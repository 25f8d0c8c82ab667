"""The default tooth springs against the FE tooth-spring tables they reproduce.

Run: ``python benchmarks/bench_springs.py [--random 30] [--seed 2026] [--no-compute]``.

The data set: the five bundled templates and ``--random`` seeded random specs whose teeth,
module, pressure angle, face width, tooth proportions, fillets, rim and bore and crown
are drawn over the supported range (``tests/random_specs.py``,
``proportions_spec``). For each, the FE tooth-spring table
(:func:`gearcoupling.fea.tooth_compliance_table`, default settings: a 3 x 3 grid of load
points, real gmsh and CalculiX; cached in ``$GEARCOUPLING_CACHE`` or the user's cache, so a
second run only reads) and the default springs (:class:`gearcoupling.loading.PlateCompliance`)
at the same load points. Printed: per spec, the largest error of the pair far field over
the grid; the error over every spec and grid point; the springs' time per spec. With
``--no-compute`` specs without a cached table are left out.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import gearcoupling as gc
from gearcoupling.errors import GearCouplingError
from gearcoupling.fea.stiffness import ComplianceTable, cache_dir, spec_hash
from random_specs import proportions_spec

TEMPLATES = ("renzo-1967", "renzo-1967-vari-crown", "renzo-1967-end-round", "industrial-m2",
             "mill-spindle")


def dataset_specs(count: int, seed: int) -> list[gc.CouplingSpec]:
    """The templates and ``count`` random specs (named ``springs-<i>-<crown>``)."""
    rng = np.random.default_rng(seed)
    specs = [gc.load_spec(name) for name in TEMPLATES]
    for i in range(count):
        s = proportions_spec(rng)
        specs.append(replace(s, name=f"springs-{i:02d}-{s.hub.crowning.kind}"))
    return specs


def cached_table(spec: gc.CouplingSpec) -> ComplianceTable | None:
    """The cached FE table of ``spec`` at the default settings, or None."""
    key = spec_hash(spec, size_mm=None, sector=3, nz=3, nr=3)
    for path in cache_dir().glob(f"*-{key}.json"):
        return ComplianceTable.from_dict(json.loads(path.read_text()))
    return None


def fe_table(spec: gc.CouplingSpec, compute: bool) -> ComplianceTable | None:
    table = cached_table(spec)
    if table is None and compute:
        from gearcoupling.fea import tooth_compliance_table

        t0 = time.perf_counter()
        table = tooth_compliance_table(spec)
        print(f"  {spec.name}: FE table in {time.perf_counter() - t0:.0f} s", flush=True)
    return table


def describe(spec: gc.CouplingSpec) -> str:
    t = spec.tooth
    return (f"{t.teeth} teeth, m {t.module:.3g}, {math.degrees(t.pressure_angle):.1f}°, "
            f"b/m {spec.hub.face_width / t.module:.1f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--random", type=int, default=30)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--no-compute", action="store_true")
    a = ap.parse_args()
    from gearcoupling.loading import PlateCompliance

    rows, worst = [], []
    for spec in dataset_specs(a.random, a.seed):
        try:
            table = fe_table(spec, not a.no_compute)
        except GearCouplingError as err:
            print(f"  {spec.name}: FE refused: {err}")
            continue
        if table is None:
            continue
        t0 = time.perf_counter()
        springs = PlateCompliance(spec)
        Z, R = np.meshgrid(table.z_mm, table.r_mm, indexing="ij")
        model = springs.pair_compliance_mm_per_N(Z, R)
        dt = time.perf_counter() - t0
        err = model / table.far_field_mm_per_N - 1.0
        rows.append((spec.name, describe(spec), err, dt))
        worst.append(err.ravel())
    print("\n| spec | teeth, module, pressure angle, face / module | largest error | "
          "mean error | springs ms |")
    print("|---|---|---|---|---|")
    for name, what, err, dt in rows:
        i = np.argmax(np.abs(err))
        print(f"| {name} | {what} | {100 * err.ravel()[i]:+.1f} % | {100 * err.mean():+.1f} % "
              f"| {1e3 * dt:.0f} |")
    e = np.concatenate(worst)
    print(f"\n{len(rows)} specs, {e.size} load points: error {100 * e.min():+.1f} … "
          f"{100 * e.max():+.1f} %, rms {100 * np.sqrt(np.mean(e**2)):.1f} %; within 10 %: "
          f"{np.mean(np.abs(e) <= 0.1) * 100:.0f} % of the points")


if __name__ == "__main__":
    main()
