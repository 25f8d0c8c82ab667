"""The parts of a coupling spec: frozen dataclasses in mm and radians, validated on
construction.

The whole spec, :class:`~gearcoupling.spec.CouplingSpec`, and reading it from TOML (units,
defaults, overrides) are :mod:`.coupling` and :mod:`.file`; the crown kinds
:mod:`.kinds`. Every invalid value or combination raises
:class:`~gearcoupling.errors.SpecError` naming the field, the value and what is allowed.
Units, frames and signs: ``docs/conventions.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ..geometry import FeedPath
from .kinds import CROWN_KINDS
from .values import (
    MM_PER_INCH,
    MODULE_RANGE_MM,
    PRESSURE_ANGLE_RANGE_DEG,
    TEETH_RANGE,
    _check,
    _positive,
)

GENERATIONS = ("enveloped", "revolved")
TIP_KINDS = ("sphere", "cylinder")


@dataclass(frozen=True)
class ToothSystem:
    """Tooth system shared by hub and sleeve.

    Attributes
    ----------
    teeth : int
        Number of teeth ``N`` (hub = sleeve), 6-300.
    module : float
        Module ``m`` in mm, 0.2-60 (diametral pitch ``P`` per inch gives ``m = 25.4 / P``).
    pressure_angle : float
        Pressure angle ``phi`` in radians, 14.5°-30°.
    """

    teeth: int
    module: float
    pressure_angle: float

    def __post_init__(self):
        lo, hi = TEETH_RANGE
        _check(isinstance(self.teeth, int) and not isinstance(self.teeth, bool)
               and lo <= self.teeth <= hi, "tooth.teeth", self.teeth,
               f"must be a whole number from {lo} to {hi}")
        lo, hi = MODULE_RANGE_MM
        _check(math.isfinite(self.module) and lo <= self.module <= hi, "tooth.module",
               self.module, f"module must be {lo}-{hi} mm (diametral pitch "
               f"{MM_PER_INCH / hi:.3g}-{MM_PER_INCH / lo:.3g} per inch)")
        lo, hi = PRESSURE_ANGLE_RANGE_DEG
        deg = math.degrees(self.pressure_angle)
        _check(math.isfinite(deg) and lo - 1e-9 <= deg <= hi + 1e-9,
               "tooth.pressure_angle_deg", deg, f"must be {lo}-{hi} degrees")

    @property
    def pitch_radius(self) -> float:
        """``R = m N / 2``."""
        return 0.5 * self.module * self.teeth

    @property
    def base_radius(self) -> float:
        """``r_b = R cos phi``."""
        return self.pitch_radius * math.cos(self.pressure_angle)

    @property
    def circular_pitch(self) -> float:
        """``p = pi m``."""
        return math.pi * self.module

    @property
    def base_pitch(self) -> float:
        """``p_b = pi m cos phi``, the normal distance of same-side flanks."""
        return self.circular_pitch * math.cos(self.pressure_angle)


@dataclass(frozen=True)
class Crowning:
    """Hub crowning: the hob feed path and the generation method.

    Attributes
    ----------
    kind : str
        A key of :data:`~gearcoupling.spec.CROWN_KINDS`: ``none`` (straight), ``circular``
        (radius ``R_c``), ``vari_crown`` (radius ``radius`` at the midplane growing
        smoothly to ``end_radius`` at the face ends), ``end_round`` (``radius`` up to
        ``start_z``, then ``end_radius``), ``table`` (``table_s``/``table_kappa`` or
        ``table_z``/``table_drop`` samples, splined).
    radius, end_radius : float
        Path radii in mm; ``inf`` means straight.
    start_z : float
        ``end_round``: axial distance from the midplane where ``end_radius`` begins.
    generation : str
        ``enveloped`` (hob-generated, exact) or ``revolved`` (constant profile in planes
        perpendicular to the hub axis, for comparison).
    """

    PATH: ClassVar[str] = "hub.crowning"
    kind: str = "circular"
    radius: float = math.inf
    end_radius: float = math.inf
    start_z: float = 0.0
    table_s: tuple[float, ...] = ()
    table_kappa: tuple[float, ...] = ()
    table_z: tuple[float, ...] = ()
    table_drop: tuple[float, ...] = ()
    generation: str = "enveloped"

    def __post_init__(self):
        p = self.PATH
        _check(self.kind in CROWN_KINDS, f"{p}.kind", self.kind, f"one of {tuple(CROWN_KINDS)}")
        _check(self.generation in GENERATIONS, f"{p}.generation", self.generation,
               f"one of {GENERATIONS}")
        for name in ("radius", "end_radius"):  # checked even where the kind ignores them
            _positive(f"{p}.{name}", getattr(self, name), finite=False)
        _check(math.isfinite(self.start_z) and self.start_z >= 0, f"{p}.start_z", self.start_z,
               "must be a length >= 0 mm")
        CROWN_KINDS[self.kind].check(self)

    def feed_path(self, pitch_radius: float, face_width: float) -> FeedPath:
        """The hob feed path of this crown, built by its kind (:data:`CROWN_KINDS`)."""
        return CROWN_KINDS[self.kind].path(self, pitch_radius, face_width)


@dataclass(frozen=True)
class HubTip:
    """Hub tip surface: a sphere about O (for centring) or a cylinder, by diameter (mm)."""

    kind: str
    diameter: float

    def __post_init__(self):
        _check(self.kind in TIP_KINDS, "hub.tip.kind", self.kind, f"one of {TIP_KINDS}")
        _positive("hub.tip.diameter", self.diameter)


@dataclass(frozen=True)
class HubRoot:
    """Hub root as cut by the hob: hob addendum below the feed path and hob tip radius (mm)."""

    dedendum: float
    fillet_radius: float

    def __post_init__(self):
        _positive("hub.root.dedendum", self.dedendum)
        _check(math.isfinite(self.fillet_radius) and 0 <= self.fillet_radius < self.dedendum,
               "hub.root.fillet_radius", self.fillet_radius,
               f"must be >= 0 and below the dedendum {self.dedendum:.6g} mm")


@dataclass(frozen=True)
class HubBody:
    """Hub body below the teeth: bore diameter and axial length centred on the midplane (mm)."""

    bore_diameter: float
    length: float

    def __post_init__(self):
        _check(math.isfinite(self.bore_diameter) and self.bore_diameter >= 0,
               "hub.body.bore_diameter", self.bore_diameter, "must be >= 0 mm (0 = solid)")
        _positive("hub.body.length", self.length)


@dataclass(frozen=True)
class Hub:
    """Crowned external hub.

    Attributes
    ----------
    face_width : float
        Axial length ``b`` of the teeth, centred on the midplane (mm).
    tooth_thickness : float
        Arc tooth thickness ``t`` at the pitch circle in the midplane (mm).
    """

    face_width: float
    tooth_thickness: float
    tip: HubTip
    root: HubRoot
    crowning: Crowning
    body: HubBody

    def __post_init__(self):
        _positive("hub.face_width", self.face_width)
        _positive("hub.tooth_thickness", self.tooth_thickness)
        _check(self.body.length >= self.face_width, "hub.body.length", self.body.length,
               f"must be at least the face width {self.face_width:.6g} mm")
        CROWN_KINDS[self.crowning.kind].check_face(self.crowning, 0.5 * self.face_width)


@dataclass(frozen=True)
class Sleeve:
    """Sleeve with straight internal involute teeth (all lengths in mm).

    Attributes
    ----------
    face_width : float
        Axial length of the sleeve teeth, centred on the hub midplane.
    minor_diameter, major_diameter : float
        Tip (inner) and root (outer) diameters of the internal teeth.
    space_width : float
        Arc space width ``s`` at the pitch circle.
    tip_chamfer : float
        Radial (= circumferential) leg of the 45° chamfer on the tooth tip corners; 0 = none.
    root_fillet_radius : float
        Radius of the fillet between flank and major circle; 0 = sharp.
    outer_diameter : float
        Outer diameter of the sleeve ring.
    """

    face_width: float
    minor_diameter: float
    major_diameter: float
    space_width: float
    tip_chamfer: float
    root_fillet_radius: float
    outer_diameter: float

    def __post_init__(self):
        for name in ("face_width", "minor_diameter", "major_diameter", "space_width",
                     "outer_diameter"):
            _positive(f"sleeve.{name}", getattr(self, name))
        for name in ("tip_chamfer", "root_fillet_radius"):
            v = getattr(self, name)
            _check(math.isfinite(v) and v >= 0, f"sleeve.{name}", v, "must be >= 0 mm")
        _check(self.major_diameter > self.minor_diameter, "sleeve.major_diameter",
               self.major_diameter, f"must exceed the minor diameter {self.minor_diameter:.6g} mm")
        _check(self.outer_diameter > self.major_diameter, "sleeve.outer_diameter",
               self.outer_diameter, f"must exceed the major diameter {self.major_diameter:.6g} mm")


# ---- inspection tolerance limits (gearcoupling compare) ----
INSPECTION_LIMITS = ("fpt", "Fp", "Fr", "f_Halpha", "f_Hbeta", "C_beta", "thickness")


@dataclass(frozen=True)
class InspectionLimits:
    """Tolerance limits in mm that ``gearcoupling compare`` checks (``inf`` = no limit).

    ``fpt`` single pitch, ``Fp`` total cumulative pitch, ``Fr`` runout, ``f_Halpha`` /
    ``f_Hbeta`` profile / lead slope, ``C_beta`` crown height deviation, ``thickness``
    tooth thickness deviation (see docs/manufacturing.md).
    """

    fpt: float = math.inf
    Fp: float = math.inf
    Fr: float = math.inf
    f_Halpha: float = math.inf
    f_Hbeta: float = math.inf
    C_beta: float = math.inf
    thickness: float = math.inf

    def __post_init__(self):
        for name in INSPECTION_LIMITS:
            v = getattr(self, name)
            _check(isinstance(v, int | float) and not isinstance(v, bool) and v > 0,
                   f"inspection.{name}", v, "must be a positive length (inf = no limit)")

    def as_dict(self) -> dict[str, float]:
        """The finite limits."""
        return {n: getattr(self, n) for n in INSPECTION_LIMITS if math.isfinite(getattr(self, n))}
# ---- end inspection limits ----
