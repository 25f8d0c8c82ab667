"""Cost and accuracy of the surface model's load studies (``gc.run``'s Wei and Renzo graphs):
each resolution against 8 rotations per tooth pitch on the load criteria's 24 x 16 cells.

Run: ``python benchmarks/bench_load_study.py [--spec renzo-1967 industrial-m2]
[--settings 4x16x10 3x12x8 ...]``. Printed per spec and setting: the CPU time of the
study (7 misalignments, T/2, T and 2T; the stage ``load_study``) and the largest relative
deviation of the largest tooth load and of the mean tilting moment from the reference.
They are the figures behind the surface model's ``SURFACE_STUDY``
(benchmarks/RESULTS.md, ``python benchmarks/results.py --full``).
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from gearcoupling.loading.models import registry
from gearcoupling.outputs import stages
from gearcoupling.spec import load_spec

REFERENCE = (8, (24, 16))


def study(spec, setting):
    """The load study at ``setting = (rotations, grid)`` and its CPU seconds."""
    stages.forget()
    registry.MODELS["surface"] = dataclasses.replace(registry.MODELS["surface"], study=setting)
    t = time.process_time()
    result = stages.load_study(spec, spec.load.torque_Nm, "surface")
    return result, time.process_time() - t


def deviation(a: dict, b: dict) -> float:
    """Largest relative deviation of the curves ``a`` from ``b`` (same keys)."""
    return max(abs(x / y - 1.0) for k in b for x, y in zip(a[k], b[k], strict=True))


def setting(text: str) -> tuple[int, tuple[int, int]]:
    rotations, n1, n2 = (int(v) for v in text.split("x"))
    return rotations, (n1, n2)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spec", nargs="+", default=["renzo-1967", "industrial-m2"])
    ap.add_argument("--settings", nargs="+", type=setting, metavar="RxN1xN2",
                    default=[setting(s) for s in ("4x16x10", "3x16x10", "2x16x10", "3x12x8")])
    args = ap.parse_args(argv)
    default = registry.MODELS["surface"]
    print("| spec | rotations per pitch | cells | CPU (s) | largest tooth load | "
          "mean tilting moment |\n|---|---|---|---|---|---|")
    try:
        for name in args.spec:
            spec = load_spec(name)
            study(spec, REFERENCE)  # compiled kernels and tables loaded before timing
            ref, t_ref = study(spec, REFERENCE)
            print(f"| {name} | {REFERENCE[0]} | {REFERENCE[1][0]} x {REFERENCE[1][1]} | "
                  f"{t_ref:.2f} | reference | reference |")
            for s in args.settings:
                res, t = study(spec, s)
                mark = " (default)" if s == default.study else ""
                print(f"| {name} | {s[0]}{mark} | {s[1][0]} x {s[1][1]} | {t:.2f} | "
                      f"{100 * deviation(res.peak_N, ref.peak_N):.2f} % | "
                      f"{100 * deviation(res.moment_Nm, ref.moment_Nm):.2f} % |", flush=True)
    finally:
        registry.MODELS["surface"] = default


if __name__ == "__main__":
    main()
