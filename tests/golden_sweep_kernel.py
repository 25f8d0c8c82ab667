"""Frozen outputs of the sweep kernel, to pin its speed-ups to the kernel they replace.

``tests/golden/sweep_kernel.npz`` holds, per template and misalignment (0, 1, 3, 6°), the
minima of tooth 0's cw flank (:func:`~gearcoupling.clearance.tooth_map.flank_minima`,
``periodic=False``, default tolerance) at :data:`THETA_DEG`; and per extreme spec
(:data:`EXTREMES`: root-fillet contact, 16 mm of interference, end_round pieces, heavy
binding) at 1° and 6° all four measures of :func:`~gearcoupling.clearance.kernel.minimise`
at :data:`EXTREME_THETA_DEG`. The template values were frozen from the kernel of main on
2026-11-23 (commit 6466353, before the sweep-speed changes), the extremes from the compiled
kernel of 9c2938a (then equal to the numpy path kept beside it within 1e-9 mm); both were
regenerated when the search came to follow each minimum from the neighbouring turning
angle's and converge it (Newton steps): every value moved by less than 1e-10 mm but two,
mill-spindle at 6° (circumferential, 112.87° and 292.87°), 3.397e-7 mm down - the search
before had stopped 3.386e-7 mm above the exact minimum (``clearance.reference.brute_force``:
0.725316137121 mm), now 1.1e-9 mm below it, within the table's error
(``test_sweep_kernel.py::test_followed_minima_match_brute_force``). Regenerate only after
an intended change of the kernel's results: ``PYTHONPATH=src python
tests/golden_sweep_kernel.py`` and review why the values moved.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

import gearcoupling as gc
from gearcoupling.clearance.flank_table import flank_table
from gearcoupling.clearance.kernel import MEASURES, Minimum, minimise
from gearcoupling.clearance.tooth_map import flank_minima
from gearcoupling.geometry.sleeve import sleeve_model
from gearcoupling.spec import load_spec

FILE = Path(__file__).parent / "golden" / "sweep_kernel.npz"
TEMPLATES = ("renzo-1967", "renzo-1967-end-round", "renzo-1967-vari-crown", "industrial-m2",
             "mill-spindle")
MISALIGNMENTS_DEG = (0.0, 1.0, 3.0, 6.0)
THETA_DEG = np.linspace(0.0, 360.0, 97)[:-1] + 0.37  # 96 turning angles, off the symmetries
KEYS = ("clearance", "normal", "pitch", "pitch_normal", "z", "r", "kind")
EXTREMES = ("above-fillet", "straight-120", "m3.6-N232", "m4.6-N293")
EXTREME_DEG = (1.0, 6.0)
EXTREME_THETA_DEG = np.linspace(0.0, 360.0, 25)[:-1] + 0.37
FIELDS = ("value_mm", "z_mm", "r_mm", "t", "kind", "rate")


def minima(name: str, mis_deg: float) -> dict[str, np.ndarray]:
    """The kernel's minima of ``name`` at ``mis_deg`` (arrays ``(96,)``)."""
    out, _ = flank_minima(load_spec(name), math.radians(mis_deg), np.radians(THETA_DEG),
                          tolerance_mm=1e-7, periodic=False)
    return {k: out[k] for k in KEYS}


def extreme_spec(name: str):
    """The extreme spec ``name`` (:data:`EXTREMES`; the dicts of ``test_sweep_robust``)."""
    from test_sweep_robust import ABOVE_FILLET, ISSUE_EXAMPLE, STALLED

    return gc.spec_from_dict({"above-fillet": ABOVE_FILLET, "straight-120": ISSUE_EXAMPLE,
                              "m3.6-N232": STALLED["m3.6-N232"],
                              "m4.6-N293": STALLED["m4.6-N293-straight-then-round"]}[name])


def extreme_minima(spec, mis_deg: float, measures: tuple[str, ...] = MEASURES,
                   table=None) -> dict[str, Minimum]:
    """:func:`minimise` of ``spec`` at ``mis_deg`` and :data:`EXTREME_THETA_DEG`."""
    return minimise(flank_table(spec) if table is None else table, sleeve_model(spec),
                    math.radians(mis_deg), np.radians(EXTREME_THETA_DEG),
                    pitch_radius=spec.tooth.pitch_radius, measures=measures)


def main() -> None:
    data = {f"{name}|{deg:g}|{k}": v for name in TEMPLATES for deg in MISALIGNMENTS_DEG
            for k, v in minima(name, deg).items()}
    for name in EXTREMES:
        spec = extreme_spec(name)
        for deg in EXTREME_DEG:
            for m, res in extreme_minima(spec, deg).items():
                data.update({f"{name}|{deg:g}|{m}|{f}": getattr(res, f) for f in FIELDS})
    np.savez_compressed(FILE, **data)
    print(f"wrote {FILE} ({len(data)} arrays)")


if __name__ == "__main__":
    main()
