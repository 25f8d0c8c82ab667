"""What a report computes and how finely: the inputs and the accuracy knobs of
:func:`gearcoupling.report`, checked once."""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass, field
from typing import Any

from ..arguments import GAP_TOLERANCE_MM, choice, count, flag, positive, real, torque_Nm
from ..errors import ArgumentError
from ..io import as_path
from ..loading import model_names
from ..spec import check_misalignment_deg

# (smallest, largest) of each count: enough to draw, small enough to stay interactive
KNOB_RANGES = {"angles": (8, 3600), "capacity_count": (2, 200), "check_angles": (1, 720),
          "surface_angles": (1, 64), "patch_teeth": (1, 12), "fit_points": (100, 1_000_000),
          "dpi": (50, 300)}


@dataclass(frozen=True)
class ReportSettings:
    """Inputs and accuracy knobs of a report (defaults: renzo-1967 in about 20 s on two cores).

    Attributes
    ----------
    misalignment_deg : float, optional
        The misalignment reported (default the spec's design angle).
    torque_Nm : float, optional
        Signed torque (default ``[load] torque_Nm``; without one the loads are not judged).
    model : {"linear", "compliance", "surface"}, optional
        Load model (default ``[load] model``).
    angles : int
        Rotations over a turn of the sweep and of the linear/compliance loads.
    tolerance_mm : float
        Chordal tolerance of the sweep's flank table.
    surface_angles : int
        Rotations over one tooth pitch of the surface model (costly: about a second each).
    capacity_count : int
        Misalignments of the capacity curve (0 to the critical misalignment; a surface-model
        capacity takes about 2 s each).
    check_angles : int
        Poses of the mesh interference check over a turn.
    patch_teeth : int
        Contact pressure maps drawn (the most loaded teeth).
    hob_diameter_mm : float, optional
        Hob outside diameter of the feed program (default ``max(50, 20 module)`` mm, an
        illustrative size).
    scan : path, optional
        A measured hub (mesh or point cloud) to inspect; ``scan_units``, ``fit_points``,
        ``grade`` (ISO 1328-1:2013 class) and ``limits`` (mm) as for
        :func:`gearcoupling.compare_part`.
    viewer : bool
        Embed the 3D viewer (the ``viewer`` extra).
    datasheet : bool
        The API 671 data sheet (with the default surface model about 15 s of CPU on
        renzo-1967, the report's costliest section).
    dpi : int
        Figure resolution.
    """

    misalignment_deg: float | None = None
    torque_Nm: float | None = None
    model: str | None = None
    angles: int = 180
    tolerance_mm: float = GAP_TOLERANCE_MM
    surface_angles: int = 6
    capacity_count: int = 7
    check_angles: int = 36
    patch_teeth: int = 6
    hob_diameter_mm: float | None = None
    scan: str | os.PathLike | None = None
    scan_units: str = "mm"
    fit_points: int = 20_000
    grade: int | None = None
    limits: dict[str, float] = field(default_factory=dict)
    viewer: bool = True
    datasheet: bool = True
    dpi: int = 110

    def __post_init__(self):
        for name, (lo, hi) in KNOB_RANGES.items():
            count(getattr(self, name), name, lo, hi)
        real(self.tolerance_mm, "tolerance_mm", 1e-9, 1e-3, unit="mm")
        if self.misalignment_deg is not None:
            check_misalignment_deg(self.misalignment_deg, "misalignment_deg", ArgumentError)
        if self.model is not None:
            choice(self.model, "model", model_names())
        if self.torque_Nm is not None:
            torque_Nm(self.torque_Nm)
        if self.hob_diameter_mm is not None:
            positive(self.hob_diameter_mm, "hob_diameter_mm")
        if self.scan is not None:
            as_path(self.scan, "scan")
        choice(self.scan_units, "scan_units", ("mm", "in", "m"))
        if self.grade is not None:
            count(self.grade, "grade", 1, 11)
        if not isinstance(self.limits, dict):
            raise ArgumentError("limits", self.limits, "a dict of limit name -> mm")
        flag(self.viewer, "viewer")
        flag(self.datasheet, "datasheet")

    def as_dict(self) -> dict[str, Any]:
        """Plain data for the report's settings table."""
        d = asdict(self)
        d["scan"] = None if self.scan is None else os.fspath(self.scan)
        return d
