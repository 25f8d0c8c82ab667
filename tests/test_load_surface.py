"""The surface load model on the exact gap field, against theory and independent checks."""

import math

import numpy as np
import pytest

from gearcoupling.clearance import sweep
from gearcoupling.clearance.design import critical_misalignment_deg
from gearcoupling.errors import ArgumentError
from gearcoupling.geometry.hub import hub_flank
from gearcoupling.geometry.sleeve import sleeve_model
from gearcoupling.loading import CantileverCompliance
from gearcoupling.loading.kernels.gapfield import (
    face_range,
    gap_field,
    lattice_windows,
    window_length,
    window_level,
    windows,
)
from gearcoupling.loading.kernels.halfspace import half_space, solve_contact
from gearcoupling.loading.models.surface import contact_modulus, patch_measures, solve_surface
from gearcoupling.spec import load_spec


@pytest.fixture(scope="module")
def renzo():
    return load_spec("renzo-1967")


def test_gap_field_minimum_is_the_sweep_gap_angle(renzo):
    """Each tooth's smallest cell gap lies just above the sweep's exact gap angle (the
    grid samples the minimum; bound: lead curvature x (cell/2)^2 + the profile slope)."""
    i = math.radians(1.0)
    sw = sweep(renzo, 1.0, [0.0])
    th = np.radians(sw.theta_deg[:, 0])
    gf = gap_field(renzo, i, th, "ccw", windows(renzo, i, np.zeros(th.size), math.inf, 96), 32)
    gmin = np.min(np.where(gf.mask, gf.gap_rad, np.inf), axis=(1, 2))
    diff_mm = (gmin - sw.gap_angle_rad[1, :, 0]) * renzo.tooth.pitch_radius
    assert np.all(diff_mm >= -1e-6)
    assert np.all(diff_mm <= 5e-4)


def test_gap_field_cut_where_the_flanks_end(renzo):
    gf = gap_field(renzo, 0.0, np.array([0.0]), "ccw",
                   windows(renzo, 0.0, [0.0], math.inf, 64), 32)
    sm = sleeve_model(renzo)
    hf = 0.5 * renzo.hub.face_width
    m = gf.mask[0]
    # aligned: the hub face ends bound the patch along the face
    assert not np.any(m[np.abs(gf.z_mm[0]) > hf + 1e-9])
    # the sphere tip cuts the depth: fewer contactable rows toward the face ends
    rows = m.sum(axis=1)
    centre, end = rows[np.argmin(np.abs(gf.z_mm[0]))], rows[np.abs(gf.z_mm[0]) < hf][0]
    assert centre > end
    tip = np.sqrt((0.5 * renzo.hub.tip.diameter) ** 2 - gf.z_mm[0][:, None] ** 2)
    assert not np.any(m & (gf.r_mm[None, :] > tip + 1e-9))
    # the depth starts at the sleeve tip chamfer edge
    assert gf.r_mm[0] > sm.r_form and gf.r_mm[0] - 0.5 * gf.ds < sm.r_form + gf.ds


def test_equilibrium_sign_and_finite(renzo):
    sw = sweep(renzo, 1.0, [0.0, 2.0])
    comp = CantileverCompliance(renzo)
    r_b = renzo.tooth.base_radius
    for T, flank in ((2000.0, "ccw"), (-2000.0, "cw")):
        res = solve_surface(renzo, sw, torque_Nm=T, compliance=comp)
        assert res["loaded_flank"] == flank
        torque = r_b * res["normal_force_N"].sum(axis=0) * 1e-3
        assert np.allclose(torque, abs(T), rtol=1e-9, atol=0)
        for name in ("normal_force_N", "max_pressure_MPa", "interior_pressure_MPa",
                     "edge_load_share", "patch_length_mm", "deflection_mm", "contact_z_mm"):
            assert np.all(np.isfinite(res[name])), name
        assert np.all(res["windup_rad"] > np.min(res["gap_angle_rad"], axis=0))
        # bending in series takes part of the wind-up
        assert np.all(res["bending_deflection_mm"][res["normal_force_N"] > 0] > 0)
    zero = solve_surface(renzo, sw, torque_Nm=0.0)
    assert np.all(zero["normal_force_N"] == 0)
    assert np.allclose(zero["windup_rad"], np.min(zero["gap_angle_rad"], axis=0))


def test_aligned_teeth_share_equally(renzo):
    sw = sweep(renzo, 0.0, [0.0])
    res = solve_surface(renzo, sw, torque_Nm=1500.0, compliance=CantileverCompliance(renzo))
    W = res["normal_force_N"][:, 0]
    assert np.max(np.abs(W / W.mean() - 1)) <= 1e-9


def _lead_curvature(spec, r):
    """Normal gap of the aligned flanks along the face at radius r, from the exact hub
    flank (Newton on the hob envelope) and the sleeve's closed form: its curvature."""
    sm = sleeve_model(spec)
    z = np.linspace(-1.0, 1.0, 21)
    pts, _ = hub_flank(spec, "cw", z, np.full_like(z, r))
    gap = sm.r_base * (np.arctan2(pts[:, 1], pts[:, 0]) + sm.half_angle(r))
    return 2.0 * np.polyfit(z, gap, 4)[2]


def test_crowned_patch_length_matches_line_contact_from_lead_curvature(renzo):
    """Aligned renzo-1967: the patch runs over the whole active depth (conformal profiles),
    so along the face it is a line contact of the lead curvature kappa under the load per
    unit depth q = W / w: half length a = sqrt(4 q / (pi E* kappa)) (Hertz, 2-D). The
    interior patch length is within 10 %; the interior pressure is compared with the
    line-contact p0 = sqrt(q E* kappa / pi): higher, because the interior peak sits where
    the pressure rises toward the edge peaks of the U-shaped profile across the depth. At
    mid-depth the peak is the line-contact p0 of the local load per unit depth within 2 %."""
    R = renzo.tooth.pitch_radius
    kappa = _lead_curvature(renzo, R)
    # Renzo's cone crowning: normal lead curvature at the pitch line sin(phi) / R_c
    assert kappa == pytest.approx(math.sin(renzo.tooth.pressure_angle) / R, rel=1e-3)
    E = contact_modulus(renzo)
    sw = sweep(renzo, 0.0, [0.0])
    for T in (500.0, 2000.0):
        res = solve_surface(renzo, sw, torque_Nm=T, keep_fields=True)
        W = res["normal_force_N"][0, 0]
        w = res["patch_width_mm"][0, 0]
        q = W / w
        a = math.sqrt(4 * q / (math.pi * E * kappa))
        assert res["patch_length_mm"][0, 0] == pytest.approx(2 * a, rel=0.10)
        p0 = math.sqrt(q * E * kappa / math.pi)
        assert res["interior_pressure_MPa"][0, 0] == pytest.approx(p0, rel=0.15)
        assert 0.1 < res["edge_load_share"][0, 0] < 0.5
        f = res["fields"][0]
        p, gf = f["pressure_MPa"][0], f["field"]
        mid = slice(p.shape[1] // 2 - 2, p.shape[1] // 2 + 2)
        q_mid = float(np.mean(p[:, mid].sum(axis=0) * gf.dz))
        p_mid = float(np.mean(p[:, mid].max(axis=0)))
        assert p_mid == pytest.approx(math.sqrt(q_mid * E * kappa / math.pi), rel=0.02)
        assert w == pytest.approx(gap_width(renzo), rel=1e-9)
        assert not res["edge_contact"].any()


def gap_width(spec):
    from gearcoupling.geometry import developed_arc
    from gearcoupling.loading.kernels.gapfield import depth_range

    lo, hi = depth_range(spec, 0.0)
    r_b = spec.tooth.base_radius
    return float(developed_arc(hi, r_b) - developed_arc(lo, r_b))


def test_edge_contact_flagged_past_the_critical_misalignment(renzo):
    crit = critical_misalignment_deg(renzo)
    assert crit is not None
    past = sweep(renzo, min(crit + 0.3, 6.0), [0.0])
    res = solve_surface(renzo, past, torque_Nm=2000.0)
    pivot = np.argmin(np.abs(np.mod(past.theta_deg[:, 0] + 90.0, 180.0) - 90.0))
    assert res["edge_contact"][pivot, 0]
    below = sweep(renzo, 1.0, [0.0])
    assert not solve_surface(renzo, below, torque_Nm=2000.0)["edge_contact"].any()
    # straight teeth, aligned: the patch runs the whole face, onto both face ends
    straight = load_spec("renzo-1967", **{"hub.crowning.kind": "none"})
    res = solve_surface(straight, sweep(straight, 0.0, [0.0]), torque_Nm=2000.0)
    assert res["edge_contact"].all()
    assert res["patch_extent_mm"][0, 0] >= straight.hub.face_width


def test_contact_moves_from_root_to_tip_across_the_pivot(renzo):
    """Near the pivot tooth the profile gap is nearly flat and tilts with theta: the sweep
    moves the first touch from the root side (sleeve tip edge) to the hub tip within a few
    degrees. Where its tip and root minima are equal (theta ~ 8° at 0.9°), the surface model
    loads both profile ends: pressure on the first and last contactable rows."""
    sw = sweep(renzo, 0.9, [0.0, 8.0, 16.0])
    kinds = sw.kind_names()[1, 0]
    assert kinds[0] == "sleeve tip edge" and kinds[2] == "tip edge"
    res = solve_surface(renzo, sw, torque_Nm=300.0, keep_fields=True)
    f = res["fields"][1]
    k = int(np.flatnonzero(f["teeth"] == 0)[0])
    p, m = f["pressure_MPa"][k], f["field"].mask[k]
    top = np.array([p[c, np.flatnonzero(m[c]).max()] if m[c].any() else 0 for c in range(len(m))])
    assert p[:, 0].max() > 0 and top.max() > 0
    assert res["patches"][0, 1] == 1


def test_two_separate_minima_give_two_patches():
    """The patch measures count separate patches (a gap with two wells: two patches)."""
    n = 48
    x = (np.arange(n) + 0.5) / n * 4.0 - 2.0
    X, Y = np.meshgrid(x, x, indexing="ij")
    gap = np.minimum((X - 1) ** 2 + Y**2, (X + 1) ** 2 + Y**2) / 40.0
    hs = half_space((n, n), x[1] - x[0], x[1] - x[0], 1.13e5)
    sol = solve_contact(hs, gap[None], load_N=200.0)

    class F:
        mask = np.ones((1, n, n), bool)
        face_cut = np.zeros((1, n, n), bool)
        dz = ds = x[1] - x[0]
        z_mm = x[None, :]
        s_mm = x

    meas = patch_measures(F, sol.pressure_MPa, 0.2)
    assert meas["patches"][0] == 2


def test_bad_input(renzo):
    sw = sweep(renzo, 1.0, [0.0])
    with pytest.raises(ArgumentError, match="grid"):
        solve_surface(renzo, sw, torque_Nm=100.0, grid=(2, 40))
    with pytest.raises(ArgumentError, match="torque_Nm"):
        solve_surface(renzo, sw, torque_Nm=float("nan"))
    with pytest.raises(ArgumentError, match="gap_offset_rad"):
        solve_surface(renzo, sw, torque_Nm=100.0, gap_offset_rad=np.zeros(3))
    with pytest.raises(ArgumentError, match="loaded_flank"):
        solve_surface(renzo, sw, torque_Nm=100.0, loaded_flank="left")


def test_load_dispatches_to_the_surface_model(renzo):
    from gearcoupling.loading import load

    res = load(renzo, 1.0, [0.0], model="surface", torque_Nm=-1500.0)
    assert res.model == "surface" and res.loaded_flank == "cw"
    assert res.windup_rad[0] < 0
    torque = np.sum(res.tangential_force_N, axis=0) * renzo.tooth.pitch_radius * 1e-3
    assert torque[0] == pytest.approx(1500.0, rel=1e-9)
    assert np.all(res.interior_pressure_MPa <= res.max_pressure_MPa + 1e-9)
    assert np.all(np.isfinite(res.max_pressure_MPa))


def test_gap_offsets_enter_as_rigid_rotations(renzo):
    """A common offset only shifts the wind-up; a tooth made proud (negative offset) takes
    more load, one set back less (index errors, docs/conventions.md, Loaded analysis)."""
    sw = sweep(renzo, 1.0, [0.0])
    base = solve_surface(renzo, sw, torque_Nm=2000.0)
    N = renzo.tooth.teeth
    shifted = solve_surface(renzo, sw, torque_Nm=2000.0, gap_offset_rad=np.full(N, 1e-4))
    assert shifted["windup_rad"][0] == pytest.approx(base["windup_rad"][0] + 1e-4, rel=1e-6)
    assert np.allclose(shifted["normal_force_N"], base["normal_force_N"], rtol=1e-4,
                       atol=1e-6 * base["normal_force_N"].max())
    k = int(np.argmax(base["normal_force_N"][:, 0]))
    off = np.zeros((2, N))
    off[1, k] = -2e-5  # ccw row: the loaded flank
    proud = solve_surface(renzo, sw, torque_Nm=2000.0, gap_offset_rad=off)
    assert proud["normal_force_N"][k, 0] > base["normal_force_N"][k, 0] * 1.05
    off[1, k] = 2e-5
    back = solve_surface(renzo, sw, torque_Nm=2000.0, gap_offset_rad=off)
    assert back["normal_force_N"][k, 0] < base["normal_force_N"][k, 0] * 0.95


@pytest.mark.slow
def test_warm_started_turn_equals_cold_poses(renzo):
    """A turn solves each rotation from its neighbour (pressure, wind-up, teeth, windows);
    each pose solved alone starts cold (coarse pass). The windows follow a rule on the
    answer, so both solve the same discrete problem: they agree to the solver's
    tolerance (1e-6 relative change per iteration; measured: loads 4e-7, interior
    pressure 1e-6, wind-up 1e-8 relative)."""
    comp = CantileverCompliance(renzo)
    angles = [0.0, 0.9, 1.8, 2.7, 3.6, 4.5]
    turn = solve_surface(renzo, sweep(renzo, 1.0, angles), torque_Nm=2000.0, compliance=comp)
    cold = [solve_surface(renzo, sweep(renzo, 1.0, [a]), torque_Nm=2000.0, compliance=comp)
            for a in angles]
    for name, rtol in (("normal_force_N", 1e-5), ("interior_pressure_MPa", 1e-5),
                       ("windup_rad", 1e-6)):
        alone = np.stack([c[name][..., 0] for c in cold], axis=-1)
        scale = np.max(np.abs(alone))
        assert np.max(np.abs(turn[name] - alone)) <= rtol * scale, name


def test_rotations_a_pitch_apart_are_one_pose_renumbered(renzo):
    """Ideal teeth: rotation psi + k pitches is rotation psi with the teeth renumbered by
    k; the turn solves it once. Checked against the pose solved on its own."""
    pitch = 360.0 / renzo.tooth.teeth
    angles = [1.0, 1.0 + 3 * pitch]
    res = solve_surface(renzo, sweep(renzo, 1.0, angles), torque_Nm=2000.0)
    W = res["normal_force_N"]
    assert np.allclose(W[:, 1], np.roll(W[:, 0], -3), rtol=0, atol=1e-9 * W.max())
    alone = solve_surface(renzo, sweep(renzo, 1.0, angles[1:]), torque_Nm=2000.0)
    assert np.max(np.abs(alone["normal_force_N"][:, 0] - W[:, 1])) <= 1e-5 * W.max()
    assert alone["windup_rad"][0] == pytest.approx(res["windup_rad"][1], rel=1e-6)


def test_progress_reports_each_solved_pose(renzo):
    calls = []
    solve_surface(renzo, sweep(renzo, 1.0, [0.0, 1.0, 2.0]), torque_Nm=1000.0,
                  progress=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 3), (2, 3), (3, 3)]


def test_window_lattices_are_symmetric_with_the_face_ends_on_cell_edges(renzo):
    """Windows of one level lie on one lattice: cell edges at whole multiples of the cell
    size, so mirrored teeth see mirrored cells and the face range ends on a cell edge; the
    level of a length is the shortest at least that long."""
    i = math.radians(1.0)
    Z = face_range(renzo, i)
    for level in (0, 3, 9):
        z, _ = lattice_windows(renzo, i, level, [-3.0, 3.0, 40.0], 48)
        dz = z[0, 1] - z[0, 0]
        edges = z[:, 0] - 0.5 * dz
        assert np.allclose(edges / dz, np.round(edges / dz), atol=1e-9)
        assert Z / dz == pytest.approx(round(Z / dz), abs=1e-9)
        assert z[0, 0] == pytest.approx(-z[1, -1], abs=1e-9)  # mirrored centres, mirrored
        assert z[2, -1] <= Z + 2 * dz  # a window past the face end is moved back onto it
    for length in (0.5, 2.0, 7.0):
        k = window_level(renzo, i, length, 48)
        assert window_length(renzo, i, k, 48) >= length > window_length(renzo, i, k + 1, 48)


def test_a_full_row_cache_gives_the_same_capacity(renzo, monkeypatch):
    """The solver keeps each tooth's gap-field rows (``FIELD_ROWS`` of them); when a call
    finds the cache full it starts again with every row it needs. A cache of 16 rows, full
    on almost every call of a capacity search, gives the same capacity as the default one
    (the rows do not depend on the cache; a KeyError on a 260-tooth spec before)."""
    from gearcoupling.loading import capacity
    from gearcoupling.loading.models import surface

    full = capacity(renzo, 1.0)
    monkeypatch.setattr(surface, "FIELD_ROWS", 16)
    small = capacity(renzo, 1.0)
    assert small.capacity_Nm == pytest.approx(full.capacity_Nm, rel=1e-12)
    assert small.solves == full.solves
