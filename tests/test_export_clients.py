"""Every export opened by its own client: gmsh reads the MSH with its
named groups and the STEP (volume, dense exact points), CalculiX runs the INP, VTK keeps
the labels and the kind names, lib3mf reads the 3MF in strict mode, the Khronos glTF
validator passes the GLB and its scene is in metres with +Y up and smooth normals.

A missing client is a skip naming what to install; ``scripts/test.sh`` installs them all.
"""

from __future__ import annotations

import json
import math
import struct
import subprocess

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.export import export_part
from gearcoupling.export.meshes import GLB_CREASE_DEG
from gearcoupling.fea.backends import gmsh_initialize
from gearcoupling.parts import SURFACE_KINDS, build_part
from gearcoupling.parts.deviation import exact_samples

import clients
from golden_values import engagement_templates

SPEC = "industrial-m2"


@pytest.fixture(scope="module")
def hub(tmp_path_factory):
    """industrial-m2 hub at the default tolerance, written in every mesh format."""
    spec = gc.load_spec(SPEC)
    mesh = build_part(spec, "hub", tolerance_mm=None)
    out = tmp_path_factory.mktemp("hub")
    files = {ext: export_part(spec, "hub", out / f"hub.{ext}", mesh=mesh)
             for ext in ("msh", "inp", "vtk", "vtu", "3mf", "glb")}
    return spec, mesh, files


def _counts(values) -> dict[int, int]:
    keys, n = np.unique(values, return_counts=True)
    return dict(zip(keys.tolist(), n.tolist(), strict=True))


# ------------------------------------------------------------------------------ gmsh


@pytest.fixture()
def gmsh():
    gmsh = clients.module("gmsh", "pip install gmsh (in the test extra)")
    gmsh_initialize(gmsh, readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.logger.start()
    yield gmsh
    gmsh.finalize()


def test_gmsh_reads_the_msh_with_named_groups(hub, gmsh):
    _, mesh, files = hub
    kind = mesh.face_attributes["kind"]
    tooth = mesh.face_attributes["tooth"]
    gmsh.open(str(files["msh"]))
    assert not [m for m in gmsh.logger.get() if m.startswith("Error")]
    groups = {gmsh.model.getPhysicalName(d, t): t for d, t in gmsh.model.getPhysicalGroups(2)}
    expected = {SURFACE_KINDS[c] for c in np.unique(kind)}
    expected |= {f"tooth_{k}" for k in range(gc.load_spec(SPEC).tooth.teeth)}
    assert set(groups) == expected

    def elements(tag):
        n = 0
        for entity in gmsh.model.getEntitiesForPhysicalGroup(2, tag):
            types, tags, _ = gmsh.model.mesh.getElements(2, entity)
            assert list(types) == [2]  # 3-node triangles
            n += len(tags[0])
        return n

    for code, n in _counts(kind).items():
        assert elements(groups[SURFACE_KINDS[code]]) == n
    for k, n in _counts(tooth[tooth >= 0]).items():
        assert elements(groups[f"tooth_{k}"]) == n
    nodes, coords, _ = gmsh.model.mesh.getNodes()
    assert len(nodes) == len(mesh.vertices)
    xyz = coords.reshape(-1, 3)[np.argsort(nodes)]
    assert np.array_equal(xyz, mesh.vertices)  # 17 significant digits: exact
    _, tri_tags, tri_nodes = gmsh.model.mesh.getElements(2)
    order = np.argsort(np.concatenate(tri_tags))
    faces = np.concatenate(tri_nodes).reshape(-1, 3)[order] - 1
    assert np.array_equal(faces, mesh.faces)


@pytest.mark.slow
@pytest.mark.parametrize("name", engagement_templates())
@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_gmsh_reads_the_step_volume_and_exact_points(tmp_path, gmsh, name, part):
    """Dense exact kernel points (crown ends, tips, fillets, roots, flanks on random teeth,
    bore / outer cylinder) lie within the tolerance of the STEP solid gmsh reads back, and
    its volume is the mesh's within tolerance x area."""
    clients.ocp()
    spec = gc.load_spec(name)
    tol = spec.tooth.module / 200
    path = export_part(spec, part, tmp_path / f"{part}.step", tolerance_mm=tol)
    gmsh.model.occ.importShapes(str(path))
    gmsh.model.occ.synchronize()
    volumes = gmsh.model.getEntities(3)
    assert len(volumes) == 1
    mesh = build_part(spec, part, tolerance_mm=tol)
    volume = gmsh.model.occ.getMass(*volumes[0])
    assert abs(volume - mesh.volume) <= tol * mesh.area
    pts = np.concatenate(list(exact_samples(spec, part, 200, seed=7).values()))
    dist = _gmsh_distance(gmsh, pts, tol)
    assert dist.max() <= tol, f"max {dist.max():.3g} mm at {pts[np.argmax(dist)]}"


def _gmsh_distance(gmsh, pts, reach):
    """Distance from each point to the nearest face among those whose bounding box is
    within ``reach`` (points farther than that from every face get ``inf``)."""
    best = np.full(len(pts), np.inf)
    for dim, tag in gmsh.model.getEntities(2):
        box = np.array(gmsh.model.getBoundingBox(dim, tag))
        near = np.all((pts >= box[:3] - 2 * reach) & (pts <= box[3:] + 2 * reach), axis=1)
        if not near.any():
            continue
        closest, _ = gmsh.model.getClosestPoint(dim, tag, pts[near].ravel())
        d = np.linalg.norm(np.reshape(closest, (-1, 3)) - pts[near], axis=1)
        best[near] = np.minimum(best[near], d)
    return best


# ---------------------------------------------------------------------- CalculiX


def test_inp_fields_fit_calculix(hub):
    _, mesh, files = hub
    lines = files["inp"].read_text().splitlines()
    assert all(len(line) <= 132 for line in lines)
    start = lines.index("*NODE, NSET=NALL") + 1
    rows = lines[start:start + len(mesh.vertices)]
    assert max(len(f.strip()) for row in rows for f in row.split(",")) <= 20
    xyz = np.array([[float(f) for f in row.split(",")[1:]] for row in rows])
    assert np.abs(xyz - mesh.vertices).max() <= 1e-12 * np.abs(mesh.vertices).max()


def test_calculix_runs_the_inp(tmp_path):
    """ccx reads the mesh deck inside an analysis deck: a static step on S3 shells of
    thickness t; the element volumes ccx prints (EVOL) per element set are area x t."""
    ccx = clients.ccx()
    spec = gc.load_spec(SPEC)
    teeth = [0, 1]
    mesh = build_part(spec, "hub", tolerance_mm=0.05, teeth=teeth)
    export_part(spec, "hub", tmp_path / "hub.inp", mesh=mesh, teeth=teeth, tolerance_mm=0.05)
    kind = mesh.face_attributes["kind"]
    tooth = mesh.face_attributes["tooth"]
    end = kind == SURFACE_KINDS.index("end")
    fix = np.unique(mesh.faces[end].ravel())
    fix = fix[mesh.vertices[fix, 2] < 0] + 1
    t = 0.01
    sets = {"EALL": np.ones(len(kind), bool), "FLANK_CW": kind == SURFACE_KINDS.index("flank_cw"),
            "TIP": kind == SURFACE_KINDS.index("tip"), "TOOTH_1": tooth == 1}
    deck = ["*INCLUDE, INPUT=hub.inp", "*NSET, NSET=FIX", *map(str, fix),
            "*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3", "*DENSITY", "7.85e-9",
            "*SHELL SECTION, ELSET=EALL, MATERIAL=STEEL", f"{t}", "*BOUNDARY", "FIX, 1, 3",
            "*STEP", "*STATIC", "*DLOAD", "EALL, GRAV, 9810., 0., 0., -1."]
    for name in sets:
        deck += [f"*EL PRINT, ELSET={name}, TOTALS=ONLY", "EVOL"]
    (tmp_path / "job.inp").write_text("\n".join([*deck, "*END STEP", ""]))
    done = subprocess.run([ccx, "job"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0 and "Job finished" in done.stdout, done.stdout[-2000:]
    assert "*ERROR" not in done.stdout
    dat = (tmp_path / "job.dat").read_text().split("total volume for set ")[1:]
    got = {block.split()[0]: float(block.split("\n\n")[1].split()[0]) for block in dat}
    for name, sel in sets.items():
        # shells are expanded about the mid-surface: volume = area x t to O(t / radius)
        assert got[name] == pytest.approx(mesh.area_faces[sel].sum() * t, rel=2e-3), name


# --------------------------------------------------------------------------- VTK


@pytest.mark.parametrize("ext", ["vtk", "vtu"])
def test_vtk_reads_labels_and_kind_names(hub, ext):
    vtk = clients.module("vtk", "pip install vtk (in the test extra)")
    from vtk.util.numpy_support import vtk_to_numpy

    _, mesh, files = hub
    if ext == "vtk":
        reader = vtk.vtkUnstructuredGridReader()
        reader.ReadAllScalarsOn()
        reader.ReadAllFieldsOn()
    else:
        reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(files[ext]))
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfCells() == len(mesh.faces)
    assert grid.GetNumberOfPoints() == len(mesh.vertices)
    assert np.array_equal(vtk_to_numpy(grid.GetPoints().GetData()), mesh.vertices)
    cells = grid.GetCellData()
    for name in ("kind", "tooth"):
        array = cells.GetArray(name)
        assert array is not None, f"{name} dropped"
        assert array.GetDataTypeAsString() == "int"
        assert np.array_equal(vtk_to_numpy(array), mesh.face_attributes[name])
    fields = grid.GetFieldData()
    names = {fields.GetArrayName(i): int(fields.GetArray(i).GetValue(0))
             for i in range(fields.GetNumberOfArrays())}
    assert names == {name: code for code, name in enumerate(SURFACE_KINDS)}


# --------------------------------------------------------------------------- 3MF


def test_lib3mf_reads_the_3mf_in_strict_mode(hub):
    lib3mf = clients.module("lib3mf", "pip install lib3mf (in the test extra)")
    _, mesh, files = hub
    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(files["3mf"]))
    assert reader.GetWarningCount() == 0
    assert model.GetUnit() == lib3mf.ModelUnit.MilliMeter
    objects = model.GetMeshObjects()
    assert objects.Count() == 1 and objects.MoveNext()
    obj = objects.GetCurrentMeshObject()
    assert obj.GetTriangleCount() == len(mesh.faces)
    assert obj.GetVertexCount() == len(mesh.vertices)
    assert obj.IsManifoldAndOriented()
    v = np.array([p.Coordinates[:] for p in obj.GetVertices()])
    # lib3mf keeps single precision
    assert np.abs(v - mesh.vertices).max() <= 1e-7 * np.abs(mesh.vertices).max()
    f = np.array([t.Indices[:] for t in obj.GetTriangleIndices()])
    assert np.array_equal(f, mesh.faces)


# --------------------------------------------------------------------------- GLB


def _glb(path):
    """JSON chunk and binary chunk of a GLB file."""
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<III", data)
    assert magic == 0x46546C67 and version == 2 and length == len(data)
    n, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + n])
    m, _ = struct.unpack_from("<II", data, 20 + n)
    return doc, data[28 + n:28 + n + m]


def _accessor(doc, blob, index):
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    dtype = {5126: "<f4", 5125: "<u4", 5123: "<u2"}[acc["componentType"]]
    width = {"VEC3": 3, "SCALAR": 1}[acc["type"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return np.frombuffer(blob, dtype, acc["count"] * width, start).reshape(acc["count"], -1)


def test_gltf_validator_passes_the_glb(hub):
    report = clients.gltf_validate(hub[2]["glb"])
    assert report["issues"]["numErrors"] == 0, report["issues"]["messages"][:5]
    assert report["issues"]["numWarnings"] == 0, report["issues"]["messages"][:5]


def test_glb_scene_is_in_metres_y_up_with_smooth_normals(hub):
    _, mesh, files = hub
    doc, blob = _glb(files["glb"])
    prim = doc["meshes"][0]["primitives"][0]
    assert not any("matrix" in n or "scale" in n or "rotation" in n for n in doc["nodes"])
    pos = _accessor(doc, blob, prim["attributes"]["POSITION"]).astype(float)
    nor = _accessor(doc, blob, prim["attributes"]["NORMAL"]).astype(float)
    idx = _accessor(doc, blob, prim["indices"]).reshape(-1, 3)
    # metres, coupling axis z -> +Y, x kept, y -> -Z
    lo, hi = mesh.bounds
    expect_lo = np.array([lo[0], lo[2], -hi[1]]) / 1000
    expect_hi = np.array([hi[0], hi[2], -lo[1]]) / 1000
    assert np.allclose(pos.min(axis=0), expect_lo, atol=1e-7)
    assert np.allclose(pos.max(axis=0), expect_hi, atol=1e-7)
    assert len(idx) == len(mesh.faces)
    # smooth: vertices are shared across smooth edges (flat shading needs 3 per triangle)
    assert len(pos) < 1.5 * len(mesh.vertices)
    assert np.allclose(np.linalg.norm(nor, axis=1), 1, atol=1e-5)
    tri = pos[idx]
    face_n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    face_n /= np.linalg.norm(face_n, axis=1, keepdims=True)
    cos = np.einsum("fk,fck->fc", face_n, nor[idx])
    # outward, and within the crease angle of each face they shade (plus averaging slack)
    assert cos.min() >= math.cos(math.radians(GLB_CREASE_DEG + 5))
