"""Interference and minimum gap of posed meshes, cross-validated against the exact sweep."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import sweep
from gearcoupling.errors import ArgumentError
from gearcoupling.interference import build_model, check_interference, posed_meshes
from gearcoupling.interference.distance import positive_integral
from gearcoupling.interference.posed import hub_pose, window_pose, window_to_sleeve
from gearcoupling.interference.submodel import hot_teeth, windows

pytestmark = [pytest.mark.needs_fcl]

FLANKS = ("cw", "ccw")


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


@pytest.fixture(scope="module")
def tight():
    """renzo-1967 with 0.001 in backlash: at 1° some teeth bind, others stay free."""
    return gc.load_spec("renzo-1967", **{"hub.backlash": 0.001})


# ----------------------------------------------------------------------------- poses


def test_hub_pose_is_design_formula():
    i, psi, delta = math.radians(2.5), 0.7, 0.01
    expected = _rz(-psi) @ _rx(i) @ _rz(psi) @ _rz(delta)
    assert np.allclose(hub_pose(i, psi, delta), expected, atol=1e-15)


@pytest.mark.parametrize("centre", [0, 3, 49])
def test_window_pose_stands_for_its_teeth(centre):
    """A point of the sector around tooth 0 posed by the window pose and turned to the
    centre tooth lands where the real hub tooth ``centre`` puts the same point."""
    N, i, psi = 50, math.radians(1.3), 0.4
    p0 = np.array([[63.0, -1.2, 3.0], [61.0, 0.8, -5.0]])
    c = 2 * math.pi * centre / N
    real = (hub_pose(i, psi) @ _rz(c) @ p0.T).T  # tooth `centre` of the real hub
    via_window = window_to_sleeve(p0 @ window_pose(i, psi, centre, N).T, centre, N)
    assert np.allclose(via_window, real, atol=1e-12)


# ------------------------------------------------------------------------ submodels


@pytest.mark.parametrize("k", [0, 1, 3])
@pytest.mark.parametrize("sel", [list(range(50)), [0, 1, 2, 3, 48, 49, 10], [7], [5, 7, 9]])
def test_windows_own_each_selected_tooth_once(k, sel):
    w = windows(sel, 50, k)
    owned = [t for _, o in w for t in o]
    assert sorted(owned) == sorted(set(sel))
    for centre, o in w:
        for t in o:  # an owned tooth lies inside its window
            assert min((t - centre) % 50, (centre - t) % 50) <= k


def test_hot_teeth_margin_and_floor():
    c = np.array([[0.05, 0.01], [0.06, 0.2], [0.2, -0.01], [0.051, 0.3]])
    gap, over = hot_teeth(c, margin_mm=0.002, floor_mm=0.015)
    assert gap[0].tolist() == [0, 3] and gap[1].tolist() == [2]
    assert over[0].tolist() == [0]  # nothing below the floor: the tightest only
    assert over[1].tolist() == [0, 2]


def test_positive_integral_matches_fine_sampling():
    rng = np.random.default_rng(5)
    v = rng.normal(size=(3, 3))
    f = np.array([[0, 1, 2]])
    area = 0.5 * np.linalg.norm(np.cross(v[1] - v[0], v[2] - v[0]))
    # barycentric grid: mean of max(0, f) over the triangle, times its area
    n = 400
    a, b = np.meshgrid((np.arange(n) + 0.5) / n, (np.arange(n) + 0.5) / n)
    inside = a + b < 1
    for vals in ([1.0, -0.5, 0.3], [0.2, -0.4, -0.1], [2.0, 1.0, 0.5], [-1.0, -2.0, -0.1]):
        vals = np.array(vals)
        lin = vals[0] * (1 - a - b) + vals[1] * a + vals[2] * b
        ref = area * np.mean(np.maximum(lin[inside], 0.0))
        assert positive_integral(v, f, vals)[0] == pytest.approx(ref, rel=5e-3, abs=1e-12)


# --------------------------------------------------------------- cross-validation


@pytest.mark.parametrize("method", ["boolean", "distance"])
def test_mesh_gap_matches_exact_clearance(renzo, method):
    """At the design angle the mesh minimum gap equals the sweep's smallest normal
    clearance within the chordal tolerance, at the same tooth and flank kind."""
    angles = [0.0, 37.0, 90.0, 161.0]
    res = check_interference(renzo, 1.0, angles, method=method)
    sw = sweep(renzo, 1.0, angles)
    exact = sw.normal_clearance_mm.min(axis=(0, 1))
    assert not res.interferes
    assert np.all(np.abs(res.min_gap_mm - exact) < res.tolerance_mm)
    assert set(res.gap_hub_surface) <= {"flank_cw", "flank_ccw"}
    for j in range(len(angles)):  # the mesh's closest tooth is tight per the sweep too
        f = FLANKS.index(res.gap_hub_surface[j][6:])
        assert sw.normal_clearance_mm[f, res.gap_tooth[j], j] < exact[j] + res.tolerance_mm


def test_sector_and_full_parts_agree(renzo):
    angles = [12.0, 200.0]
    a = check_interference(renzo, 1.0, angles, teeth="sweep")
    b = check_interference(renzo, 1.0, angles, teeth="all")
    c = check_interference(renzo, 1.0, angles, teeth=1)
    assert np.allclose(a.min_gap_mm, b.min_gap_mm, atol=1e-3 * a.tolerance_mm)
    assert np.allclose(c.min_gap_mm, b.min_gap_mm, atol=1e-3 * a.tolerance_mm)
    assert b.windows.tolist() == [1, 1] and np.all(a.windows >= 1)


def test_gap_finer_mesh_is_closer(renzo):
    angles = [25.0]
    exact = sweep(renzo, 1.0, angles).normal_clearance_mm.min()
    errs = [abs(check_interference(renzo, 1.0, angles, tolerance_mm=t).min_gap_mm[0] - exact)
            for t in (0.02, 0.002)]
    assert errs[1] < 0.002 and errs[1] < errs[0]


@pytest.mark.parametrize("method", ["boolean", "distance"])
def test_tight_spec_overlaps_exactly_where_sweep_is_negative(tight, method):
    tol = 0.005
    angles = [0.0, 20.0, 45.0, 100.0]
    res = check_interference(tight, 1.0, angles, method=method, tolerance_mm=tol)
    nc = sweep(tight, 1.0, angles).normal_clearance_mm  # (flank, tooth, angle)
    found = {(o.angle_index, o.tooth, FLANKS.index(o.flank)) for o in res.overlaps}
    must = {(j, k, f) for f, k, j in zip(*np.nonzero(nc < -tol), strict=True)}
    never = {(j, k, f) for f, k, j in zip(*np.nonzero(nc > tol), strict=True)}
    assert must, "the tight spec must bind somewhere"
    assert never, "and be free elsewhere"
    assert must <= found
    assert not (found & never)
    assert res.interferes
    # depth is the negated smallest clearance, within the tolerance
    assert np.all(np.abs(res.overlap_depth_mm + nc.min(axis=(0, 1))) < tol)
    assert np.all(res.min_gap_mm == -res.overlap_depth_mm)
    for o in res.overlaps:  # centroids sit at the teeth they name
        ang = math.atan2(o.centroid_mm[1], o.centroid_mm[0])
        assert abs((ang - 2 * math.pi * o.tooth / tight.tooth.teeth + math.pi)
                   % (2 * math.pi) - math.pi) < math.pi / tight.tooth.teeth


def test_estimated_volume_close_to_boolean_volume(tight):
    kw = dict(tolerance_mm=0.005)
    b = check_interference(tight, 1.0, [30.0], method="boolean", **kw)
    d = check_interference(tight, 1.0, [30.0], method="distance", **kw)
    assert b.volume_exact and not d.volume_exact
    assert d.overlap_volume_mm3[0] == pytest.approx(b.overlap_volume_mm3[0], rel=0.2)
    assert sorted(b.teeth_involved(0)) == sorted(d.teeth_involved(0))


@pytest.mark.parametrize("sign, flank", [(1, "ccw"), (-1, "cw")])
def test_hub_turned_past_backlash_overlaps_on_expected_flank(renzo, sign, flank):
    """Aligned: each flank has half the free turn; turning the hub by 0.6 of the backlash
    closes one flank side of every tooth, 0.4 closes none."""
    free = float(sweep(renzo, 0.0, [0.0]).backlash_rad[0])
    past = check_interference(renzo, 0.0, [0.0, 3.0],
                              hub_rotation_deg=sign * math.degrees(0.6 * free))
    short = check_interference(renzo, 0.0, [0.0],
                               hub_rotation_deg=sign * math.degrees(0.4 * free))
    N = renzo.tooth.teeth
    assert past.interferes and not short.interferes
    assert {o.flank for o in past.overlaps} == {flank}
    for j in range(2):
        assert past.teeth_involved(j) == list(range(N))
    assert short.min_gap_mm[0] > 0
    # misaligned: turning past the smallest backlash closes the expected flank only
    mis = sweep(renzo, 1.0, [0.0]).backlash_rad[0]
    tilted = check_interference(renzo, 1.0, [0.0], hub_rotation_deg=sign * math.degrees(mis))
    assert tilted.interferes and {o.flank for o in tilted.overlaps} == {flank}


@pytest.mark.parametrize("name, mis", [("renzo-1967", 6.0), ("industrial-m2", 0.0)])
def test_extremes_stay_finite(name, mis):
    spec = gc.load_spec(name)
    res = check_interference(spec, mis, [0.0, 33.0], method="distance")
    for arr in (res.min_gap_mm, res.overlap_volume_mm3, res.overlap_depth_mm,
                res.hub_point_mm, res.sleeve_point_mm):
        assert np.all(np.isfinite(arr))
    exact = sweep(spec, mis, [0.0, 33.0]).normal_clearance_mm.min(axis=(0, 1))
    # the meshes hold every surface, the sweep only the hub flank: never farther apart
    assert np.all(res.min_gap_mm < exact + res.tolerance_mm)
    flanks = np.array([h.startswith("flank") and s.startswith("flank")
                       for h, s in zip(res.gap_hub_surface, res.gap_sleeve_surface, strict=True)])
    assert np.all(np.abs(res.min_gap_mm - exact)[flanks] < res.tolerance_mm)


def test_aligned_mesh_gap_is_between_flanks_and_matches_the_sweep():
    """industrial-m2 aligned: the sleeve tips clear the hub form circle (spec validation
    refuses anything else), so the closest pair on the meshes is flank to flank and its gap
    is the sweep's exact normal clearance."""
    spec = gc.load_spec("industrial-m2")
    res = check_interference(spec, 0.0, [0.0], tolerance_mm=0.002)
    exact = sweep(spec, 0.0, [0.0]).normal_clearance_mm.min()
    assert res.gap_hub_surface[0].startswith("flank")
    assert res.gap_sleeve_surface[0].startswith("flank")
    assert res.min_gap_mm[0] == pytest.approx(exact, abs=res.tolerance_mm)


def test_straight_teeth_aligned_gap_is_half_backlash_normal():
    spec = gc.load_spec("renzo-1967", **{"hub.crowning.kind": "none"})
    res = check_interference(spec, 0.0, [0.0], teeth=0)
    # aligned straight spur teeth: normal gap per flank = r_b * (backlash / 2R) exactly
    B = spec.derived["aligned_backlash_mm"]
    expected = spec.tooth.base_radius * B / (2 * spec.tooth.pitch_radius)
    assert res.min_gap_mm[0] == pytest.approx(expected, abs=res.tolerance_mm)


def test_posed_meshes_of_overlapping_pose(tight):
    res = check_interference(tight, 1.0, [0.0], tolerance_mm=0.005)
    meshes = posed_meshes(res, 0)
    assert set(meshes) == {"hub", "sleeve", "overlap"}
    assert meshes["overlap"].volume == pytest.approx(res.overlap_volume_mm3[0], rel=1e-6)
    # the posed sector hub teeth sit at their real positions: polar angles of the closest
    # pair agree with the reported tooth
    ang = math.atan2(res.hub_point_mm[0, 1], res.hub_point_mm[0, 0])
    k = res.gap_tooth[0]
    assert abs((ang - 2 * math.pi * k / 50 + math.pi) % (2 * math.pi) - math.pi) < math.pi / 50


def test_model_reused_across_calls(renzo):
    model = build_model(renzo, 0.0127, 0)
    a = check_interference(renzo, 1.0, [5.0], tolerance_mm=0.0127, model=model)
    b = check_interference(renzo, 1.0, [5.0], tolerance_mm=0.0127, model=model)
    assert a.prepared is b.prepared is model
    assert a.min_gap_mm[0] == b.min_gap_mm[0]
    with pytest.raises(ValueError, match="does not match"):
        check_interference(renzo, 1.0, [5.0], tolerance_mm=0.0127, model=model, teeth="all")


# ----------------------------------------------------------------------- bad input


@pytest.mark.parametrize("kwargs, match", [
    (dict(method="voxel"), "method = 'voxel'"),
    (dict(teeth="most"), "teeth = 'most'"),
    (dict(teeth=30), "teeth = 30"),
    (dict(tolerance_mm=-1.0), "tolerance_mm = -1.0"),
    (dict(hub_rotation_deg=5.0), "hub_rotation_deg"),
    (dict(margin_mm=float("nan")), "margin_mm"),
])
def test_bad_input_names_the_field(renzo, kwargs, match):
    with pytest.raises(ValueError, match=match):
        check_interference(renzo, 1.0, [0.0], **kwargs)


@pytest.mark.parametrize("mis, angles", [(7.0, [0.0]), (1.0, []), (1.0, [float("nan")])])
def test_bad_angles_raise_spec_error(renzo, mis, angles):
    with pytest.raises(ArgumentError):
        check_interference(renzo, mis, angles)


def test_missing_backend_names_the_extra(renzo, monkeypatch):
    import sys

    from gearcoupling.errors import BackendError

    model = build_model(renzo, 0.0127, 0)  # fresh: its fcl tree is not built yet
    monkeypatch.setitem(sys.modules, "fcl", None)  # import fcl now raises ImportError
    with pytest.raises(BackendError, match=r"gearcoupling\[interference\]"):
        check_interference(renzo, 1.0, [0.0], tolerance_mm=0.0127, model=model)


@pytest.mark.parametrize("over, mis", [({}, 1.0), ({}, 0.0), ({"hub.backlash": 0.001}, 1.0)])
def test_mesh_backlash_matches_sweep(over, mis):
    """Free turn of the hub on the meshes (both flank sides, distance queries) against the
    sweep's backlash: each side's gap is within the tolerance, so the sum is within
    2 tol at the base circle, i.e. 2 tol R / r_b at the pitch circle."""
    spec = gc.load_spec("renzo-1967", **over)
    angles = [0.0, 17.0, 90.0]
    res = check_interference(spec, mis, angles, backlash=True, method="distance")
    sw = sweep(spec, mis, angles)
    bound = 2 * res.tolerance_mm * spec.tooth.pitch_radius / spec.tooth.base_radius
    assert np.all(np.abs(res.backlash_mm - sw.backlash_mm) < bound)
    assert np.allclose(res.backlash_mm, spec.tooth.pitch_radius * res.backlash_rad)
    assert np.allclose(res.side_gap_rad.sum(axis=0), res.backlash_rad)
    if over:
        assert np.all(res.backlash_mm < 0)  # binds: negative free turn


def test_mesh_backlash_matches_exact_free_turn_of_the_outlines():
    """industrial-m2 aligned: the mesh free turn of each flank side equals the exact 2-D
    free turn of the transverse outlines (shapely, bisection on the rotation) and the
    sweep's half backlash (the flanks touch first: no tip or fillet contact)."""
    import shapely
    from shapely.affinity import rotate

    from gearcoupling.geometry.section import transverse_section

    spec = gc.load_spec("industrial-m2")
    tol = 0.002
    res = check_interference(spec, 0.0, [0.0], backlash=True, tolerance_mm=tol, teeth=0)
    hub = shapely.Polygon(transverse_section(spec, "hub", 0.0, 1e-4))
    space = shapely.Polygon(transverse_section(spec, "sleeve", 0.0, 1e-4))

    def free(sign):
        lo, hi = 0.0, 0.02
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            inside = rotate(hub, sign * mid, origin=(0, 0), use_radians=True).within(space)
            lo, hi = (mid, hi) if inside else (lo, mid)
        return lo

    R, r_b = spec.tooth.pitch_radius, spec.tooth.base_radius
    for f, sign in ((0, -1), (1, 1)):
        assert res.side_gap_rad[f, 0] == pytest.approx(free(sign), abs=tol / r_b)
    half_sweep = 0.5 * float(sweep(spec, 0.0, [0.0]).backlash_mm[0])
    assert R * res.side_gap_rad[0, 0] == pytest.approx(half_sweep, abs=2 * tol * R / r_b)


def test_overlap_attribution_is_one_rule():
    """Points just either side of tooth centres go to that tooth and to the flank on their
    side (docs/conventions.md, Loaded analysis: tooth k centred at 2 pi k / N, ccw beyond the
    centre)."""
    from gearcoupling.interference.attribution import FLANKS, flank_index, nearest_tooth

    n = 7
    k = np.arange(-3, 4)
    eps = 0.2 * 2 * np.pi / n
    for side, sign in ((0, -1), (1, 1)):
        a = 2 * np.pi * k / n + sign * eps
        pts = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=-1) * 40.0
        assert np.array_equal(nearest_tooth(pts, n), k)
        assert np.all(flank_index(pts, k, n) == side)
        assert FLANKS[side] == ("cw", "ccw")[side]


def test_plot_returns_a_figure_accepts_ax_and_keeps_the_backend(renzo):
    import subprocess
    import sys

    code = (
        "import matplotlib, sys\n"
        "matplotlib.use('svg')\n"
        "import gearcoupling as gc\n"
        "from gearcoupling.interference import check_interference, plot_interference\n"
        "from matplotlib.figure import Figure\n"
        "res = check_interference(gc.load_spec('renzo-1967'), 1.0, [0.0, 3.0], "
        "tolerance_mm=0.05)\n"
        "fig = plot_interference(res, res.min_gap_mm)\n"
        "assert isinstance(fig, Figure) and len(fig.axes) == 2\n"
        "line = fig.axes[1].lines[0]\n"
        "assert list(line.get_ydata()) == list(res.min_gap_mm)\n"
        "own = Figure()\n"
        "axes = own.subplots(2, 1)\n"
        "assert plot_interference(res, ax=axes) is own and axes[0].lines\n"
        "assert matplotlib.get_backend() == 'svg', matplotlib.get_backend()\n"
        "assert 'matplotlib.pyplot' not in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
