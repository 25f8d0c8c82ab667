"""The whole coupling in a spec: its arrangement (:class:`CouplingLayout`, the ``[coupling]``
table) and how the shafts sit (:class:`ShaftAlignment`, the ``[alignment]`` table),
docs/coupling.md.

Each dataclass checks its own fields on construction (an
:class:`~gearcoupling.errors.ArgumentError` naming the field, the value and what is
allowed); read from a spec file, the same refusal is a
:class:`~gearcoupling.errors.SpecError` naming the file's key (``coupling.span``,
``alignment.offset``). What needs the hubs and the mesh angles (a span the hubs do not fit
in, a spacer that does not fit the flanges, a mesh beyond 6°) is checked where the
coupling is resolved, :func:`gearcoupling.coupling.coupling_geometry`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..arguments import choice, count, real
from ..errors import ArgumentError, SpecError
from ..io import Table
from .values import MISALIGNMENT_RANGE_DEG

if TYPE_CHECKING:
    from .coupling import CouplingSpec

SLEEVES = ("one-piece", "flanged")
#: the largest angle between the shafts: each mesh takes at most the supported 6°
MAX_SHAFT_ANGLE_DEG = 2 * MISALIGNMENT_RANGE_DEG[1]
#: the ``[coupling]`` table's lengths (file units), each the layout's field ``<key>_mm``
COUPLING_LENGTHS = ("span", "flange_outer_diameter", "flange_thickness",
                    "spacer_outer_diameter", "spacer_inner_diameter", "spacer_length")
COUPLING_KEYS = ("engagements", "sleeve", *COUPLING_LENGTHS)
ALIGNMENT_KEYS = ("offset", "offset_azimuth_deg", "angle_deg", "angle_azimuth_deg")


def _length(value, name: str, *, zero: bool = False) -> float:
    return real(value, name, 0.0, open_lo=not zero, unit="mm")


def _optional(value, name: str, *, zero: bool = False) -> float | None:
    return None if value is None else _length(value, name, zero=zero)


@dataclass(frozen=True)
class CouplingLayout:
    """The coupling's arrangement of hubs, sleeve and spacer (lengths in mm).

    Attributes
    ----------
    engagements : {1, 2}
        1: one hub in a sleeve fixed to shaft B (the spec alone); 2: two hubs in a
        floating member.
    span_mm : float, optional
        Distance between the two hubs' tooth midplane centres, measured along the shafts
        (docs/coupling.md, Conventions). Left out, it follows from the flanges and the
        spacer (``flanged``).
    sleeve : {"one-piece", "flanged"}
        ``one-piece``: one floating sleeve, its two toothed rings joined by a tube of the
        sleeve's outside and major diameters. ``flanged``: two half-sleeves, each its
        toothed ring with a flange on the inboard face, bolted together or to a spacer.
    flange_outer_diameter_mm, flange_thickness_mm : float, optional
        The flanges (``flanged`` only, then required); bore: the sleeve's major diameter.
    spacer_outer_diameter_mm, spacer_inner_diameter_mm : float, optional
        A spacer tube between the flanges (``flanged`` only); inner diameter 0: solid.
    spacer_length_mm : float, optional
        Flange face to flange face; with ``span_mm`` both must agree, left out it follows.
    hub_b : CouplingSpec, optional
        The spec of the second engagement (hub B and its sleeve ring; a template name or
        TOML path is loaded where the coupling is resolved); default the first.
    """

    engagements: int = 2
    span_mm: float | None = None
    sleeve: str = "one-piece"
    flange_outer_diameter_mm: float | None = None
    flange_thickness_mm: float | None = None
    spacer_outer_diameter_mm: float | None = None
    spacer_inner_diameter_mm: float | None = None
    spacer_length_mm: float | None = None
    hub_b: CouplingSpec | None = field(default=None, compare=False)

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "engagements", count(self.engagements, "engagements", 1, 2))
        set_(self, "sleeve", choice(self.sleeve, "sleeve", SLEEVES))
        for name in ("span_mm", "flange_outer_diameter_mm", "flange_thickness_mm",
                     "spacer_outer_diameter_mm", "spacer_length_mm"):
            set_(self, name, _optional(getattr(self, name), name))
        set_(self, "spacer_inner_diameter_mm", _optional(
            self.spacer_inner_diameter_mm, "spacer_inner_diameter_mm", zero=True))
        if self.engagements == 1:
            return
        flanged = self.sleeve == "flanged"
        for name in ("flange_outer_diameter_mm", "flange_thickness_mm"):
            if flanged and getattr(self, name) is None:
                raise ArgumentError(name, None, "a flanged sleeve needs its flanges' outer "
                                    "diameter and thickness (mm)")
        spacer = [getattr(self, n) for n in ("spacer_outer_diameter_mm",
                                             "spacer_inner_diameter_mm")]
        if self.spacer_length_mm is not None and spacer[0] is None:
            raise ArgumentError("spacer_outer_diameter_mm", None, "a spacer length needs the "
                                "spacer's outer and inner diameter")
        if spacer[0] is None and spacer[1] is None:
            if self.span_mm is None and not flanged:
                raise ArgumentError("span_mm", None, "the distance between the hub midplanes "
                                    "(mm): only a flanged sleeve's span follows from its parts")
            return
        if not flanged:
            raise ArgumentError("sleeve", self.sleeve, "'flanged' for a spacer: the spacer "
                                "tube is bolted between the two half-sleeves' flanges")
        od, bore = spacer
        if od is None or bore is None:
            missing = "spacer_outer_diameter_mm" if od is None else "spacer_inner_diameter_mm"
            raise ArgumentError(missing, None, "a spacer needs its outer and inner diameter")
        if bore >= od:
            raise ArgumentError("spacer_inner_diameter_mm", bore, f"below the spacer's outer "
                                f"diameter {od:g} mm (0 for a solid spacer)")
        assert self.flange_outer_diameter_mm is not None
        if od > self.flange_outer_diameter_mm:
            raise ArgumentError("spacer_outer_diameter_mm", od, f"at most the flange outer "
                                f"diameter {self.flange_outer_diameter_mm:g} mm: the spacer "
                                "bolts against the flange face")

    @property
    def has_spacer(self) -> bool:
        return self.spacer_outer_diameter_mm is not None


@dataclass(frozen=True)
class ShaftAlignment:
    """How shaft B sits against shaft A (docs/coupling.md, Conventions).

    Attributes
    ----------
    offset_mm : float
        Parallel offset of shaft B's axis from shaft A's, at the coupling's centre (the
        plane across shaft A halfway along the span), >= 0.
    offset_azimuth_deg : float
        Its direction about shaft A, from shaft A's ``x``.
    angle_deg : float
        Angle between the shafts, 0 to 12° (each mesh takes at most 6°).
    angle_azimuth_deg : float
        The direction about shaft A toward which shaft B leans.
    """

    offset_mm: float = 0.0
    offset_azimuth_deg: float = 0.0
    angle_deg: float = 0.0
    angle_azimuth_deg: float = 0.0

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "offset_mm", _length(self.offset_mm, "offset_mm", zero=True))
        set_(self, "angle_deg", real(self.angle_deg, "angle_deg", 0.0, MAX_SHAFT_ANGLE_DEG,
                                     unit="degrees"))
        for name in ("offset_azimuth_deg", "angle_azimuth_deg"):
            set_(self, name, real(getattr(self, name), name, -720.0, 720.0, unit="degrees"))

    def replace(self, **changes) -> ShaftAlignment:
        """A copy with fields changed (checked again)."""
        return ShaftAlignment(**{**self.__dict__, **changes})

    def summary(self) -> dict[str, float]:
        return {"offset_mm": self.offset_mm, "offset_azimuth_deg": self.offset_azimuth_deg,
                "angle_deg": self.angle_deg, "angle_azimuth_deg": self.angle_azimuth_deg}


#: the single engagement a spec without a ``[coupling]`` table describes
SINGLE = CouplingLayout(engagements=1)


def file_key(table: str, name: str) -> str:
    """The spec file's key of a layout or alignment field (``span_mm`` ->
    ``coupling.span``, ``offset_mm`` -> ``alignment.offset``)."""
    return f"{table}.{name.removesuffix('_mm')}"


def read_coupling(t: Table) -> CouplingLayout:
    """The ``[coupling]`` table (lengths in the file's units); without one a single
    engagement."""
    kw: dict[str, Any] = {"engagements": t.get("engagements", int, 1)}
    if t.has("sleeve"):
        kw["sleeve"] = t.string("sleeve", "one-piece")
    for key in COUPLING_LENGTHS:
        if t.has(key):
            kw[f"{key}_mm"] = t.length(key)
    t.done(COUPLING_KEYS)
    if kw["engagements"] == 1 and len(kw) > 1:
        name = next(k for k in kw if k != "engagements")
        raise SpecError(file_key("coupling", name), kw[name], "only for engagements = 2 (a "
                        "double-engagement coupling); one engagement is a hub in a sleeve "
                        "fixed to shaft B")
    try:
        return CouplingLayout(**kw)
    except ArgumentError as err:
        raise SpecError(file_key("coupling", err.field), err.value, err.allowed) from None


def write_coupling(layout: CouplingLayout) -> dict[str, Any]:
    """The ``[coupling]`` table in mm (empty for a single engagement: nothing written)."""
    if layout.engagements == 1:
        return {}
    out: dict[str, Any] = {"engagements": layout.engagements, "sleeve": layout.sleeve}
    for key in COUPLING_LENGTHS:
        value = getattr(layout, f"{key}_mm")
        if value is not None:
            out[key] = value
    return out


def read_alignment(t: Table) -> ShaftAlignment | None:
    """The ``[alignment]`` table (the offset in the file's units); None without one."""
    if not t.data:
        return None
    kw = {"offset_mm": t.length("offset", 0.0),
          **{k: t.number(k, 0.0) for k in ALIGNMENT_KEYS[1:]}}
    t.done(ALIGNMENT_KEYS)
    try:
        return ShaftAlignment(**kw)
    except ArgumentError as err:
        raise SpecError(file_key("alignment", err.field), err.value, err.allowed) from None


def write_alignment(alignment: ShaftAlignment | None) -> dict[str, Any]:
    """The ``[alignment]`` table in mm (empty where the spec gives none)."""
    if alignment is None:
        return {}
    return {"offset": alignment.offset_mm, "offset_azimuth_deg": alignment.offset_azimuth_deg,
            "angle_deg": alignment.angle_deg, "angle_azimuth_deg": alignment.angle_azimuth_deg}


__all__ = ["ALIGNMENT_KEYS", "COUPLING_KEYS", "MAX_SHAFT_ANGLE_DEG", "SINGLE", "SLEEVES",
           "CouplingLayout", "ShaftAlignment", "file_key", "read_alignment", "read_coupling",
           "write_alignment", "write_coupling"]
