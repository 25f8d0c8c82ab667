"""The clearance stages: the design point (critical and binding angles), the smallest
backlash against misalignment, and the sweep over a turn with ``sweep.csv``,
``sweep_summary.json`` and the sweep plots."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, backlash_curve, design_quantities, sweep, sweep_figures
from ..errors import ArgumentError
from ..io import plain, write_csv_rows, write_json
from ..plots import save_figure
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec
from .stage import StageInputs

BACKLASH_POINTS = 25  # misalignments of the backlash curve


@dataclass(frozen=True)
class DesignPoint:
    """The root-found design angles at a misalignment
    (:func:`~gearcoupling.clearance.design_quantities`, kept as plain data in
    :attr:`quantities`)."""

    misalignment_deg: float
    quantities: dict[str, Any]

    @property
    def critical_deg(self) -> float | None:
        """Where the pivot teeth's contact reaches a face end (None: not up to 6°)."""
        return self.quantities["critical_misalignment_deg"]

    @property
    def binding_deg(self) -> float | None:
        """Where the smallest backlash over a turn reaches 0 (None: not up to 6°)."""
        return self.quantities["binding_angle_deg"]


@dataclass(frozen=True)
class BacklashCurve:
    """The smallest backlash over a turn (mm at the pitch radius) at each misalignment."""

    misalignments_deg: NDArray[np.float64]
    min_backlash_mm: NDArray[np.float64]


def turn_angles(angles: int) -> NDArray[np.float64]:
    """``angles`` rotations evenly over a turn (degrees); at least one."""
    if angles < 1:
        raise ArgumentError("angles", angles, "at least 1")
    return np.arange(angles) * 360.0 / angles


def backlash_range_deg(spec: CouplingSpec, binding_deg: float | None,
                       misalignment_deg: float) -> float:
    """The top of the backlash-against-misalignment grid: twice the binding angle (3° when
    it does not bind), at least 1.5 times the misalignment, at most 6°."""
    return min(MISALIGNMENT_RANGE_DEG[1], max(2.0 * (binding_deg or 3.0),
                                              1.5 * misalignment_deg))


def design(inputs: StageInputs) -> DesignPoint:
    """The stage ``design``."""
    mis = inputs.point.misalignment_deg
    return DesignPoint(mis, design_quantities(inputs.spec, mis))


def backlash(inputs: StageInputs) -> BacklashCurve:
    """The stage ``backlash`` (:func:`backlash_points`)."""
    return backlash_points(inputs.spec, inputs.get("design", DesignPoint))


def backlash_points(spec: CouplingSpec, point: DesignPoint) -> BacklashCurve:
    """:data:`BACKLASH_POINTS` misalignments from 0 to :func:`backlash_range_deg` and the
    smallest backlash over a turn at each (8 rotations per tooth pitch)."""
    top = backlash_range_deg(spec, point.binding_deg, point.misalignment_deg)
    mis = np.linspace(0.0, top, BACKLASH_POINTS)
    return BacklashCurve(mis, backlash_curve(spec, mis))


def turn(inputs: StageInputs) -> SweepResult:
    """The stage ``sweep``: the settings' rotations over a turn (less a mesh's phase),
    checked finite."""
    s, p = inputs.settings, inputs.point
    return sweep(inputs.spec, p.misalignment_deg, p.rotations(turn_angles(s.angles)),
                 tolerance_mm=s.tolerance_mm).check_finite()


def files(sw: SweepResult, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``sweep``'s files: data, summary and every plot."""
    return sweep_files(sw, inputs.spec, folder, inputs.get("design", DesignPoint),
                       inputs.get("backlash", BacklashCurve), dpi=inputs.settings.dpi)


def summary(sw: SweepResult, point: DesignPoint | None) -> dict[str, Any]:
    """``sweep_summary.json``: the sweep's summary with the design quantities."""
    out = sw.summary()
    if point is not None:
        out.update(point.quantities)
    return out


def sweep_files(sw: SweepResult, spec: CouplingSpec, folder: Path, point: DesignPoint | None,
                curve: BacklashCurve | None, *, plots: bool = True, studies: bool = True,
                dpi: int = 130) -> list[Path]:
    """``sweep.csv``, ``sweep_summary.json`` (with the design quantities), the backlash
    over the turn and, with ``plots``, the pictures; ``studies`` (with a design point and
    its backlash curve) adds the backlash against misalignment, the critical angle against
    R_c and the two generation methods."""
    data = summary(sw, point)
    plain(data, "sweep_summary.json")  # refuses NaN before anything is written
    paths = [sw.write_csv(folder / "sweep.csv"),
             write_json(folder / "sweep_summary.json", data),
             write_csv_rows(folder / "backlash_over_turn.csv",
                            ("psi_deg", "backlash_mm", "backlash_deg"),
                            zip(sw.angles_deg, sw.backlash_mm, np.degrees(sw.backlash_rad),
                                strict=True))]
    if not plots:
        return paths
    drawn = None
    if studies and point is not None and curve is not None:
        drawn = (curve.misalignments_deg, curve.min_backlash_mm)
        paths.append(write_csv_rows(folder / "backlash_vs_misalignment.csv",
                                    ("misalignment_deg", "min_backlash_mm"),
                                    zip(*drawn, strict=True)))
    figures = sweep_figures(sw, spec, design=None if point is None else point.quantities,
                            studies=drawn is not None, backlash=drawn)
    return paths + [save_figure(make(), folder / name, dpi) for name, make in figures.items()]


def write_sweep(spec: CouplingSpec, out: Path, misalignment_deg: float, angles: int = 360, *,
                tolerance_mm: float = GAP_TOLERANCE_MM, design: bool = True, plots: bool = True,
                studies: bool = True, progress: Callable[[int, int], None] | None = None
                ) -> tuple[SweepResult, DesignPoint | None, list[Path]]:
    """``gearcoupling sweep``: sweep ``angles`` rotations over a turn and write its files
    (:func:`sweep_files`); ``design`` adds the design point (root finding, a few seconds).
    Returns the sweep, the design point (None without it) and the paths.
    ``progress(done, 3)`` after the sweep, the design point and the files."""
    def tick(done: int) -> None:
        if progress is not None:
            progress(done, 3)

    result = sweep(spec, float(misalignment_deg), turn_angles(angles),
                   tolerance_mm=tolerance_mm).check_finite()
    tick(1)
    point = curve = None
    if design:
        point = DesignPoint(float(misalignment_deg),
                            design_quantities(spec, float(misalignment_deg)))
        curve = backlash_points(spec, point) if plots and studies else None
    tick(2)
    paths = sweep_files(result, spec, out, point, curve, plots=plots, studies=studies)
    tick(3)
    return result, point, paths
