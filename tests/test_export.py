"""Exports: every format round-trips, cell data survive, writes are atomic, STEP solids are
B-spline solids of the exact geometry whose read-back volume matches the part, CLI."""

from __future__ import annotations

import importlib
import json
import sys

import numpy as np
import pytest
import trimesh

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.errors import ArgumentError, BackendError
from gearcoupling.export import WRITERS, Writer, export_part, formats
from gearcoupling.export.meshes import read_mesh
from gearcoupling.io.lock import RECORD_NAME
from gearcoupling.parts import SURFACE_KINDS, build_part

import clients

MESH_FORMATS = ["stl", "ply", "obj", "glb", "3mf", "vtu", "vtk", "msh", "inp"]
CELL_DATA_FORMATS = ["vtu", "vtk", "msh"]
TOL = 0.05


@pytest.fixture(scope="module")
def hub_sector():
    spec = gc.load_spec("renzo-1967")
    return spec, build_part(spec, "hub", tolerance_mm=TOL, teeth=[49, 0, 1])


def test_every_format_is_registered():
    assert {*MESH_FORMATS, "step", "stp"} <= set(formats())
    assert formats("volume") == ["inp", "msh", "vtu"]
    keys = [(w.kind, s) for w in WRITERS for s in w.suffixes]
    assert len(keys) == len(set(keys))  # one writer per kind and extension
    for w in WRITERS:  # each "module:function" imports (at the call) to a function
        module, _, name = w.writer.partition(":")
        assert callable(getattr(importlib.import_module(f"gearcoupling.export.{module}"), name))


def test_a_format_registered_in_one_place_writes_and_is_a_cli_choice(tmp_path, hub_sector,
                                                                     monkeypatch):
    spec, mesh = hub_sector

    def write_xyz(job, path):  # a toy format: one line per vertex
        np.savetxt(path, job.mesh.vertices)

    monkeypatch.setattr("gearcoupling.export.registry.WRITERS",
                        (*WRITERS, Writer("xyz", ("xyz",), "surface", write_xyz)))
    assert "xyz" in formats() and "xyz" not in formats("volume")
    path = export_part(spec, "hub", tmp_path / "hub.xyz", mesh=mesh)
    np.testing.assert_array_equal(np.loadtxt(path), mesh.vertices)
    rc = main(["generate", "renzo-1967", "--parts", "hub", "--format", "xyz", "--teeth", "0",
               "-o", str(tmp_path / "cli")])
    assert rc == 0 and len(list((tmp_path / "cli").rglob("*.xyz"))) == 1


@pytest.mark.parametrize("ext", MESH_FORMATS)
def test_mesh_round_trip(tmp_path, hub_sector, ext):
    spec, mesh = hub_sector
    path = export_part(spec, "hub", tmp_path / f"hub.{ext}", tolerance_mm=TOL,
                       teeth=[49, 0, 1], mesh=mesh)
    assert path.is_file() and [p.name for p in tmp_path.iterdir()] == [f"hub.{ext}"]
    v, f, data, sets = read_mesh(path)
    back = trimesh.Trimesh(v, f, process=True)
    assert len(back.faces) == len(mesh.faces)
    assert back.is_watertight and back.is_winding_consistent
    # float32 formats (STL, PLY, GLB) keep volume to single precision
    assert back.volume == pytest.approx(mesh.volume, rel=1e-6)
    scale = np.abs(mesh.vertices).max()
    assert np.abs(np.sort(back.vertices, axis=0) - np.sort(mesh.vertices, axis=0)).max() \
        < 1e-6 * scale
    if ext in CELL_DATA_FORMATS:
        # MSH lists nodes and triangles by entity (kind, tooth): match exact coordinates,
        # then compare the triangles as sorted rows
        index = {tuple(p): i for i, p in enumerate(mesh.vertices.tolist())}
        f = np.array([index[tuple(p)] for p in v.tolist()])[f]
        order = np.lexsort(f.T[::-1])
        ref = np.lexsort(mesh.faces.T[::-1])
        assert np.array_equal(f[order], mesh.faces[ref])
        for name in ("kind", "tooth"):
            assert np.array_equal(data[name].ravel()[order], mesh.face_attributes[name][ref])
    if ext == "inp":
        kind = mesh.face_attributes["kind"]
        for code, name in enumerate(SURFACE_KINDS):
            if np.any(kind == code):
                assert np.array_equal(np.sort(sets[name.upper()]), np.flatnonzero(kind == code))
        for k in (49, 0, 1):
            assert np.array_equal(np.sort(sets[f"TOOTH_{k}"]),
                                  np.flatnonzero(mesh.face_attributes["tooth"] == k))


def test_stl_is_binary(tmp_path, hub_sector):
    spec, mesh = hub_sector
    path = export_part(spec, "hub", tmp_path / "hub.stl", mesh=mesh)
    assert path.stat().st_size == 84 + 50 * len(mesh.faces)


def test_a_failing_writer_leaves_no_file(tmp_path, hub_sector, monkeypatch):
    spec, mesh = hub_sector
    target = tmp_path / "hub.stl"
    target.write_bytes(b"old")

    def broken(job, path):
        path.write_bytes(b"half")
        raise RuntimeError("disk full")

    monkeypatch.setattr("gearcoupling.export.registry.WRITERS",
                        (Writer("stl", ("stl",), "surface", broken), *WRITERS))
    with pytest.raises(RuntimeError):
        export_part(spec, "hub", target, mesh=mesh)
    assert target.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["hub.stl"]


def test_unknown_extension_names_the_allowed_ones(tmp_path, hub_sector):
    spec, mesh = hub_sector
    with pytest.raises(ArgumentError, match=r"hub\.dxf.*stl.*'dxf' is not a supported format"):
        export_part(spec, "hub", tmp_path / "hub.dxf", mesh=mesh)


def test_missing_opencascade_is_a_backend_error(tmp_path, monkeypatch):
    spec = gc.load_spec("renzo-1967")
    monkeypatch.setitem(sys.modules, "OCP", None)
    with pytest.raises(BackendError, match=r"gearcoupling\[step\]"):
        export_part(spec, "sleeve", tmp_path / "sleeve.step", tolerance_mm=TOL)
    assert not list(tmp_path.iterdir())


# ---------------------------------------------------------------------------- STEP

def _step_distance(shape, points):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt

    out = []
    for q in points:
        v = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, q))).Vertex()
        out.append(BRepExtrema_DistShapeShape(v, shape).Value())
    return np.array(out)


def _face_types(shape):
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    types = {}
    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        t = BRepAdaptor_Surface(TopoDS.Face(exp.Current())).GetType().name
        types[t] = types.get(t, 0) + 1
        exp.Next()
    return types


@pytest.mark.parametrize("name, part", [("renzo-1967", "sleeve"), ("renzo-1967", "hub"),
                                        ("renzo-1967-end-round", "hub")])
@pytest.mark.slow
def test_step_solid_is_exact_geometry_and_round_trips(tmp_path, name, part):
    clients.ocp()
    from gearcoupling.export import read_step_volume
    from gearcoupling.parts import part_solid, shape_volume
    from gearcoupling.parts.deviation import hub_samples, sleeve_samples

    spec = gc.load_spec(name)
    tol = 0.0127
    shape = part_solid(spec, part, tol)
    types = _face_types(shape)
    n = spec.tooth.teeth
    # flanks are smooth surfaces, one face per flank, not facets
    assert "GeomAbs_Plane" in types and sum(types.values()) < 20 * n
    smooth = types.get("GeomAbs_BSplineSurface", 0) + types.get("GeomAbs_SurfaceOfExtrusion", 0)
    assert smooth >= 2 * n
    samples = (hub_samples if part == "hub" else sleeve_samples)(spec, 4, np.random.default_rng(3))
    pts = np.concatenate(list(samples.values()))
    assert _step_distance(shape, pts).max() <= tol
    path = export_part(spec, part, tmp_path / f"{part}.step", tolerance_mm=tol)
    mesh = build_part(spec, part, tolerance_mm=tol)
    v_back = read_step_volume(path)
    assert v_back == pytest.approx(shape_volume(shape), rel=1e-9)
    # the mesh is within tol of the exact surface, so volumes differ by at most tol x area
    assert abs(v_back - mesh.volume) <= tol * mesh.area
    assert abs(v_back - mesh.volume) <= 1e-3 * mesh.volume


@pytest.mark.slow
def test_step_sector_matches_the_mesh_sector(tmp_path):
    clients.ocp()
    from gearcoupling.export import read_step_volume

    spec = gc.load_spec("renzo-1967")
    teeth = [49, 0, 1]
    for part in ("sleeve", "hub"):
        path = export_part(spec, part, tmp_path / f"{part}.stp", tolerance_mm=TOL, teeth=teeth)
        mesh = build_part(spec, part, tolerance_mm=TOL, teeth=teeth)
        assert abs(read_step_volume(path) - mesh.volume) <= TOL * mesh.area


# ----------------------------------------------------------------------------- CLI


def test_generate_writes_parts_and_report(tmp_path, capsys):
    rc = main(["generate", "renzo-1967", "--parts", "sleeve,hub", "--format", "stl,vtu",
               "--teeth", "0-1,49", "--tolerance", "0.05", "-o", str(tmp_path)])
    assert rc == 0
    names = sorted(p.name for p in tmp_path.iterdir() if p.name != RECORD_NAME)
    assert names == ["hub-teeth-0-1-49.stl", "hub-teeth-0-1-49.vtu", "parts.json",
                     "sleeve-teeth-0-1-49.stl", "sleeve-teeth-0-1-49.vtu"]
    report = json.loads((tmp_path / "parts.json").read_text())
    assert report["teeth"] == [0, 1, 49] and report["tolerance_mm"] == 0.05
    for part in ("hub", "sleeve"):
        info = report["parts"][part]
        assert info["valid"] and info["genus"] == 0
        assert 0 < info["measured_deviation_mm"] <= 0.05
        mesh = trimesh.load(tmp_path / f"{part}-teeth-0-1-49.stl")
        assert len(mesh.faces) == info["triangles"]
        assert mesh.volume == pytest.approx(info["volume_mm3"], rel=1e-6)
    out = capsys.readouterr().out.split()
    assert str(tmp_path / "parts.json") in out


@pytest.mark.parametrize("argv, field", [
    (["--format", "dxf"], "--format"), (["--parts", "shaft"], "--parts"),
    (["--teeth", "50"], "--teeth"), (["--teeth", "a-b"], "--teeth"),
    (["--tolerance", "-1"], "--tolerance"),
])
def test_generate_bad_options_exit_2(tmp_path, capsys, argv, field):
    rc = main(["generate", "renzo-1967", "-o", str(tmp_path), *argv])
    assert rc == 2
    assert field in capsys.readouterr().err
    assert not any(p.suffix in (".stl", ".step") for p in tmp_path.iterdir())


def test_run_has_parts_and_step_steps(tmp_path):
    from gearcoupling.outputs import STEPS, write_parts

    assert "parts" in STEPS and "step" in STEPS
    spec = gc.load_spec("industrial-m2")
    written, _ = write_parts(spec, tmp_path)
    assert {p.name for p in written} == {"hub.stl", "sleeve.stl", "parts.json"}
    for part in ("hub", "sleeve"):
        assert trimesh.load(tmp_path / f"{part}.stl").is_watertight


@pytest.mark.parametrize("data", [
    {"design_misalignment_deg": 6.0,
     "tooth": {"teeth": 6, "module": 60.0, "pressure_angle_deg": 30},
     "hub": {"face_width": 36.0, "crowning": {"kind": "circular", "radius": 180.0},
             "root": {"dedendum": 48.0, "fillet_radius": 18.0}}},
    {"tooth": {"teeth": 24, "module": 3.0},
     "hub": {"face_width": 20.0, "tip": {"kind": "cylinder"}, "crowning": {"kind": "none"},
             "body": {"bore_diameter": 0.0, "length": 20.0}}},
    {"tooth": {"teeth": 30, "module": 2.0},
     "hub": {"face_width": 16.0, "crowning": {"kind": "table", "z": [0, 4, 8],
                                               "drop": [0, 0.05, 0.2],
                                               "generation": "revolved"}}},
], ids=["6-teeth-m60", "straight-solid", "table-revolved"])
def test_step_of_unusual_specs_matches_the_mesh(data):
    clients.ocp()
    from gearcoupling.parts import part_solid, shape_volume

    spec = gc.spec_from_dict(data)
    tol = spec.tooth.module / 50
    for part in ("hub", "sleeve"):
        mesh = build_part(spec, part, tolerance_mm=tol)
        assert abs(shape_volume(part_solid(spec, part, tol)) - mesh.volume) <= tol * mesh.area


def test_curvature_breaks_only_where_the_feed_path_jumps():
    from gearcoupling.geometry.hub import hub_model
    from gearcoupling.parts.loft import curvature_breaks

    spec = gc.load_spec("renzo-1967-end-round")
    assert curvature_breaks(hub_model(spec)) == pytest.approx([0.15 * 25.4], rel=1e-9)
    for name in ("renzo-1967", "renzo-1967-vari-crown"):
        assert curvature_breaks(hub_model(gc.load_spec(name))).size == 0


def test_export_package_imports_no_opencascade():
    import subprocess

    code = ("import sys, gearcoupling.export, gearcoupling.parts; "
            "assert 'OCP' not in sys.modules, 'OCP imported eagerly'")
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.slow
def test_run_lists_the_step_files_in_parts_json(tmp_path, capsys):
    clients.ocp()
    rc = main(["run", "renzo-1967", "--only", "parts,step", "-o", str(tmp_path)])
    assert rc == 0
    report = json.loads((tmp_path / "parts.json").read_text())
    for part in ("hub", "sleeve"):
        files = report["parts"][part]["files"]
        assert files == [f"{part}.stl", f"{part}.step"]
        assert all((tmp_path / name).is_file() for name in files)
    printed = capsys.readouterr().out.split()
    assert sorted(printed) == sorted(str(tmp_path / n) for n in
                                     ("hub.stl", "sleeve.stl", "parts.json", "hub.step",
                                      "sleeve.step", "run_summary.json"))


def test_profile_fit_uses_the_fewest_poles_within_the_tolerance():
    """A quarter circle (radius 10) in 3 sections scaled 1, 1.1, 1.2: the fit deviates at
    most ``tol`` from every exact point, one fewer pole would not, and every section shares
    the knots; more tolerance never needs more poles."""
    from scipy.interpolate import BSpline

    from gearcoupling.parts.fit import (
        _knot_vector,
        _lsq,
        fit_sections,
        shared_chord_parameters,
    )

    a = np.linspace(0, np.pi / 2, 60)
    arc = 10.0 * np.stack([np.cos(a), np.sin(a)], axis=-1)
    pts = np.stack([s * arc for s in (1.0, 1.1, 1.2)])
    counts = []
    for tol in (1e-2, 1e-3, 1e-4, 1e-5):
        fit = fit_sections(pts, tol)
        k = fit.poles.shape[1]
        counts.append(k)
        assert fit.deviation <= tol
        assert fit.mults.sum() == k + 4 and fit.poles.shape == (3, k, 2)
        # end points kept exactly (the wire's edges must meet)
        assert np.allclose(fit.poles[:, 0], pts[:, 0], atol=1e-12)
        assert np.allclose(fit.poles[:, -1], pts[:, -1], atol=1e-12)
        if k > 4:
            _, _, fewer = _lsq(pts, shared_chord_parameters(pts), k - 1)
            assert fewer > tol
        assert np.allclose(np.repeat(fit.knots, fit.mults), _knot_vector(k))
    assert counts == sorted(counts) and counts[0] < counts[-1]
    # the deviation reported is the real distance of the data to the fitted curve's points
    fit = fit_sections(pts, 1e-4)
    u = shared_chord_parameters(pts)
    curve = BSpline(np.repeat(fit.knots, fit.mults), fit.poles[1], 3)
    assert np.linalg.norm(curve(u) - pts[1], axis=-1).max() <= 1e-4
