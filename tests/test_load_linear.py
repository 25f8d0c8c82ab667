"""Renzo's linear load-sharing model: exact kernel, equilibrium, sharing, signs."""

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import sweep
from gearcoupling.errors import SpecError
from gearcoupling.loading import load_from_sweep
from gearcoupling.loading.kernels.windup import solve_windup


def brute_windup(g, K, T):
    """Independent check: bisection on sum K max(0, x - g) = T, one column."""
    lo, hi = np.min(g), np.min(g) + T / np.min(K) + 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sum(K * np.maximum(mid - g, 0)) < T else (lo, mid)
    return 0.5 * (lo + hi)


def test_kernel_matches_bisection_and_balances_torque():
    rng = np.random.default_rng(1)
    g = rng.uniform(0, 1e-3, (37, 9))
    g[3, 2] = np.inf  # a tooth that never touches
    K = rng.uniform(1e6, 5e6, (37, 9))
    for T in (0.0, 10.0, 3e3, 1e6):
        w = solve_windup(g, K, T)
        tq = np.sum(np.where(np.isfinite(g), K * np.maximum(w - g, 0), 0), axis=0)
        assert np.all(np.abs(tq - T) <= 1e-9 * max(T, 1e-300))
        for j in range(9):
            gj = g[np.isfinite(g[:, j]), j]
            Kj = K[np.isfinite(g[:, j]), j]
            assert w[j] == pytest.approx(brute_windup(gj, Kj, T), rel=1e-9, abs=1e-15)


def test_kernel_refuses_zero_stiffness():
    with pytest.raises(SpecError, match="stiffness"):
        solve_windup(np.zeros((4, 2)), 0.0, 1.0)


@pytest.fixture(scope="module")
def renzo():
    spec = gc.load_spec("renzo-1967")
    return spec, sweep(spec, 1.0, np.arange(0.0, 7.2, 0.9))


def test_equilibrium_and_sign_convention(renzo):
    spec, sw = renzo
    R = spec.tooth.pitch_radius
    for T in (1500.0, -1500.0):
        r = load_from_sweep(sw, torque_Nm=T, model="linear")
        assert r.loaded_flank == ("ccw" if T > 0 else "cw")
        assert np.sign(r.windup_rad).min() == np.sign(T)
        tq = r.tangential_force_N.sum(axis=0) * R * 1e-3
        np.testing.assert_allclose(tq, abs(T), rtol=1e-9)
        assert np.all(r.tangential_force_N >= 0)
        assert np.all(np.isfinite(r.max_pressure_MPa))


def test_aligned_perfect_teeth_share_equally():
    spec = gc.load_spec("renzo-1967")
    sw = sweep(spec, 0.0, [0.0, 3.0])
    r = load_from_sweep(sw, torque_Nm=2000.0, model="linear")
    P = r.tangential_force_N
    expect = 2000e3 / (spec.tooth.pitch_radius * spec.tooth.teeth)
    np.testing.assert_allclose(P, expect, rtol=1e-9)
    assert r.q() == pytest.approx(1.0, rel=1e-9)


def test_gap_offset_moves_load_like_a_spacing_error(renzo):
    spec, _ = renzo
    sw = sweep(spec, 0.0, [0.0])
    N = spec.tooth.teeth
    C = spec.load.mesh_stiffness_N_per_mm
    R = spec.tooth.pitch_radius
    off = np.zeros(N)
    off[0] = 1e-4 / R  # tooth 0 stands 0.1 µm back at the pitch circle
    r = load_from_sweep(sw, torque_Nm=2000.0, model="linear", gap_offset_rad=off)
    P = r.tangential_force_N[:, 0]
    # the others close 0.1 µm more than tooth 0 (which still touches)
    assert P[0] > 0 and P[1] - P[0] == pytest.approx(C * 1e-4, rel=1e-9)


def test_zero_torque_is_finite(renzo):
    _spec, sw = renzo
    r = load_from_sweep(sw, torque_Nm=0.0, model="linear")
    assert np.all(r.tangential_force_N == 0) and 0 < r.q() <= 1
    assert math.isfinite(float(np.max(r.max_pressure_MPa)))


def test_missing_torque_is_a_clear_error():
    spec = gc.load_spec("renzo-1967").replace(**{"load.torque_Nm": None})
    sw = sweep(spec, 1.0, [0.0])
    with pytest.raises(SpecError, match="torque"):
        load_from_sweep(sw, model="linear")


def test_public_api_from_the_top_level():
    spec = gc.load_spec("renzo-1967")
    res = gc.load(spec, 1.0, [0.0, 1.0], model="linear", tolerance_mm=1e-6)
    assert isinstance(res, gc.LoadResult) and res.tangential_force_N.shape == (50, 2)
    # the same as sweeping first and loading that sweep
    sw = gc.sweep(spec, 1.0, [0.0, 1.0], tolerance_mm=1e-6)
    again = gc.load_from_sweep(sw, model="linear")
    np.testing.assert_array_equal(again.tangential_force_N, res.tangential_force_N)
    assert callable(gc.capacity) and callable(gc.capacity_curve)
