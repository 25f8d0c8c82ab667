"""What the pipeline's stages compute and how finely: the operating point and the accuracy
knobs that ``gc.run`` and ``gc.report`` share, checked once, and where each stage runs
(:class:`Scope`: the spec, or each mesh of a double-engagement coupling)."""

from __future__ import annotations

import dataclasses
import os
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..arguments import GAP_TOLERANCE_MM, PHASES, choice, count, positive, real, torque_Nm
from ..coupling import MESHES, CouplingGeometry, mesh_torque_Nm, spec_geometry
from ..errors import ArgumentError
from ..io import as_path
from ..loading import model_names, resolve_torque_Nm
from ..spec import MAX_SHAFT_ANGLE_DEG, CouplingLayout, CouplingSpec, check_misalignment_deg
from ..wear import WearSettings

# (smallest, largest) of each count: enough to draw, small enough to stay interactive
KNOB_RANGES = {"angles": (8, 3600), "phases": (1, 64), "capacity_count": (2, 200),
               "check_angles": (1, 720), "patch_teeth": (1, 12),
               "fit_points": (100, 1_000_000), "dpi": (50, 300), "wear_phases": (1, 64)}
#: the settings that change a double-engagement spec's ``[alignment]``, each with the
#: field of :class:`~gearcoupling.coupling.ShaftAlignment` it sets
ALIGNMENT_SETTINGS = {"offset_mm": "offset_mm", "offset_azimuth_deg": "offset_azimuth_deg",
                      "shaft_angle_deg": "angle_deg", "angle_azimuth_deg": "angle_azimuth_deg"}
MAX_WEAR_HOURS = 1e7  # as gearcoupling.wear's
MAX_WEAR_SPEED_RPM = 1e6


def wear_grid(grid: Any) -> tuple[int, int]:
    """``wear_grid``: (cells along the face, cells across the depth), each 4-512."""
    try:
        nf, nd = (count(v, "wear_grid", 4, 512) for v in grid)
    except (TypeError, ValueError):
        raise ArgumentError("wear_grid", grid, "(cells along the face, cells across the "
                            "depth), each 4-512") from None
    return nf, nd


#: the root scope (a single engagement, or the whole of a double-engagement coupling)
ROOT = ""
#: a mesh's spec is a single engagement
SINGLE_LAYOUT = CouplingLayout(engagements=1)


@dataclass(frozen=True)
class StageSettings:
    """The operating point and the accuracy knobs of the stages.

    Attributes
    ----------
    misalignment_deg : float, optional
        The misalignment analysed (default the spec's design angle); a single
        engagement's only.
    offset_mm, offset_azimuth_deg, shaft_angle_deg, angle_azimuth_deg : float, optional
        A double-engagement coupling's shaft alignment, each in place of its key of the
        spec's ``[alignment]`` (``offset``, ``offset_azimuth_deg``, ``angle_deg``,
        ``angle_azimuth_deg``; docs/coupling.md): each mesh is analysed at the angle and
        rotation phase it gives.
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
        Poses of the mesh interference check over a turn (36: the smallest mesh gap of 72
        on every template, docs/report.md).
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
    wear_hours, wear_speed_rpm : float, optional
        The hours and the speed of the stage ``wear`` at the operating point, each in place
        of its key of the spec's ``[wear]`` (``hours``, ``speed_rpm``): where both are
        given (here or there) the stage runs and is among ``gc.run``'s defaults.
    wear_grid : (int, int), optional
        The wear history's surface model cells per loaded tooth (default the wear default,
        docs/wear.md).
    wear_phases : int
        The wear history's rotations per tooth pitch.
    """

    misalignment_deg: float | None = None
    torque_Nm: float | None = None
    offset_mm: float | None = None
    offset_azimuth_deg: float | None = None
    shaft_angle_deg: float | None = None
    angle_azimuth_deg: float | None = None
    model: str | None = None
    angles: int = 360
    tolerance_mm: float = GAP_TOLERANCE_MM
    phases: int = PHASES
    capacity_count: int = 7
    check_angles: int = 36
    patch_teeth: int = 6
    hob_diameter_mm: float | None = None
    scan: str | os.PathLike | np.ndarray | None = None
    scan_units: str = "mm"
    fit_points: int = 20_000
    grade: int | None = None
    limits: dict[str, float] = field(default_factory=dict)
    dpi: int = 110
    wear_hours: float | None = None
    wear_speed_rpm: float | None = None
    wear_grid: tuple[int, int] | None = None
    wear_phases: int = 2

    def __post_init__(self):
        for name, (lo, hi) in KNOB_RANGES.items():
            count(getattr(self, name), name, lo, hi)
        real(self.tolerance_mm, "tolerance_mm", 1e-9, 1e-3, unit="mm")
        if self.misalignment_deg is not None:
            check_misalignment_deg(self.misalignment_deg, "misalignment_deg", ArgumentError)
        if self.offset_mm is not None:
            real(self.offset_mm, "offset_mm", 0.0, unit="mm")
        if self.shaft_angle_deg is not None:
            real(self.shaft_angle_deg, "shaft_angle_deg", 0.0, MAX_SHAFT_ANGLE_DEG,
                 unit="degrees")
        for name in ("offset_azimuth_deg", "angle_azimuth_deg"):
            if getattr(self, name) is not None:
                real(getattr(self, name), name, -720.0, 720.0, unit="degrees")
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
        if self.wear_hours is not None:
            real(self.wear_hours, "wear_hours", 0.0, MAX_WEAR_HOURS, open_lo=True, unit="h")
        if self.wear_speed_rpm is not None:
            real(self.wear_speed_rpm, "wear_speed_rpm", 0.0, MAX_WEAR_SPEED_RPM, open_lo=True,
                 unit="rpm")
        if self.wear_grid is not None:
            wear_grid(self.wear_grid)

    def wear_asked(self, spec: CouplingSpec) -> bool:
        """Whether the stage ``wear`` runs on ``spec``: a speed and hours given, each here
        or in the spec's ``[wear]``; one without the other is refused, and where they are
        given the spec's ``[wear]`` values are checked (a :class:`SpecError` naming
        ``wear.<key>``) before any work."""
        table = WearSettings.from_spec(spec)
        given = {"wear_hours": self.wear_hours, "wear_speed_rpm": self.wear_speed_rpm}
        keys = {"wear_hours": "hours", "wear_speed_rpm": "speed_rpm"}
        have = {name: value if value is not None else getattr(table, keys[name])
                for name, value in given.items()}
        missing = [name for name, value in have.items() if value is None]
        if len(missing) == 1:
            other = next(n for n in have if n not in missing)
            what = other if given[other] is not None else f"[wear] {keys[other]}"
            raise ArgumentError(missing[0], None, f"needed with {what}: a wear history takes "
                                f"both the hours and the speed (or the spec's [wear] "
                                f"{keys[missing[0]]})")
        return not missing

    def as_dict(self, engagements: int = 1) -> dict[str, Any]:
        """Plain data (the report's settings table); the alignment's settings only for
        two ``engagements``, the misalignment only for one."""
        d = asdict(self)
        d["scan"] = (None if self.scan is None else f"{len(self.scan)} points"
                     if isinstance(self.scan, np.ndarray) else os.fspath(self.scan))
        for name in (("misalignment_deg",) if engagements == 2 else ALIGNMENT_SETTINGS):
            d.pop(name)
        return d

    def alignment_changes(self) -> dict[str, float]:
        """The alignment's settings given, by the field of
        :class:`~gearcoupling.coupling.ShaftAlignment` each sets."""
        return {field_: float(getattr(self, name)) for name, field_ in
                ALIGNMENT_SETTINGS.items() if getattr(self, name) is not None}

    def resolve(self, spec: CouplingSpec) -> OperatingPoint:
        """The operating point these settings give ``spec``: a single engagement's, or the
        whole of a double-engagement coupling's (its resolved ``coupling``; the
        misalignment the larger mesh angle). Settings that do not apply to the spec are
        refused: an alignment for one engagement, a misalignment for two."""
        torque = None
        if self.torque_Nm is not None or spec.load.torque_Nm is not None:
            torque = resolve_torque_Nm(spec, self.torque_Nm)
        model = self.model or spec.load.model
        changes = self.alignment_changes()
        if spec.coupling.engagements == 1:
            if changes:
                name = next(n for n, f in ALIGNMENT_SETTINGS.items() if f in changes)
                raise ArgumentError(name, getattr(self, name), "only for a double-engagement "
                                    "coupling ([coupling] engagements = 2): one engagement "
                                    "takes misalignment_deg")
            mis = spec.design_misalignment_deg if self.misalignment_deg is None else \
                self.misalignment_deg
            mis = check_misalignment_deg(mis, "misalignment_deg", ArgumentError)
            return OperatingPoint(float(mis), torque, model)
        if self.misalignment_deg is not None:
            raise ArgumentError("misalignment_deg", self.misalignment_deg, "not for a double-"
                                "engagement coupling: each mesh's angle follows from the "
                                "shaft alignment (offset_mm, shaft_angle_deg and their "
                                "azimuths, or the spec's [alignment])")
        geom = spec_geometry(spec, changes, names={f: n for n, f in
                                                   ALIGNMENT_SETTINGS.items()})
        top = max(geom.misalignment_deg(m) for m in geom.meshes)
        return OperatingPoint(check_misalignment_deg(top, "misalignment_deg", ArgumentError),
                              torque, model, coupling=geom)

    def scopes(self, spec: CouplingSpec) -> dict[str, Scope]:
        """Where the stages run: the root (the spec at :meth:`resolve`'s point) and, for a
        double-engagement coupling, each mesh (``mesh-a``, ``mesh-b``): its hub's spec at
        its angle, its torque (hub B's the negative: the sleeve drives it, docs/coupling.md)
        and its rotation phase."""
        point = self.resolve(spec)
        out = {ROOT: Scope(ROOT, spec, point)}
        geom = point.coupling
        if geom is None:
            return out
        for m in geom.meshes:
            mesh_spec = dataclasses.replace(geom.spec(m), name=f"{spec.name}, mesh {m}",
                                            coupling=SINGLE_LAYOUT, alignment=None)
            torque = None if point.torque_Nm is None else mesh_torque_Nm(m, point.torque_Nm)
            mis = check_misalignment_deg(geom.misalignment_deg(m), "misalignment_deg",
                                         ArgumentError)
            out[scope_name(m)] = Scope(scope_name(m), mesh_spec, OperatingPoint(
                mis, torque, point.model, phase_deg=geom.tilt_axis_deg(m), mesh=m))
        return out


def scope_name(mesh: str) -> str:
    """The scope (and folder) of a mesh: ``mesh-a``, ``mesh-b``."""
    return f"mesh-{mesh.lower()}"


#: the folders of a double-engagement coupling's meshes
MESH_SCOPES = tuple(scope_name(m) for m in MESHES)


@dataclass(frozen=True)
class OperatingPoint:
    """The operating point of a run: misalignment (deg), signed torque (N·m, None: no
    torque given) and load model. In a mesh's scope of a double-engagement coupling also
    its rotation phase (the turns over which it is analysed are the coupling's less
    ``phase_deg``: its tilt axis's azimuth) and its name; at the root of one, the resolved
    ``coupling``."""

    misalignment_deg: float
    torque_Nm: float | None
    model: str
    phase_deg: float = 0.0
    mesh: str = ""
    coupling: CouplingGeometry | None = field(default=None, compare=False, repr=False)

    def rotations(self, angles_deg: np.ndarray) -> np.ndarray:
        """The engagement's rotations at the coupling's rotations ``angles_deg``: less the
        phase (the same array where there is none)."""
        return angles_deg - self.phase_deg if self.phase_deg else angles_deg

    @property
    def flank(self) -> str:
        """The loaded flank: ``cw`` under a negative torque, else ``ccw``."""
        return "cw" if (self.torque_Nm or 0.0) < 0 else "ccw"


@dataclass(frozen=True)
class Scope:
    """Where a stage runs: ``name`` (the root ``""``, or a mesh's ``mesh-a`` / ``mesh-b``,
    also the folder of its files), the spec it analyses and its operating point."""

    name: str
    spec: CouplingSpec
    point: OperatingPoint
