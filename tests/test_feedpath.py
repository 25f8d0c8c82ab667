"""Feed paths against closed forms and independent numerical integration."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from gearcoupling import load_spec
from gearcoupling.geometry.feedpath import FeedPath, drop_table_to_curvature, feed_path
from gearcoupling.spec import Crowning

R = 63.5


def integrate(path_kappa, s, kinks=()):
    """Independent position by scipy.quad of (-sin e, cos e) with e = ∫ kappa."""
    pts = [k for k in kinks if k < s] or None

    def e(x):
        return quad(path_kappa, 0, x, epsabs=1e-14, epsrel=1e-14,
                    points=[k for k in kinks if k < x] or None)[0]

    qv = R - quad(lambda x: math.sin(e(x)), 0, s, epsabs=1e-13, epsrel=1e-13, points=pts)[0]
    qz = quad(lambda x: math.cos(e(x)), 0, s, epsabs=1e-13, epsrel=1e-13, points=pts)[0]
    return e(s), qv, qz


def test_circular_is_a_circle_about_C():
    rc = 50.0
    p = feed_path(Crowning("circular", radius=rc), R, 20.0)
    s = np.linspace(-30, 30, 41)
    kap, e, qv, qz = p.evaluate(s)
    assert np.allclose(kap, 1 / rc, rtol=0, atol=1e-15)
    assert np.allclose(e, s / rc, atol=1e-15)
    assert np.allclose(np.hypot(qv - (R - rc), qz), rc, atol=1e-12)
    assert np.allclose(np.arctan2(qz, qv - (R - rc)), e, atol=1e-14)


def test_straight_limit_is_continuous():
    s = np.linspace(-10, 10, 21)
    big = feed_path(Crowning("circular", radius=1e12), R, 20).evaluate(s)
    none = feed_path(Crowning("none"), R, 20).evaluate(s)
    for a, b in zip(big, none, strict=True):
        assert np.allclose(a, b, atol=1e-9)
    assert np.all(none[2] == R) and np.allclose(none[3], s)


@pytest.mark.parametrize("s", [0.7, 4.0, 9.9, 14.0])
def test_vari_crown_matches_quadrature(s):
    c = Crowning("vari_crown", radius=40.0, end_radius=90.0)
    b = 20.0
    p = feed_path(c, R, b)
    se = b / 2

    def kappa(x):
        return 1 / 40 + (1 / 90 - 1 / 40) * (min(x, se) / se) ** 2

    e, qv, qz = integrate(kappa, s, kinks=(se,))
    _, e1, qv1, qz1 = p.evaluate(s)
    assert e1 == pytest.approx(e, abs=1e-12)
    assert qv1 == pytest.approx(qv, abs=1e-10)
    assert qz1 == pytest.approx(qz, abs=1e-10)
    # curvature is largest in the midplane and smaller toward the ends
    k = p.evaluate(np.linspace(0, se, 20))[0]
    assert np.all(np.diff(k) < 0)


def test_end_round_is_tangent_continuous_and_sharper():
    c = Crowning("end_round", radius=60.0, end_radius=15.0, start_z=5.0)
    p = feed_path(c, R, 20.0)
    s0 = 60 * math.asin(5 / 60)
    kap, e, qv, qz = p.evaluate(np.array([s0 - 1e-9, s0 + 1e-9]))
    assert qz[0] == pytest.approx(5.0, abs=1e-8)
    assert abs(e[1] - e[0]) < 1e-9 and abs(qv[1] - qv[0]) < 1e-8
    assert kap[0] == pytest.approx(1 / 60) and kap[1] == pytest.approx(1 / 15)


def test_table_of_constant_curvature_is_circular():
    s = (0.0, 3.0, 7.0, 12.0, 20.0)
    table = feed_path(Crowning("table", table_s=s, table_kappa=(1 / 45,) * 5), R, 30)
    circ = feed_path(Crowning("circular", radius=45.0), R, 30)
    x = np.linspace(-25, 25, 51)
    for a, b in zip(table.evaluate(x), circ.evaluate(x), strict=True):
        assert np.allclose(a, b, atol=1e-12)


def test_drop_table_reproduces_the_drop():
    rc = 60.0
    z = np.linspace(0, 12, 7)
    drop = rc - np.sqrt(rc**2 - z**2)
    c = Crowning("table", table_z=tuple(z), table_drop=tuple(drop))
    p = feed_path(c, R, 24)
    zz = np.linspace(-12, 12, 25)
    assert np.allclose(p.drop(zz), rc - np.sqrt(rc**2 - zz**2), atol=2e-5)
    s, kap = drop_table_to_curvature(z, drop)
    assert np.all(np.isfinite(kap)) and s[0] == 0 and np.all(np.diff(s) > 0)


def test_solve_plane_puts_rack_points_in_the_plane(renzo):
    m = feed_path(renzo.hub.crowning, renzo.tooth.pitch_radius, renzo.hub.face_width)
    z = np.linspace(-6, 6, 13)[:, None]
    h = np.linspace(-3, 3, 7)[None, :]
    _, _, e, _, qz = m.solve_plane(z, h)
    assert np.allclose(qz - h * np.sin(e), z, atol=1e-12)


def test_feedpath_generic_segments_join_continuously():
    p = FeedPath(R, [(5.0, 1 / 30), (5.0, 0.0), (math.inf, 1 / 10)])
    x = np.array([5 - 1e-10, 5 + 1e-10, 10 - 1e-10, 10 + 1e-10])
    _, e, qv, qz = p.evaluate(x)
    assert abs(e[1] - e[0]) < 1e-9 and abs(e[3] - e[2]) < 1e-9
    assert abs(qz[1] - qz[0]) < 1e-9 and abs(qv[3] - qv[2]) < 1e-9
    assert load_spec("renzo-1967-vari-crown").hub.crowning.kind == "vari_crown"
