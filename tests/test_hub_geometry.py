"""Hub flank kernels against theory (Renzo eq. 1, spur involute, base pitch) and against an
independent brute-force envelope of the hob's cone."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import gearcoupling as gc
from gearcoupling.geometry.hub import form_radius, hub_flank_model, hub_model, tip_radius

from conftest import flank_grid


def polar(p):
    return np.arctan2(p[..., 1], p[..., 0])


def test_spur_involute_when_not_crowned(template):
    spec = template.replace(**{"hub.crowning.kind": "none", "hub.crowning.radius": math.inf})
    m = hub_model(spec)
    z, r = flank_grid(m)
    pts, nrm = gc.hub_flank(spec, "cw", z, r)
    rb = m.R * math.cos(m.phi)
    ang = -(m.thickness / (2 * m.R) + gc.inv(m.phi) - gc.inv(np.arccos(rb / r)))
    assert np.max(np.abs(pts[..., 0] - r * np.cos(ang))) < 1e-9
    assert np.max(np.abs(pts[..., 1] - r * np.sin(ang))) < 1e-9
    assert np.max(np.abs(pts[..., 2] - z)) < 1e-12
    # involute normal: tangent to the base circle, no axial component
    assert np.max(np.abs(nrm[..., 2])) < 1e-12
    lever = np.abs(pts[..., 0] * nrm[..., 1] - pts[..., 1] * nrm[..., 0])
    assert np.max(np.abs(lever - rb)) < 1e-9


@pytest.mark.parametrize("rc_in", [2.5, 1.2, 6.0])
def test_renzo_eq1_transverse_pressure_angle_at_pitch_line(rc_in):
    spec = gc.load_spec("renzo-1967", **{"hub.crowning.radius": rc_in})
    m = hub_model(spec)
    z = np.linspace(-m.half_face, m.half_face, 21)
    pts, nrm = gc.hub_flank(spec, "cw", z, m.R)
    radial = pts[:, :2] / np.linalg.norm(pts[:, :2], axis=1)[:, None]
    tangential = np.stack([-radial[:, 1], radial[:, 0]], axis=-1)
    phi_t = np.arctan2(np.einsum("ij,ij->i", nrm[:, :2], radial),
                       np.abs(np.einsum("ij,ij->i", nrm[:, :2], tangential)))
    e = np.arctan(z / (rc_in * 25.4))  # tan e = z / R_c on the pitch line
    expected = np.arctan(math.tan(m.phi) * np.cos(e))
    assert np.max(np.abs(phi_t - expected)) < 1e-9
    assert np.max(np.abs(np.linalg.norm(pts[:, :2], axis=1) - m.R)) < 1e-9


def test_same_side_flanks_keep_base_pitch(template):
    m = hub_model(template)
    pb = template.tooth.base_pitch
    z, r = flank_grid(m, nz=11, nr=9, margin=0.05)
    pts, nrm = gc.hub_flank(template, "cw", z, r)
    q = pts + pb * nrm  # lands on the cw flank of tooth N-1
    a = 2 * math.pi / m.teeth
    rot = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    q0, n0 = q @ rot.T, nrm @ rot.T
    rq = np.hypot(q0[..., 0], q0[..., 1])
    inside = (np.abs(q0[..., 2]) < m.half_face) & (rq < tip_radius(m, q0[..., 2])) & (
        rq > form_radius(m, q0[..., 2]))
    assert inside.sum() > 20
    back, nback, _ = hub_flank_model(m, "cw", q0[..., 2][inside], rq[inside])
    assert np.max(np.linalg.norm(back - q0[inside], axis=-1)) < 1e-9
    assert np.max(np.linalg.norm(nback - n0[inside], axis=-1)) < 1e-9


@pytest.mark.parametrize("gen", ["enveloped", "revolved"])
def test_normals_are_unit_and_normal_to_the_surface(gen, template):
    spec = template.replace(**{"hub.crowning.generation": gen})
    m = hub_model(spec)
    z, r = flank_grid(m, nz=5, nr=5, margin=0.1)
    d = 1e-5 * m.R
    p, n = gc.hub_flank(spec, "ccw", z, r)
    tz = (gc.hub_flank(spec, "ccw", z + d, r)[0] - gc.hub_flank(spec, "ccw", z - d, r)[0])
    tr = (gc.hub_flank(spec, "ccw", z, r + d)[0] - gc.hub_flank(spec, "ccw", z, r - d)[0])
    assert np.allclose(np.linalg.norm(n, axis=-1), 1, atol=1e-13)
    for t in (tz, tr):
        t = t / np.linalg.norm(t, axis=-1)[..., None]
        assert np.max(np.abs(np.einsum("...i,...i", t, n))) < 1e-7
    # outward: the ccw flank faces increasing polar angle
    tang = np.stack([-p[..., 1], p[..., 0]], axis=-1)
    assert np.all(np.einsum("...i,...i", tang, n[..., :2]) > 0)


def test_cw_and_ccw_mirror(template):
    m = hub_model(template)
    z, r = flank_grid(m)
    pc, nc = gc.hub_flank(template, "cw", z, r)
    pa, na = gc.hub_flank(template, "ccw", z, r)
    mirror = np.array([1.0, -1.0, 1.0])
    assert np.array_equal(pa, pc * mirror) and np.array_equal(na, nc * mirror)
    assert np.all(polar(pc) < 0)


def brute_force_polar(spec, z, r):
    """Hub cw-flank polar angle at (z, r) as the boundary of all rack positions.

    The circular-crown rack flank is the cone ``u = t/2 + (R_c - rho) tan(phi)`` with
    ``rho`` the distance from the crowning axis; for every rack shift ``sigma`` the rack
    (turned back by the roll ``sigma / R``) covers polar angles up to ``alpha(sigma)`` at
    radius ``r``; the hub flank is the largest of them. No code shared with the kernels.
    """
    R, phi = spec.tooth.pitch_radius, spec.tooth.pressure_angle
    rc, t = spec.hub.crowning.radius, spec.hub.tooth_thickness

    def u_of(v):
        return t / 2 + (rc - math.hypot(v - R + rc, z)) * math.tan(phi)

    def alpha(sigma):
        v = brentq(lambda v: math.hypot(v, u_of(v) + sigma) - r, 0.5 * r, r, xtol=1e-15)
        return math.atan2(-(u_of(v) + sigma), v) + sigma / R

    grid = np.linspace(-0.3 * R, 0.3 * R, 601)
    vals = [alpha(s) for s in grid]
    k = int(np.argmax(vals))
    res = minimize_scalar(lambda s: -alpha(s), bounds=(grid[k - 1], grid[k + 1]),
                          method="bounded", options={"xatol": 1e-12})
    return -res.fun


@pytest.mark.parametrize("z, r", [(0.0, 61.6), (2.0, 63.5), (-4.5, 65.0), (6.2, 62.3)])
def test_envelope_matches_brute_force_generation(renzo, z, r):
    p, _ = gc.hub_flank(renzo, "cw", z, r)
    assert r * abs(polar(p) - brute_force_polar(renzo, z, r)) < 1e-9


def test_enveloped_and_revolved_agree_in_midplane_and_differ_like_renzo_fig7(renzo):
    rev = renzo.replace(**{"hub.crowning.generation": "revolved"})
    m, mr = hub_model(renzo), hub_model(rev)
    r = np.linspace(form_radius(m, 0.0) + 0.01, m.tip_radius - 0.01, 9)
    a, _ = gc.hub_flank(renzo, "cw", 0.0, r)
    b, _ = gc.hub_flank(rev, "cw", 0.0, r)
    assert np.max(np.abs(a - b)) < 1e-12
    # away from the midplane: revolved keeps phi in planes g (Fig. 7: "too large"),
    # the hob-generated flank follows eq. (1)
    z = np.linspace(0.3, 1.0, 5) * m.half_face
    pe, ne = gc.hub_flank(renzo, "cw", z, m.R)
    pr, nr_ = gc.hub_flank(rev, "cw", z, m.R)

    def transverse(p, n):
        rad = p[:, :2] / np.linalg.norm(p[:, :2], axis=1)[:, None]
        return np.arctan2(np.einsum("ij,ij->i", n[:, :2], rad),
                          np.abs(n[:, 0] * rad[:, 1] - n[:, 1] * rad[:, 0]))

    assert np.max(np.abs(transverse(pr, nr_) - m.phi)) < 1e-9
    assert np.all(transverse(pe, ne) < transverse(pr, nr_) - 1e-5)
    # revolved: the midplane profile moved in by the crown drop -> thinner by 2 delta tan(phi)
    delta = mr.path.drop(z)
    thick = 2 * m.R * np.abs(polar(pr))
    assert np.max(np.abs(thick - (m.thickness - 2 * delta * math.tan(m.phi)))) < 1e-9


def test_off_flank_raises(renzo):
    m = hub_model(renzo)
    with pytest.raises(gc.GeometryError, match="off the cw flank"):
        gc.hub_flank(renzo, "cw", m.half_face * 1.01, m.R)
    with pytest.raises(gc.GeometryError):
        gc.hub_flank(renzo, "cw", 0.0, m.tip_radius + 0.01)
    with pytest.raises(gc.GeometryError):
        gc.hub_flank(renzo, "cw", 0.0, float(form_radius(m, 0.0)) - 0.01)
    with pytest.raises(ValueError, match="flank"):
        gc.hub_flank(renzo, "left", 0.0, m.R)


def test_straight_limit_is_continuous(renzo):
    big = renzo.replace(**{"hub.crowning.radius": 1e9})
    none = renzo.replace(**{"hub.crowning.kind": "none", "hub.crowning.radius": math.inf})
    z, r = flank_grid(hub_model(none))
    a, na = gc.hub_flank(big, "cw", z, r)
    b, nb = gc.hub_flank(none, "cw", z, r)
    assert np.max(np.abs(a - b)) < 1e-6 and np.max(np.abs(na - nb)) < 1e-7
