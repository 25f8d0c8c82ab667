"""Hob feed program: centre path against closed forms, program within its tolerance."""

import math
import re

import numpy as np
import pytest
from scipy.spatial import cKDTree

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.geometry.hub import hub_model
from gearcoupling.hob import hob_program

TABLE = {"hub.crowning.kind": "table", "hub.crowning.radius": math.inf,
         "hub.crowning.z": [0.0, 3.0, 6.0, 9.0, 12.0],
         "hub.crowning.drop": [0.0, 0.02, 0.09, 0.21, 0.40]}
CASES = {
    "circular": ("renzo-1967", {}),
    "end_round": ("renzo-1967-end-round", {}),
    "vari_crown": ("renzo-1967-vari-crown", {}),
    "table": ("renzo-1967", TABLE),
    "none": ("industrial-m2", {"hub.crowning.kind": "none"}),
}


def spec_of(kind):
    name, changes = CASES[kind]
    spec = gc.load_spec(name)
    return spec.replace(**changes) if changes else spec


def exact_centre_polyline(spec, r_h, s_max, n=200_001):
    """Hob centre from the path points with the normal by central differences of q(s)."""
    m = hub_model(spec)
    s = np.linspace(-1.01 * s_max, 1.01 * s_max, n)  # one-sided differences off the ends
    _, _, qv, qz = m.path.evaluate(s)
    dv, dz = np.gradient(qv, s), np.gradient(qz, s)
    norm = np.hypot(dv, dz)
    nv, nz = dz / norm, -dv / norm  # tangent (-sin e, cos e) turned to the outward normal
    return np.stack([qz + r_h * nz, qv + r_h * nv], axis=-1)


def distance_to_polyline(points, poly):
    """Distance of points to a dense polyline (nearest vertex, then its two segments)."""
    _, i = cKDTree(poly).query(points)
    best = np.full(len(points), np.inf)
    for j0 in (np.maximum(i - 1, 0), i):
        a, b = poly[j0], poly[np.minimum(j0 + 1, len(poly) - 1)]
        d = b - a
        t = np.clip(np.einsum("ij,ij->i", points - a, d) / np.maximum(
            np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
        best = np.minimum(best, np.linalg.norm(points - a - t[:, None] * d, axis=1))
    return best


def sample_moves(prog, n=400):
    """Points along every feed-path move: straight chords or arcs about their centres."""
    out = []
    t = np.linspace(0, 1, n)
    for mv in prog.moves[1:-1]:
        a, b = np.array(mv.start), np.array(mv.end)
        if mv.kind == "line":
            out.append(a + t[:, None] * (b - a))
        else:
            c = np.array(mv.centre)
            r = np.linalg.norm(a - c)
            assert abs(np.linalg.norm(b - c) - r) < 1e-9 * r
            a0 = math.atan2(*(a - c)[::-1])
            a1 = math.atan2(*(b - c)[::-1])
            ang = a0 + t * (a1 - a0)
            out.append(c + r * np.stack([np.cos(ang), np.sin(ang)], axis=-1))
    return np.concatenate(out)


def test_circular_centre_lies_on_circle_about_crowning_axis():
    spec = spec_of("circular")
    prog = hob_program(spec, 101.6)
    rc, R = spec.hub.crowning.radius, spec.tooth.pitch_radius
    r_h = 0.5 * 101.6 - spec.hub.root.dedendum
    assert prog.hob_pitch_radius_mm == pytest.approx(r_h, abs=1e-12)
    zx = np.stack([prog.table["z_mm"], prog.table["x_mm"]], axis=-1)
    C = np.array([0.0, R - rc])
    assert np.max(np.abs(np.linalg.norm(zx - C, axis=1) - (rc + r_h))) < 1e-9
    (arc,) = [m for m in prog.moves if m.kind == "arc"]
    assert np.allclose(arc.centre, C, atol=1e-9) and arc.clockwise
    for p in (arc.start, arc.end):
        assert abs(np.linalg.norm(np.array(p) - C) - (rc + r_h)) < 1e-9
    assert prog.max_deviation_mm == 0.0


@pytest.mark.parametrize("kind", list(CASES))
@pytest.mark.parametrize("tol_module", [1e-3, 1e-4])
def test_program_follows_exact_path_within_tolerance(kind, tol_module):
    spec = spec_of(kind)
    D = 40.0 * spec.tooth.module
    tol = tol_module * spec.tooth.module
    prog = hob_program(spec, D, tolerance_mm=tol)
    poly = exact_centre_polyline(spec, prog.hob_pitch_radius_mm, prog.s_generate_mm)
    ends = np.array([m.start for m in prog.moves[1:-1]] + [prog.moves[-2].end])
    assert np.max(distance_to_polyline(ends, poly)) < 1e-7  # vertices on the path
    dev = distance_to_polyline(sample_moves(prog), poly)
    assert np.max(dev) <= tol * (1 + 1e-6) + 1e-7
    # the reported deviation is what an independent dense check finds (to 2 %)
    assert prog.max_deviation_mm == pytest.approx(np.max(dev), rel=0.02, abs=2e-7)
    # run-outs are straight at the end infeeds, approach = sqrt(H (D - H))
    H = prog.whole_depth_mm
    assert prog.approach_mm == pytest.approx(math.sqrt(H * (D - H)), rel=1e-12)
    assert prog.moves[0].start[1] == prog.moves[0].end[1]
    assert prog.z_start_mm <= -0.5 * spec.hub.face_width - prog.approach_mm + 1e-9


def test_straight_hub_is_one_line_at_constant_infeed():
    spec = spec_of("none")
    prog = hob_program(spec, 80.0)
    assert all(m.kind == "line" for m in prog.moves)
    x = 0.5 * 80.0 - spec.hub.root.dedendum + spec.tooth.pitch_radius
    assert np.allclose(prog.table["x_mm"], x, atol=1e-12)
    assert prog.crown_drop_end_mm == 0.0 and len(prog.moves) == 3


def test_crown_drop_at_the_ends_is_the_circle_sagitta():
    spec = spec_of("circular")
    rc, b = spec.hub.crowning.radius, spec.hub.face_width
    prog = hob_program(spec, 101.6)
    assert prog.crown_drop_end_mm == pytest.approx(rc - math.sqrt(rc**2 - (b / 2) ** 2),
                                                   abs=1e-12)


def test_cli_writes_gcode_that_replays_onto_the_path(tmp_path, capsys):
    out = tmp_path / "hob"
    assert main(["hob", "renzo-1967-end-round", "--hob-diameter", "101.6", "-o",
                 str(out)]) == 0
    spec = spec_of("end_round")
    prog = hob_program(spec, 101.6)
    text = (out / "hob_program.nc").read_text()
    pos, arcs = (0.0, 0.0), 0
    for line in text.splitlines():
        if not line.startswith("G"):
            continue  # comments, %, M30
        words = dict(re.findall(r"([A-Z])(-?[\d.]+)", line))
        code = line.split()[0]
        end = (float(words.get("Z", pos[0])), float(words.get("X", pos[1])))
        if code in ("G2", "G3"):
            centre = (pos[0] + float(words["K"]), pos[1] + float(words["I"]))
            assert abs(math.dist(pos, centre) - math.dist(end, centre)) < 2e-5
            mv = prog.moves[1 + arcs]
            assert math.dist(centre, mv.centre) < 2e-5 and (code == "G2") == mv.clockwise
            assert math.dist(end, mv.end) < 1e-5
            arcs += 1
        pos = end
    assert arcs == 3
    assert math.dist(pos, (prog.z_end_mm, prog.moves[-1].end[1] + prog.whole_depth_mm)) < 1e-4
    rows = (out / "hob_path.csv").read_text().splitlines()
    assert rows[0].startswith("#") and rows[1].startswith("s_mm,z_mm,x_mm,infeed_mm")


@pytest.mark.parametrize("argv", [["--hob-diameter", "nan"], ["--hob-diameter", "3"],
                                  ["--hob-diameter", "100", "--tolerance", "0"],
                                  ["--hob-diameter", "100", "--feed", "-1"]])
def test_bad_hob_input_exits_2(argv, tmp_path, capsys):
    assert main(["hob", "renzo-1967", "-o", str(tmp_path), *argv]) == 2
    assert "gearcoupling: error:" in capsys.readouterr().err
