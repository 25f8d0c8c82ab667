"""Reading spec files: TOML tables in mm or inches into the parts of a spec, with their
defaults; the bundled templates.

Spec files are TOML with ``units = "mm"`` (default) or ``"in"`` for lengths and angles in
degrees (keys ending in ``_deg``). :func:`read_parts` reads the tables in a fixed order;
every invalid value or combination raises :class:`~gearcoupling.errors.SpecError` naming
the field, the value as the file gave it (with the mm value beside it in an inch file,
:func:`explained`) and what is allowed. Keys left out get defaults (:data:`DEFAULT_RULES`)
chosen to always validate. A top-level table that stands on its own is one
:class:`SpecTable` of :data:`TABLES`. Loading a file with overrides: :mod:`.coupling`.
Defaults and errors: ``docs/spec-and-cli.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import GeometryError, SpecError, brief
from ..geometry import HubModel, feed_path, inv_inverse, radius_squared
from ..io import Table, bundled_names, escaped, resolve_bundled, unknown_key
from .arrangement import (
    ALIGNMENT_KEYS,
    COUPLING_KEYS,
    read_alignment,
    read_coupling,
    write_alignment,
    write_coupling,
)
from .kinds import CROWN_FIELDS, CROWN_KINDS
from .load import material_table, parse_load, parse_material, without_none
from .model import (
    INSPECTION_LIMITS,
    Crowning,
    Hub,
    HubBody,
    HubRoot,
    HubTip,
    InspectionLimits,
    Sleeve,
    ToothSystem,
)
from .values import MAX_NAME_CHARS, MM_PER_INCH, UNITS, _check, _positive, check_misalignment_deg
from .wear import WEAR_TABLE_KEYS, parse_wear, wear_table


@dataclass(frozen=True)
class SpecTable:
    """A top-level table of a spec file that stands on its own: read into the
    :class:`~gearcoupling.spec.CouplingSpec` field of the same name and written back by
    ``CouplingSpec.to_dict``.

    Attributes
    ----------
    key : str
        The table's key, and the name of its field.
    read : callable
        ``read(table)`` -> the part, from a :class:`~gearcoupling.io.Table` (which it
        empties, refusing a key left over).
    write : callable
        ``write(part)`` -> the table as plain data in mm and degrees.
    keys : tuple of str or None
        Its keys, refused before anything is read when unknown (:func:`check_keys`);
        ``None``: ``read`` refuses them in turn.
    optional : bool
        Left out of ``to_dict`` when it holds nothing (a table added later: the resolved
        spec, and so every cache key made of it, stays what it was without it).
    """

    key: str
    read: Callable[[Table], Any]
    write: Callable[[Any], dict[str, Any]] = asdict
    keys: tuple[str, ...] | None = None
    optional: bool = False


def _inspection(t: Table) -> InspectionLimits:
    """The ``inspection`` table: tolerance limits for compare."""
    limits = InspectionLimits(**{k: t.length(k, math.inf) for k in INSPECTION_LIMITS})
    t.done(INSPECTION_LIMITS)
    return limits


#: the self-contained top-level tables, in the order they are read and written (after
#: tooth, hub and sleeve)
TABLES: tuple[SpecTable, ...] = (
    SpecTable("inspection", _inspection, keys=INSPECTION_LIMITS),
    SpecTable("load", parse_load, without_none),
    SpecTable("material", parse_material, material_table),
    SpecTable("wear", parse_wear, wear_table, keys=WEAR_TABLE_KEYS, optional=True),
    SpecTable("coupling", read_coupling, write_coupling, COUPLING_KEYS,
              optional=True),
    SpecTable("alignment", read_alignment, write_alignment, ALIGNMENT_KEYS,
              optional=True),
)

#: the keys of a hub table and its sub-tables (``[hub]``, and ``[hub_b]``: hub B of a
#: double-engagement coupling, each of its keys replacing that of ``[hub]``)
HUB_KEYS: dict[str, tuple[str, ...]] = {
    "": ("face_width", "tooth_thickness", "backlash", "tip", "root", "crowning", "body"),
    ".tip": ("kind", "diameter"),
    ".root": ("dedendum", "fillet_radius"),
    ".crowning": ("kind", *CROWN_FIELDS, "generation"),
    ".body": ("bore_diameter", "length"),
}

# every key a spec file may hold, per table (unknown keys are reported before anything else)
SPEC_KEYS: dict[str, tuple[str, ...]] = {
    "": ("units", "name", "design_misalignment_deg", "tooth", "hub", "sleeve",
         *(t.key for t in TABLES), "hub_b"),
    "tooth": ("teeth", "module", "diametral_pitch", "pressure_angle_deg"),
    **{f"{hub}{sub}": keys for hub in ("hub", "hub_b") for sub, keys in HUB_KEYS.items()},
    "sleeve": ("face_width", "minor_diameter", "major_diameter", "space_width", "tip_chamfer",
               "root_fillet_radius", "outer_diameter"),
    **{t.key: t.keys for t in TABLES if t.keys is not None},
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


def explained(err: SpecError, root: Table) -> SpecError:
    """``err`` raised while reading ``root``, saying so where its field took a default
    (:data:`DEFAULT_RULES`: which key to set) and quoting the value as the file gave it in
    an inch file; ``err`` itself otherwise."""
    if err.field in root.defaulted:
        return SpecError(err.field, err.value, f"{err.allowed} [not in the spec: derived as "
                         f"{DEFAULT_RULES.get(err.field, 'a default')}; set {err.field} "
                         "explicitly]")
    if err.field in root.given and root.scale != 1.0:
        typed, scale = root.given[err.field]
        return _as_typed(err, typed, scale, root.scale)
    return err


def _as_typed(err: SpecError, typed: Any, scale: float, unit_mm: float) -> SpecError:
    """``err`` quoting the value as the file gave it (``typed``, read times ``scale`` into
    mm or 1/mm; ``unit_mm`` is the file's unit) with the converted value beside it; ``err``
    itself where its value is not the converted one (a count or a derived value)."""
    given = list(typed) if isinstance(typed, tuple) else [typed]
    got = list(err.value) if isinstance(err.value, tuple) else [err.value]
    if len(got) != len(given) or not all(
            isinstance(g, int | float) and math.isclose(g, v * scale, rel_tol=1e-12)
            for g, v in zip(got, given, strict=True)):
        return err
    unit = next(u for u, f in UNITS.items() if f == unit_mm)
    unit, mm = (unit, "mm") if scale == unit_mm else (f"1/{unit}", "1/mm")
    if isinstance(typed, tuple):
        return SpecError(err.field, typed, err.allowed, f"{given!r} {unit} ({got!r} {mm})")
    return SpecError(err.field, typed, err.allowed, f"{typed!r} {unit} ({err.value!r} {mm})")


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


def read_parts(root: Table, name: str) -> dict[str, Any]:
    """The fields of a :class:`~gearcoupling.spec.CouplingSpec` from a spec file's
    ``root`` table; tables and keys are read in a fixed order, which decides the error
    raised first."""
    units, name, misalignment = _header(root, name)
    tooth = _tooth_system(root)
    s = root.table("sleeve")
    space_width = s.length("space_width", 0.5 * math.pi * tooth.module)
    _positive("sleeve.space_width", space_width)
    hub, tip_default = _hub(root, tooth, space_width)
    sleeve = _sleeve(s, tooth, hub, space_width, tip_default)
    parts = {t.key: t.read(root.table(t.key)) for t in TABLES}
    root.done(SPEC_KEYS.get(root.where, ()))
    return dict(tooth=tooth, hub=hub, sleeve=sleeve, design_misalignment=misalignment,
                name=name, units=units, **parts)


def _header(root: Table, name: str) -> tuple[str, str, float]:
    """The top-level ``units`` (which sets ``root.scale``), ``name`` and the design
    misalignment in radians."""
    units = root.string("units", "mm")
    _check(units in UNITS, "units", units, f"one of {tuple(UNITS)}")
    root.scale = UNITS[units]
    # a name from the file is refused with a control character; one from a file's stem
    # (the argument) gets them shown escaped: a name never becomes a line of an output
    name = root.string("name", name) if root.has("name") else escaped(name)
    _check(name.isprintable(), "name", brief(name, 40), "printable characters only (no "
           "control character such as a line break, tab, ESC or NUL, no format character, "
           "no space but ' ')")
    _check(len(name) <= MAX_NAME_CHARS, "name", brief(name, 40),
           f"at most {MAX_NAME_CHARS} characters (it names files and reports)")
    misalignment = math.radians(check_misalignment_deg(root.number("design_misalignment_deg",
                                                                   0.0),
                                                       "design_misalignment_deg"))
    return units, name, misalignment


def _tooth_system(root: Table) -> ToothSystem:
    """The ``tooth`` table: teeth, module (or diametral pitch) and pressure angle."""
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
    return tooth


def _hub(root: Table, tooth: ToothSystem, space_width: float) -> tuple[Hub, float]:
    """The ``hub`` table and its sub-tables, with the default tip radius the sleeve's
    default major diameter is derived from."""
    h = root.table("hub")
    face = h.length("face_width")
    _positive("hub.face_width", face)
    thickness = _hub_thickness(h, tooth, space_width)
    # defaults: standard proportions, kept below where hub teeth or sleeve spaces turn
    # pointed (which matters for few teeth)
    crowning = _crowning(h)
    tip, tip_default = _hub_tip(h, tooth, thickness, crowning, face)
    hub_root = _hub_root(h, tooth, thickness, crowning, face)
    body = _hub_body(h, tooth, hub_root, face)
    hub = Hub(face, thickness, tip, hub_root, crowning, body)
    h.done(SPEC_KEYS.get(h.where, ()))
    return hub, tip_default


def _hub_thickness(h: Table, tooth: ToothSystem, space_width: float) -> float:
    """Hub tooth thickness: given, or the sleeve space width less the backlash."""
    if h.has("tooth_thickness"):
        _check(not h.has("backlash"), "hub.backlash", None,
               "give tooth_thickness or backlash, not both")
        thickness = h.length("tooth_thickness")
    else:
        backlash = h.length("backlash", 0.04 * tooth.module)
        _check(math.isfinite(backlash) and 0 <= backlash < space_width, "hub.backlash",
               backlash, f"must be >= 0 and below the sleeve space width {space_width:.6g} mm")
        thickness = space_width - backlash
    _positive("hub.tooth_thickness", thickness)
    return thickness


def _crowning(h: Table) -> Crowning:
    """The ``hub.crowning`` table: the keys of :data:`.kinds.CROWN_FIELDS` (required where
    the kind needs them)."""
    c = h.table("crowning")
    kind = c.string("kind", "circular")
    known = CROWN_KINDS.get(kind)
    needs = known.needs if known is not None else ()
    values: dict[str, Any] = {}
    for key, (attr, default, power) in CROWN_FIELDS.items():
        if isinstance(default, tuple):
            values[attr] = c.array(key, c.scale if power > 0 else 1.0 / c.scale)
        else:
            values[attr] = c.length(key, None if key in needs else default)
    crowning = Crowning(kind=kind, **values, generation=c.string("generation", "enveloped"))
    c.done(SPEC_KEYS.get(c.where, ()))
    return crowning


def _hub_tip(h: Table, tooth: ToothSystem, thickness: float, crowning: Crowning,
             face: float) -> tuple[HubTip, float]:
    """The ``hub.tip`` table, and the default tip radius: R + m, lowered where the teeth
    would be pointed, at the face ends too."""
    R, m = tooth.pitch_radius, tooth.module
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
    return tip, tip_default


def _hub_root(h: Table, tooth: ToothSystem, thickness: float, crowning: Crowning,
              face: float) -> HubRoot:
    """The ``hub.root`` table; the default dedendum is derived only when none is given."""
    root_t = h.table("root")
    dedendum = root_t.length("dedendum") if root_t.has("dedendum") else root_t.length(
        "dedendum", default_dedendum(tooth, thickness, crowning, face))
    _positive("hub.root.dedendum", dedendum)
    hub_root = HubRoot(dedendum, root_t.length("fillet_radius",
                                               default_fillet_radius(tooth, thickness, dedendum)))
    root_t.done(SPEC_KEYS.get(root_t.where, ()))
    return hub_root


def _hub_body(h: Table, tooth: ToothSystem, hub_root: HubRoot, face: float) -> HubBody:
    """The ``hub.body`` table: bore below the root diameter, length the face width."""
    m, R = tooth.module, tooth.pitch_radius
    root_dia = 2 * (R - hub_root.dedendum)
    b = h.table("body")
    body = HubBody(b.length("bore_diameter", max(0.0, root_dia - 2 * max(3 * m, 0.15 * R))),
                   b.length("length", face))
    b.done(SPEC_KEYS.get(b.where, ()))
    return body


def _sleeve(s: Table, tooth: ToothSystem, hub: Hub, space_width: float,
            tip_default: float) -> Sleeve:
    """The rest of the ``sleeve`` table (``space_width`` is read before the hub)."""
    m, R = tooth.module, tooth.pitch_radius
    r_space_pointed = _pointed_radius(tooth, space_width)
    major = s.length("major_diameter", 2 * min(R + 1.25 * m,
                                               tip_default + 0.5 * (r_space_pointed - tip_default)))
    # the sleeve tips stay above the hub's form circle (all contact on the involutes)
    hub_root = hub.root
    h_form = hub_root.dedendum - hub_root.fillet_radius * (1 - math.sin(tooth.pressure_angle))
    r_form_hub = math.hypot(R - h_form, h_form / math.tan(tooth.pressure_angle))
    minor_default = max(r_form_hub + 0.05 * m, R - hub_root.dedendum + 0.25 * m,
                        tooth.base_radius + 0.1 * m)
    sleeve = Sleeve(
        face_width=s.length("face_width", hub.face_width + 4 * m),
        minor_diameter=s.length("minor_diameter", 2 * minor_default),
        major_diameter=major,
        space_width=space_width,
        tip_chamfer=s.length("tip_chamfer", 0.1 * m),
        root_fillet_radius=s.length("root_fillet_radius", min(
            0.25 * m, 0.3 * (r_space_pointed - 0.5 * major) * math.tan(tooth.pressure_angle))),
        outer_diameter=s.length("outer_diameter", major + 2 * max(3 * m, 0.1 * R)),
    )
    s.done(SPEC_KEYS.get(s.where, ()))
    return sleeve


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
