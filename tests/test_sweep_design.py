"""Design quantities: critical and binding angles to 1e-4°, backlash, double engagement,
the summary, bad input and the extremes of the supported range."""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import KINDS, sweep
from gearcoupling.clearance.design import (
    binding_angle_deg,
    critical_misalignment_deg,
    design_quantities,
    double_engagement,
    mesh_angles,
    min_backlash_rad,
    pivot_on_face_end,
)
from gearcoupling.errors import ArgumentError


@pytest.fixture(scope="module")
def renzo():
    return gc.load_spec("renzo-1967")


def test_critical_misalignment_root_to_1e_4_deg(renzo):
    c = critical_misalignment_deg(renzo)
    assert 1.5 < c < 2.5
    assert not pivot_on_face_end(renzo, math.radians(c - 1e-4))
    assert pivot_on_face_end(renzo, math.radians(c + 1e-4))
    # and the contact kind the sweep reports there says so
    res = sweep(renzo, c + 1e-3, [0.0])
    assert KINDS[res.contact_kind[0, 0, 0]] == "face end"


@pytest.mark.parametrize("name, deg", [("renzo-1967", 2.065), ("industrial-m2", 4.28)])
def test_the_pivot_contact_reaches_the_face_end_where_the_exact_gap_says(name, deg):
    """Just below the critical misalignment the exact gap (``clearance.reference``: the
    exact flank, the active interval's ends by bisection, a dense grid in t) of the pivot
    tooth is lower 1 mm inside the face end than at it, so the contact has not reached the
    face end: the kernel says so too. (The search that stopped within the tolerance in
    value, 1e-7 mm, declared it reached here: renzo-1967 at 2.0645°, industrial-m2 at
    4.2798°.)"""
    from gearcoupling.clearance.reference import _plane_min
    from gearcoupling.geometry import hub_model

    spec = gc.load_spec(name)
    hf = hub_model(spec).half_face
    inside, at_end = _plane_min(spec, math.radians(deg), 0.0, np.array([hf - 1e-3, hf]),
                                True, 241)
    assert inside < at_end - 1e-9
    assert not pivot_on_face_end(spec, math.radians(deg))
    assert pivot_on_face_end(spec, math.radians(deg + 0.01))


def test_binding_angle_root_to_1e_4_deg(renzo):
    b = binding_angle_deg(renzo)
    assert 1.0 < b < 3.0
    assert min_backlash_rad(renzo, b - 1e-4) > 0
    assert min_backlash_rad(renzo, b + 1e-4) < 0
    # a sweep over a turn just below it keeps a little backlash, just above has none
    below = sweep(renzo, b - 0.01, np.arange(0.0, 360.0, 1.0))
    above = sweep(renzo, b + 0.01, np.arange(0.0, 360.0, 1.0))
    assert below.backlash_mm.min() > 0 > above.backlash_mm.max()


def test_backlash_falls_from_the_aligned_value(renzo):
    """Aligned backlash is s - t (to the 1e-7 mm tolerance of each flank's minimum)."""
    s, t = renzo.sleeve.space_width, renzo.hub.tooth_thickness
    values = [min_backlash_rad(renzo, a) * renzo.tooth.pitch_radius
              for a in (0.0, 0.5, 1.0, 1.5)]
    assert values[0] == pytest.approx(s - t, abs=2e-7)
    assert all(a > b for a, b in itertools.pairwise(values))


def test_no_binding_or_edge_for_straight_teeth_aligned_range():
    """Straight teeth (R_c -> inf) never move their contact axially: it sits at a face end
    at once, so the critical angle is ~0; with enough backlash they still bind by 6°."""
    spec = gc.load_spec("renzo-1967", **{"hub.crowning.kind": "none"})
    c = critical_misalignment_deg(spec, tolerance_deg=1e-3)
    assert c is not None and c < 0.01
    res = sweep(spec, 0.0, [0.0, 10.0])
    assert np.allclose(res.backlash_mm, spec.sleeve.space_width - spec.hub.tooth_thickness,
                       atol=1e-9)


def test_mesh_angles_of_a_double_engagement_coupling():
    L = 200.0
    a = mesh_angles(2.0, 0.0, L)  # pure parallel offset: equal angles atan(d / L)
    assert a.a_deg == pytest.approx(math.degrees(math.atan(2.0 / L)), rel=1e-12)
    assert a.b_deg == pytest.approx(a.a_deg, rel=1e-12)
    b = mesh_angles(0.0, 1.5, L)  # pure angular: all at mesh B
    assert b.a_deg == pytest.approx(0.0, abs=1e-12) and b.b_deg == pytest.approx(1.5)
    g = math.degrees(math.atan(2.0 / L))
    c = mesh_angles(2.0, 2 * g, L)  # tilt in the offset plane by twice the sleeve angle
    assert c.a_deg == pytest.approx(g) and c.b_deg == pytest.approx(g)
    d = mesh_angles(2.0, g, L, angle_azimuth_deg=90.0)  # tilt at right angles to offset
    assert d.b_deg == pytest.approx(math.degrees(math.acos(math.cos(math.radians(g)) ** 2)),
                                    rel=1e-9)
    with pytest.raises(ArgumentError, match="span_mm"):
        mesh_angles(1.0, 0.0, 0.0)


def test_double_engagement_sweeps_each_mesh(renzo):
    mesh, a, b = double_engagement(renzo, 1.0, 0.3, 150.0, [0.0, 90.0])
    assert a.misalignment_deg == pytest.approx(mesh.a_deg)
    assert b.misalignment_deg == pytest.approx(mesh.b_deg)
    assert mesh.b_deg < mesh.a_deg  # the shaft tilt partly follows the sleeve
    with pytest.raises(ArgumentError, match="mesh A angle"):
        double_engagement(renzo, 30.0, 0.0, 100.0, [0.0])


def test_summary_and_design_quantities_are_plain_json(renzo):
    res = sweep(renzo, 1.0, np.arange(0.0, 360.0, 10.0))
    data = res.summary()
    data.update(design_quantities(renzo, 1.0, tolerance_deg=1e-2))
    text = json.dumps(data, allow_nan=False)
    back = json.loads(text)
    for key in ("critical_misalignment_deg", "binding_angle_deg", "pivot_contact_z_mm",
                "min_backlash_mm", "aligned_backlash_mm", "pitch_line_peak_to_peak_normal_mm",
                "flank_peak_to_peak_circumferential_mm", "contacting_tooth_theta_deg"):
        assert key in back
    assert back["min_backlash_mm"] < back["aligned_backlash_mm"]
    rows = list(res.rows())
    assert len(rows) == 36 * 50 * 2


@pytest.mark.parametrize("bad", [-0.1, 6.5, math.nan, math.inf])
def test_bad_misalignment_names_the_field(renzo, bad):
    with pytest.raises(ArgumentError, match="misalignment_deg"):
        sweep(renzo, bad, [0.0])


def test_bad_angles_and_tolerance(renzo):
    with pytest.raises(ArgumentError, match="angles_deg"):
        sweep(renzo, 1.0, [0.0, math.nan])
    with pytest.raises(ArgumentError, match="angles_deg"):
        sweep(renzo, 1.0, [])
    with pytest.raises(ValueError, match="tolerance"):
        sweep(renzo, 1.0, [0.0], tolerance_mm=0.0)


def test_zero_misalignment_is_continuous(renzo):
    """i = 0 and i -> 0 agree (no special case), every tooth alike."""
    a = sweep(renzo, 0.0, [0.0, 33.0])
    b = sweep(renzo, 1e-6, [0.0, 33.0])
    assert np.ptp(a.clearance_mm) < 1e-12
    assert np.allclose(a.clearance_mm, b.clearance_mm, atol=1e-8)


EXTREMES = [  # (tooth, hub overrides): the range ends that build (as in test_random_specs)
    ({"teeth": 6, "module": 60.0, "pressure_angle_deg": 30},
     {"root": {"dedendum": 0.8 * 60, "fillet_radius": 0.3 * 60}}),
    ({"teeth": 300, "module": 0.2, "pressure_angle_deg": 14.5}, {}),
    ({"teeth": 40, "module": 0.2, "pressure_angle_deg": 20},
     {"crowning": {"kind": "circular", "radius": 1.0}}),
    ({"teeth": 300, "module": 60.0, "pressure_angle_deg": 14.5},
     {"crowning": {"kind": "none"}}),
]


@pytest.mark.parametrize("tooth, hub", EXTREMES)
@pytest.mark.parametrize("mis", [0.0, 6.0])
def test_extremes_are_finite(tooth, hub, mis):
    R = tooth["module"] * tooth["teeth"] / 2
    data = {"tooth": tooth,
            "hub": {"face_width": 0.2 * R, "crowning": {"kind": "circular", "radius": R},
                    **hub}}
    spec = gc.spec_from_dict(data)
    res = sweep(spec, mis, [0.0, 45.0, 123.0])
    for name in ("clearance_mm", "normal_clearance_mm", "pitch_clearance_mm",
                 "contact_z_mm", "contact_r_mm", "backlash_mm"):
        assert not np.any(np.isnan(getattr(res, name))), name
    touching = res.contact_kind != KINDS.index("no contact")
    assert np.all(np.isfinite(res.clearance_mm[touching]))
    assert np.all(np.abs(res.contact_z_mm) <= 0.5 * spec.hub.face_width + 1e-9)
    if mis == 0.0:  # aligned: every tooth alike, backlash s - t within both flanks' accuracy
        assert np.ptp(res.normal_clearance_mm) < 1e-9 * (1 + R)
        accuracy = 2 * (res.tolerance_mm + res.table_error_mm)
        assert res.backlash_mm == pytest.approx(
            np.full(3, spec.sleeve.space_width - spec.hub.tooth_thickness), abs=accuracy)
