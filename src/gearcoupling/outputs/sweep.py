"""``sweep.csv``, ``sweep_summary.json`` and the sweep plots."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, plot_all
from ..errors import ArgumentError
from ..io import plain, write_json
from ..spec import CouplingSpec
from .stages import backlash_grid, backlash_range_deg, design_point, turn_sweep


def turn_angles(angles: int) -> np.ndarray:
    """``angles`` rotations evenly over a turn (degrees); at least one."""
    if angles < 1:
        raise ArgumentError("angles", angles, "at least 1")
    return np.arange(angles) * 360.0 / angles


def write_sweep(spec: CouplingSpec, out: Path, misalignment_deg: float, angles: int = 360, *,
                tolerance_mm: float = GAP_TOLERANCE_MM, design: bool = True, plots: bool = True,
                studies: bool = True, progress: Callable[[int, int], None] | None = None
                ) -> tuple[SweepResult, list[Path]]:
    """Sweep ``angles`` rotations over a turn and write ``sweep.csv``,
    ``sweep_summary.json`` (with the design quantities: the stage :func:`design_point`)
    and the plots; returns the sweep and the paths. ``progress(done, 3)`` after the sweep,
    the design quantities and the plots."""
    def tick(done: int) -> None:
        if progress is not None:
            progress(done, 3)

    turn_angles(angles)  # checks the count
    result = turn_sweep(spec, float(misalignment_deg), angles, tolerance_mm)
    tick(1)
    summary = result.summary()
    extra = design_point(spec, float(misalignment_deg)) if design else {}
    tick(2)
    summary.update(extra)
    plain(summary, "sweep_summary.json")  # refuses NaN before anything is written
    paths = [result.write_csv(out / "sweep.csv"),
             write_json(out / "sweep_summary.json", summary)]
    if plots:
        curve = None
        if studies and design:
            top = backlash_range_deg(spec, extra.get("binding_angle_deg"), misalignment_deg)
            curve = backlash_grid(spec, top)
        paths += plot_all(result, spec, out, design=extra if design else None,
                          studies=studies, backlash=curve)
    tick(3)
    return result, paths
