"""Hub and sleeve solids: validity, measured deviation from the exact surfaces, volume
convergence, sectors, labels, bad input and seeded random specs."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.geometry.hub import hub_flank_model, hub_model
from gearcoupling.geometry.sleeve import flank_point, sleeve_model
from gearcoupling.parts import SURFACE_KINDS, build_part
from gearcoupling.parts.deviation import distance_to_mesh, measure_deviation
from gearcoupling.parts.validity import check_part
from random_specs import STRATA, random_spec_data

KIND = {k: i for i, k in enumerate(SURFACE_KINDS)}


def _tol(spec, per_module):
    return spec.tooth.module * per_module


@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_every_template_builds_a_valid_solid_within_tolerance(template, part):
    tol = _tol(template, 1 / 100)
    mesh = build_part(template, part, tolerance_mm=tol)
    check = check_part(mesh)
    assert check.ok, check.problems()
    assert check.genus == (1 if part == "sleeve" or template.hub.body.bore_diameter > 0 else 0)
    assert check.bodies == 1
    dev = measure_deviation(template, mesh, samples=1500)
    assert dev["max"] <= tol, dev
    # every surface kind of the tooth was sampled, including fillets and the tip
    assert {"flank_cw", "flank_ccw", "fillet_cw", "fillet_ccw", "tip", "root"} <= set(dev)


@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_finer_tolerance_holds_and_volume_converges(renzo, part):
    tols = [0.1, 0.02, 0.004]
    meshes = [build_part(renzo, part, tolerance_mm=t) for t in tols]
    for t, m in zip(tols, meshes, strict=True):
        assert measure_deviation(renzo, m, samples=800)["max"] <= t
    ref = build_part(renzo, part, tolerance_mm=0.0008)
    errs = [abs(m.volume - ref.volume) for m in meshes]
    # the volume error is bounded by tolerance x area and shrinks with the tolerance
    for t, m, e in zip(tols, meshes, errs, strict=True):
        assert e <= t * m.area
    assert errs[0] > errs[1] > errs[2]
    assert len(meshes[0].faces) < len(meshes[1].faces) < len(meshes[2].faces)


def test_triangles_go_where_the_surface_curves(renzo):
    """Straight teeth with a cylindrical tip need far fewer planes than crowned ones."""
    straight = renzo.replace(**{"hub.crowning.kind": "none", "hub.tip.kind": "cylinder",
                                "hub.tip.diameter": 2 * 64.0})
    tol = 0.01
    n_crowned = len(build_part(renzo, "hub", tolerance_mm=tol).faces)
    n_straight = len(build_part(straight, "hub", tolerance_mm=tol).faces)
    assert n_straight < 0.5 * n_crowned
    mesh = build_part(straight, "hub", tolerance_mm=tol)
    assert measure_deviation(straight, mesh, samples=500)["max"] <= tol


def test_band_vertices_lie_on_the_exact_flank(renzo):
    mesh = build_part(renzo, "hub", tolerance_mm=0.02, teeth=[0])
    m = hub_model(renzo)
    faces = mesh.faces[mesh.face_attributes["kind"] == KIND["flank_cw"]]
    v = mesh.vertices[np.unique(faces)]
    v = v[np.abs(v[:, 2]) <= m.half_face]
    r = np.hypot(v[:, 0], v[:, 1])
    exact, _, _ = hub_flank_model(m, "cw", v[:, 2], r, check=False)
    assert np.max(np.linalg.norm(exact - v, axis=1)) < 1e-9 * m.R


def test_sleeve_flank_vertices_are_exact_involute_points(renzo):
    mesh = build_part(renzo, "sleeve", tolerance_mm=0.02, teeth=[0])
    sm = sleeve_model(renzo)
    v = mesh.vertices[np.unique(mesh.faces[mesh.face_attributes["kind"] == KIND["flank_cw"]])]
    r = np.hypot(v[:, 0], v[:, 1])
    p, _ = flank_point(sm, r)
    assert np.max(np.linalg.norm(p - v[:, :2], axis=1)) < 1e-9 * sm.R


@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_labels_and_orientation(renzo, part):
    mesh = build_part(renzo, part, tolerance_mm=0.02)
    kind, tooth = mesh.face_attributes["kind"], mesh.face_attributes["tooth"]
    c = mesh.triangles_center
    beta = np.stack([-c[:, 1], c[:, 0]], axis=1) / np.hypot(c[:, 0], c[:, 1])[:, None]
    nb = np.sum(mesh.face_normals[:, :2] * beta, axis=1)
    # cw flanks face decreasing polar angle, ccw flanks increasing (out of the material)
    sign = 1 if part == "hub" else -1
    assert np.all(sign * nb[kind == KIND["flank_cw"]] < 0)
    assert np.all(sign * nb[kind == KIND["flank_ccw"]] > 0)
    area = np.bincount(kind, weights=mesh.area_faces, minlength=len(SURFACE_KINDS))
    assert area[KIND["flank_cw"]] == pytest.approx(area[KIND["flank_ccw"]], rel=1e-9)
    # tooth index: the polar angle of a flank triangle is within half a pitch of its tooth
    n = renzo.tooth.teeth
    flank = np.isin(kind, [KIND["flank_cw"], KIND["flank_ccw"]])
    ang = np.arctan2(c[flank, 1], c[flank, 0])
    off = np.angle(np.exp(1j * (ang - 2 * np.pi * tooth[flank] / n)))
    assert np.all(np.abs(off) < np.pi / n)
    assert set(np.unique(tooth[flank])) == set(range(n))
    ends = kind == KIND["end"]
    assert np.allclose(np.abs(mesh.face_normals[ends, 2]), 1.0)


@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_sectors_are_exact_fractions_of_the_part(renzo, part):
    n = renzo.tooth.teeth
    full = build_part(renzo, part, tolerance_mm=0.05)
    for teeth in ([0, 1, 2, n - 1], [5], [3, 7, 8]):
        sector = build_part(renzo, part, tolerance_mm=0.05, teeth=teeth)
        check = check_part(sector)
        assert check.ok, check.problems()
        runs = 1 if teeth[0] == 0 else len({k - i for i, k in enumerate(teeth)})
        assert check.bodies == runs and check.genus == 0
        # the full part is n congruent pitch sectors
        assert sector.volume == pytest.approx(full.volume * len(teeth) / n, rel=1e-9)
        labelled = set(np.unique(sector.face_attributes["tooth"])) - {-1}
        assert labelled == set(teeth)
        assert np.count_nonzero(sector.face_attributes["kind"] == KIND["side"]) > 0


def test_selecting_every_tooth_is_the_whole_part(renzo):
    n = renzo.tooth.teeth
    whole = build_part(renzo, "hub", tolerance_mm=0.05, teeth=range(n))
    check = check_part(whole)
    assert check.ok and check.genus == 1
    full = build_part(renzo, "hub", tolerance_mm=0.05)
    assert whole.volume == pytest.approx(full.volume, rel=1e-12)


def test_solid_hub_and_body_as_long_as_the_face(renzo):
    for changes, genus in (({"hub.body.bore_diameter": 0.0}, 0),
                           ({"hub.body.length": renzo.hub.face_width}, 1),
                           ({"hub.body.bore_diameter": 0.0,
                             "hub.body.length": renzo.hub.face_width}, 0)):
        spec = renzo.replace(**changes)
        for teeth in (None, [0, 1]):
            mesh = build_part(spec, "hub", tolerance_mm=0.03, teeth=teeth)
            check = check_part(mesh)
            assert check.ok, (changes, teeth, check.problems())
            assert check.genus == (genus if teeth is None else 0)
        mesh = build_part(spec, "hub", tolerance_mm=0.03)
        assert measure_deviation(spec, mesh, samples=300)["max"] <= 0.03


def test_bore_and_outer_diameter_volumes_match_theory(renzo):
    """Solid minus bored hub is the bore cylinder; the sleeve ring outside the major circle
    is an annulus: both exact up to the circle chords (tolerance x area)."""
    tol = 0.002
    bored = build_part(renzo, "hub", tolerance_mm=tol)
    solid = build_part(renzo.replace(**{"hub.body.bore_diameter": 0.0}), "hub", tolerance_mm=tol)
    r, L = 0.5 * renzo.hub.body.bore_diameter, renzo.hub.body.length
    bore = math.pi * r * r * L
    assert solid.volume - bored.volume == pytest.approx(bore, abs=tol * 2 * math.pi * r * L)


def test_bad_input_is_refused_with_a_clear_message(renzo):
    with pytest.raises(ValueError, match="part"):
        build_part(renzo, "shaft")
    for tol in (0.0, -1.0, float("nan"), float("inf"), 10.0, "fine"):
        with pytest.raises(ValueError, match="tolerance_mm"):
            build_part(renzo, "hub", tolerance_mm=tol)
    for teeth in ([50], [-1], [], ["a"]):
        with pytest.raises(ValueError, match="teeth"):
            build_part(renzo, "hub", tolerance_mm=0.05, teeth=teeth)


def test_distance_to_mesh_against_a_known_surface():
    import trimesh

    box = trimesh.creation.box(extents=(2.0, 2.0, 2.0))
    pts = np.array([[0.0, 0.0, 1.5], [0.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.3, -0.2, 1.0]])
    d = distance_to_mesh(pts, box.vertices, box.faces)
    assert d == pytest.approx([0.5, 1.0, math.sqrt(2.0), 0.0], abs=1e-12)


@pytest.mark.parametrize("stratum", STRATA[::3], ids="-".join)
def test_random_specs_build_valid_parts_within_tolerance(stratum):
    """One seeded random spec per sampled stratum (crown kind x generation x tip): the first
    of a few draws that the spec validation accepts must build valid parts and sectors."""
    rng = np.random.default_rng(20261123 + STRATA.index(stratum))
    for _ in range(8):
        try:
            spec = gc.spec_from_dict(random_spec_data(rng, *stratum))
            break
        except gc.SpecError:
            continue
    else:
        pytest.fail(f"no spec of stratum {stratum} accepted in 8 draws")
    tol = _tol(spec, 0.05)
    for part in ("hub", "sleeve"):
        for teeth in (None, [0, 1, spec.tooth.teeth - 1]):
            mesh = build_part(spec, part, tolerance_mm=tol, teeth=teeth)
            check = check_part(mesh)
            assert check.ok, (part, teeth, check.problems())
            assert np.all(np.isfinite(mesh.vertices))
        sector = build_part(spec, part, tolerance_mm=tol, teeth=[0])
        assert measure_deviation(spec, sector, samples=200)["max"] <= tol


@pytest.mark.parametrize("tooth, hub", [
    ({"teeth": 6, "module": 60.0, "pressure_angle_deg": 30},
     {"root": {"dedendum": 0.8 * 60, "fillet_radius": 0.3 * 60}}),
    ({"teeth": 300, "module": 0.2, "pressure_angle_deg": 14.5}, {}),
    ({"teeth": 40, "module": 0.2, "pressure_angle_deg": 20},
     {"crowning": {"kind": "circular", "radius": 1.0}}),
])
def test_the_extremes_of_the_range_build_valid_parts(tooth, hub):
    R = tooth["module"] * tooth["teeth"] / 2
    data = {"design_misalignment_deg": 6.0, "tooth": tooth,
            "hub": {"face_width": 0.2 * R, "crowning": {"kind": "circular", "radius": R}, **hub}}
    spec = gc.spec_from_dict(data)
    tol = _tol(spec, 0.02)
    for part in ("hub", "sleeve"):
        mesh = build_part(spec, part, tolerance_mm=tol)
        check = check_part(mesh)
        assert check.ok, (part, check.problems())
        assert measure_deviation(spec, mesh, samples=300)["max"] <= tol


GOLDEN_PARTS = json.loads((Path(__file__).parent / "golden" / "parts.json").read_text())


@pytest.mark.parametrize("name", sorted(GOLDEN_PARTS))
@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_mesh_volume_is_pinned_per_template(name, part):
    """Mesh at the default tolerance against ``golden/parts.json`` (source and regeneration:
    ``tests/golden_parts.py``): triangles exact, volume to 1e-9; and the golden volume
    against the STEP solid of the exact geometry (within tolerance x area)."""
    gold = GOLDEN_PARTS[name][part]
    spec = gc.load_spec(name)
    mesh = build_part(spec, part, tolerance_mm=None)
    assert len(mesh.faces) == gold["triangles"]
    assert mesh.volume == pytest.approx(gold["volume_mm3"], rel=1e-9)
    assert abs(gold["volume_mm3"] - gold["step_volume_mm3"]) <= \
        (gold["tolerance_mm"] + gold["step_tolerance_mm"]) * gold["area_mm2"]
