"""Coupling specs: frozen dataclasses in mm and radians, validated on construction.

Spec files are TOML with ``units = "mm"`` (default) or ``"in"`` for lengths and angles in
degrees (keys ending in ``_deg``). :func:`load_spec` reads a bundled template by name or a
file by path and applies dotted overrides; every invalid value or combination raises
:class:`~gearcoupling.errors.SpecError` naming the field, the value and what is allowed.
Keys left out get defaults (:data:`DEFAULT_RULES`) chosen to always validate. Units,
frames and signs: ``docs/conventions.md``; defaults and errors: ``docs/spec-and-cli.md``.
"""

from __future__ import annotations

import copy
import math
import numbers
import os
from dataclasses import asdict, dataclass, field
from functools import cached_property
from itertools import pairwise
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from .errors import ArgumentError, GeometryError, SpecError, brief
from .geometry import (
    MAX_END_TANGENT_DEG,
    HubModel,
    check_spec,
    derived_values,
    feed_path,
    inv_inverse,
    radius_squared,
    use_spec_loader,
)
from .io import (
    Table,
    as_path,
    bundled_names,
    read_toml,
    resolve_bundled,
    set_dotted,
    unknown_key,
)
from .loadspec import UNIT_SIBLINGS, LoadSpec, Materials, parse_load, parse_material

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
        return spec_from_dict(data, name=self.name)

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
        cr = out["hub"]["crowning"]
        for key in ("s", "kappa", "z", "drop"):  # the file's keys of a tabulated path
            samples = list(cr.pop(f"table_{key}"))
            if samples:
                cr[key] = samples
        return out


# --------------------------------------------------------------------------- loading


# every key a spec file may hold, per table (unknown keys are reported before anything else)
SPEC_KEYS: dict[str, tuple[str, ...]] = {
    "": ("units", "name", "design_misalignment_deg", "tooth", "hub", "sleeve", "load",
         "material", "inspection"),
    "tooth": ("teeth", "module", "diametral_pitch", "pressure_angle_deg"),
    "hub": ("face_width", "tooth_thickness", "backlash", "tip", "root", "crowning", "body"),
    "hub.tip": ("kind", "diameter"),
    "hub.root": ("dedendum", "fillet_radius"),
    "hub.crowning": ("kind", "radius", "end_radius", "start_z", "s", "kappa", "z", "drop",
                     "generation"),
    "hub.body": ("bore_diameter", "length"),
    "sleeve": ("face_width", "minor_diameter", "major_diameter", "space_width", "tip_chamfer",
               "root_fillet_radius", "outer_diameter"),
    "inspection": INSPECTION_LIMITS,
}

# how each derived default is chosen (quoted when a derived value is refused)
DEFAULT_RULES: dict[str, str] = {
    "hub.backlash": "0.04 m",
    "hub.tip.diameter": "2 (R + m), lowered where the teeth would be pointed (few teeth, "
                        "and at the face ends by the crown drop)",
    "hub.root.dedendum": "1.25 m, reduced to 90 % of the deepest cut free of undercut in "
                         "every plane of the face (few teeth, small pressure angles)",
    "hub.root.fillet_radius": "0.3 m, reduced to 80 % of the largest hob tip round that fits "
                              "in the tooth space, and to at most half the dedendum",
    "hub.body.bore_diameter": "root diameter minus max(6 m, 0.3 R)",
    "hub.body.length": "the face width",
    "sleeve.space_width": "pi m / 2",
    "sleeve.face_width": "hub face width + 4 m",
    "sleeve.minor_diameter": "just above the hub form diameter",
    "sleeve.major_diameter": "2 (R + 1.25 m), lowered for few teeth",
    "sleeve.tip_chamfer": "0.1 m",
    "sleeve.root_fillet_radius": "0.25 m, reduced to fit the space",
    "sleeve.outer_diameter": "major diameter + 2 max(3 m, 0.1 R)",
}


def check_keys(data: Any, path: str = "") -> None:
    """Refuse the first unknown key of a spec file (depth-first), before anything else is
    read, so that a misspelt key is named rather than reported as a missing one."""
    known = SPEC_KEYS.get(path)
    if known is None or not isinstance(data, dict):
        return
    for key in sorted(data):
        name = f"{path}.{key}" if path else key
        if key not in known:
            raise unknown_key(name, data[key], known)
        check_keys(data[key], name)


def spec_from_dict(data: dict[str, Any], name: str = "custom") -> CouplingSpec:
    """Build a :class:`CouplingSpec` from parsed TOML data (file units, angles in degrees).

    Keys left out get the defaults of :data:`DEFAULT_RULES`, chosen so that they always
    fit; if a derived value is refused anyway, the error says so and names the key to set.
    """
    if not isinstance(data, dict):
        raise ArgumentError("data", data, "a dict of spec tables, as read from a TOML "
                            "spec file")
    if not isinstance(name, str):
        raise ArgumentError("name", name, "a str")
    check_keys(data)
    defaulted: set[str] = set()
    try:
        return _build(Table(copy.deepcopy(data), defaulted=defaulted), name)
    except SpecError as err:
        if err.field not in defaulted:
            raise
        raise SpecError(err.field, err.value, f"{err.allowed} [not in the spec: derived as "
                        f"{DEFAULT_RULES.get(err.field, 'a default')}; set {err.field} "
                        "explicitly]") from None


def default_fillet_radius(tooth: ToothSystem, thickness: float, dedendum: float) -> float:
    """Hob tip radius: 0.3 m, or 80 % of the largest that fits between adjacent flanks
    (and at most half the dedendum).

    The round centre ``u_c = t/2 + (d - f) tan phi + f / cos phi`` must stay within half a
    circular pitch of the tooth centre (:class:`HubModel.round_centre`).
    """
    phi = tooth.pressure_angle
    room = 0.5 * (tooth.circular_pitch - thickness) - dedendum * math.tan(phi)
    largest = room / (1.0 / math.cos(phi) - math.tan(phi))
    return max(0.0, min(0.3 * tooth.module, 0.8 * largest, 0.5 * dedendum))


def default_dedendum(tooth: ToothSystem, thickness: float, crowning: Crowning,
                     face_width: float) -> float:
    """Hob addendum: 1.25 m, or 90 % of the deepest form depth free of undercut in every
    plane of the face (few teeth, small pressure angles), found by bisection."""
    m, phi, R = tooth.module, tooth.pressure_angle, tooth.pitch_radius
    d = 1.25 * m
    f = default_fillet_radius(tooth, thickness, d)
    model = HubModel(R, phi, tooth.teeth, thickness, d, f, "cylinder", R, 0.5 * face_width,
                     crowning.generation == "revolved", feed_path(crowning, R, face_width))
    planes = np.linspace(0.0, 0.5 * face_width, 17)
    z = planes

    def undercut(h: float) -> bool:
        try:
            with np.errstate(all="ignore"):
                d_r2 = radius_squared(model, z, h, phi)[1]
        except GeometryError:
            return True
        return not bool(np.all(d_r2 < 0))

    lift = 1.0 - math.sin(phi)  # form depth = dedendum - fillet * lift
    if not undercut(d - f * lift):
        return d

    def deepest() -> float:
        lo, hi = 0.0, d - f * lift
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if not undercut(mid) else (lo, mid)
        return lo

    lo = deepest()  # crowning is a negative profile shift at the face ends: fit them too
    if lo < 0.1 * R * math.sin(phi) ** 2:  # no useful depth fits: the crown is to blame;
        z = planes[:1]  # fit the midplane and let the checks name the crown
        lo = deepest()
    for _ in range(8):  # the default fillet depends on the dedendum: fixed point
        d = 0.9 * lo + default_fillet_radius(tooth, thickness, d) * lift
    return d


def _build(root: Table, name: str) -> CouplingSpec:
    units = root.string("units", "mm")
    _check(units in UNITS, "units", units, f"one of {tuple(UNITS)}")
    root.scale = UNITS[units]
    name = root.string("name", name)
    _check(len(name) <= MAX_NAME_CHARS, "name", brief(name, 40),
           f"at most {MAX_NAME_CHARS} characters (it names files and reports)")
    misalignment = math.radians(check_misalignment_deg(root.number("design_misalignment_deg",
                                                                   0.0),
                                                       "design_misalignment_deg"))

    t = root.table("tooth")
    teeth = t.integer("teeth")
    if t.has("diametral_pitch"):
        _check(not t.has("module"), "tooth.module", t.data.get("module"),
               f"give module or diametral_pitch, not both (diametral_pitch = "
               f"{t.data.get('diametral_pitch')!r} is set too)")
        pd = t.number("diametral_pitch")
        _check(pd > 0 and math.isfinite(pd), "tooth.diametral_pitch", pd,
               "must be a positive number of teeth per inch of pitch diameter")
        module = MM_PER_INCH / pd
    else:
        module = t.length("module")
    tooth = ToothSystem(teeth, module, t.angle("pressure_angle_deg", 20.0))
    t.done(SPEC_KEYS.get(t.where, ()))
    m, R = module, tooth.pitch_radius

    s = root.table("sleeve")
    space_width = s.length("space_width", 0.5 * math.pi * m)
    _positive("sleeve.space_width", space_width)
    h = root.table("hub")
    face = h.length("face_width")
    _positive("hub.face_width", face)
    if h.has("tooth_thickness"):
        _check(not h.has("backlash"), "hub.backlash", None,
               "give tooth_thickness or backlash, not both")
        thickness = h.length("tooth_thickness")
    else:
        backlash = h.length("backlash", 0.04 * m)
        _check(math.isfinite(backlash) and 0 <= backlash < space_width, "hub.backlash",
               backlash, f"must be >= 0 and below the sleeve space width {space_width:.6g} mm")
        thickness = space_width - backlash
    _positive("hub.tooth_thickness", thickness)

    # defaults: standard proportions, kept below where hub teeth or sleeve spaces turn
    # pointed (which matters for few teeth)
    c = h.table("crowning")
    kind = c.string("kind", "circular")
    needs_radius = kind in ("circular", "vari_crown", "end_round")
    crowning = Crowning(
        kind=kind,
        radius=c.length("radius", None if needs_radius else math.inf),
        end_radius=c.length("end_radius", math.inf),
        start_z=c.length("start_z", 0.0),
        table_s=c.array("s", root.scale),
        table_kappa=c.array("kappa", 1.0 / root.scale),
        table_z=c.array("z", root.scale),
        table_drop=c.array("drop", root.scale),
        generation=c.string("generation", "enveloped"),
    )
    c.done(SPEC_KEYS.get(c.where, ()))
    # the crown drop thins the teeth toward the face ends: keep the tip below where they
    # would be pointed there too (a sphere tip falls with z by itself)
    r_hub_pointed = _pointed_radius(tooth, thickness)
    tip_t = h.table("tip")
    tip_kind = tip_t.string("kind", "sphere")
    tip_default = min(R + m, R + 0.75 * (r_hub_pointed - R))
    z_end = 0.5 * face
    drop_end = _crown_drop(crowning, R, face, z_end)
    if tip_kind == "sphere":
        drop_end -= tip_default - math.sqrt(max(tip_default**2 - z_end**2, 0.0))
    tip_default = min(tip_default, r_hub_pointed - max(drop_end, 0.0)
                      - 0.25 * (r_hub_pointed - R))
    tip = HubTip(tip_kind, tip_t.length("diameter", 2 * tip_default))
    tip_t.done(SPEC_KEYS.get(tip_t.where, ()))
    root_t = h.table("root")
    dedendum = root_t.length("dedendum") if root_t.has("dedendum") else root_t.length(
        "dedendum", default_dedendum(tooth, thickness, crowning, face))
    _positive("hub.root.dedendum", dedendum)
    hub_root = HubRoot(dedendum, root_t.length("fillet_radius",
                                               default_fillet_radius(tooth, thickness, dedendum)))
    root_t.done(SPEC_KEYS.get(root_t.where, ()))
    root_dia = 2 * (R - hub_root.dedendum)
    b = h.table("body")
    body = HubBody(b.length("bore_diameter", max(0.0, root_dia - 2 * max(3 * m, 0.15 * R))),
                   b.length("length", face))
    b.done(SPEC_KEYS.get(b.where, ()))
    hub = Hub(face, thickness, tip, hub_root, crowning, body)
    h.done(SPEC_KEYS.get(h.where, ()))

    r_space_pointed = _pointed_radius(tooth, space_width)
    major = s.length("major_diameter", 2 * min(R + 1.25 * m,
                                               tip_default + 0.5 * (r_space_pointed - tip_default)))
    # the sleeve tips stay above the hub's form circle (all contact on the involutes)
    h_form = hub_root.dedendum - hub_root.fillet_radius * (1 - math.sin(tooth.pressure_angle))
    r_form_hub = math.hypot(R - h_form, h_form / math.tan(tooth.pressure_angle))
    minor_default = max(r_form_hub + 0.05 * m, R - hub_root.dedendum + 0.25 * m,
                        tooth.base_radius + 0.1 * m)
    sleeve = Sleeve(
        face_width=s.length("face_width", face + 4 * m),
        minor_diameter=s.length("minor_diameter", 2 * minor_default),
        major_diameter=major,
        space_width=space_width,
        tip_chamfer=s.length("tip_chamfer", 0.1 * m),
        root_fillet_radius=s.length("root_fillet_radius", min(
            0.25 * m, 0.3 * (r_space_pointed - 0.5 * major) * math.tan(tooth.pressure_angle))),
        outer_diameter=s.length("outer_diameter", major + 2 * max(3 * m, 0.1 * R)),
    )
    s.done(SPEC_KEYS.get(s.where, ()))
    load = parse_load(root.table("load"))
    material = parse_material(root.table("material"))
    ins = root.table("inspection")  # tolerance limits for compare
    inspection = InspectionLimits(**{k: ins.length(k, math.inf) for k in INSPECTION_LIMITS})
    ins.done(SPEC_KEYS.get(ins.where, ()))
    root.done(SPEC_KEYS.get(root.where, ()))
    return CouplingSpec(tooth, hub, sleeve, misalignment, name=name, units=units, load=load,
                        material=material, inspection=inspection)


def _crown_drop(crowning: Crowning, R: float, face: float, z: float) -> float:
    """Feed-path crown drop at ``z`` for a default; 0 where the path does not reach ``z``
    (the checks then refuse the crown itself, with a better reason)."""
    try:
        with np.errstate(all="ignore"):
            drop = float(feed_path(crowning, R, face).drop(z))
    except GeometryError:
        return 0.0
    return drop if math.isfinite(drop) else 0.0


def _pointed_radius(tooth: ToothSystem, arc_width: float) -> float:
    """Radius where a spur tooth (or space) of ``arc_width`` at the pitch circle is pointed."""
    phi = tooth.pressure_angle
    alpha = float(inv_inverse(0.5 * arc_width / tooth.pitch_radius + math.tan(phi) - phi))
    return tooth.base_radius / math.cos(alpha)


def template_names() -> list[str]:
    """Names of the bundled templates."""
    return bundled_names("templates")


def resolve_spec_path(name_or_path: str | Path) -> Path:
    """A template name or a file path, as a path to a TOML file."""
    return resolve_bundled("templates", name_or_path)


def load_spec(name_or_path: str | Path, **overrides: Any) -> CouplingSpec:
    """Load a template (by name) or a TOML spec file, with dotted overrides in file units.

    >>> spec = load_spec("renzo-1967", **{"hub.crowning.radius": 2.0})  # doctest: +SKIP
    """
    as_path(name_or_path, "name_or_path")
    path = resolve_spec_path(name_or_path)
    data, _ = read_toml(path)
    for key, value in overrides.items():
        set_dotted(data, key, value, UNIT_SIBLINGS)
    return spec_from_dict(data, name=path.stem)


def as_spec(spec: Any, field: str = "spec") -> CouplingSpec:
    """``spec`` when it is a :class:`CouplingSpec`; a template name or the path of a TOML
    spec is loaded (:func:`load_spec`); anything else is an :class:`ArgumentError` naming
    ``field``. Every public function that takes a spec starts with this."""
    if isinstance(spec, CouplingSpec):
        return spec
    if isinstance(spec, str | os.PathLike):
        return load_spec(as_path(spec, field))
    raise ArgumentError(field, spec, "a CouplingSpec (gearcoupling.load_spec), a "
                        "template name or the path of a TOML spec")


use_spec_loader(as_spec)  # the geometry's public functions take names too

__all__ = [
    "CouplingSpec",
    "Crowning",
    "Hub",
    "HubBody",
    "HubRoot",
    "HubTip",
    "Sleeve",
    "ToothSystem",
    "as_spec",
    "load_spec",
    "spec_from_dict",
    "template_names",
]
