"""The whole coupling in space: its two meshes' angles, tilt axes and frames from the shaft
alignment, and the floating member's parts along its axis (docs/coupling.md, Conventions).

The coupling frame: origin ``O_A`` (hub A's tooth midplane centre), ``z`` along shaft A,
``x`` shaft A's reference direction. The floating member's axis ``s`` runs through ``O_A``
and hub B's midplane centre ``O_B`` (:func:`gearcoupling.clearance.mesh_angles`, the offset
measured at the coupling's centre). Each mesh ``m`` is the single-engagement pose of its
hub in its sleeve ring: its frame ``F_m`` has ``z`` along ``s`` and ``x`` along the tilt
axis ``s x h_m`` (``h_m`` the shaft's axis, both pointing from A toward B), the hub is
``F_m Rx(i_m)``, and at the coupling's rotation ``psi`` (shaft A's turn) the mesh is at
the single-engagement rotation ``psi - tilt axis azimuth``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..clearance import MeshAngles, mesh_angles
from ..errors import ArgumentError, SpecError
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec, file_key
from .layout import CouplingLayout, ShaftAlignment, is_close

MESHES = ("A", "B")
#: where the alignment's offset is measured: the coupling's centre (half the span)
OFFSET_AT = 0.5


def turn(axis: ArrayLike, angle_rad: float) -> NDArray[np.float64]:
    """The rotation ``(3, 3)`` by ``angle_rad`` about the unit ``axis`` (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle_rad) * K + (1.0 - math.cos(angle_rad)) * K @ K


@dataclass(frozen=True)
class Annulus:
    """A plain revolved part of the floating member: radii and axial extent along the
    floating axis from ``O_A`` (mm)."""

    name: str
    inner_mm: float
    outer_mm: float
    z0_mm: float
    z1_mm: float

    @property
    def length_mm(self) -> float:
        return self.z1_mm - self.z0_mm

    def below(self, z_mm: float, name: str) -> Annulus | None:
        """Its part below ``z_mm`` (None if none)."""
        if z_mm <= self.z0_mm:
            return None
        return Annulus(name, self.inner_mm, self.outer_mm, self.z0_mm, min(self.z1_mm, z_mm))

    def above(self, z_mm: float, name: str) -> Annulus | None:
        """Its part above ``z_mm`` (None if none)."""
        if z_mm >= self.z1_mm:
            return None
        return Annulus(name, self.inner_mm, self.outer_mm, max(self.z0_mm, z_mm), self.z1_mm)


@dataclass(frozen=True, eq=False)
class CouplingGeometry:
    """A checked coupling and alignment, resolved in space (module docstring).

    Attributes
    ----------
    spec_a, spec_b : CouplingSpec
        The engagements' specs (``spec_b`` is ``spec_a`` unless the layout gives hub B).
    layout : CouplingLayout
    alignment : ShaftAlignment
    span_mm : float
        The span (given, or what the flanges and spacer make).
    angles : MeshAngles
        Both meshes' angles and tilt-axis azimuths.
    sleeve_axis : (3,) float
        The floating axis ``s`` (a single engagement: shaft B's axis).
    reference : (3, 3) float
        The floating member's frame at rotation 0: columns ``e0, e1, s`` (``e0`` shaft A's
        ``x`` carried onto the sleeve by the smallest turn).
    centre_b_mm : (3,) float
        ``O_B`` in the coupling frame.
    annuli : tuple of Annulus
        The floating member's plain parts (flanges, spacer or tube) along its axis.
    """

    spec_a: CouplingSpec = field(repr=False)
    spec_b: CouplingSpec = field(repr=False)
    layout: CouplingLayout
    alignment: ShaftAlignment
    span_mm: float
    angles: MeshAngles
    sleeve_axis: NDArray[np.float64]
    reference: NDArray[np.float64]
    centre_b_mm: NDArray[np.float64]
    annuli: tuple[Annulus, ...] = ()

    @property
    def meshes(self) -> tuple[str, ...]:
        return MESHES[:self.layout.engagements]

    def spec(self, mesh: str) -> CouplingSpec:
        return self.spec_a if mesh == "A" else self.spec_b

    def misalignment_deg(self, mesh: str) -> float:
        return self.angles.a_deg if mesh == "A" else self.angles.b_deg

    def tilt_axis_deg(self, mesh: str) -> float:
        """Azimuth of the mesh's tilt axis about the floating axis (degrees)."""
        return self.angles.a_tilt_axis_deg if mesh == "A" else self.angles.b_tilt_axis_deg

    def mesh_rotations_deg(self, mesh: str, psi_deg: ArrayLike) -> NDArray[np.float64]:
        """The single-engagement rotations of ``mesh`` at the coupling rotations
        ``psi_deg`` (shaft A's turn): ``psi - tilt axis azimuth``."""
        return np.asarray(psi_deg, dtype=float) - self.tilt_axis_deg(mesh)

    def centre_mm(self, mesh: str) -> NDArray[np.float64]:
        return np.zeros(3) if mesh == "A" else self.centre_b_mm.copy()

    def mesh_frame(self, mesh: str) -> NDArray[np.float64]:
        """``F_m (3, 3)``: the mesh's sleeve frame in the coupling frame (columns: tilt
        axis, ``s x`` tilt axis, ``s``)."""
        return self.reference @ turn([0.0, 0.0, 1.0], math.radians(self.tilt_axis_deg(mesh)))

    def hub_frame(self, mesh: str) -> NDArray[np.float64]:
        """``H_m = F_m Rx(i_m)``: the frame ``hub_wrench`` and the load results use (``x``
        the tilt axis, ``z`` the hub's axis), in the coupling frame."""
        return self.mesh_frame(mesh) @ turn([1.0, 0.0, 0.0],
                                            math.radians(self.misalignment_deg(mesh)))

    def hub_axis(self, mesh: str) -> NDArray[np.float64]:
        return self.hub_frame(mesh)[:, 2]

    def hub_pose(self, mesh: str, psi_deg: float) -> NDArray[np.float64]:
        """Hub body frame ``(3, 3)`` in the coupling frame at the coupling rotation."""
        psi = math.radians(float(self.mesh_rotations_deg(mesh, psi_deg)))
        return self.hub_frame(mesh) @ turn([0.0, 0.0, 1.0], psi)

    def sleeve_pose(self, psi_deg: float) -> NDArray[np.float64]:
        """Floating member's body frame ``(3, 3)`` at the coupling rotation."""
        return self.reference @ turn([0.0, 0.0, 1.0], math.radians(float(psi_deg)))

    def summary(self) -> dict[str, Any]:
        out: dict[str, Any] = {"engagements": self.layout.engagements,
                               "span_mm": self.span_mm, "sleeve": self.layout.sleeve,
                               "alignment": self.alignment.summary()}
        for m in self.meshes:
            out[f"mesh_{m}"] = {"spec": self.spec(m).name,
                                "misalignment_deg": self.misalignment_deg(m),
                                "tilt_axis_deg": self.tilt_axis_deg(m)}
        out["sleeve_tilt_deg"] = self.angles.sleeve_tilt_deg
        out["sleeve_azimuth_deg"] = self.angles.sleeve_azimuth_deg
        return out


def coupling_geometry(spec: CouplingSpec, layout: CouplingLayout,
                      alignment: ShaftAlignment) -> CouplingGeometry:
    """``spec`` (hub A) in ``layout`` at ``alignment``, checked and resolved.

    Raises
    ------
    ArgumentError
        A span the hubs or sleeve rings do not fit in, flanges or a spacer that do not fit
        the sleeve, an offset or angle that puts a mesh beyond 6°, an offset on a single
        engagement (each naming its field).
    """
    spec_a = as_spec(spec)
    if not isinstance(layout, CouplingLayout):
        raise ArgumentError("layout", layout, "a gearcoupling.coupling.CouplingLayout")
    if not isinstance(alignment, ShaftAlignment):
        raise ArgumentError("alignment", alignment, "a gearcoupling.coupling.ShaftAlignment")
    spec_b = spec_a if layout.hub_b is None else as_spec(layout.hub_b, "hub_b")
    if layout.engagements == 1:
        return _single(spec_a, layout, alignment)
    span, annuli = _floating_parts(spec_a, spec_b, layout)
    angles = mesh_angles(alignment.offset_mm, alignment.angle_deg, span,
                         offset_azimuth_deg=alignment.offset_azimuth_deg,
                         angle_azimuth_deg=alignment.angle_azimuth_deg, offset_at=OFFSET_AT)
    _check_mesh_angles(alignment, angles)
    ob = np.array(angles.centre_b_mm)
    return CouplingGeometry(spec_a, spec_b, layout, alignment, span, angles,
                            *_axes(ob), ob, annuli)


def spec_geometry(spec: CouplingSpec, changes: dict[str, float] | None = None, *,
                  names: dict[str, str] | None = None) -> CouplingGeometry:
    """The coupling a double-engagement spec describes (its ``[coupling]`` table), resolved
    at its ``[alignment]`` with ``changes`` (fields of :class:`ShaftAlignment`) put in
    place; without an ``[alignment]`` table, at the parallel offset that puts each mesh at
    the spec's design misalignment (azimuth 0, no angle).

    Every refusal names where the value came from: the spec's key (``coupling.span``,
    ``alignment.offset``: a :class:`SpecError`) or, where ``changes`` made the alignment
    refused, the changed field's name in ``names`` (an option such as ``--offset``: an
    :class:`ArgumentError`).
    """
    spec = as_spec(spec)
    changes, names = _changes(changes), _names(names)
    if spec.coupling.engagements != 2:
        raise ArgumentError("engagements", spec.coupling.engagements, "2: the spec describes "
                            "one engagement ([coupling] engagements = 2 for two)")
    try:
        if spec.alignment is not None:
            base = spec.alignment
        else:
            probe = coupling_geometry(spec, spec.coupling, ShaftAlignment())
            base = ShaftAlignment(offset_mm=probe.span_mm * math.tan(spec.design_misalignment))
        alignment = base.replace(**changes) if changes else base
        return coupling_geometry(spec, spec.coupling, alignment)
    except ArgumentError as err:
        table = "alignment" if err.field in ShaftAlignment.__dataclass_fields__ else "coupling"
        changed = err.field if err.field in changes else next(
            (f for f in ("offset_mm", "angle_deg", *changes) if f in changes), None)
        if changed is not None and table == "alignment":  # the alignment given made it
            raise ArgumentError(names.get(changed, changed), changes[changed],
                                err.allowed) from None
        raise SpecError(file_key(table, err.field), err.value, err.allowed) from None


def _changes(changes: Any) -> dict[str, Any]:
    """``changes`` as a dict of :class:`ShaftAlignment` fields (None: none)."""
    if changes is None:
        return {}
    fields = tuple(ShaftAlignment.__dataclass_fields__)
    if not isinstance(changes, dict) or not all(k in fields for k in changes):
        raise ArgumentError("changes", changes, f"a dict of ShaftAlignment fields: "
                            f"{', '.join(fields)}")
    return dict(changes)


def _names(names: Any) -> dict[str, str]:
    """``names`` as a dict of field -> the name a refusal gives it (None: none)."""
    if names is None:
        return {}
    if not isinstance(names, dict) or not all(isinstance(v, str) for v in names.values()):
        raise ArgumentError("names", names, "a dict of ShaftAlignment field -> name")
    return dict(names)


def _single(spec: CouplingSpec, layout: CouplingLayout,
            alignment: ShaftAlignment) -> CouplingGeometry:
    """One engagement: the sleeve is fixed to shaft B, so its axis is shaft B's."""
    if alignment.offset_mm > 0:
        raise ArgumentError("offset_mm", alignment.offset_mm, "0 for a single engagement: one "
                            "gear mesh takes an angle, not a parallel offset")
    top = MISALIGNMENT_RANGE_DEG[1]
    if alignment.angle_deg > top:
        raise ArgumentError("angle_deg", alignment.angle_deg, f"at most {top:g}° for a single "
                            "engagement (the mesh takes the whole shaft angle)")
    angles = mesh_angles(0.0, alignment.angle_deg, 1.0, offset_at=0.0,
                         angle_azimuth_deg=alignment.angle_azimuth_deg)
    ob = np.array(angles.centre_b_mm)
    return CouplingGeometry(spec, spec, layout, alignment, 0.0, angles, *_axes(ob),
                            np.zeros(3))


def _axes(ob: NDArray) -> tuple[NDArray, NDArray]:
    """The floating axis through ``O_A`` and ``ob`` and its reference frame (columns
    ``e0, e1, s``: shaft A's frame carried onto it by the smallest turn)."""
    s = ob / np.linalg.norm(ob)
    k = np.cross([0.0, 0.0, 1.0], s)
    sin = float(np.linalg.norm(k))
    if sin == 0.0:
        return s, np.eye(3)
    return s, turn(k / sin, math.atan2(sin, float(s[2])))


def _check_mesh_angles(alignment: ShaftAlignment, angles: MeshAngles) -> None:
    top = MISALIGNMENT_RANGE_DEG[1]
    worst = max(angles.a_deg, angles.b_deg)
    if worst <= top + 1e-9:
        return
    field_, value = (("offset_mm", alignment.offset_mm) if alignment.offset_mm > 0 else
                     ("angle_deg", alignment.angle_deg))
    mesh = "A" if angles.a_deg >= angles.b_deg else "B"
    raise ArgumentError(field_, value, f"puts mesh {mesh} at {worst:.4g}°, beyond the "
                        f"{top:g}° a mesh takes: reduce the offset or angle, or lengthen the "
                        "span")


def _floating_parts(spec_a: CouplingSpec, spec_b: CouplingSpec,
                    layout: CouplingLayout) -> tuple[float, tuple[Annulus, ...]]:
    """The span and the floating member's plain parts, checked against the sleeves."""
    sa, sb = spec_a.sleeve, spec_b.sleeve
    rings = 0.5 * (sa.face_width + sb.face_width)
    if layout.sleeve == "one-piece":
        span = layout.span_mm
        assert span is not None
        _check_span(spec_a, spec_b, span)
        inner = 0.5 * max(sa.major_diameter, sb.major_diameter)
        outer = 0.5 * min(sa.outer_diameter, sb.outer_diameter)
        z0, z1 = 0.5 * sa.face_width, span - 0.5 * sb.face_width
        return span, ((Annulus("tube", inner, outer, z0, z1),) if z1 > z0 else ())
    fod, t = layout.flange_outer_diameter_mm, layout.flange_thickness_mm
    assert fod is not None and t is not None
    for s in (sa, sb):
        if fod <= s.outer_diameter:
            raise ArgumentError("flange_outer_diameter_mm", fod, f"above the sleeve's outside "
                                f"diameter {s.outer_diameter:g} mm")
    fixed = rings + 2 * t
    span = _flanged_span(layout, fixed)
    _check_span(spec_a, spec_b, span)
    z_a, z_b = 0.5 * sa.face_width, span - 0.5 * sb.face_width
    parts = [Annulus("flange A", 0.5 * sa.major_diameter, 0.5 * fod, z_a, z_a + t),
             Annulus("flange B", 0.5 * sb.major_diameter, 0.5 * fod, z_b - t, z_b)]
    if layout.has_spacer:
        parts.insert(1, _spacer(spec_a, spec_b, layout, z_a + t, z_b - t, z_a + t))
    return span, tuple(parts)


def _flanged_span(layout: CouplingLayout, fixed: float) -> float:
    """The span of flanged half-sleeves: the rings and flanges (``fixed``) plus the spacer."""
    span, length = layout.span_mm, layout.spacer_length_mm
    if not layout.has_spacer:
        if span is not None and not is_close(span, fixed):
            raise ArgumentError("span_mm", span, f"{fixed:.6g} mm: flanged half-sleeves "
                                "without a spacer are bolted face to face (a longer span "
                                "needs a spacer)")
        return fixed
    if span is None:
        if length is None:
            raise ArgumentError("span_mm", None, "the span or the spacer length (mm)")
        return fixed + length
    if span <= fixed:
        raise ArgumentError("span_mm", span, f"above {fixed:.6g} mm: the sleeve rings and "
                            "flanges leave no room for the spacer")
    if length is not None and not is_close(length, span - fixed):
        raise ArgumentError("spacer_length_mm", length, f"{span - fixed:.6g} mm: the span less "
                            "the sleeve rings' half face widths and the flanges")
    return span


def _spacer(spec_a: CouplingSpec, spec_b: CouplingSpec, layout: CouplingLayout,
            z0: float, z1: float, reach: float) -> Annulus:
    """The spacer tube from ``z0`` to ``z1``, ``reach`` beyond each hub's midplane."""
    od, bore = layout.spacer_outer_diameter_mm, layout.spacer_inner_diameter_mm
    assert od is not None and bore is not None
    flange_bore = max(spec_a.sleeve.major_diameter, spec_b.sleeve.major_diameter)
    if od <= flange_bore:
        raise ArgumentError("spacer_outer_diameter_mm", od, f"above the flange bore "
                            f"{flange_bore:g} mm (the sleeve's major diameter): the spacer "
                            "bolts against the flange face")
    for spec in (spec_a, spec_b):
        if 0.5 * spec.hub.body.length > reach and bore < _hub_body_diameter(spec):
            raise ArgumentError("spacer_inner_diameter_mm", bore, f"at least "
                                f"{_hub_body_diameter(spec):.6g} mm: hub {spec.name}'s body "
                                "reaches past its flange into the spacer")
    return Annulus("spacer", 0.5 * bore, 0.5 * od, z0, z1)


def _hub_body_diameter(spec: CouplingSpec) -> float:
    """The hub's body diameter beyond the teeth (its root diameter, an upper bound)."""
    return 2.0 * (spec.tooth.pitch_radius - spec.hub.root.dedendum)


def _check_span(spec_a: CouplingSpec, spec_b: CouplingSpec, span: float) -> None:
    need = 0.5 * (max(spec_a.hub.body.length, spec_a.sleeve.face_width)
                  + max(spec_b.hub.body.length, spec_b.sleeve.face_width))
    if span < need:
        raise ArgumentError("span_mm", span, f"at least {need:.6g} mm: the two hubs (their "
                            "body lengths) and sleeve rings (their face widths), each centred "
                            "on its midplane, must not overlap")


__all__ = ["MESHES", "OFFSET_AT", "Annulus", "CouplingGeometry", "coupling_geometry",
           "spec_geometry", "turn"]
