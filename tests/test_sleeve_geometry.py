"""Sleeve flank, fillet and chamfer against the involute formula and tangency conditions."""

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.geometry.sleeve import flank_point, sleeve_model


def test_flank_is_the_involute_space_of_design_md(template):
    sm = sleeve_model(template)
    r = np.linspace(sm.r_form, sm.r_fillet, 25)
    z = np.linspace(-sm.half_face, sm.half_face, 25)
    p, n = gc.sleeve_flank(template, "cw", z, r)
    R, phi, s = template.tooth.pitch_radius, template.tooth.pressure_angle, sm.space_width
    half = s / (2 * R) + gc.inv(phi) - gc.inv(np.arccos(sm.r_base / r))
    assert np.max(np.abs(np.arctan2(p[:, 1], p[:, 0]) + half)) < 1e-13
    assert np.max(np.abs(np.hypot(p[:, 0], p[:, 1]) - r)) < 1e-12
    assert np.array_equal(p[:, 2], z) and np.all(n[:, 2] == 0)
    # involute normals are tangent to the base circle and point into the space
    lever = p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0]
    assert np.max(np.abs(np.abs(lever) - sm.r_base)) < 1e-9
    assert np.all(-p[:, 1] * n[:, 0] + p[:, 0] * n[:, 1] > 0)
    pc, _ = gc.sleeve_flank(template, "ccw", z, r)
    assert np.array_equal(pc, p * np.array([1, -1, 1]))


def test_normals_are_normal_to_the_flank(template):
    sm = sleeve_model(template)
    r = np.linspace(sm.r_form, sm.r_fillet, 9)[1:-1]
    d = 1e-6 * sm.R
    _, n = flank_point(sm, r)
    t = flank_point(sm, r + d)[0] - flank_point(sm, r - d)[0]
    t /= np.linalg.norm(t, axis=1)[:, None]
    assert np.max(np.abs(np.einsum("ij,ij->i", t, n))) < 1e-8


def test_root_fillet_is_tangent_to_flank_and_major_circle(template):
    sm = sleeve_model(template)
    if sm.fillet == 0:
        pytest.skip("sharp root")
    c = np.array(sm.fillet_centre)
    p, n = flank_point(sm, sm.r_fillet)
    assert np.linalg.norm(p + sm.fillet * n - c) < 1e-9
    assert abs(np.linalg.norm(c) + sm.fillet - sm.r_major) < 1e-9


def test_aligned_space_at_pitch_is_the_space_width(template):
    sm = sleeve_model(template)
    R = template.tooth.pitch_radius
    assert 2 * R * float(sm.half_angle(R)) == pytest.approx(template.sleeve.space_width, rel=1e-14)
    # chamfer: 45° legs of the given size
    assert sm.r_form - sm.r_minor == pytest.approx(template.sleeve.tip_chamfer)
    leg = sm.r_minor * (-float(sm.half_angle(sm.r_form)) - sm.chamfer_tip_angle)
    assert leg == pytest.approx(template.sleeve.tip_chamfer, rel=1e-12)
    assert math.isfinite(sm.major_angle) and sm.major_angle < 0


def test_off_flank_raises(renzo):
    sm = sleeve_model(renzo)
    with pytest.raises(gc.GeometryError, match="off the sleeve flank"):
        gc.sleeve_flank(renzo, "cw", 0.0, sm.r_minor)
