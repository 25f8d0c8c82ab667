"""The whole coupling through the spec file, the pipeline, every command, the report and the
viewer (docs/coupling.md): the [coupling], [alignment] and [hub_b] tables (round trip, units,
refusals naming the key), each mesh's scope equal to a single engagement at the mesh's
angle and torque, the whole coupling's stages equal to the coupling package's own
calculations, the report's whole section, the commands' options and refusals, the placed
assembly read back, and the whole coupling's scene."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.coupling import whole_capacity, whole_loads
from gearcoupling.outputs import StageSettings, compute

MODEL = "compliance"  # the cheap model: what is tested here is the coupling's composition
CHEAP = dict(model=MODEL, angles=36, phases=2, capacity_count=3, check_angles=4)


def close_coupled(**overrides):
    return gc.load_spec("close-coupled", **overrides)


# --------------------------------------------------------------------------- the spec


def test_the_tables_round_trip_in_mm_and_a_single_spec_writes_none():
    spec = gc.load_spec("spacer-double")
    data = spec.to_dict()
    assert data["coupling"] == {"engagements": 2, "sleeve": "flanged",
                                "flange_outer_diameter": 150.0, "flange_thickness": 14.0,
                                "spacer_outer_diameter": 110.0, "spacer_inner_diameter": 90.0,
                                "spacer_length": 250.0}
    assert data["alignment"] == {"offset": 0.5, "offset_azimuth_deg": 0.0, "angle_deg": 0.1,
                                 "angle_azimuth_deg": 90.0}
    again = gc.spec_from_dict(json.loads(json.dumps(data)), spec.name)
    assert again.coupling == spec.coupling and again.alignment == spec.alignment
    assert again.to_dict() == data
    # one engagement: the file's tables as before (spec.json unchanged)
    single = gc.load_spec("industrial-m2").to_dict()
    assert list(single) == ["name", "units", "design_misalignment_deg", "tooth", "hub",
                            "sleeve", "inspection", "load", "material"]


def test_the_tables_read_lengths_in_the_files_units():
    """renzo-1967 is an inch file: the span and the offset are inches, held in mm; a
    refusal quotes the value as typed with its mm beside it."""
    spec = gc.load_spec("renzo-1967", **{"coupling.engagements": 2, "coupling.span": 10.0,
                                         "alignment.offset": 0.02})
    assert spec.coupling.span_mm == pytest.approx(254.0, rel=1e-15)
    assert spec.alignment.offset_mm == pytest.approx(0.508, rel=1e-15)
    assert spec.to_dict()["coupling"]["span"] == pytest.approx(254.0, rel=1e-15)
    with pytest.raises(gc.SpecError) as err:
        gc.load_spec("renzo-1967", **{"coupling.engagements": 2, "coupling.span": -1.0})
    assert err.value.field == "coupling.span" and "-1.0 in (-25.4 mm)" in str(err.value)


@pytest.mark.parametrize("overrides, key", [
    ({"coupling.engagements": 3}, "coupling.engagements"),
    ({"coupling.sleeve": "bolted"}, "coupling.sleeve"),
    ({"coupling.flange_thickness": -3.0}, "coupling.flange_thickness"),
    ({"coupling.spacer_outer_diameter": 160.0}, "coupling.spacer_outer_diameter"),
    ({"coupling.spacer_inner_diameter": 120.0}, "coupling.spacer_inner_diameter"),
    ({"coupling.flange_outer_diameter": None}, "coupling.flange_outer_diameter"),
    ({"coupling.bolts": 8}, "coupling.bolts"),
    ({"alignment.angle_deg": 13.0}, "alignment.angle_deg"),
    ({"alignment.offset": float("nan")}, "alignment.offset"),
    ({"alignment.offset_azimuth_deg": "north"}, "alignment.offset_azimuth_deg"),
])
def test_a_tables_own_values_are_refused_as_it_is_read(overrides, key):
    with pytest.raises(gc.SpecError) as err:
        gc.load_spec("spacer-double", **overrides)
    assert err.value.field == key, str(err.value)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("overrides, key", [
    ({"alignment.offset": 0.1}, "alignment"),
    ({"hub_b.face_width": 14.0}, "hub_b"),
    ({"coupling.span": 300.0}, "coupling.span"),
])
def test_a_single_engagement_refuses_the_whole_couplings_tables(overrides, key):
    with pytest.raises(gc.SpecError) as err:
        gc.load_spec("industrial-m2", **overrides)
    assert err.value.field == key and "engagements = 2" in err.value.allowed


@pytest.mark.parametrize("overrides, changes, field", [
    ({"coupling.span": 30.0}, None, "coupling.span"),  # shorter than both hubs
    ({"alignment.offset": 8.0}, None, "alignment.offset"),  # a mesh beyond 6 degrees
    ({}, {"offset_mm": 8.0}, "--offset"),  # the option that set it is named
    ({}, {"angle_deg": 12.0}, "--shaft-angle"),
])
def test_the_checks_that_need_the_hubs_name_the_key_or_the_option(overrides, changes,
                                                                   field):
    spec = close_coupled(**overrides) if field.startswith("coupling") or not changes else \
        close_coupled()
    names = {"offset_mm": "--offset", "angle_deg": "--shaft-angle"}
    with pytest.raises((gc.SpecError, gc.ArgumentError)) as err:
        gc.spec_geometry(spec, changes, names=names)
    assert err.value.field == field, str(err.value)
    assert isinstance(err.value, gc.ArgumentError if field.startswith("--") else gc.SpecError)


def test_a_spacer_that_does_not_fit_the_flanges_names_its_key():
    spec = gc.load_spec("spacer-double", **{"coupling.spacer_outer_diameter": 80.0,
                                            "coupling.spacer_inner_diameter": 60.0})
    with pytest.raises(gc.SpecError) as err:  # not past the flange bore (81 mm)
        gc.spec_geometry(spec)
    assert err.value.field == "coupling.spacer_outer_diameter"


def test_without_an_alignment_each_mesh_takes_the_design_angle():
    spec = close_coupled(**{"alignment": None})
    assert spec.alignment is None
    geom = gc.spec_geometry(spec)
    for m in ("A", "B"):
        assert geom.misalignment_deg(m) == pytest.approx(spec.design_misalignment_deg,
                                                         abs=1e-12)


def test_hub_b_replaces_its_keys_of_the_first_hub_and_names_its_own():
    spec = close_coupled(**{"hub_b.face_width": 14.0,
                            "hub_b.crowning": {"kind": "circular", "radius": 60.0}})
    b = spec.coupling.hub_b
    assert b.hub.face_width == 14.0 and b.hub.crowning.radius == 60.0
    assert spec.hub.face_width == 16.0 and spec.hub.crowning.radius == 38.0
    assert b.hub.body == spec.hub.body and b.sleeve == spec.sleeve  # the rest is hub A's
    data = spec.to_dict()
    assert data["hub_b"]["face_width"] == 14.0
    again = gc.spec_from_dict(data, spec.name)
    assert again.coupling.hub_b == b and again.to_dict() == data
    geom = gc.spec_geometry(spec)
    assert geom.spec_b == b and geom.spec_a == spec
    with pytest.raises(gc.SpecError) as err:
        close_coupled(**{"hub_b.crowning": {"kind": "circular", "radius": 1.0}})
    assert err.value.field == "hub_b.crowning.radius"


# --------------------------------------------------------------------------- scopes


@pytest.fixture(scope="module")
def split_angle():
    """close-coupled without offset and the shaft angle split evenly, 0.3° each mesh:
    loads, ratings and sweeps of both scopes."""
    spec = close_coupled(**{"alignment": {"angle_deg": 0.6, "angle_azimuth_deg": 30.0}})
    settings = StageSettings(model=MODEL, phases=2, angles=36)
    return spec, settings, compute(spec, settings, ["load", "rating", "sweep"], workers=1)


def test_each_mesh_is_the_single_engagement_at_its_angle_torque_and_phase(split_angle):
    """A double spec with no offset and the shaft angle split evenly gives each mesh the
    single-engagement results at half the angle: tooth loads, wind-up, capacity and the
    clearance sweep at its rotations (hub B at the negative torque), to 1e-9."""
    spec, _, res = split_angle
    T = spec.load.torque_Nm
    assert set(res.values) >= {f"mesh-{m}/{s}" for m in "ab" for s in ("load", "rating",
                                                                       "sweep")}
    phases = []
    for m, sign, flank in (("a", 1.0, "ccw"), ("b", -1.0, "cw")):
        mesh = res.scope(f"mesh-{m}")
        load = mesh.get("load", gc.LoadResult)
        assert load.misalignment_deg == pytest.approx(0.3, abs=1e-12)
        single = gc.load(spec, 0.3, load.angles_deg, torque_Nm=sign * T, model=MODEL)
        assert np.max(np.abs(load.tangential_force_N - single.tangential_force_N)) < \
            1e-9 * np.max(single.tangential_force_N)
        assert np.max(np.abs(load.windup_rad - single.windup_rad)) < 1e-9 * np.max(
            np.abs(single.windup_rad))
        cap = mesh.values["rating"].capacity
        assert cap.loaded_flank == flank
        assert cap.capacity_Nm == pytest.approx(gc.capacity(spec, 0.3, model=MODEL,
                                                            loaded_flank=flank).capacity_Nm,
                                                rel=1e-9)
        sw = mesh.get("sweep", gc.SweepResult)
        ref = gc.sweep(spec, 0.3, sw.angles_deg)
        # the same to the search's rounding (the tracking search starts from the
        # neighbouring rotation's minimum, and the stage's rotations start elsewhere)
        np.testing.assert_allclose(sw.normal_clearance_mm, ref.normal_clearance_mm, rtol=0,
                                   atol=1e-9)
        psi = np.arange(36) * 10.0
        phases.append(psi[0] - sw.angles_deg[0])
    assert abs(abs(phases[0] - phases[1]) - 180.0) < 1e-9  # an angle alone: 180° apart


def test_the_whole_stages_are_the_coupling_packages_own(split_angle):
    """whole_loads (from both scopes' loads) and whole_capacity (from their ratings) equal
    gc.whole_loads and gc.whole_capacity computed afresh; the floating member balances."""
    spec, settings, _ = split_angle
    res = compute(spec, settings, ["whole_loads", "whole_capacity", "alignment"], workers=1)
    got = res.get("whole_loads", gc.WholeLoads)
    geom = res.get("alignment", gc.CouplingGeometry)
    psi = got.angles_deg
    want = whole_loads(spec, spec.coupling, geom.alignment, spec.load.torque_Nm,
                       angles_deg=psi, model=MODEL)
    for m in ("A", "B"):
        for key, v in got.machine_loads(m).items():
            w = want.machine_loads(m)[key]
            assert np.max(np.abs(v - w)) <= 1e-9 * max(1.0, np.max(np.abs(w))), key
    eq = got.equilibrium()
    assert eq["relative_force"] < 1e-6 and eq["relative_moment"] < 1e-6
    cap = res.get("whole_capacity", gc.WholeCapacity)
    ref = whole_capacity(spec, spec.coupling, geom.alignment, model=MODEL)
    assert cap.capacity_Nm == pytest.approx(ref.capacity_Nm, rel=1e-9)
    assert (cap.governing_mesh, cap.criterion) == (ref.governing_mesh, ref.criterion)


def test_stage_settings_refuse_what_does_not_apply(tmp_path):
    with pytest.raises(gc.ArgumentError, match="offset_mm") as err:
        gc.run("industrial-m2", tmp_path / "a", only=["spec"], offset_mm=0.2)
    assert "engagements = 2" in err.value.allowed
    with pytest.raises(gc.ArgumentError) as err:
        gc.run("close-coupled", tmp_path / "b", only=["spec"], misalignment_deg=0.5)
    assert err.value.field == "misalignment_deg"
    with pytest.raises(gc.ArgumentError) as err:
        gc.run("close-coupled", tmp_path / "c", only=["spec"], offset_mm=9.0)
    assert err.value.field == "offset_mm" and "beyond the 6°" in err.value.allowed
    assert not any(tmp_path.iterdir())
    res = compute(close_coupled(), StageSettings(), ["datasheet"], workers=1)
    assert "whole_datasheet" in res.skipped["datasheet"]
    res = compute(gc.load_spec("industrial-m2"), StageSettings(), ["alignment"], workers=1)
    assert "engagements = 2" in res.skipped["alignment"]


def test_a_link_at_a_meshs_folder_is_refused_before_any_work(tmp_path, capsys):
    """A mesh's folder is the pipeline's own: a symbolic link planted there (its files
    would go where it points) is refused, naming it, before anything is written."""
    out, elsewhere = tmp_path / "out", tmp_path / "elsewhere"
    out.mkdir()
    elsewhere.mkdir()
    (out / "mesh-b").symlink_to(elsewhere, target_is_directory=True)
    with pytest.raises(gc.ArgumentError, match="mesh-b") as err:
        gc.run("close-coupled", out, only=["sweep"], workers=1)
    assert "symbolic link" in err.value.allowed
    line = _one_line_error(capsys, ["sweep", "close-coupled", "-o", str(out)])
    assert "mesh-b" in line and "symbolic link" in line
    assert list(elsewhere.iterdir()) == [] and sorted(p.name for p in out.iterdir()) == \
        ["mesh-b"]


# --------------------------------------------------------------------------- commands


def _one_line_error(capsys, argv) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("argv, named", [
    (["sweep", "industrial-m2", "--offset", "0.2"], "--offset = 0.2"),
    (["load", "industrial-m2", "--shaft-angle", "0.2"], "--shaft-angle = 0.2"),
    (["report", "close-coupled", "--misalignment", "0.5"], "--misalignment = 0.5"),
    (["run", "close-coupled", "--offset", "10"], "--offset = 10.0"),
    (["check", "close-coupled", "--set", "coupling.span=30"], "coupling.span = 30.0"),
    (["capacity", "spacer-double", "--set", "alignment.offset=40"], "alignment.offset = 40.0"),
    (["datasheet", "spacer-double", "--set", "coupling.spacer_outer_diameter=200"],
     "coupling.spacer_outer_diameter = 200.0"),
    (["capacity", "close-coupled", "--compare", "industrial-m2"], "--compare"),
    (["check", "close-coupled", "--method", "distance"], "--method = 'distance'"),
])
def test_commands_refuse_in_one_line_naming_the_option_or_key(capsys, tmp_path, argv,
                                                               named):
    line = _one_line_error(capsys, [*argv, "-o", str(tmp_path / "out")])
    assert line.startswith("gearcoupling: error: ") and named in line, line
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_capacity_gives_each_mesh_the_whole_and_the_allowable_offset(capsys, tmp_path):
    out = tmp_path / "cap"
    assert main(["capacity", "close-coupled", "--count", "2", "--set",
                 f"load.model={MODEL}", "--offset", "0.4", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    off = json.loads((out / "allowable_offset.json").read_text())
    spec = close_coupled(**{"load.model": MODEL, "alignment.offset": 0.4})
    geom = gc.spec_geometry(spec)
    want = gc.allowable_offset(spec, spec.coupling, geom.alignment, 400.0, model=MODEL)
    assert off["allowable_offset_mm"] == pytest.approx(want.offset_mm, abs=1e-9)
    assert off["offset_mm"] == 0.4 and off["within"] is (0.4 <= want.offset_mm)
    assert f"{want.offset_mm:.4g} mm at 400 N·m (mesh {want.governing_mesh}" in text
    assert "mesh A: capacity at" in text and "mesh B: capacity at" in text
    for m in "ab":
        assert (out / f"mesh-{m}" / "capacity.csv").is_file()


# --------------------------------------------------------------------------- the report


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("whole-report")
    return out, gc.report("spacer-double", out, viewer=False, workers=2, **CHEAP)


@pytest.mark.slow
def test_the_report_judges_the_whole_coupling(report):
    out, res = report
    html = res.html.read_text(encoding="utf-8")
    for key in ("whole", "whole-datasheet", "clearance-mesh-a", "clearance-mesh-b",
                "loads-mesh-a", "loads-mesh-b", "capacity-mesh-b", "interference-mesh-a"):
        assert f'id="{key}"' in html, key
    assert 'id="datasheet"' not in html  # one engagement's data sheet: not this one
    off = json.loads((out / "allowable_offset.json").read_text())
    assert f"{off['allowable_offset_mm']:.4g}" in html
    assert "parallel offset ≤ allowable offset at the span" in html
    assert "mesh A: teeth do not bind" in html and "mesh B: torque ≤ capacity" in html
    data = json.loads((out / "whole_datasheet.json").read_text())
    assert f"{data['lateral_frequency_Hz']:.4g}" in html
    loads = json.loads((out / "whole_loads.json").read_text())
    assert loads["equilibrium"]["relative_force"] < 1e-6
    assert 'href="mesh-a/load.csv"' in html and 'href="machine_loads.csv"' in html
    assert res.verdict != "fail" and res.verdict_text.startswith("PASS"), res.verdict_text


@pytest.mark.slow
def test_the_report_writes_each_meshs_files_in_its_folder(report):
    out, _ = report
    from gearcoupling.reporting import ReportSettings, report_files

    allowed = set(report_files(ReportSettings(viewer=False, **CHEAP), engagements=2))
    made = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()}
    assert made - {"report.html"} <= allowed
    assert {"mesh-a/sweep.csv", "mesh-b/load.csv", "machine_loads.csv", "coupling.glb",
            "whole_datasheet.csv", "torsion_chain.csv"} <= made


@pytest.mark.slow
def test_run_writes_both_meshes_and_the_whole_coupling(tmp_path):
    res = gc.run("close-coupled", tmp_path, workers=2, skip=["step", "assembly_step"],
                 **CHEAP)
    summary = json.loads((tmp_path / "run_summary.json").read_text())
    assert set(summary["skipped"]) == {"mesh-a/q_graph", "mesh-b/q_graph"}  # no Renzo limits
    assert {"mesh-a/load", "mesh-b/check", "whole_loads", "allowable_offset",
            "assembly"} <= set(summary["step_seconds"])
    assert "mesh-b/load_summary.json" in summary["files"]
    rows = (tmp_path / "machine_loads.csv").read_text().splitlines()
    assert sum(not r.startswith("#") for r in rows) == 1 + 2 * 2 * 38  # header, 2 meshes
    assert res.results.scope("mesh-b").get("load", gc.LoadResult).torque_Nm == -400.0


# --------------------------------------------------------------------------- the assembly


@pytest.mark.slow
@pytest.mark.needs_fea
def test_generate_writes_the_placed_assembly_read_back_by_gmsh(tmp_path):
    """coupling.step holds one named volume per part (gmsh over OpenCASCADE) whose centre
    of mass is where the assembly places the part; coupling.glb one node per part."""
    import gmsh
    import trimesh

    assert main(["generate", "close-coupled", "-o", str(tmp_path), "--offset", "0.6"]) == 0
    spec = close_coupled(**{"alignment.offset": 0.6})
    geom = gc.spec_geometry(spec)
    asm = gc.coupling_assembly(spec, spec.coupling, geom.alignment)
    names = [p.name for p in asm.parts]
    scene = trimesh.load(tmp_path / "coupling.glb", force="scene")
    assert sorted(n for n in scene.graph.nodes_geometry) == sorted(names)
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.importShapes(str(tmp_path / "coupling.step"))
        gmsh.model.occ.synchronize()
        vols = gmsh.model.getEntities(3)
        assert len(vols) == len(names)
        found = {}
        for dim, tag in vols:
            found[gmsh.model.getEntityName(dim, tag).split("/")[-1]] = \
                gmsh.model.occ.getCenterOfMass(dim, tag)
    finally:
        gmsh.finalize()
    meshes = asm.meshes()
    for name in names:
        cg = np.asarray(found[name])
        assert np.linalg.norm(cg - meshes[name].center_mass) < 1e-2, name


# --------------------------------------------------------------------------- the viewer


def test_each_meshs_pose_is_its_single_engagement_pose():
    """In the placed assembly each hub sits in its sleeve ring as the single engagement at
    the mesh's angle and rotation, and the viewer's state of each mesh is that engagement's
    (offset and angle in different planes: the phases differ)."""
    from gearcoupling.viewer.scene import hub_rotation, pose_state

    spec = close_coupled()
    pose = gc.assembly_pose(spec, psi_deg=17.0, changes={"offset_mm": 0.5})
    geom = pose.geometry
    assert geom.alignment.offset_mm == 0.5 and geom.alignment.angle_deg == 0.3
    for m in ("A", "B"):
        hub, ring = pose.placements[f"hub {m}"], pose.placements[f"sleeve {m}"]
        rot = float(geom.mesh_rotations_deg(m, 17.0))
        relative = ring[:3, :3].T @ hub[:3, :3]
        assert np.max(np.abs(relative - hub_rotation(geom.misalignment_deg(m), rot))) < 1e-12
        single = pose_state(spec, geom.misalignment_deg(m), rot)
        assert np.array_equal(pose.states[m].clearance_mm, single.clearance_mm)
    assert abs(float(geom.mesh_rotations_deg("A", 0.0) - geom.mesh_rotations_deg("B", 0.0))) \
        > 1.0


@pytest.mark.needs_viewer
def test_the_scene_moves_the_parts_and_recolours_each_mesh(tmp_path):
    """The live viewer of a double spec: the offset slider moves every part to the new
    placements, each mesh's flanks take its clearance colours, a mesh beyond 6° is said
    in the status line, and the static HTML shows the whole coupling."""
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.scene import clearance_colors, quaternion_wxyz

    spec = close_coupled()
    app = gc.serve(spec, port=free_port(), html_path=tmp_path / "viewer.html")
    try:
        assert isinstance(app, gc.AssemblyApp)
        app.panel.offset.value = 2.0
        app.panel.angle.value = 0.0
        app.apply({"pose"})
        sc = app.scene
        want = gc.assembly_pose(spec, 0.0, {"offset_mm": 2.0, "angle_deg": 0.0,
                                            "offset_azimuth_deg": 0.0,
                                            "angle_azimuth_deg": 90.0})
        for name, P in want.placements.items():
            frame = sc.frames[name]
            assert np.allclose(frame.position, P[:3, 3], atol=1e-9), name
            assert np.allclose(np.abs(np.dot(frame.wxyz, quaternion_wxyz(P[:3, :3]))), 1.0)
        i = math.degrees(math.atan(2.0 / 64.0))
        assert want.geometry.misalignment_deg("B") == pytest.approx(i, abs=1e-9)
        for m in ("A", "B"):
            cols = clearance_colors(want.states[m].clearance_mm, sc.color_scale_mm)
            assert tuple(sc.flanks[m][1][5].color) == tuple(int(c) for c in cols[1, 5])
            assert f"mesh {m}: i = {i:.4f}°" in app.panel.status.content
        app.panel.offset.value = 7.0  # over 64 mm: beyond 6° a mesh
        assert app.wait_ticks(2)
        assert "beyond the 6°" in app.panel.status.content
        app.panel.offset.value = 0.3
        app.apply({"save"})
        page = (tmp_path / "viewer.html").read_text(encoding="utf-8")
        assert "mesh A i = " in page and "mesh B i = " in page
    finally:
        app.stop()
