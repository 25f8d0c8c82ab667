"""The clearance kernel against exact brute force, the aligned case and the pose algebra."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcoupling.geometry.hub import hub_flank_model, hub_model
from gearcoupling.geometry.sleeve import sleeve_model
from gearcoupling.spec import load_spec
from gearcoupling.sweep import sweep
from gearcoupling.sweep.clearance import minimise
from gearcoupling.sweep.flank_table import exact_alpha, flank_table
from gearcoupling.sweep.pose import hub_to_sleeve, map_polar, rot_z


@pytest.fixture(scope="module")
def renzo():
    return load_spec("renzo-1967")


def exact_gap(spec, mis, theta, z, r, normal):
    """Gap of the exact hub flank point (z, r) of tooth 0 to space 0 (independent path)."""
    m, sm = hub_model(spec), sleeve_model(spec)
    pts, _, _ = hub_flank_model(m, "cw", z, r, check=False)
    q = pts @ hub_to_sleeve(mis, theta).T
    rq = np.hypot(q[..., 0], q[..., 1])
    a = np.arctan2(q[..., 1], q[..., 0])
    d = a + sm.half_angle(rq)
    return (sm.r_base if normal else rq) * d, rq, q[..., 2]


def brute_force(spec, mis, theta, normal, nz=1201, nt=201):
    """Dense exact grid; in each plane t runs from the sleeve tip edge (solved by bisection
    on the exact flank) to the hub tip."""
    m, sm = hub_model(spec), sleeve_model(spec)
    z = np.linspace(-m.half_face, m.half_face, nz)

    def rq_at(t):
        r, a = exact_alpha(m, z, t)
        return exact_gap_from_polar(spec, mis, theta, r, a, z)[1]

    lo, hi = np.zeros(nz), np.ones(nz)
    below = rq_at(lo) < sm.r_form
    for _ in range(45):
        mid = 0.5 * (lo + hi)
        up = rq_at(mid) >= sm.r_form
        hi, lo = np.where(up, mid, hi), np.where(up, lo, mid)
    t0 = np.where(below, hi, 0.0)
    t = t0[:, None] + np.linspace(0.0, 1.0, nt)[None, :] * (1.0 - t0[:, None])
    zz = np.broadcast_to(z[:, None], t.shape)
    r, a = exact_alpha(m, zz, t)
    g, rq, zq = exact_gap_from_polar(spec, mis, theta, r, a, zz, normal)
    ok = (rq >= sm.r_form - 1e-9) & (np.abs(zq) <= sm.half_face)
    return float(np.min(np.where(ok, g, np.inf)))


def exact_gap_from_polar(spec, mis, theta, r, a, z, normal=False):
    sm = sleeve_model(spec)
    p = np.stack(np.broadcast_arrays(r * np.cos(a), r * np.sin(a), z), axis=-1)
    q = p @ hub_to_sleeve(mis, theta).T
    rq = np.hypot(q[..., 0], q[..., 1])
    d = np.arctan2(q[..., 1], q[..., 0]) + sm.half_angle(rq)
    return (sm.r_base if normal else rq) * d, rq, q[..., 2]


@pytest.mark.parametrize("theta_deg", [0.0, 8.0, 47.0, 133.0, 300.0])
@pytest.mark.parametrize("normal", [False, True])
def test_minimum_matches_brute_force(renzo, theta_deg, normal):
    """Kernel minimum is attained on the exact flank and no dense exact grid point beats it
    by more than 1e-9 mm; the dense grid (1201 x 201) is within 1e-6 mm of it."""
    mis = math.radians(1.0)
    th = math.radians(theta_deg)
    res = minimise(flank_table(renzo), sleeve_model(renzo), mis, [th],
                   pitch_radius=renzo.tooth.pitch_radius)["normal" if normal else "circumferential"]
    value, z, r = float(res.value_mm[0]), float(res.z_mm[0]), float(res.r_mm[0])
    attained, _, _ = exact_gap(renzo, mis, th, z, r, normal)
    assert abs(float(attained) - value) < 1e-8
    dense = brute_force(renzo, mis, th, normal)
    assert value <= dense + 1e-9
    assert dense - value < 1e-6, dense - value


def test_aligned_clearances_equal_backlash_share(renzo):
    """Aligned, the midplane profile is the sleeve's involute offset by (s - t)/2 at R:
    pitch clearance (s - t)/2, normal r_b (s - t)/(2R), backlash s - t."""
    res = sweep(renzo, 0.0, np.arange(0.0, 360.0, 30.0))
    s, t = renzo.sleeve.space_width, renzo.hub.tooth_thickness
    R, rb = renzo.tooth.pitch_radius, renzo.tooth.base_radius
    assert np.allclose(res.pitch_clearance_mm, 0.5 * (s - t), atol=1e-9)
    assert np.allclose(res.normal_clearance_mm, rb * 0.5 * (s - t) / R, atol=1e-9)
    assert np.allclose(res.backlash_mm, s - t, atol=1e-9)
    # circumferential: the same angle at the lowest radius that faces the sleeve flank
    r_low = max(float(res.contact_r_mm.min()), sleeve_model(renzo).r_form)
    assert np.all(res.clearance_mm <= 0.5 * (s - t) * r_low / R + 1e-9)


def test_reduced_pose_equals_full_pose(renzo):
    """Tooth k at rotation psi against space k equals tooth 0 at theta_k against space 0."""
    rng = np.random.default_rng(1)
    N = renzo.tooth.teeth
    mis = math.radians(3.0)
    for _ in range(5):
        k = int(rng.integers(N))
        psi = float(rng.uniform(0, 2 * np.pi))
        r, a, z = 62.0, -0.02, float(rng.uniform(-6, 6))
        p0 = np.array([r * math.cos(a), r * math.sin(a), z])
        pk = rot_z(2 * np.pi * k / N) @ p0
        q = hub_to_sleeve(mis, psi) @ pk
        a_full = math.atan2(q[1], q[0]) - 2 * np.pi * k / N
        a_full = (a_full + np.pi) % (2 * np.pi) - np.pi
        rq, aq, zq = map_polar(r, a, z, mis, psi + 2 * np.pi * k / N)
        assert abs(a_full - float(aq)) < 1e-12
        assert abs(math.hypot(q[0], q[1]) - float(rq)) < 1e-10
        assert abs(q[2] - float(zq)) < 1e-10


def test_ccw_flank_against_exact_ccw_geometry(renzo):
    """The ccw values (from the mirror theta -> pi - theta) equal the exact ccw hub flank
    against the sleeve's ccw flank at the reported contact point."""
    res = sweep(renzo, 2.0, [0.0, 17.0])
    m, sm = hub_model(renzo), sleeve_model(renzo)
    N = renzo.tooth.teeth
    for k in (0, 3, 20, 41):
        for j, psi in enumerate(np.radians([0.0, 17.0])):
            z, r = res.contact_z_mm[1, k, j], res.contact_r_mm[1, k, j]
            p, _, _ = hub_flank_model(m, "ccw", z, r, check=False)
            q = hub_to_sleeve(math.radians(2.0), psi) @ (rot_z(2 * np.pi * k / N) @ p)
            rq = math.hypot(q[0], q[1])
            a = math.atan2(q[1], q[0]) - 2 * np.pi * k / N
            a = (a + np.pi) % (2 * np.pi) - np.pi
            gap = sm.r_base * (float(sm.half_angle(rq)) - a)
            assert abs(gap - res.normal_clearance_mm[1, k, j]) < 1e-8


def test_periodic_and_per_tooth_paths_agree(renzo):
    angles = np.array([0.0, 13.0, 101.0])
    a = sweep(renzo, 1.5, angles)
    b = sweep(renzo, 1.5, angles, periodic=False)
    for name in ("clearance_mm", "normal_clearance_mm", "pitch_clearance_mm", "contact_z_mm"):
        assert np.allclose(getattr(a, name), getattr(b, name), atol=1e-9), name


def test_flank_table_error_measured_small(renzo):
    table = flank_table(renzo)
    assert table.max_error_mm < 1e-7
    # independent spot check away from nodes and cell centres
    m = hub_model(renzo)
    z = np.array([-5.9, -1.234, 0.3, 4.4])
    t = np.array([0.03, 0.41, 0.77, 0.99])
    r_ex, a_ex = exact_alpha(m, z, t)
    r_in, a_in = table.evaluate(z, t)
    assert np.max(np.abs(r_ex * a_ex - r_in * a_in)) < 1e-7
