"""The sweep kernel against its frozen outputs (``tests/golden_sweep_kernel.py``): a
speed-up must not move any minimum by more than 1e-9 mm.

These are regression pins (outputs of the kernel, frozen before a speed-up), not an
independent reference; the kernel against theory and a brute-force exact search is in
``test_sweep_kernel.py``.

The minimum *values* are well conditioned and are compared directly. *Where* a minimum
lies is not: along a flat valley of the gap a change of 1e-12 mm in the value (a
different rounding in a newer numpy) moves the location by micrometres. The location is
therefore checked by what it is for: the exact gap (:func:`~gearcoupling.clearance.reference.
exact_gap`, on the exact flank, not the kernel's table) at the point found equals the exact
gap at the frozen point within 1e-9 mm, and it equals the reported minimum within the
kernel's tolerance plus its flank table error.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcoupling.clearance.flank_table import flank_table
from gearcoupling.clearance.kernel import MEASURES
from gearcoupling.clearance.reference import exact_gap
from gearcoupling.spec import load_spec
from golden_sweep_kernel import (
    EXTREME_DEG,
    EXTREMES,
    FILE,
    MISALIGNMENTS_DEG,
    TEMPLATES,
    THETA_DEG,
    extreme_minima,
    extreme_spec,
    minima,
)

VALUES = ("clearance", "normal", "pitch", "pitch_normal")
TOLERANCE_MM = 1e-9  # values and the gap at the located point, against the frozen kernel


@pytest.fixture(scope="module")
def frozen():
    with np.load(FILE) as data:
        return dict(data)


def _exact_normal_gaps(spec, deg: float, theta_rad, z, r) -> np.ndarray:
    """Exact normal gap of tooth 0's cw flank at points ``(z, r)``, one per turning angle."""
    return np.array([exact_gap(spec, math.radians(deg), t, zi, ri, True)[0]
                     for t, zi, ri in zip(theta_rad, z, r, strict=True)])


@pytest.mark.parametrize("deg", MISALIGNMENTS_DEG)
@pytest.mark.parametrize("name", TEMPLATES)
def test_minima_equal_frozen_kernel(frozen, name, deg):
    got = minima(name, deg)
    for key in VALUES:
        ref = frozen[f"{name}|{deg:g}|{key}"]
        assert np.array_equal(np.isfinite(got[key]), np.isfinite(ref)), key
        fin = np.isfinite(ref)
        assert np.max(np.abs(got[key][fin] - ref[fin]), initial=0.0) <= TOLERANCE_MM, key
    # where the minimum lies, by the gap there (well conditioned), not by its co-ordinates
    spec = load_spec(name)
    fin = np.isfinite(frozen[f"{name}|{deg:g}|normal"])
    theta = np.radians(THETA_DEG)[fin]
    at_found = _exact_normal_gaps(spec, deg, theta, got["z"][fin], got["r"][fin])
    at_frozen = _exact_normal_gaps(spec, deg, theta, frozen[f"{name}|{deg:g}|z"][fin],
                                   frozen[f"{name}|{deg:g}|r"][fin])
    assert np.max(np.abs(at_found - at_frozen), initial=0.0) <= TOLERANCE_MM
    # and the point found holds the minimum reported (exact flank vs the kernel's table)
    bound = 1e-7 + flank_table(spec, 1e-7).max_error_mm
    assert np.max(np.abs(at_found - got["normal"][fin]), initial=0.0) <= bound


@pytest.mark.parametrize("deg", EXTREME_DEG)
@pytest.mark.parametrize("name", EXTREMES)
def test_extremes_equal_frozen_kernel(frozen, name, deg):
    """The extremes (root-fillet contact, 16 mm of interference where the gaps to the
    involute and to the fillet differ at the fillet start, end_round pieces, heavy
    binding), each measure alone and all four: values within 1e-9 mm of the frozen ones;
    radius and turning rate where the point found is the frozen one."""
    spec = extreme_spec(name)
    for measures in [MEASURES, *((m,) for m in MEASURES)]:
        got = extreme_minima(spec, deg, measures)
        for m in measures:
            a = got[m]
            ref = {f: frozen[f"{name}|{deg:g}|{m}|{f}"] for f in ("value_mm", "z_mm", "r_mm",
                                                                  "t", "rate")}
            fin = np.isfinite(ref["value_mm"])
            assert np.array_equal(np.isfinite(a.value_mm), fin), m
            assert np.max(np.abs(a.value_mm[fin] - ref["value_mm"][fin]),
                          initial=0.0) <= TOLERANCE_MM, m
            same = fin & (np.abs(a.z_mm - ref["z_mm"]) <= 1e-9) & (np.abs(a.t - ref["t"]) <= 1e-9)
            assert np.allclose(a.r_mm[same], ref["r_mm"][same], rtol=0.0, atol=1e-8), m
            assert np.allclose(a.rate[same], ref["rate"][same], rtol=1e-9, atol=0.0), m
