"""Inspection of synthetic measured hubs with known errors (index, thickness, crown),
noise, random placement, partial scans, wrong parts, units and bad files."""

import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.geometry.hub import hub_flank_model
from gearcoupling.hob import measuring_charts
from gearcoupling.inspection import RegistrationError, compare_part
from gearcoupling.inspection.surface import deviation, flank_table
from inspection_synth import label_map, random_placement, synthetic_hub

UM = 1e-3


@pytest.fixture(scope="module")
def renzo():
    return gc.load_spec("renzo-1967")


def test_tabulated_flank_matches_exact_kernel_and_normal_offsets(renzo):
    table = flank_table(renzo)
    assert table.table_error_mm < 1e-6
    m = table.model
    rng = np.random.default_rng(5)
    z = rng.uniform(-table.half_lead, table.half_lead, 500)
    r = rng.uniform(table.r_lo, table.r_hi, 500)
    for flank in ("cw", "ccw"):
        p, n, _ = hub_flank_model(m, flank, z, r)
        for delta in (-0.02, 0.0, 0.01):
            dev = deviation(table, p + delta * n)
            # a normal offset moves (z, r) too: second-order error ~ delta^2 / radius
            assert np.max(np.abs(dev.d - delta)) < 1e-6 + 2 * delta**2
            assert np.all(dev.flank == (flank == "ccw")) and np.all(dev.tooth == 0)


def test_index_errors_thickness_noise_and_random_placement_are_recovered(renzo):
    N = renzo.tooth.teeth
    index = {3: 0.020, 17: -0.012}
    thick, noise = 0.010, 0.001
    pts = synthetic_hub(renzo, index_mm=index, thickness_mm=thick, noise_mm=noise)
    moved, Rp = random_placement(pts)
    rep = compare_part(renzo, moved)
    assert rep.part["teeth_measured"] == N and len(rep.teeth) == N
    labels, flipped = label_map(rep, Rp, N)
    sgn = -1.0 if flipped else 1.0  # a flipped axis reverses the polar angle
    for f in ("cw", "ccw"):
        fpk = rep.flank[f]["Fpk_mm"]
        for k, eps in index.items():
            others = np.delete(fpk, [labels[j] for j in index])
            # the robust fit keeps the two teeth from pulling the axis (plain least squares
            # leaked ~2 eps / N = 0.8 um into the other teeth)
            assert fpk[labels[k]] - np.median(others) == pytest.approx(sgn * eps, abs=0.6 * UM)
            assert rep.flank[f]["fpt_mm"][labels[k]] == pytest.approx(sgn * eps, abs=0.6 * UM)
        assert np.max(np.abs(others - np.median(others))) < 1.5 * UM
    # thickness: every tooth within 1.5 um, the mean within 0.5 um
    assert rep.part["thickness_dev_mean_mm"] == pytest.approx(thick, abs=0.5 * UM)
    assert np.max(np.abs(rep.tooth["thickness_dev_mm"] - thick)) < 1.5 * UM
    # crown unchanged: nominal C_beta within 1 um on every flank
    cnom = measuring_charts(renzo).values["cw"]["C_beta_mm"]
    for f in ("cw", "ccw"):
        assert np.max(np.abs(rep.flank[f]["C_beta_mm"] - cnom)) < 1.0 * UM
    # F_p is the index error range; the known errors dominate the registration residual
    assert rep.part["F_p_mm"] == pytest.approx(0.032, abs=1.5 * UM)
    assert rep.registration.rms_mm < 0.01


def test_changed_crown_radius_is_recovered_as_crown_height(renzo):
    bigger = renzo.replace(**{"hub.crowning.radius": 1.25 * renzo.hub.crowning.radius})
    pts = synthetic_hub(bigger, noise_mm=0.0005)
    rep = compare_part(renzo, random_placement(pts, seed=11)[0])
    want = measuring_charts(bigger).values["cw"]["C_beta_mm"]
    nominal = measuring_charts(renzo).values["cw"]["C_beta_mm"]
    assert want < nominal - 0.01  # a real change of > 10 um
    for f in ("cw", "ccw"):
        c = rep.flank[f]["C_beta_mm"]
        assert np.median(c) == pytest.approx(want, abs=0.5 * UM)
        assert np.max(np.abs(c - want)) < 1.5 * UM
        assert np.max(np.abs(rep.flank[f]["crown_position_mm"])) < 0.2


def test_partial_scan_reports_only_the_scanned_teeth(renzo):
    pts = synthetic_hub(renzo, teeth=[5, 6, 7, 8, 9], noise_mm=0.0005)
    rep = compare_part(renzo, pts)
    assert rep.teeth.tolist() == [5, 6, 7, 8, 9]
    assert rep.registration.coarse.startswith("none")
    # single pitch only where the previous tooth was measured
    assert np.isnan(rep.flank["cw"]["fpt_mm"][0]) and np.all(
        np.abs(rep.flank["cw"]["fpt_mm"][1:]) < 1 * UM)


def test_part_of_another_spec_is_refused_with_the_reason(renzo):
    other = synthetic_hub(gc.load_spec("industrial-m2"), per_flank=60)
    with pytest.raises(RegistrationError, match="tip radius"):
        compare_part(renzo, other)
    same_size = renzo.replace(**{"tooth.teeth": 48, "tooth.module": 2.54 * 50 / 48})
    pts = synthetic_hub(same_size, per_flank=100)
    with pytest.raises(RegistrationError, match=r"repeats 48 times per turn.*50 teeth"):
        compare_part(renzo, random_placement(pts)[0])


def test_inch_scan_is_detected_by_its_scale(renzo, tmp_path):
    pts = synthetic_hub(renzo, per_flank=80) / 25.4
    with pytest.raises(gc.ArgumentError, match="inches") as err:
        compare_part(renzo, pts)
    assert err.value.field == "units"
    rep = compare_part(renzo, pts, units="in")
    assert rep.part["teeth_measured"] == renzo.tooth.teeth


@pytest.mark.parametrize("content, words", [
    ("", "none"), ("# only a comment\n", "none"), ("x y z\n1 2\n", "three coordinates"),
    ("1 2 3\n4 nan 6\n", "NaN"), ("1 2 3\nabc def ghi\n", "numeric"),
])
def test_bad_point_files_give_clear_errors(renzo, tmp_path, content, words):
    path = tmp_path / "scan.xyz"
    path.write_text(content)
    with pytest.raises(gc.ArgumentError, match=words):
        compare_part(renzo, path)


def test_unreadable_files_give_clear_errors(renzo, tmp_path, capsys):
    bad_stl = tmp_path / "broken.stl"
    bad_stl.write_bytes(b"\x00\x01garbage" * 3)
    binary_xyz = tmp_path / "scan.xyz"
    binary_xyz.write_bytes(bytes(range(256)) * 4)
    for path in (tmp_path / "missing.ply", bad_stl, binary_xyz, tmp_path / "scan.docx"):
        if path.suffix == ".docx":
            path.write_text("x")
        with pytest.raises(gc.ArgumentError):
            compare_part(renzo, path)
        assert main(["compare", "renzo-1967", str(path), "-o", str(tmp_path / "o")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert err[-1].startswith("gearcoupling: error: file = ")
        assert not any("Traceback" in line for line in err)
    assert not (tmp_path / "o" / "inspection.json").exists()


def test_generated_mesh_matches_its_nominal(tmp_path):
    spec = gc.load_spec("industrial-m2")
    mesh = gc.build_part(spec, "hub", tolerance_mm=0.01)
    path = tmp_path / "hub.stl"
    mesh.export(path)
    rep = compare_part(spec, path)
    assert rep.part["teeth_measured"] == spec.tooth.teeth
    # vertices lie on the exact surface (float32 STL: ~1e-5 mm rounding)
    assert rep.registration.rms_mm < 1e-4
    assert rep.part["F_p_mm"] < 2e-4 and abs(rep.part["thickness_dev_mean_mm"]) < 1e-4


def test_two_parts_compare_as_geometry_regression(renzo, tmp_path, capsys):
    a = synthetic_hub(renzo, per_flank=150, noise_mm=0.0003)
    b = synthetic_hub(renzo, per_flank=150, thickness_mm=0.008, noise_mm=0.0003, seed=2)
    np.savetxt(tmp_path / "a.xyz", a)
    np.savetxt(tmp_path / "b.csv", b, delimiter=",", header="x,y,z", comments="")
    cmp = compare_part(renzo, tmp_path / "a.xyz", tmp_path / "b.csv")
    diffs = np.array([row["thickness_dev_diff_mm"] for row in cmp.rows()])
    assert len(diffs) == renzo.tooth.teeth
    assert np.max(np.abs(diffs - 0.008)) < 1.0 * UM
    # every flank value is compared: each flank moved out by 4 um * cos(phi) along its normal
    offsets = np.array([[row[f"offset_{f}_diff_mm"] for f in ("cw", "ccw")] for row in cmp.rows()])
    np.testing.assert_allclose(offsets, 0.004 * math.cos(renzo.tooth.pressure_angle), atol=UM)
    assert max(abs(row["fpt_cw_diff_mm"]) for row in cmp.rows()) < UM
    out = tmp_path / "cmp"
    assert main(["compare", "renzo-1967", str(tmp_path / "a.xyz"), str(tmp_path / "b.csv"),
                 "-o", str(out)]) == 0
    summary = json.loads((out / "comparison.json").read_text())
    assert summary["max_abs_diff"]["thickness_dev_diff_mm"] == pytest.approx(0.008,
                                                                             abs=1.0 * UM)


def test_cli_limits_fail_the_teeth_with_index_errors(renzo, tmp_path, capsys):
    pts = synthetic_hub(renzo, per_flank=150, index_mm={7: 0.015}, noise_mm=0.0005)
    np.savetxt(tmp_path / "scan.xyz", pts)
    out = tmp_path / "rep"
    assert main(["compare", "renzo-1967", str(tmp_path / "scan.xyz"), "--limit", "fpt=0.008",
                 "--limit", "Fp=0.05", "-o", str(out)]) == 1
    summary = json.loads((out / "inspection.json").read_text())
    # tooth 7 (f_pt = +15 um) and tooth 8 (f_pt = -15 um after it) fail, nothing else
    assert summary["failed_teeth"] == [7, 8]
    assert summary["part"]["F_p_pass"] is True
    for name in ("inspection.csv", "inspection.png", "deviation_map.png", "deviation.ply"):
        assert (out / name).stat().st_size > 0
    assert main(["compare", "renzo-1967", str(tmp_path / "scan.xyz"), "--limit", "bogus=1",
                 "-o", str(out)]) == 2
    assert main(["compare", "renzo-1967", str(tmp_path / "scan.xyz"), "--limit", "fpt=-1",
                 "-o", str(out)]) == 2
    assert math.isfinite(summary["registration"]["rms_mm"])


def test_spec_inspection_limits_are_read_and_used(renzo, tmp_path):
    from gearcoupling.spec import resolve_spec_path

    text = resolve_spec_path("renzo-1967").read_text()
    path = tmp_path / "limits.toml"
    path.write_text(text + "\n[inspection]\nfpt = 0.0003\nFp = 0.002\n")
    spec = gc.load_spec(path)
    assert spec.inspection.fpt == pytest.approx(0.0003 * 25.4, rel=1e-12)  # inch file
    assert spec.inspection.as_dict() == pytest.approx({"fpt": 0.00762, "Fp": 0.0508})
    path.write_text(text + "\n[inspection]\nfp = 0.0003\n")
    with pytest.raises(gc.SpecError, match=r"inspection\.fp "):
        gc.load_spec(path)
    pts = synthetic_hub(renzo, per_flank=150, index_mm={7: 0.015}, noise_mm=0.0005)
    rep = compare_part(spec, pts)
    assert rep.summary()["failed_teeth"] == [7, 8] and rep.part["F_p_pass"] is True
    # a limit given to the call overrides the spec's
    assert compare_part(spec, pts, limits={"fpt": 0.02}).part["pass"] is True


def test_heatmap_colours_and_viser_scene(renzo, tmp_path):
    from gearcoupling.inspection.heatmap import (
        add_deviation_heatmap,
        deviation_colours,
        write_deviation_ply,
    )

    rgb = deviation_colours(np.array([-1.0, 0.0, 1.0, 5.0]), 1.0)
    assert rgb[1].tolist() == [247, 247, 247] and rgb[2].tolist() == rgb[3].tolist()
    assert rgb[0, 2] > rgb[0, 0] and rgb[2, 0] > rgb[2, 2]  # blue minus, red plus
    pts = synthetic_hub(renzo, per_flank=80, index_mm={4: 0.02})
    rep = compare_part(renzo, pts)
    ply = write_deviation_ply(rep, tmp_path / "dev.ply", limit_mm=0.02)
    import trimesh

    cloud = trimesh.load(ply)
    assert len(cloud.vertices) == len(rep.sample["d"])
    # the reddest points are on tooth 4's ccw flank (turned into the space: + material)
    red = np.asarray(cloud.colors)[:, 0].astype(int) - np.asarray(cloud.colors)[:, 2]
    top = np.argsort(red)[-20:]
    assert set(rep.sample["tooth"][top].tolist()) == {4}
    viser = pytest.importorskip("viser")
    from gearcoupling.viewer.html import free_port

    server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        handle = add_deviation_heatmap(server, rep)
        assert np.asarray(handle.points).shape == (len(rep.sample["d"]), 3)
    finally:
        server.stop()


def test_too_sparse_scan_is_refused_not_passed(renzo):
    pts = synthetic_hub(renzo, per_flank=12)
    with pytest.raises(RegistrationError, match="no tooth has both flanks measured"):
        compare_part(renzo, pts, coarse="none")


def test_runout_is_measured_from_the_bore_when_the_scan_has_it(renzo):
    """An eccentric tooth ring: invisible to the teeth-only fit, 2 e of runout to the bore."""
    rng = np.random.default_rng(0)
    teeth = synthetic_hub(renzo, per_flank=150, noise_mm=0.0005)
    rb, L = 0.5 * renzo.hub.body.bore_diameter, renzo.hub.body.length
    th, z = rng.uniform(0, 2 * np.pi, 4000), rng.uniform(-0.4 * L, 0.4 * L, 4000)
    e = np.array([0.02, -0.01])
    bore = np.stack([rb * np.cos(th) + e[0], rb * np.sin(th) + e[1], z], axis=-1)
    only = compare_part(renzo, random_placement(teeth)[0])
    assert only.part["runout_datum"] == "teeth best-fit axis" and only.part["F_r_mm"] < 1 * UM
    rep = compare_part(renzo, random_placement(np.concatenate([teeth, bore]))[0])
    assert rep.part["runout_datum"] == "bore axis"
    # sampled at 50 spaces the sinusoid's range is 2 e cos(small angle) ~ 2 e
    N = renzo.tooth.teeth
    ang = 2 * np.pi * (np.arange(N) + 0.5) / N
    expect = np.ptp(-(e[0] * np.cos(ang) + e[1] * np.sin(ang)))
    assert rep.part["F_r_mm"] == pytest.approx(expect, abs=1 * UM)
    assert np.hypot(*rep.part["bore"]["centre_mm"]) == pytest.approx(np.hypot(*e), abs=0.5 * UM)
