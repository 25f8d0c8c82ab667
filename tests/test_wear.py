"""Wear over life (docs/wear.md): Archard's law globally, the time-coefficient scaling, the
step and grid convergence, the run-in of a crown under reciprocating sliding, physical
sense, the files and bad input. Coarse grids where the property does not depend on them."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.geometry import hub_to_sleeve, sleeve_model
from gearcoupling.wear import REGIMES, DutyPoint, WearSettings, wear, write_wear
from gearcoupling.wear.history import tooth_losses
from gearcoupling.wear.model import PointSolver, WearMaps, flank_grids
from gearcoupling.wear.settings import Accuracy

COARSE = {"grid": (16, 8), "phases": 2}


@pytest.fixture(scope="module")
def short(renzo):
    """A few steps of renzo-1967 at 1°, keeping every step's solved poses."""
    return wear(renzo, 1.0, 2000.0, 1800.0, 60.0, step_fraction=0.5, keep=True, **COARSE)


def _slip_speed(spec, mis_rad, theta, flank, z, r):
    """Sliding speed (mm/rad) of the hub point at the sleeve cells ``(z, r)`` of a tooth at
    turning angle ``theta``, by central differences of its position in the sleeve frame and
    a flank normal from differences of the sleeve flank: independent of the model's
    kernel."""
    sm = sleeve_model(spec)
    a = -sm.half_angle(r)
    q = np.stack(np.broadcast_arrays(r * np.cos(a), r * np.sin(a), z), axis=-1)
    th = math.pi - theta if flank == 1 else theta
    p_hub = q @ hub_to_sleeve(mis_rad, th)  # P^T q, rows as vectors
    eps = 1e-5
    v = (p_hub @ hub_to_sleeve(mis_rad, th + eps).T - p_hub @ hub_to_sleeve(mis_rad, th - eps).T
         ) / (2 * eps)
    dr = 1e-6
    a2 = -sm.half_angle(r + dr)
    t = np.stack([(r + dr) * np.cos(a2) - r * np.cos(a), (r + dr) * np.sin(a2) - r * np.sin(a)],
                 axis=-1)
    n = np.stack([-t[..., 1], t[..., 0]], axis=-1)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    vn = v[..., 0] * n[..., 0] + v[..., 1] * n[..., 1]
    return np.sqrt(np.maximum(np.sum(v * v, axis=-1) - vn * vn, 0.0))


def test_archard_global_volume_equals_k_times_load_times_sliding(renzo, short):
    """The worn volume of all flanks equals k x sum(normal force x sliding distance) over
    the history, the sum taken independently from every step's solved pressures (sliding
    by finite differences of the poses), to 1e-6."""
    res = short
    assert res.steps >= 3
    k = res.settings.coefficient_mm3_per_Nm
    p = res.duty[0]
    M = renzo.tooth.teeth * COARSE["phases"]
    mis = math.radians(p.misalignment_deg)
    theta = np.radians(gc.sweep(renzo, p.misalignment_deg,
                                np.arange(M) * 360.0 / M).theta_deg)
    work = 0.0  # N·mm of every pressure cell times its sliding, over the history
    for dx, turns in res.steps_kept:
        (fields,) = turns
        rev = 0.0
        for j, teeth, gf, pressure, _, _ in fields:
            r = np.sqrt(gf.base_radius ** 2 + 2 * gf.base_radius * gf.s_mm)
            for i, tooth in enumerate(teeth):
                v = _slip_speed(renzo, mis, theta[tooth, j], 1, gf.z_mm[i][:, None],
                                r[None, :])
                rev += float(np.sum(pressure[i] * v)) * gf.dz * gf.ds * 2 * math.pi / M
        work += dx / k * p.revolutions_per_hour * rev  # hours x rev/h x N·mm per rev
    volume = sum(float(np.sum(m)) * g.area_mm2 for m, g in
                 ((res.hub_depth_mm, res.hub_grid), (res.sleeve_depth_mm, res.sleeve_grid)))
    expected = 2 * k * 1e-3 * work  # hub and sleeve, k in mm³/(N·m)
    assert volume == pytest.approx(expected, rel=1e-6)
    assert res.hub_depth_mm.shape[1] == 1  # ideal teeth: one map for every tooth


def test_twice_the_coefficient_for_half_the_time_is_the_same_history(renzo):
    """The history is a function of k t: 2k over t/2 equals k over t (depth maps 1e-9)."""
    a = wear(renzo, 1.0, 2000.0, 1800.0, 40.0, coefficient_mm3_per_Nm=1e-8, **COARSE)
    b = wear(renzo, 1.0, 2000.0, 1800.0, 20.0, coefficient_mm3_per_Nm=2e-8, **COARSE)
    assert a.steps == b.steps >= 2
    for x, y in ((a.hub_depth_mm, b.hub_depth_mm), (a.sleeve_depth_mm, b.sleeve_depth_mm)):
        assert np.max(np.abs(x - y)) <= 1e-9 * np.max(np.abs(x))
    assert np.allclose(a.hours, 2 * b.hours, rtol=1e-12)
    assert a.life_h == pytest.approx(2 * b.life_h, rel=1e-12)


@pytest.mark.slow
def test_halving_the_step_changes_the_life_by_less_than_2_percent(renzo):
    """The life to the default wear limit at the default step and at half of it (the
    whole life, about 90 and 160 steps, on a coarse grid and one rotation per pitch)."""
    kw = {"grid": (16, 8), "phases": 1}
    default = wear(renzo, 1.0, 2260.0, 1800.0, 20_000.0, **kw)
    half = wear(renzo, 1.0, 2260.0, 1800.0, 20_000.0,
                step_fraction=0.5 * Accuracy().step_fraction, **kw)
    assert default.limit_reached and half.limit_reached
    assert half.steps > 1.5 * default.steps
    assert abs(half.life_h / default.life_h - 1) < 0.02


@pytest.mark.slow
def test_the_next_finer_flank_grid_changes_the_largest_depth_by_less_than_5_percent(renzo):
    depth = []
    for grid in (Accuracy().grid, (32, 24)):
        res = wear(renzo, 1.0, 2260.0, 1800.0, 100.0, grid=grid, phases=2)
        depth.append(max(np.max(res.hub_max_mm[-1]), np.max(res.sleeve_max_mm[-1])))
    assert abs(depth[1] / depth[0] - 1) < 0.05


def _face_sigma(res) -> list[float]:
    """Per state, the standard deviation of the (one, aligned) tooth's load along the face
    over the half-length of its patch: 0.5 for Hertz's semi-ellipse, 1/sqrt(3) for a
    uniform pressure."""
    out = []
    for _, turns in res.steps_kept:
        (fields,) = turns
        gf, p = fields[0][2], fields[0][3][0]
        w = np.sum(p, axis=1)
        z = gf.z_mm[0]
        on = z[w > 0]
        mean = np.sum(w * z) / np.sum(w)
        sigma = math.sqrt(np.sum(w * (z - mean) ** 2) / np.sum(w))
        out.append(sigma / (0.5 * (on[-1] - on[0] + gf.dz)))
    return out


@pytest.mark.slow
def test_a_crown_under_reciprocating_sliding_wears_toward_uniform_pressure(renzo):
    """A circular crown at 0° with an axial float (pure reciprocating axial sliding) and a
    sleeve that does not wear: the crown wears toward uniform pressure along the face
    (Archard's run-in limit: uniform wear needs uniform pressure where the sliding is
    uniform). The peak pressure falls at every step and the load along the face goes from
    Hertz's semi-ellipse toward a uniform one (its standard deviation over the patch's
    half-length from 0.5 toward 1/sqrt(3))."""
    res = wear(renzo, 0.0, 500.0, 1800.0, 30.0, axial_float_mm=1.0, sleeve_factor=0.0,
               grid=(48, 8), phases=1, step_fraction=0.5, keep=True)
    peak = res.stats["max_interior_pressure_MPa"][:, 0]
    assert res.steps >= 5
    assert np.all(np.diff(peak) < 0)
    assert peak[-1] < 0.25 * peak[0]
    sigma = _face_sigma(res)
    uniform = 1 / math.sqrt(3)
    assert abs(sigma[0] - 0.5) < 0.07  # the unworn crown: Hertz's line contact, near enough
    assert abs(sigma[-1] - uniform) < 0.1 * uniform
    assert abs(sigma[-1] - uniform) < 0.5 * abs(sigma[0] - uniform)
    assert np.max(res.sleeve_depth_mm) == 0.0


def test_no_wear_without_sliding_and_none_where_nothing_presses(renzo):
    """At 0° nothing slides: loaded teeth, no wear, the life is the cap. At 1° the unloaded
    flank does not wear."""
    still = wear(renzo, 0.0, 2000.0, 1800.0, 100.0, **COARSE)
    assert still.stats["max_tooth_load_N"][0, 0] > 0
    assert np.max(still.hub_depth_mm) == 0.0 and np.max(still.sleeve_depth_mm) == 0.0
    assert still.life_basis == "no wear" and still.life_h == 1e9
    res = wear(renzo, 1.0, 2000.0, 1800.0, 20.0, **COARSE)
    assert np.max(res.hub_depth_mm[1]) > 0 and np.max(res.hub_depth_mm[0]) == 0.0
    assert np.max(res.sleeve_depth_mm[0]) == 0.0


def test_straight_teeth_wear_their_face_ends_first(renzo):
    spec = renzo.replace(**{"hub.crowning.kind": "none"})
    res = wear(spec, 1.0, 2000.0, 1800.0, 20.0, **COARSE)
    depth = res.hub_maps[-1, 1]  # (nz, ns) of the loaded flank
    z = res.hub_grid.z_mm
    half = 0.5 * spec.hub.face_width
    ends = np.max(depth[np.abs(z) > 0.8 * half])
    middle = np.max(depth[np.abs(z) < 0.5 * half])
    assert ends > 5 * middle


def test_backlash_grows_by_the_worn_depth_over_cos_phi(renzo):
    """A uniform depth h on the hub and sleeve flanks of both sides opens each flank's gap
    by 2h along the normal: the backlash, measured on the worn whole-face grids, grows by
    4 h R / r_b at the pitch circle."""
    point = DutyPoint(1.0, 2000.0, 1800.0, 1.0)
    acc = Accuracy.checked(grid=COARSE["grid"], phases=COARSE["phases"])
    hg, sg = flank_grids(renzo, (point,), acc.grid)
    zero = WearMaps(np.zeros((2, 1, hg.nz, hg.ns)), np.zeros((2, 1, sg.nz, sg.ns)), hg, sg)
    solver = PointSolver(renzo, point, acc, zero)
    h = 0.013
    worn = WearMaps(zero.hub + h, zero.sleeve + h, hg, sg)
    fields: dict = {}
    grown = solver.backlash_mm(worn, fields) - solver.backlash_mm(zero, fields)
    R, r_b = renzo.tooth.pitch_radius, renzo.tooth.base_radius
    assert grown == pytest.approx(4 * h * R / r_b, rel=1e-9)
    hub, sleeve = tooth_losses(renzo, worn)
    assert hub[0] == pytest.approx(2 * h * R / r_b, rel=1e-12)
    assert sleeve[0] == pytest.approx(2 * h * R / r_b, rel=1e-12)


def test_backlash_of_a_history_grows_with_the_thinning(short):
    """The backlash grows with the wear, by no more than both members' thinning."""
    b = short.backlash_mm[:, 0]
    assert np.all(np.diff(b) >= -1e-9)
    assert b[-1] - b[0] <= short.thickness_loss_mm[-1].sum() + 1e-9
    assert b[-1] > b[0]


def test_reversing_torque_wears_both_flanks(renzo):
    res = wear(renzo, duty=[(1.0, 2000.0, 1800.0, 10.0), (1.0, -2000.0, 1800.0, 10.0)],
               **COARSE)
    assert np.max(res.hub_depth_mm[0]) > 0 and np.max(res.hub_depth_mm[1]) > 0
    assert res.backlash_mm.shape == (res.steps + 1, 2)


def test_index_errors_make_the_teeth_wear_each_on_its_own(renzo):
    off = np.zeros(renzo.tooth.teeth)
    off[0] = -2e-5  # tooth 0 touches first
    res = wear(renzo, 1.0, 2000.0, 1800.0, 5.0, gap_offset_rad=off, grid=(16, 8), phases=1)
    per_tooth = np.max(res.hub_depth_mm[1], axis=(1, 2))
    assert per_tooth.shape == (renzo.tooth.teeth,)
    assert np.argmax(per_tooth) == 0


def test_partial_slip_is_said(renzo):
    """At 0° a small axial float slides less than the contact's half-width (fretting), a
    large one more (gross slip)."""
    small = wear(renzo, 0.0, 500.0, 1800.0, 1.0, axial_float_mm=0.02, grid=(24, 8), phases=1)
    large = wear(renzo, 0.0, 500.0, 1800.0, 1.0, axial_float_mm=3.0, grid=(24, 8), phases=1)
    assert small.summary()["partial_slip_share"] == pytest.approx(1.0)
    assert any("partial slip" in n for n in small.summary()["notes"])
    assert large.summary()["partial_slip_share"] == 0.0


def test_summary_rows_and_files_are_finite(short, tmp_path):
    s = short.summary()
    numbers = []

    def walk(v):
        if isinstance(v, dict):
            for x in v.values():
                walk(x)
        elif isinstance(v, list | tuple):
            for x in v:
                walk(x)
        elif isinstance(v, int | float) and not isinstance(v, bool):
            numbers.append(float(v))

    walk(s)
    assert numbers and all(math.isfinite(x) for x in numbers)
    lo, hi = s["life_band_h"]
    k_lo, k_hi = s["coefficient_band_mm3_per_Nm"]
    assert lo == pytest.approx(s["life_h"] * s["coefficient_mm3_per_Nm"] / k_hi)
    assert hi == pytest.approx(s["life_h"] * s["coefficient_mm3_per_Nm"] / k_lo)
    paths = write_wear(short, tmp_path, plots=False)
    assert [p.name for p in paths] == ["wear.csv", "wear_depth.csv", "wear_summary.json"]
    assert json.loads(paths[2].read_text())["steps"] == short.steps
    df = short.to_dataframe()
    assert len(df) == short.steps + 1 and np.all(np.isfinite(df["q"]))


def test_coefficients_and_the_wear_table(renzo):
    for r in REGIMES.values():
        assert 0 < r.low < r.nominal < r.high and r.source
    s = WearSettings.from_spec(renzo.replace(**{"wear.regime": "oil",
                                                 "wear.limit_fraction": 0.2}))
    assert s.coefficient_mm3_per_Nm == REGIMES["oil"].nominal and s.limit_fraction == 0.2
    s = WearSettings.from_spec(renzo, coefficient_mm3_per_Nm=1e-12)
    assert s.band_mm3_per_Nm[0] == 1e-12  # the band widened to hold the coefficient


@pytest.mark.parametrize("kwargs, field", [
    ({"hours": -5.0}, "hours"),
    ({"hours": 0.0}, "hours"),
    ({"speed_rpm": 0.0}, "speed_rpm"),
    ({"speed_rpm": math.nan}, "speed_rpm"),
    ({"coefficient_mm3_per_Nm": 0.0}, "coefficient_mm3_per_Nm"),
    ({"coefficient_mm3_per_Nm": -1e-8}, "coefficient_mm3_per_Nm"),
    ({"regime": "water"}, "regime"),
    ({"limit_fraction": 1.5}, "limit_fraction"),
    ({"torque_Nm": 0.0}, "torque_Nm"),
    ({"misalignment_deg": 7.0}, "misalignment_deg"),
    ({"step_fraction": 0.0}, "step_fraction"),
    ({"grid": (2, 8)}, "grid"),
    ({"phases": 0}, "phases"),
    ({"gap_offset_rad": [1.0, 2.0]}, "gap_offset_rad"),
    ({"duty": [(1.0, 2000.0, 1800.0)]}, "duty[0]"),
    ({"duty": [(1.0, 2000.0, -1.0, 10.0)]}, "duty[0].speed_rpm"),
    ({"duty": [(1.0, 2000.0, 1800.0, 10.0)]}, "misalignment_deg"),
])
def test_bad_arguments_are_refused_naming_the_field(renzo, kwargs, field):
    args = {"misalignment_deg": 1.0, "torque_Nm": 2000.0, "speed_rpm": 1800.0, "hours": 10.0}
    if "duty" in kwargs and field != "misalignment_deg":  # a duty instead of the point
        args = {"hours": 10.0}
    args.update(kwargs)
    with pytest.raises(gc.ArgumentError) as err:
        wear(renzo, **args)
    assert err.value.field == field


@pytest.mark.parametrize("key, value", [("coefficient_mm3_per_Nm", -1.0),
                                        ("regime", "sand"), ("sleeve_factor", -1.0),
                                        ("limit_fraction", 0.0),
                                        ("coefficient_band_mm3_per_Nm", [1e-7, 1e-9]),
                                        ("required_life_h", 0.0)])
def test_bad_wear_table_values_are_spec_errors_naming_the_key(renzo, key, value):
    spec = renzo.replace(**{f"wear.{key}": value})
    with pytest.raises(gc.SpecError) as err:
        wear(spec, 1.0, 2000.0, 1800.0, 10.0)
    assert err.value.field == f"wear.{key}"


def test_unknown_wear_key_is_refused_when_the_spec_is_read(renzo):
    with pytest.raises(gc.SpecError, match=r"wear\.coeficient"):
        renzo.replace(**{"wear.coeficient": 1e-8})


def test_cli_writes_the_files(tmp_path, capsys):
    out = tmp_path / "w"
    code = main(["wear", "renzo-1967", "--hours", "40", "--speed", "1800", "--grid", "16x8",
                 "--phases", "2", "--no-plots", "-o", str(out),
                 "--set", "wear.required_life_h=1e6"])
    stdout = capsys.readouterr().out
    assert code == 1, stdout  # the life falls short of the required: a design finding
    assert "FAIL: wear life" in stdout
    names = sorted(p.name for p in out.iterdir())
    assert names == ["wear.csv", "wear_depth.csv", "wear_summary.json"]
    summary = json.loads((out / "wear_summary.json").read_text())
    assert summary["meets_required_life"] is False


@pytest.mark.parametrize("args, text", [
    (("--hours", "-1", "--speed", "1800"), "--hours"),
    (("--hours", "10", "--speed", "0"), "--speed"),
    (("--point", "1,2000,1800", "--hours", "10"), "--point"),
    (("--hours", "10", "--speed", "1800", "--grid", "big"), "--grid"),
    (("--hours", "10", "--speed", "1800", "--phases", "0"), "--phases"),
])
def test_cli_bad_input_exits_2_naming_the_option(tmp_path, capsys, monkeypatch, args, text):
    monkeypatch.chdir(tmp_path)
    code = main(["wear", "renzo-1967", *args, "-o", str(tmp_path / "w")])
    err = capsys.readouterr().err
    assert code == 2 and text in err, err
    assert not (tmp_path / "w").exists()
