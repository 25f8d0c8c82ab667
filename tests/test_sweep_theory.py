"""Agreement with the theory of docs/conventions.md, Tooth geometry (Renzo et al. 1967) for both
generation methods."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcoupling.clearance import sweep
from gearcoupling.clearance.design import contact_travel, critical_misalignment_deg
from gearcoupling.clearance.tooth_map import flank_minima
from gearcoupling.spec import load_spec

GENERATIONS = ("enveloped", "revolved")


def renzo_spec(generation: str):
    return load_spec("renzo-1967", **{"hub.crowning.generation": generation})


def z0_mm(spec, i: float) -> float:
    rc = spec.hub.crowning.radius
    return 0.5 * rc * math.tan(i) ** 2 / math.tan(spec.tooth.pressure_angle)


@pytest.mark.parametrize("generation", GENERATIONS)
@pytest.mark.parametrize("deg", [0.25, 1.0])
def test_pitch_line_separation_is_renzo_z0(generation, deg):
    """R_c = R, i <= 1°: peak-to-peak pitch-line separation of one flank is z0 measured
    normal to the flank and z0 / cos(phi) circumferentially, within 1 %; the contacting
    tooth sits near theta = phi/2 (not at the pivot, theta = 0)."""
    spec = renzo_spec(generation)
    assert spec.hub.crowning.radius == pytest.approx(spec.tooth.pitch_radius)
    i = math.radians(deg)
    theta = np.linspace(-math.pi / 2, math.pi / 2, 1441)
    mins, _ = flank_minima(spec, i, theta, tolerance_mm=1e-8)
    z0 = z0_mm(spec, i)
    phi = spec.tooth.pressure_angle
    assert np.ptp(mins["pitch_normal"]) == pytest.approx(z0, rel=0.01)
    assert np.ptp(mins["pitch"]) == pytest.approx(z0 / math.cos(phi), rel=0.01)
    star = abs(math.degrees(theta[np.argmin(mins["pitch_normal"])]))
    assert abs(star - math.degrees(phi) / 2) < 2.0


def test_renzo_worked_example_in_inches():
    """renzo-1967 at 1°: z0 = 0.00105 in (Renzo eq. 4) from the sweep's summary."""
    res = sweep(load_spec("renzo-1967"), 1.0, np.arange(0.0, 360.0, 0.5))
    s = res.summary()
    assert s["renzo_z0_mm"] / 25.4 == pytest.approx(0.00105, abs=5e-6)
    for flank in ("cw", "ccw"):
        assert s["pitch_line_peak_to_peak_normal_mm"][flank] == pytest.approx(
            s["renzo_z0_mm"], rel=0.01)
        assert s["pitch_line_peak_to_peak_circumferential_mm"][flank] == pytest.approx(
            s["renzo_z0_circumferential_mm"], rel=0.01)
        assert abs(abs(s["contacting_tooth_theta_deg"][flank]) - 10.0) < 2.0


@pytest.mark.parametrize("generation, rel_flank", [("enveloped", 0.01), ("revolved", 0.06)])
@pytest.mark.parametrize("deg", [0.25, 0.5])
def test_pivot_contact_travel_is_rc_cot_phi_i(generation, rel_flank, deg):
    """Small angles: the contact on the pivot teeth moves axially by R_c cot(phi) i; the
    pitch-line minimum within 2 %, the point of first touch within 1 % (enveloped) or 6 %
    (revolved, whose transverse profile is not the enveloped one)."""
    t = contact_travel(renzo_spec(generation), deg)
    rc = 63.5
    expected = rc / math.tan(math.radians(20.0)) * math.radians(deg)
    assert t["renzo_mm"] == pytest.approx(expected, rel=1e-12)
    assert t["pitch_line_z_mm"] == pytest.approx(expected, rel=0.02)
    assert t["pitch_line_z_opposite_mm"] == pytest.approx(-expected, rel=0.02)
    assert t["flank_z_mm"] == pytest.approx(expected, rel=rel_flank)


def test_critical_misalignment_falls_as_rc_grows():
    """Edge contact starts when R_c cot(phi) i reaches the half face: the critical angle
    falls with R_c and follows b/2 tan(phi) / R_c within 5 %."""
    spec = load_spec("renzo-1967")
    R, hf = spec.tooth.pitch_radius, 0.5 * spec.hub.face_width
    crit = []
    for q in (0.8, 1.0, 2.0):
        s = spec.replace(**{"hub.crowning.radius": q * R})
        c = critical_misalignment_deg(s, tolerance_deg=1e-3)
        crit.append(c)
        estimate = math.degrees(hf * math.tan(spec.tooth.pressure_angle) / (q * R))
        assert c == pytest.approx(estimate, rel=0.05)
    assert crit[0] > crit[1] > crit[2]


def test_generation_methods_differ_little_on_the_pitch_line():
    """Both constructions keep the pitch line (same crown drop), so their pitch-line
    clearances agree closely while whole-flank values differ (Renzo Fig. 7)."""
    i = math.radians(1.0)
    theta = np.linspace(0.0, math.pi, 91)
    a, _ = flank_minima(renzo_spec("enveloped"), i, theta, tolerance_mm=1e-8)
    b, _ = flank_minima(renzo_spec("revolved"), i, theta, tolerance_mm=1e-8)
    assert np.max(np.abs(a["pitch"] - b["pitch"])) < 2e-3 * np.ptp(a["pitch"])
    assert np.max(np.abs(a["clearance"] - b["clearance"])) > 1e-4
