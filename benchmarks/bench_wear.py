"""Speed and accuracy of the wear history (docs/wear.md): a 20 000-hour history of
renzo-1967 at one operating point with the default knobs, and each accuracy knob's cost
and effect.

Run: ``python benchmarks/bench_wear.py [--speed] [--knobs] [--renzo]``. ``--speed`` (the
default): the history of ``gearcoupling wear renzo-1967 --hours 20000 --speed 1800`` (1°,
the spec's 2260 N·m, the grease default), its CPU seconds, steps and turn solves.
``--knobs``: the same history at the step fraction halved and doubled, at the next finer
grid and at other rotations per tooth pitch: CPU seconds, steps, life, largest depth, q
and interior pressure at the end, each against the default. ``--renzo``: Renzo's question,
renzo-1967 and its Vari-Crown and End Round variants and straight teeth at 0.5-3°: life,
q and peak pressure unworn and at the end, edge-contact teeth.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

from gearcoupling.spec import load_spec
from gearcoupling.wear import Accuracy, wear

HOURS, SPEED_RPM = 20_000.0, 1800.0
DESIGNS = {"renzo-1967": ("renzo-1967", {}),
           "vari-crown": ("renzo-1967-vari-crown", {}),
           "end-round": ("renzo-1967-end-round", {}),
           "straight": ("renzo-1967", {"hub.crowning.kind": "none"})}
ANGLES = (0.5, 1.0, 2.0, 3.0)


def history(spec, misalignment_deg: float = 1.0, **knobs):
    """The history and its CPU seconds."""
    t = time.process_time()
    res = wear(spec, misalignment_deg, None, SPEED_RPM, HOURS, **knobs)
    return res, time.process_time() - t


def _end(res) -> tuple[float, float, float]:
    depth = max(float(np.max(res.hub_max_mm[-1])), float(np.max(res.sleeve_max_mm[-1])))
    return depth, float(res.stats["q"][-1, 0]), float(
        res.stats["max_interior_pressure_MPa"][-1, 0])


def speed() -> None:
    spec = load_spec("renzo-1967")
    wear(spec, 1.0, None, SPEED_RPM, 1.0, grid=(16, 8), phases=1)  # tables and kernels
    res, cpu = history(spec)
    print("| history | CPU s | steps | turn solves | life h | life band h |\n"
          "|---|---|---|---|---|---|")
    lo, hi = res.life_band_h
    print(f"| renzo-1967, 1°, 2260 N·m, 1800 rpm, {HOURS:.0f} h (defaults) | {cpu:.1f} | "
          f"{res.steps} | {res.solves} | {res.life_h:.0f} ({res.life_basis}) | "
          f"{lo:.0f}-{hi:.0f} |")


def knobs() -> None:
    spec = load_spec("renzo-1967")
    d = Accuracy()
    settings = [("default", {}),
                ("step fraction / 2", {"step_fraction": d.step_fraction / 2}),
                ("step fraction / 4", {"step_fraction": d.step_fraction / 4}),
                ("grid 32 x 24", {"grid": (32, 24)}),
                ("grid 16 x 12", {"grid": (16, 12)}),
                ("phases 4", {"phases": 4}),
                ("phases 8", {"phases": 8})]
    print("| knobs | CPU s | steps | life h | largest depth mm | q at the end | "
          "interior p at the end MPa |\n|---|---|---|---|---|---|---|")
    ref = None
    for name, kw in settings:
        res, cpu = history(spec, **kw)
        depth, q, p = _end(res)
        row = (res.life_h, depth, q, p)
        if ref is None:
            ref = row
            cells = [f"{v:.4g}" for v in row]
        else:
            cells = [f"{v:.4g} ({100 * (v / r - 1):+.1f} %)" for v, r in zip(row, ref,
                                                                             strict=True)]
        print(f"| {name} | {cpu:.1f} | {res.steps} | " + " | ".join(cells) + " |")


def renzo() -> None:
    print("| design | misalignment ° | life h | q unworn → end | peak interior p MPa unworn "
          "→ end | edge-contact teeth unworn → end | CPU s |\n|---|---|---|---|---|---|---|")
    for name, (template, overrides) in DESIGNS.items():
        spec = load_spec(template, **overrides)
        for mis in ANGLES:
            res, cpu = history(spec, mis)
            s = res.stats
            print(f"| {name} | {mis:g} | {res.life_h:.0f} ({res.life_basis}) | "
                  f"{s['q'][0, 0]:.3f} → {s['q'][-1, 0]:.3f} | "
                  f"{s['max_interior_pressure_MPa'][0, 0]:.0f} → "
                  f"{s['max_interior_pressure_MPa'][-1, 0]:.0f} | "
                  f"{s['edge_contact_teeth'][0, 0]:.0f} → {s['edge_contact_teeth'][-1, 0]:.0f} | "
                  f"{cpu:.0f} |", flush=True)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", action="store_true", help="the default history (default)")
    ap.add_argument("--knobs", action="store_true", help="each accuracy knob")
    ap.add_argument("--renzo", action="store_true", help="Renzo's question")
    args = ap.parse_args(argv)
    if args.speed or not (args.knobs or args.renzo):
        speed()
    if args.knobs:
        knobs()
    if args.renzo:
        renzo()


if __name__ == "__main__":
    main()
