"""Transverse sections: simple, counter-clockwise, within the chordal tolerance of the exact
curves, and refining as the tolerance shrinks."""

import math

import numpy as np
import pytest
import shapely

import gearcoupling as gc
from gearcoupling.geometry.hub import envelope, form_radius, hub_model, round_point, tip_radius
from gearcoupling.geometry.sleeve import sleeve_model


def planes(spec):
    b = spec.hub.face_width / 2
    return [0.0, 0.37 * b, -0.81 * b, b]


@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_sections_are_simple_ccw_polygons(template, part):
    tol = 2e-3 * template.tooth.module
    for z in planes(template):
        poly = gc.transverse_section(template, part, z, tol)
        assert poly.ndim == 2 and poly.shape[1] == 2 and np.all(np.isfinite(poly))
        ring = shapely.LinearRing(poly)
        assert ring.is_simple, f"{template.name} {part} z={z} self-intersects"
        assert shapely.Polygon(poly).is_valid
        x, y = poly.T
        area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
        assert area > 0  # counter-clockwise
        # N-fold symmetry: rotating by one pitch maps vertex i to vertex i + n/N
        n = len(poly) // template.tooth.teeth
        a = 2 * math.pi / template.tooth.teeth
        rot = poly[:n] @ np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
        assert np.max(np.abs(rot - poly[n:2 * n])) < 1e-9 * template.tooth.pitch_radius


@pytest.mark.parametrize("tol", [1e-2, 1e-3, 1e-4])
def test_hub_section_within_tolerance_of_exact_flank(renzo, tol):
    m = hub_model(renzo)
    for z in planes(renzo):
        ring = shapely.LinearRing(gc.transverse_section(renzo, "hub", z, tol))
        r = np.linspace(form_radius(m, z), tip_radius(m, z), 400)
        zz = np.full_like(r, z)
        for flank in ("cw", "ccw"):
            p, _ = gc.hub_flank(renzo, flank, zz, r)
            d = shapely.distance(shapely.points(p[..., :2].reshape(-1, 2)), ring)
            assert np.max(d) <= tol * (1 + 1e-6)
            assert np.max(d) > 0.05 * tol  # the polygon is not needlessly fine
        gamma = np.linspace(m.phi, math.pi / 2, 300)
        fillet, _ = envelope(m, z, *round_point(m, gamma), gamma)
        d = shapely.distance(shapely.points(fillet[:, :2]), ring)
        assert np.max(d) <= tol * (1 + 1e-6)


def test_sleeve_section_within_tolerance_of_exact_flank(renzo):
    sm = sleeve_model(renzo)
    r = np.linspace(sm.r_form, sm.r_fillet, 500)
    for tol in (1e-2, 1e-4):
        ring = shapely.LinearRing(gc.transverse_section(renzo, "sleeve", 0.0, tol))
        p, _ = gc.sleeve_flank(renzo, "ccw", 0.0, r)
        d = shapely.distance(shapely.points(p[:, :2]), ring)
        assert np.max(d) <= tol * (1 + 1e-6)


def test_vertex_count_grows_like_inverse_sqrt_tolerance(renzo):
    n = [len(gc.transverse_section(renzo, "hub", 0.0, t)) for t in (1e-3, 1e-5)]
    ratio = n[1] / n[0]
    assert 6 < ratio < 14  # chordal sampling: ~ sqrt(100) = 10


def test_section_rejects_bad_arguments(renzo):
    with pytest.raises(gc.GeometryError, match="outside the hub face"):
        gc.transverse_section(renzo, "hub", 10.0, 1e-3)
    with pytest.raises(ValueError, match="tolerance_mm"):
        gc.transverse_section(renzo, "hub", 0.0, 0.0)
    with pytest.raises(ValueError, match="part"):
        gc.transverse_section(renzo, "shaft", 0.0, 1e-3)
