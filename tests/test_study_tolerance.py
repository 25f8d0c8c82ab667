"""Tolerance Monte Carlo: rigid offsets against the exact per-tooth geometry, K = 1 without
errors, Renzo's linear capacity against the load package's solver."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.errors import ArgumentError, SpecError
from gearcoupling.study.tolerance import (
    CrownMaps,
    Tolerances,
    ToothErrors,
    draw_errors,
    exact_map,
    gap_offsets_rad,
    ideal_map,
    linear_outputs,
    no_errors,
    rotations,
    summarise_k,
    tolerance_sample,
)

N = 50


@pytest.fixture(scope="module")
def spec():
    return gc.load_spec("renzo-1967")


def errors(**one):
    arrays = {k: np.zeros(N) for k in ("position_mm", "radial_mm", "thickness_mm", "crown_mm")}
    for name, (tooth, value) in one.items():
        arrays[name][tooth] = value
    return ToothErrors(**arrays)


@pytest.mark.parametrize("path", ["fast", "interpolated"])
def test_zero_errors_give_k_exactly_one(spec, path):
    out = tolerance_sample(spec, 1.0, Tolerances(), seed=3, sample=0, path=path, steps=1)
    assert out["K"] == 1.0 and out["capacity_Nm"] == out["nominal_capacity_Nm"] > 0
    scatter = tolerance_sample(spec, 1.0, Tolerances(index_sd_mm=0.005), seed=3, sample=0,
                               path=path, steps=1)
    assert scatter["K"] < 1.0  # and errors cost capacity


def test_index_error_moves_one_gap_by_eps_over_r(spec):
    eps, k = 0.005, 3  # mm of arc at the pitch circle on tooth 3
    R = spec.tooth.pitch_radius
    off = gap_offsets_rad(spec, errors(position_mm=(k, eps)))
    assert off[0, k] == eps / R and off[1, k] == -eps / R  # cw opens, ccw closes
    assert np.count_nonzero(off) == 2
    psi = rotations(spec, 1)[:4]
    for mis_deg, rel in ((0.0, 1e-9), (1.0, 1e-3)):
        i = math.radians(mis_deg)
        base = exact_map(spec, i, psi, no_errors(N), 1e-7)
        d = exact_map(spec, i, psi, errors(position_mm=(k, eps)), 1e-7) - base
        # exact geometry (the tooth's flanks rotated): only tooth k moves, by eps/R; at 1°
        # the sweep's first-order gap angle normal/(r_b rate) differs by (1/rate - 1) eps/R;
        # the other teeth to rounding (the tracking search starts from another minimum)
        assert np.max(np.abs(np.delete(d, k, axis=1))) <= 1e-9 * eps / R
        np.testing.assert_allclose(d[:, k], off[:, k, None] * np.ones((2, psi.size)), rtol=rel)


def test_thickness_change_is_a_rigid_rotation_of_each_flank(spec):
    ds, k = 0.01, 7
    psi = rotations(spec, 1)[:4]
    base = exact_map(spec, 0.0, psi, no_errors(N), 1e-7)
    d = exact_map(spec, 0.0, psi, errors(thickness_mm=(k, ds)), 1e-7) - base
    np.testing.assert_allclose(d[:, k], -0.5 * ds / spec.tooth.pitch_radius, rtol=1e-9)


def test_crown_interpolation_against_exact_geometry(spec):
    i, k, dh = math.radians(1.0), 5, 0.003
    psi = rotations(spec, 1)[:6]
    maps = CrownMaps(spec, i, psi, crown_sd_mm=0.002, tolerance_mm=1e-7)
    err = errors(crown_mm=(k, dh))
    exact = exact_map(spec, i, psi, err, 1e-7)
    effect = np.max(np.abs(exact - exact_map(spec, i, psi, no_errors(N), 1e-7)))
    assert effect > 1e-7  # the crown change is visible in the gaps
    assert np.max(np.abs(maps.gap(err) - exact)) < 1e-3 * effect
    np.testing.assert_array_equal(maps.gap(no_errors(N)), ideal_map(spec, i, psi, 1e-7))


def test_linear_capacity_matches_the_load_solver(spec):
    from gearcoupling.clearance import sweep
    from gearcoupling.loading import load_from_sweep

    sw = sweep(spec, 1.0, np.degrees(rotations(spec, 1)))
    off = gap_offsets_rad(spec, draw_errors(Tolerances(index_sd_mm=0.005), N,
                                            np.random.default_rng(1)))
    gap = sw.gap_angle_rad + off[:, :, None]
    out = linear_outputs(spec, gap, 2000.0)
    res = load_from_sweep(sw, torque_Nm=out["capacity_Nm"], model="linear",
                          gap_offset_rad=off)
    # at the capacity the most-loaded tooth over the turn carries exactly P_i
    assert np.max(res.tangential_force_N) == pytest.approx(spec.load.allowable_tooth_load_N,
                                                           rel=1e-9)
    res = load_from_sweep(sw, torque_Nm=2000.0, model="linear", gap_offset_rad=off)
    assert out["max_tooth_load_N"] == pytest.approx(np.max(res.tangential_force_N), rel=1e-12)


def test_error_model_statistics():
    rng = np.random.default_rng(0)
    e = draw_errors(Tolerances(hub_runout_mm=0.02), N, rng)
    amp = np.hypot(e.position_mm, e.radial_mm)  # a pure eccentricity e = F_r / 2
    np.testing.assert_allclose(amp, 0.01, rtol=1e-12)
    e = draw_errors(Tolerances(pitch_sd_mm=0.003), N, rng)
    assert abs(np.mean(e.position_mm)) < 1e-15 and np.std(e.position_mm) > 0.003


def test_k_summary_and_sample_count():
    k = np.random.default_rng(2).normal(0.8, 0.05, 4000)
    s = summarise_k(k, precision=0.002)
    assert s["K_mean_low"] < 0.8 < s["K_mean_high"]
    # n = (z sd / precision)^2 samples give a half-width of the precision
    assert s["samples_needed"] == pytest.approx((1.96 * 0.05 / 0.002) ** 2, rel=0.06)


def test_bad_tolerances_refused(spec):
    with pytest.raises(SpecError, match="index_sd_mm"):
        Tolerances(index_sd_mm=-1.0)
    with pytest.raises(SpecError, match="unknown limit"):
        Tolerances.from_limits(runout=0.1)
    with pytest.raises(ArgumentError, match="path"):
        tolerance_sample(spec, 1.0, Tolerances(), 0, 0, path="slow")


def test_renzo_capacity_is_the_load_packages_tooth_load_criterion(spec):
    from gearcoupling.clearance import sweep
    from gearcoupling.loading.capacity import capacity_from_sweep

    sw = sweep(spec, 1.0, np.degrees(rotations(spec, 1)))
    cap = capacity_from_sweep(sw, model="linear").criteria_Nm["tooth_load"]
    mine = linear_outputs(spec, sw.gap_angle_rad, 2000.0)["capacity_Nm"]
    assert cap == pytest.approx(spec.load.accuracy_factor * mine, rel=1e-9)


def test_compliance_model_k(spec):
    zero = tolerance_sample(spec, 1.0, Tolerances(), 1, 0, steps=1, model="compliance")
    assert zero["K"] == 1.0
    out = tolerance_sample(spec, 1.0, Tolerances(pitch_sd_mm=0.003), 1, 0, steps=1,
                           model="compliance")
    assert 0 < out["K"] < 1.0
