"""Every bundled template builds, says where its numbers come from, and matches its golden
values (derived sizes to 1e-9 relative, flank points to 1e-9 mm, normals to 1e-12)."""

import json

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.io import bundled_dir

from golden_values import GOLDEN, golden


def test_at_least_the_issue_templates_exist():
    names = set(gc.template_names())
    assert {"renzo-1967", "renzo-1967-vari-crown", "renzo-1967-end-round", "industrial-m2",
            "mill-spindle"} <= names
    kinds = {gc.load_spec(n).hub.crowning.kind for n in names}
    assert {"circular", "vari_crown", "end_round"} <= kinds
    assert max(gc.load_spec(n).design_misalignment for n in names) >= np.radians(3)


@pytest.mark.parametrize("name", gc.template_names())
def test_template_is_headed_by_its_source_and_a_disclaimer(name):
    head = (bundled_dir("templates") / f"{name}.toml").read_text().split("\n\n")[0]
    assert head.startswith(f"# {name}") and "not a standard" in head


@pytest.mark.parametrize("name", gc.template_names())
def test_template_matches_golden_values(name):
    path = GOLDEN / f"{name}.json"
    want = json.loads(path.read_text())
    got = golden(gc.load_spec(name))
    assert got["derived"] == pytest.approx(want["derived"], rel=1e-9, abs=1e-12)
    for flank in ("cw", "ccw"):
        g, w = got["flanks"][flank], want["flanks"][flank]
        assert np.max(np.abs(np.array(g["points_mm"]) - w["points_mm"])) < 1e-9
        assert np.max(np.abs(np.array(g["normals"]) - w["normals"])) < 1e-12


@pytest.mark.parametrize("name", gc.template_names())
def test_template_sections_build(name):
    spec = gc.load_spec(name)
    for part in ("hub", "sleeve"):
        poly = gc.transverse_section(spec, part, 0.5 * spec.hub.face_width, 1e-3)
        assert len(poly) > 10 * spec.tooth.teeth and np.all(np.isfinite(poly))
