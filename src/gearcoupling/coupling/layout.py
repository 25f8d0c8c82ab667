"""What the whole coupling is and how its shafts sit: :class:`CouplingLayout` (engagements,
span, sleeve arrangement, flanges, spacer, hub B) and :class:`ShaftAlignment` (parallel
offset and angle of shaft B against shaft A, with their directions). docs/coupling.md.

Each checks its own fields on construction; what needs the hubs' specs (a span that the
hubs fill, a spacer that does not fit the flanges) is checked by
:func:`~.geometry.coupling_geometry`, which every calculation calls first. Every refusal is
an :class:`~gearcoupling.errors.ArgumentError` naming the field, the value and what is
allowed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..arguments import choice, count, real
from ..errors import ArgumentError
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec

SLEEVES = ("one-piece", "flanged")
#: the largest angle between the shafts: each mesh takes at most the supported 6°
MAX_SHAFT_ANGLE_DEG = 2 * MISALIGNMENT_RANGE_DEG[1]
#: how far a given span may differ from the one the flanges and spacer make (mm)
SPAN_SLACK_MM = 1e-6


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
        The spec of the second engagement (hub B and its sleeve ring); default the first.
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
        if self.hub_b is not None:
            set_(self, "hub_b", as_spec(self.hub_b))
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


def is_close(a: float, b: float) -> bool:
    """Whether two lengths agree to :data:`SPAN_SLACK_MM` (mm)."""
    return math.isclose(a, b, rel_tol=0.0, abs_tol=SPAN_SLACK_MM)


__all__ = ["MAX_SHAFT_ANGLE_DEG", "SLEEVES", "CouplingLayout", "ShaftAlignment"]
