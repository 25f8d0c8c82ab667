"""Coupling specs: frozen dataclasses in mm and radians, validated on construction.

The dataclasses and their ranges; reading them from TOML (units, defaults, overrides) is
:mod:`gearcoupling.specfile`. Every invalid value or combination raises
:class:`~gearcoupling.errors.SpecError` naming the field, the value and what is allowed.
Units, frames and signs: ``docs/conventions.md``.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from functools import cached_property
from itertools import pairwise
from typing import Any, ClassVar

from .errors import ArgumentError, SpecError
from .geometry import MAX_END_TANGENT_DEG, check_spec, derived_values
from .io import set_dotted
from .loadspec import UNIT_SIBLINGS, LoadSpec, Materials

MM_PER_INCH = 25.4
UNITS = {"mm": 1.0, "in": MM_PER_INCH}
TEETH_RANGE = (6, 300)
MODULE_RANGE_MM = (0.2, 60.0)
PRESSURE_ANGLE_RANGE_DEG = (14.5, 30.0)
MISALIGNMENT_RANGE_DEG = (0.0, 6.0)
CROWNING_KINDS = ("none", "circular", "vari_crown", "end_round", "table")
GENERATIONS = ("enveloped", "revolved")
TIP_KINDS = ("sphere", "cylinder")
MAX_NAME_CHARS = 200
_ROUNDING_DEG = 1e-9  # slack for degree <-> radian round trips (6° -> 6.000000000000001)


def check_misalignment_deg(value: object, field_name: str = "misalignment_deg",
                           error: type[SpecError] | type[ArgumentError] = SpecError) -> float:
    """A misalignment in degrees, validated once for every caller (0-6°).

    Values within ``1e-9°`` outside the range (a degree-radian round trip) are clamped
    onto it; anything else outside, non-numeric or non-finite raises ``error``: a
    :class:`SpecError` for a spec value, an :class:`ArgumentError` for an argument.
    """
    lo, hi = MISALIGNMENT_RANGE_DEG
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (
            math.isfinite(value) and lo - _ROUNDING_DEG <= float(value) <= hi + _ROUNDING_DEG):
        raise error(field_name, value, f"must be a finite angle from {lo} to {hi} degrees")
    return min(max(float(value), lo), hi)


def _check(ok: bool, field_name: str, value: object, allowed: str) -> None:
    if not ok:
        raise SpecError(field_name, value, allowed)


def _positive(path: str, value: float, *, finite: bool = True) -> None:
    good = value > 0 and (math.isfinite(value) or not finite) and not math.isnan(value)
    _check(good, path, value, "must be a positive finite length in mm" if finite else
           "must be positive (inf allowed)")


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
        ``none`` (straight), ``circular`` (radius ``R_c``), ``vari_crown`` (radius
        ``radius`` at the midplane growing smoothly to ``end_radius`` at the face ends),
        ``end_round`` (``radius`` up to ``start_z``, then ``end_radius``), ``table``
        (``table_s``/``table_kappa`` or ``table_z``/``table_drop`` samples, splined).
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
        _check(self.kind in CROWNING_KINDS, f"{p}.kind", self.kind, f"one of {CROWNING_KINDS}")
        _check(self.generation in GENERATIONS, f"{p}.generation", self.generation,
               f"one of {GENERATIONS}")
        for name in ("radius", "end_radius"):  # checked even where the kind ignores them
            _positive(f"{p}.{name}", getattr(self, name), finite=False)
        _check(math.isfinite(self.start_z) and self.start_z >= 0, f"{p}.start_z", self.start_z,
               "must be a length >= 0 mm")
        if self.kind in ("circular", "vari_crown", "end_round"):
            _positive(f"{p}.radius", self.radius, finite=self.kind == "vari_crown")
        if self.kind == "vari_crown":
            _check(self.radius < self.end_radius, f"{p}.end_radius", self.end_radius,
                   f"vari_crown is less curved toward the ends: end_radius must exceed "
                   f"radius = {self.radius:.6g} mm (inf allowed)")
        if self.kind == "end_round":
            _positive(f"{p}.end_radius", self.end_radius)
            _check(self.end_radius < self.radius, f"{p}.end_radius", self.end_radius,
                   f"end_round turns sharper at the ends: end_radius must be below "
                   f"radius = {self.radius:.6g} mm")
            limit = self.radius * math.sin(math.radians(MAX_END_TANGENT_DEG))
            _check(math.isfinite(self.start_z) and 0 <= self.start_z <= limit, f"{p}.start_z",
                   self.start_z, f"must be a length from 0 to radius * sin 45° = {limit:.6g} mm")
        if self.kind == "table":
            self._check_table()

    def _check_table(self):
        p = self.PATH
        by_s = bool(self.table_s or self.table_kappa)
        by_z = bool(self.table_z or self.table_drop)
        _check(by_s != by_z, f"{p}.s|z", None,
               "give either s and kappa samples or z and drop samples, not both or neither")
        xs, ys, xn, yn = (
            (self.table_s, self.table_kappa, "s", "kappa") if by_s
            else (self.table_z, self.table_drop, "z", "drop")
        )
        _check(len(xs) == len(ys) and len(xs) >= 3, f"{p}.{yn}", len(ys),
               f"needs as many samples as {xn} ({len(xs)}), at least 3")
        _check(all(math.isfinite(x) for x in xs + ys), f"{p}.{xn}", xs, "samples must be finite")
        _check(xs[0] == 0 and all(b > a for a, b in pairwise(xs)), f"{p}.{xn}",
               xs, "must start at 0 (the midplane) and increase strictly")
        if by_z:
            _check(ys[0] == 0 and all(d >= 0 for d in ys), f"{p}.drop", ys,
                   "crown drop must be 0 at z = 0 and >= 0 elsewhere")
        else:
            _check(all(k >= 0 for k in ys), f"{p}.kappa", ys, "curvatures must be >= 0 (1/mm)")


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
        c = self.crowning
        if c.kind == "end_round":
            _check(c.start_z < 0.5 * self.face_width, "hub.crowning.start_z", c.start_z,
                   f"must lie inside the half face width {0.5 * self.face_width:.6g} mm")


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


@dataclass(frozen=True)
class CouplingSpec:
    """A complete coupling: tooth system, hub, sleeve and design misalignment (radians)."""

    tooth: ToothSystem
    hub: Hub
    sleeve: Sleeve
    design_misalignment: float = 0.0
    name: str = field(default="custom", compare=False)
    load: LoadSpec = field(default_factory=LoadSpec)  # [load] (loadspec.py)
    material: Materials = field(default_factory=Materials)  # [material] (loadspec.py)
    units: str = field(default="mm", compare=False)
    inspection: InspectionLimits = field(default_factory=InspectionLimits, compare=False)
    wear: tuple[tuple[str, Any], ...] = ()  # [wear] as read (loadspec.parse_wear)

    def __post_init__(self):
        check_misalignment_deg(math.degrees(self.design_misalignment), "design_misalignment_deg")
        check_spec(self)  # geometry kernels check what needs them (one-way: spec -> geometry)

    @property
    def design_misalignment_deg(self) -> float:
        """The design misalignment in degrees to 12 digits (as the file gave it: no
        round-trip excess through radians), inside 0-6°."""
        return check_misalignment_deg(float(f"{math.degrees(self.design_misalignment):.12g}"),
                                      "design_misalignment_deg")

    def replace(self, **changes: Any) -> CouplingSpec:
        """A copy with dotted file keys changed, re-read and re-validated.

        Overrides follow one rule everywhere: they are keys of the spec file, in the units
        of the file they change. The file of a resolved spec is :meth:`to_dict`, in mm and
        degrees, so here ``{"hub.crowning.radius": 80.0}`` is 80 mm and
        ``{"tooth.pressure_angle_deg": 25}`` 25°; ``None`` removes a key (its default
        applies); one key of an SI/inch-pound pair replaces the other.
        """
        data = self.to_dict()
        for key, value in changes.items():
            set_dotted(data, key, value, UNIT_SIBLINGS)
        return _read_spec(data, self.name)

    @cached_property
    def derived(self) -> dict[str, float]:
        """Derived values in mm and degrees (see :func:`derived_values`)."""
        return derived_values(self)

    def to_dict(self) -> dict[str, Any]:
        """The resolved spec as plain data in mm and degrees (keys say their unit)."""
        out: dict[str, Any] = {"name": self.name, "units": "mm",
                               "design_misalignment_deg": self.design_misalignment_deg}
        d = asdict(self)
        tooth = d["tooth"]
        tooth["pressure_angle_deg"] = math.degrees(tooth.pop("pressure_angle"))
        out.update(tooth=tooth, hub=d["hub"], sleeve=d["sleeve"], inspection=d["inspection"])
        out["load"] = {k: v for k, v in d["load"].items() if v is not None}
        out["material"] = {p: {k: v for k, v in m.items() if k != "part" and v is not None}
                           for p, m in d["material"].items()}
        if self.wear:
            out["wear"] = {k: list(v) if isinstance(v, tuple) else v for k, v in self.wear}
        cr = out["hub"]["crowning"]
        for key in ("s", "kappa", "z", "drop"):  # the file's keys of a tabulated path
            samples = list(cr.pop(f"table_{key}"))
            if samples:
                cr[key] = samples
        return out


def _unset_reader(data: dict[str, Any], name: str) -> CouplingSpec:
    raise RuntimeError("gearcoupling.specfile is not imported")


#: builds a spec from file data (``spec_from_dict``): set by :mod:`gearcoupling.specfile`,
#: which comes after the dataclasses (one-way imports)
_read_spec: Callable[[dict[str, Any], str], CouplingSpec] = _unset_reader


def use_spec_reader(read: Callable[[dict[str, Any], str], CouplingSpec]) -> None:
    """Let :meth:`CouplingSpec.replace` re-read a spec's file with ``read(data, name)``."""
    global _read_spec
    _read_spec = read
