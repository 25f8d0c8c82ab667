"""What the pipeline's stages compute and how finely: the operating point and the accuracy
knobs that ``gc.run`` and ``gc.report`` share, checked once."""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..arguments import GAP_TOLERANCE_MM, PHASES, choice, count, positive, real, torque_Nm
from ..errors import ArgumentError
from ..io import as_path
from ..loading import model_names, resolve_torque_Nm
from ..spec import CouplingSpec, check_misalignment_deg

# (smallest, largest) of each count: enough to draw, small enough to stay interactive
KNOB_RANGES = {"angles": (8, 3600), "phases": (1, 64), "capacity_count": (2, 200),
               "check_angles": (1, 720), "patch_teeth": (1, 12),
               "fit_points": (100, 1_000_000), "dpi": (50, 300)}


@dataclass(frozen=True)
class StageSettings:
    """The operating point and the accuracy knobs of the stages.

    Attributes
    ----------
    misalignment_deg : float, optional
        The misalignment analysed (default the spec's design angle).
    torque_Nm : float, optional
        Signed torque (default ``[load] torque_Nm``; without one the loads are skipped).
    model : {"linear", "compliance", "surface"}, optional
        Load model (default ``[load] model``).
    angles : int
        Rotations over a turn of the clearance sweep.
    tolerance_mm : float
        Chordal tolerance of the sweep's flank table.
    phases : int
        Rotations per tooth pitch of the loads over a turn (with ideal teeth a turn holds
        only these poses).
    capacity_count : int
        Misalignments of the capacity curve, 0 to the critical misalignment.
    check_angles : int
        Poses of the mesh interference check over a turn.
    patch_teeth : int
        Contact pressure maps drawn (the most loaded teeth).
    hob_diameter_mm : float, optional
        Hob outside diameter of the feed program (default ``max(50, 20 module)`` mm, an
        illustrative size).
    scan : path or (n, 3) float array, optional
        A measured hub (mesh or point cloud file, or its points) to inspect;
        ``scan_units``, ``fit_points``, ``grade`` (ISO 1328-1:2013 class) and ``limits``
        (mm) as for :func:`gearcoupling.compare_part`.
    dpi : int
        Figure resolution.
    """

    misalignment_deg: float | None = None
    torque_Nm: float | None = None
    model: str | None = None
    angles: int = 360
    tolerance_mm: float = GAP_TOLERANCE_MM
    phases: int = PHASES
    capacity_count: int = 7
    check_angles: int = 72
    patch_teeth: int = 6
    hob_diameter_mm: float | None = None
    scan: str | os.PathLike | np.ndarray | None = None
    scan_units: str = "mm"
    fit_points: int = 20_000
    grade: int | None = None
    limits: dict[str, float] = field(default_factory=dict)
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
        if self.scan is not None and not isinstance(self.scan, np.ndarray):
            as_path(self.scan, "scan")
        choice(self.scan_units, "scan_units", ("mm", "in", "m"))
        if self.grade is not None:
            count(self.grade, "grade", 1, 11)
        if not isinstance(self.limits, dict):
            raise ArgumentError("limits", self.limits, "a dict of limit name -> mm")

    def as_dict(self) -> dict[str, Any]:
        """Plain data (the report's settings table)."""
        d = asdict(self)
        d["scan"] = (None if self.scan is None else f"{len(self.scan)} points"
                     if isinstance(self.scan, np.ndarray) else os.fspath(self.scan))
        return d

    def resolve(self, spec: CouplingSpec) -> OperatingPoint:
        """The operating point these settings give ``spec``."""
        mis = spec.design_misalignment_deg if self.misalignment_deg is None else \
            self.misalignment_deg
        mis = check_misalignment_deg(mis, "misalignment_deg", ArgumentError)
        torque = None
        if self.torque_Nm is not None or spec.load.torque_Nm is not None:
            torque = resolve_torque_Nm(spec, self.torque_Nm)
        return OperatingPoint(float(mis), torque, self.model or spec.load.model)


@dataclass(frozen=True)
class OperatingPoint:
    """The operating point of a run: misalignment (deg), signed torque (N·m, None: no
    torque given) and load model."""

    misalignment_deg: float
    torque_Nm: float | None
    model: str

    @property
    def flank(self) -> str:
        """The loaded flank: ``cw`` under a negative torque, else ``ccw``."""
        return "cw" if (self.torque_Nm or 0.0) < 0 else "ccw"
