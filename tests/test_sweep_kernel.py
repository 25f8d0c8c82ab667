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


def _plane_min(spec, mis, theta, z, normal, nt):
    """Exact minimum over a dense t grid in each plane ``z`` (array); the active interval's
    ends (sleeve tip edge, sleeve face ends) solved by bisection on the exact flank."""
    m, sm = hub_model(spec), sleeve_model(spec)
    z = np.atleast_1d(np.asarray(z, dtype=float))

    def mapped(t):
        r, a = exact_alpha(m, z, t)
        return exact_gap_from_polar(spec, mis, theta, r, a, z, normal)

    def crossing(fun, f0, f1):
        """Bisection for fun(t) = 0 on [0, 1] per plane (where f0, f1 differ in sign)."""
        lo, hi = np.zeros(z.shape), np.ones(z.shape)
        for _ in range(34):
            mid = 0.5 * (lo + hi)
            same = np.sign(fun(mid)) == np.sign(f0)
            lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
        return 0.5 * (lo + hi)

    # each constraint is monotone in t (rq grows with t, zq moves one way): its feasible
    # part is [c, 1] or [0, c]; the active interval is their intersection
    zero, one = np.zeros(z.shape), np.ones(z.shape)
    _, rq0, zq0 = mapped(zero)
    _, rq1, zq1 = mapped(one)
    lo_in, hi_in = zero.copy(), one.copy()
    empty = rq1 < sm.r_form
    cut = (rq0 < sm.r_form) & ~empty
    tc = crossing(lambda t: mapped(t)[1] - sm.r_form, rq0 - sm.r_form, rq1 - sm.r_form)
    lo_in = np.where(cut, tc, lo_in)
    for sign in (1.0, -1.0):
        v0, v1 = sign * zq0 - sm.half_face, sign * zq1 - sm.half_face
        empty |= (v0 > 0) & (v1 > 0)
        tf = crossing(lambda t, sign=sign: sign * mapped(t)[2] - sm.half_face, v0, v1)
        lo_in = np.where((v0 > 0) & (v1 <= 0), np.maximum(lo_in, tf), lo_in)
        hi_in = np.where((v1 > 0) & (v0 <= 0), np.minimum(hi_in, tf), hi_in)
    any_ok = ~empty & (lo_in <= hi_in)
    t = lo_in[:, None] + np.linspace(0.0, 1.0, nt)[None, :] * (hi_in - lo_in)[:, None]
    zz = np.broadcast_to(z[:, None], t.shape)
    r, a = exact_alpha(m, zz, t)
    g, rq, zq = exact_gap_from_polar(spec, mis, theta, r, a, zz, normal)
    ok = (rq >= sm.r_form - 1e-9) & (np.abs(zq) <= sm.half_face + 1e-9)
    g = np.where(ok, g, np.inf)
    j = np.argmin(g, axis=1)
    rows = np.arange(z.size)
    best = g[rows, j]
    # parabolic vertex through the best grid point and its neighbours, evaluated exactly
    jm, jp = np.clip(j - 1, 0, nt - 1), np.clip(j + 1, 0, nt - 1)
    y0, y1, y2 = g[rows, jm], best, g[rows, jp]
    h = (hi_in - lo_in) / (nt - 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        curv = y0 - 2 * y1 + y2
        tv = t[rows, j] + 0.5 * h * (y0 - y2) / curv
        inside = (j > 0) & (j < nt - 1) & np.isfinite(tv) & (curv > 0)
    tv = np.where(inside, np.clip(tv, lo_in, hi_in), t[rows, j])
    rv, av = exact_alpha(m, z, tv)
    gv, rqv, zqv = exact_gap_from_polar(spec, mis, theta, rv, av, z, normal)
    okv = inside & (rqv >= sm.r_form - 1e-9) & (np.abs(zqv) <= sm.half_face + 1e-9)
    best = np.where(okv, np.minimum(best, gv), best)
    return np.where(any_ok, best, np.inf)


def brute_force(spec, mis, theta, normal, nz=401, nt=121):
    """Dense exact grid (``nz`` planes x ``nt`` heights between the exact ends of the
    active interval, with a parabolic step in ``t``), then golden-section search over
    ``z`` around the best plane to resolve corners of the active region."""
    m = hub_model(spec)
    z = np.linspace(-m.half_face, m.half_face, nz)
    g = _plane_min(spec, mis, theta, z, normal, nt)
    j = int(np.argmin(g))
    a, b = z[max(j - 1, 0)], z[min(j + 1, nz - 1)]
    best = float(g[j])
    ratio = (math.sqrt(5.0) - 1.0) / 2.0  # golden section: copes with inf past a corner
    x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
    f1, f2 = (float(_plane_min(spec, mis, theta, x, normal, nt)[0]) for x in (x1, x2))
    while b - a > 1e-6:  # value error below slope * 1e-6 mm
        if f1 <= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - ratio * (b - a)
            f1 = float(_plane_min(spec, mis, theta, x1, normal, nt)[0])
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + ratio * (b - a)
            f2 = float(_plane_min(spec, mis, theta, x2, normal, nt)[0])
    return min(best, f1, f2)


def exact_gap_from_polar(spec, mis, theta, r, a, z, normal=False):
    sm = sleeve_model(spec)
    p = np.stack(np.broadcast_arrays(r * np.cos(a), r * np.sin(a), z), axis=-1)
    q = p @ hub_to_sleeve(mis, theta).T
    rq = np.hypot(q[..., 0], q[..., 1])
    d = np.arctan2(q[..., 1], q[..., 0]) + sm.half_angle(rq)
    return (sm.r_base if normal else rq) * d, rq, q[..., 2]


@pytest.mark.parametrize("theta_deg", [8.0, 165.4])
@pytest.mark.parametrize("normal", [False, True])
def test_minimum_matches_brute_force(renzo, theta_deg, normal):
    """Kernel minimum is attained on the exact flank and the brute-force reference (dense
    exact grid, polished) neither beats it nor lies more than 1e-6 mm above it."""
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


@pytest.mark.parametrize("name, deg, theta_deg, normal", [
    ("industrial-m2", 0.75, 12.0, True),
    ("industrial-m2", 3.0, 200.0, False),
    ("mill-spindle", 1.0, 95.0, True),
    ("renzo-1967", 5.0, 40.0, False),
    ("renzo-1967", 0.0, 0.0, True),
])
def test_other_templates_match_brute_force(name, deg, theta_deg, normal):
    """Same check on other templates, larger angles (the hub end leaves the sleeve face at
    5° on renzo-1967) and a vari-crown path; tolerance 1e-6 mm plus the flank table's
    measured interpolation error."""
    spec = load_spec(name)
    sm = sleeve_model(spec)
    mis, th = math.radians(deg), math.radians(theta_deg)
    table = flank_table(spec)
    res = minimise(table, sm, mis, [th],
                   pitch_radius=spec.tooth.pitch_radius)["normal" if normal else "circumferential"]
    value = float(res.value_mm[0])
    attained, rq, zq = exact_gap(spec, mis, th, float(res.z_mm[0]), float(res.r_mm[0]), normal)
    assert abs(float(attained) - value) < 1e-8 + 2 * table.max_error_mm
    assert rq >= sm.r_form - 1e-7 and abs(zq) <= sm.half_face + 1e-7  # a real, facing point
    dense = brute_force(spec, mis, th, normal)
    assert value <= dense + 1e-9 + 2 * table.max_error_mm
    assert dense - value < 1e-6 + 2 * table.max_error_mm, dense - value
