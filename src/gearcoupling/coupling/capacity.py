"""The whole coupling's capacity: the smaller of its meshes', and the allowable parallel
offset at its span (docs/coupling.md, Capacity).

Each mesh's capacity is the single-engagement capacity at its own angle on the flank the
torque loads there (hub A's ccw and hub B's cw for positive torque:
:func:`~.loads.mesh_torque_Nm`). The allowable offset is the parallel offset (in the
alignment's offset direction, its shaft angle held) at which the first mesh reaches its
allowable misalignment at the torque: the smaller of its critical angle and the largest
angle whose capacity still carries the torque
(:func:`gearcoupling.rotordynamics.allowable_misalignment`). The ideal teeth are mirror
symmetric, so a mesh's allowable angle is the same on either flank.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..arguments import real
from ..clearance import mesh_angles
from ..errors import ArgumentError
from ..loading import Capacity, capacity, resolve_model, resolve_torque_Nm
from ..rotordynamics import allowable_misalignment
from ..spec import CouplingSpec
from .geometry import OFFSET_AT, CouplingGeometry, coupling_geometry
from .layout import CouplingLayout, ShaftAlignment

#: accuracy of the allowable offset (mm) and of the allowable angles it comes from (deg)
OFFSET_TOLERANCE_MM = 1e-6
ANGLE_TOLERANCE_DEG = 0.01


@dataclass(frozen=True, eq=False)
class WholeCapacity:
    """Each mesh's capacity at its angle and the whole coupling's, the smaller.

    ``capacity_Nm`` is None where no criterion limits either mesh; ``governing_mesh`` and
    ``criterion`` name the mesh and the criterion that limit it.
    """

    geometry: CouplingGeometry = field(repr=False)
    meshes: dict[str, Capacity] = field(repr=False)
    capacity_Nm: float | None
    governing_mesh: str
    criterion: str

    def summary(self) -> dict[str, Any]:
        out: dict[str, Any] = {"capacity_Nm": self.capacity_Nm,
                               "governing_mesh": self.governing_mesh,
                               "criterion": self.criterion}
        for m, c in self.meshes.items():
            out[f"mesh_{m}"] = {"misalignment_deg": c.misalignment_deg,
                                "loaded_flank": c.loaded_flank, "capacity_Nm": c.capacity_Nm,
                                "governing": c.governing, "q": c.q}
        return out


def whole_capacity(spec: CouplingSpec, layout: CouplingLayout, alignment: ShaftAlignment, *,
                   model: str | None = None, loaded_flank: str = "ccw") -> WholeCapacity:
    """The capacity of each mesh at its angle and of the whole coupling (module docstring).

    ``loaded_flank``: hub A's (``ccw`` for positive torque); hub B's is the other.
    """
    geom = coupling_geometry(spec, layout, alignment)
    model = resolve_model(geom.spec_a, model)
    other = {"ccw": "cw", "cw": "ccw"}
    flanks = {"A": loaded_flank, "B": other.get(loaded_flank, loaded_flank)}
    caps = {m: capacity(geom.spec(m), geom.misalignment_deg(m), model=model,
                        loaded_flank=flanks[m]) for m in geom.meshes}

    def key(m: str) -> float:
        c = caps[m].capacity_Nm
        return math.inf if c is None else c

    gov = min(caps, key=key)
    return WholeCapacity(geom, caps, caps[gov].capacity_Nm, gov, caps[gov].governing)


@dataclass(frozen=True, eq=False)
class AllowableOffset:
    """The parallel offset at which the coupling reaches its allowable misalignment.

    Attributes
    ----------
    offset_mm : float
        At the coupling's centre, in the alignment's offset direction with its shaft angle;
        0 where the angle alone already reaches it.
    governing_mesh : str
        The mesh that reaches its allowable angle first.
    criterion : str
        What limits that mesh: ``"capacity"`` (then ``capacity_criterion``), ``"critical
        angle"`` or ``"range"`` (neither within 6°).
    capacity_criterion : str or None
    allowable_deg : dict of str -> float
        Each mesh's allowable misalignment at the torque.
    mesh_angles_deg : dict of str -> float
        Each mesh's angle at the allowable offset.
    torque_Nm : float
    span_mm : float
    """

    offset_mm: float
    governing_mesh: str
    criterion: str
    capacity_criterion: str | None
    allowable_deg: dict[str, float]
    mesh_angles_deg: dict[str, float]
    torque_Nm: float
    span_mm: float
    alignment: ShaftAlignment = field(repr=False)

    def summary(self) -> dict[str, Any]:
        return {"allowable_offset_mm": self.offset_mm, "governing_mesh": self.governing_mesh,
                "criterion": self.criterion, "capacity_criterion": self.capacity_criterion,
                "allowable_deg": dict(self.allowable_deg),
                "mesh_angles_deg": dict(self.mesh_angles_deg), "torque_Nm": self.torque_Nm,
                "span_mm": self.span_mm, "alignment": self.alignment.summary()}


def allowable_offset(spec: CouplingSpec, layout: CouplingLayout,
                     alignment: ShaftAlignment | None = None, torque_Nm: float | None = None,
                     *, model: str | None = None,
                     tolerance_deg: float = ANGLE_TOLERANCE_DEG) -> AllowableOffset:
    """The allowable parallel offset at the layout's span (module docstring).

    Parameters
    ----------
    alignment : ShaftAlignment, optional
        Its offset direction, shaft angle and angle direction are held (its offset is not
        used); default aligned shafts.
    torque_Nm : float, optional
        Signed; default the spec's ``[load]`` torque.
    tolerance_deg : float
        Accuracy of each mesh's allowable angle (the offset is solved to 1e-6 mm on them).
    """
    alignment = ShaftAlignment() if alignment is None else alignment
    geom = coupling_geometry(spec, layout, alignment)  # checks what it is given first
    geom = coupling_geometry(geom.spec_a, layout, alignment.replace(offset_mm=0.0))
    if geom.layout.engagements == 1:
        raise ArgumentError("engagements", 1, "2: a single engagement takes no offset")
    T = resolve_torque_Nm(geom.spec_a, torque_Nm)
    model = resolve_model(geom.spec_a, model)
    tolerance_deg = real(tolerance_deg, "tolerance_deg", 1e-6, 0.5, unit="degrees")
    limits: dict[str, tuple[float, str, float | None, float | None, str | None]] = {}
    for m in geom.meshes:
        same = m == "B" and geom.spec_b is geom.spec_a
        limits[m] = limits["A"] if same else allowable_misalignment(
            geom.spec(m), T, model=model, tolerance_deg=tolerance_deg)
    allowed = {m: float(v[0]) for m, v in limits.items()}

    def angles(d: float) -> dict[str, float]:
        a = mesh_angles(d, alignment.angle_deg, geom.span_mm,
                        offset_azimuth_deg=alignment.offset_azimuth_deg,
                        angle_azimuth_deg=alignment.angle_azimuth_deg, offset_at=OFFSET_AT)
        return {"A": a.a_deg, "B": a.b_deg}

    def excess(d: float) -> float:
        return max(v - allowed[m] for m, v in angles(d).items())

    d = _first_root(excess, geom.span_mm * math.tan(math.radians(min(allowed.values()))))
    at = angles(d)
    gov = max(at, key=lambda m: at[m] - allowed[m])
    _, criterion, _, _, cap_crit = limits[gov]
    return AllowableOffset(d, gov, criterion, cap_crit if criterion == "capacity" else None,
                           allowed, at, T, geom.span_mm, alignment)


def _first_root(f, scale: float) -> float:
    """The smallest ``d >= 0`` with ``f(d) = 0`` for ``f`` negative at 0 (0 if it is not),
    bracketed by steps from ``scale / 16``, each a tenth longer than the last, and refined
    by Brent's method."""
    from scipy.optimize import brentq  # at the call: importing the package stays light

    if f(0.0) >= 0:
        return 0.0
    step = max(scale, 1e-3) / 16.0
    lo = 0.0
    for _ in range(1000):
        hi = lo + step
        if f(hi) >= 0:
            return float(brentq(f, lo, hi, xtol=OFFSET_TOLERANCE_MM, rtol=1e-12))
        lo = hi
        step *= 1.1
    raise RuntimeError("no allowable offset found")  # unreachable: the angles grow to 90°


__all__ = ["AllowableOffset", "WholeCapacity", "allowable_offset", "whole_capacity"]
