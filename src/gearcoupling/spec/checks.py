"""Spec checks that need the geometry, and the derived values a designer reads.

:func:`check_spec` runs from ``CouplingSpec.__post_init__``; it turns every geometric
impossibility into a :class:`~gearcoupling.errors.SpecError` naming the field to change
(what is particular to a crown kind comes from its entry of :data:`.kinds.CROWN_KINDS`).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import GeometryError, SpecError
from ..geometry import (
    HubModel,
    SleeveModel,
    SpecLike,
    form_radius,
    hub_flank_model,
    hub_model,
    radius_squared,
    renzo_z0_mm,
    root_radius,
    sleeve_model,
    tip_radius,
)
from .kinds import CROWN_FIELDS, CROWN_KINDS, MAX_END_TANGENT_DEG

_Z_SAMPLES = 17  # planes from the midplane to the face end checked for undercut and points


def _max_curvature(m: HubModel) -> float:
    """The largest curvature of the feed path up to past the face end."""
    s = np.linspace(0.0, m.half_face * 1.5, 400)
    return float(np.max(np.abs(m.path.evaluate(s)[0])))


def check_spec(spec: SpecLike) -> None:
    """Raise :class:`SpecError` if the spec's geometry cannot be built as specified."""
    _check_proportions(spec)
    m = hub_model(spec)
    _check_hob_rounds(spec, m)
    _check_crown(spec, m)
    sm = _checked_sleeve_model(spec)
    r_tip0 = float(tip_radius(m, 0.0))
    _check_radial_overlap(spec, m, sm, r_tip0)
    z = np.linspace(0.0, m.half_face, _Z_SAMPLES)
    _check_undercut(spec, m, z)
    _check_fillet_reach(spec, m, sm, r_tip0)
    pts, r_form = _check_flank_to_tip(spec, m, z)
    r_root_min = float(np.min(root_radius(m, z)))
    rim_limit = 2 * r_root_min - spec.tooth.module
    if spec.hub.body.bore_diameter > rim_limit:
        raise SpecError("hub.body.bore_diameter", spec.hub.body.bore_diameter,
                        f"leaves less than half a module of rim under the tooth roots: must "
                        f"be at most {rim_limit:.6g} mm")
    if not (np.all(np.isfinite(pts)) and np.all(np.isfinite(r_form))):
        raise SpecError("spec", spec.name, "geometry is not finite (please report this spec)")


def _check_proportions(spec: SpecLike) -> None:
    """The hub tooth fits the sleeve space and the sleeve face covers the hub's."""
    hub, sl = spec.hub, spec.sleeve
    if hub.tooth_thickness > sl.space_width:
        raise SpecError("hub.tooth_thickness", hub.tooth_thickness,
                        f"exceeds the sleeve space width {sl.space_width:.6g} mm: the parts "
                        "would interfere when aligned (aligned backlash must be >= 0)")
    if sl.face_width < hub.face_width:
        raise SpecError("sleeve.face_width", sl.face_width,
                        f"must cover the hub face width {hub.face_width:.6g} mm")


def _check_hob_rounds(spec: SpecLike, m: HubModel) -> None:
    """The hob tooth is not pointed above the dedendum and the tip rounds of adjacent flanks
    do not overlap (the round centre within half a circular pitch)."""
    t, hub = spec.tooth, spec.hub
    u_c, _ = m.round_centre
    if u_c <= 0.5 * t.circular_pitch:
        return
    if 0.5 * hub.tooth_thickness + hub.root.dedendum * math.tan(t.pressure_angle) \
            > 0.5 * t.circular_pitch:
        raise SpecError("hub.root.dedendum", hub.root.dedendum,
                        "too deep for the tooth space: the hob tooth is pointed before "
                        "this depth; use a smaller dedendum or a thinner hub tooth")
    raise SpecError("hub.root.fillet_radius", hub.root.fillet_radius,
                    "too large: the hob tip rounds of adjacent flanks overlap; use a "
                    "smaller radius or a thinner hub tooth")


def _check_crown(spec: SpecLike, m: HubModel) -> None:
    """The crown along its path (its kind's check), its curvature against the dedendum and
    the feed-path tangent at the face ends."""
    hub, cr = spec.hub, spec.hub.crowning
    kind = CROWN_KINDS[cr.kind]
    kind.check_path(cr, m.path, m.half_face)
    kmax = _max_curvature(m)
    if kmax * hub.root.dedendum > 0.5:
        raise SpecError(f"{cr.PATH}.{kind.curvature_key(cr, True)}",
                        1.0 / kmax, f"crowning radius must be at least twice the hub dedendum "
                        f"({2 * hub.root.dedendum:.6g} mm)")
    try:
        depths = np.array([-(m.tip_radius - spec.tooth.pitch_radius), hub.root.dedendum])
        e_end = float(np.max(np.abs(m.path.solve_plane(m.half_face, depths)[2])))
    except GeometryError:
        e_end = math.pi / 2
    if abs(math.degrees(e_end)) > MAX_END_TANGENT_DEG:
        key = kind.curvature_key(cr, False)
        raise SpecError(f"{cr.PATH}.{key}", getattr(cr, CROWN_FIELDS[key][0]),
                        f"too small for the face width {hub.face_width:.6g} mm: the feed path "
                        f"turns {math.degrees(e_end):.1f}° by the face end, at most "
                        f"{MAX_END_TANGENT_DEG:g}° allowed")


def _checked_sleeve_model(spec: SpecLike) -> SleeveModel:
    """The sleeve model, its failures and pointed spaces or teeth named by the field to
    change."""
    t, sl = spec.tooth, spec.sleeve
    try:
        sm = sleeve_model(spec)
    except GeometryError as err:
        if sl.minor_diameter < 2 * t.base_radius:
            raise SpecError("sleeve.minor_diameter", sl.minor_diameter,
                            f"must be at least the base diameter {2 * t.base_radius:.6g} mm "
                            "(the involute starts there)") from err
        raise SpecError("sleeve.root_fillet_radius", sl.root_fillet_radius,
                        "does not fit between the flank and the major circle") from err
    if sm.major_angle >= 0:
        raise SpecError("sleeve.major_diameter", sl.major_diameter,
                        "too large: the sleeve space is pointed before the major circle")
    if sm.chamfer_tip_angle <= -math.pi / t.teeth:
        raise SpecError("sleeve.minor_diameter", sl.minor_diameter,
                        "too small: the sleeve teeth are pointed at the minor circle "
                        "(with the tip chamfer)")
    return sm


def _check_radial_overlap(spec: SpecLike, m: HubModel, sm: SleeveModel, r_tip0: float) -> None:
    """In the midplane the hub tips clear the sleeve root, the sleeve tips the hub root, and
    the hub tips reach the sleeve flank (``r_tip0``: hub tip radius there)."""
    hub, sl = spec.hub, spec.sleeve
    if r_tip0 >= sm.r_major:
        raise SpecError("hub.tip.diameter", hub.tip.diameter,
                        f"hub tips reach the sleeve root: must be below the sleeve major "
                        f"diameter {sl.major_diameter:.6g} mm")
    r_root0 = float(root_radius(m, 0.0))
    if sm.r_minor <= r_root0:
        raise SpecError("sleeve.minor_diameter", sl.minor_diameter,
                        f"sleeve tips reach the hub root: must exceed the hub root diameter "
                        f"{2 * r_root0:.6g} mm")
    if r_tip0 <= sm.r_form:
        raise SpecError("hub.tip.diameter", hub.tip.diameter,
                        f"the hub teeth do not reach the sleeve flank, which starts at "
                        f"diameter {2 * sm.r_form:.6g} mm")


def _check_undercut(spec: SpecLike, m: HubModel, z: np.ndarray) -> None:
    """The rack reaches the form depth without undercut in every plane ``z``."""
    hub = spec.hub
    try:
        _, d_r2 = radius_squared(m, z, m.h_form, m.phi)
    except GeometryError as err:
        raise SpecError("hub.crowning.radius", hub.crowning.radius, f"the rack cannot reach "
                        f"the dedendum {hub.root.dedendum:.6g} mm in every plane") from err
    if np.any(d_r2 >= 0):
        zi = float(z[np.argmax(d_r2 >= 0)])
        raise SpecError("hub.root.dedendum", hub.root.dedendum,
                        f"undercut at z = {zi:.4g} mm: the hob's straight flank reaches below "
                        "the base circle, which the generator does not model; use more teeth, "
                        "a larger pressure angle, a smaller dedendum or a larger fillet radius"
                        + (" (or a flatter crown: the undercut is off the midplane)"
                           if zi > 0 else ""))


def _check_fillet_reach(spec: SpecLike, m: HubModel, sm: SleeveModel, r_tip0: float) -> None:
    """In the midplane neither part's tips reach into the other's root fillets."""
    hub, sl = spec.hub, spec.sleeve
    r_form0 = float(form_radius(m, 0.0))
    if sm.r_minor < r_form0:
        raise SpecError("sleeve.minor_diameter", sl.minor_diameter,
                        f"sleeve tips reach into the hub root fillets: must be at least the hub "
                        f"form diameter {2 * r_form0:.6g} mm, so that all contact is on the "
                        f"involute flanks")
    if r_tip0 > sm.r_fillet:
        raise SpecError("hub.tip.diameter", hub.tip.diameter,
                        f"hub tips reach into the sleeve root fillets: must be at most "
                        f"{2 * sm.r_fillet:.6g} mm, where the sleeve fillets start")


def _check_flank_to_tip(spec: SpecLike, m: HubModel,
                        z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """In every plane ``z`` a hub flank is left above the form radius and generated up to
    the tip without a point; returns the flank points ``(n, 3)`` and form radii ``(nz,)``."""
    tip = spec.hub.tip
    r_form = form_radius(m, z)
    r_tip = tip_radius(m, z)
    if np.any(r_form >= r_tip):
        zi = float(z[np.argmax(r_form >= r_tip)])
        raise SpecError("hub.tip.diameter", tip.diameter,
                        f"no flank left at z = {zi:.4g} mm: the tip falls below the form "
                        "radius (crown drop too large for the tooth depth"
                        + ("; a spherical tip drops faster than a crown of radius above R: "
                           "use a larger tip diameter, tip kind cylinder or a smaller face "
                           "width)" if tip.kind == "sphere" else ")"))
    try:
        pts, _, _ = hub_flank_model(m, "cw", z, r_tip, check=False)
    except GeometryError as err:
        raise SpecError("hub.tip.diameter", tip.diameter,
                        "the flank cannot be generated up to the tip") from err
    if np.any(pts[:, 1] >= 0):
        zi = float(z[np.argmax(pts[:, 1] >= 0)])
        raise SpecError("hub.tip.diameter", tip.diameter,
                        f"hub teeth are pointed at z = {zi:.4g} mm: lower the tip or the crown")
    return pts, r_form


def derived_values(spec: SpecLike) -> dict[str, float]:
    """Derived sizes (mm, degrees) a designer checks, keyed with their unit.

    Includes Renzo's maximum separation ``z0 = R_c cot(phi) tan^2(i) / 2`` (eq. 4) at the
    design misalignment, with ``R_c`` the midplane crowning radius.
    """
    t, hub = spec.tooth, spec.hub
    m = hub_model(spec)
    sm = sleeve_model(spec)
    R = t.pitch_radius
    kappa0 = float(m.path.evaluate(0.0)[0])
    rc = math.inf if kappa0 == 0 else 1.0 / kappa0
    i = spec.design_misalignment
    z0 = renzo_z0_mm(rc, i, t.pressure_angle)
    backlash = spec.sleeve.space_width - hub.tooth_thickness
    zend = m.half_face
    return {
        "module_mm": t.module,
        "pitch_radius_mm": R,
        "base_radius_mm": t.base_radius,
        "circular_pitch_mm": t.circular_pitch,
        "base_pitch_mm": t.base_pitch,
        "crowning_radius_midplane_mm": rc,
        "crown_drop_at_face_end_mm": float(m.path.drop(zend)),
        "hub_tip_radius_midplane_mm": float(tip_radius(m, 0.0)),
        "hub_tip_radius_face_end_mm": float(tip_radius(m, zend)),
        "hub_root_radius_midplane_mm": float(root_radius(m, 0.0)),
        "hub_root_radius_face_end_mm": float(root_radius(m, zend)),
        "hub_form_radius_midplane_mm": float(form_radius(m, 0.0)),
        "sleeve_minor_radius_mm": sm.r_minor,
        "sleeve_major_radius_mm": sm.r_major,
        "sleeve_form_radius_mm": sm.r_form,
        "sleeve_fillet_start_radius_mm": sm.r_fillet,
        "aligned_backlash_mm": backlash,
        "aligned_backlash_deg": math.degrees(backlash / R),
        "design_misalignment_deg": math.degrees(i),
        "renzo_z0_mm": z0,
        "renzo_z0_circumferential_mm": z0 / math.cos(t.pressure_angle),
    }
