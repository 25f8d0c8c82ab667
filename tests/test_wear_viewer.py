"""The worn hub flanks as a heat map in the viewer (issue 41): every flank vertex of the
scene carries the colour of the history's depth map at its axial position and involute arc
length (interpolated here independently, with scipy), the unloaded flanks stay grey, and
the static page is self-contained with the spec's name as escaped text."""

from __future__ import annotations

import contextlib
import io

import numpy as np
import pytest

import gearcoupling as gc

pytestmark = pytest.mark.needs_viewer


@pytest.fixture(scope="module")
def worn(renzo):
    """A 200-h history at 1°, 2000 N·m (the ccw flanks loaded), coarse knobs."""
    return gc.wear(renzo, 1.0, 2000.0, 1800.0, 200.0, grid=(16, 8), phases=1)


@pytest.fixture(scope="module")
def scene(worn):
    import viser

    from gearcoupling.viewer import ViewSettings
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.wear import WearScene

    with contextlib.redirect_stdout(io.StringIO()):
        server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        yield WearScene(server, worn, ViewSettings(misalignment_deg=1.0))
    finally:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()


def _expected_depth(worn, f, k, vertices):
    """The depth map at the vertices, by scipy's linear interpolation between the cell
    centres (the edge values held beyond them)."""
    from scipy.interpolate import RegularGridInterpolator

    g = worn.hub_grid
    z, s = g.z_mm, g.s_mm
    r_b = worn.spec.tooth.base_radius
    v = vertices.astype(float)
    sv = (v[:, 0] ** 2 + v[:, 1] ** 2 - r_b ** 2) / (2 * r_b)
    depth = worn.hub_depth_mm[f, k if worn.hub_depth_mm.shape[1] > 1 else 0]
    points = np.column_stack([np.clip(v[:, 2], z[0], z[-1]), np.clip(sv, s[0], s[-1])])
    return RegularGridInterpolator((z, s), depth)(points)


def test_the_scene_colours_each_flank_vertex_by_the_depth_map(worn, scene):
    import trimesh

    from gearcoupling.viewer.scene.wear import UNWORN_RGB, wear_colors

    pieces = scene.meshes.hub_pieces
    teeth = worn.spec.tooth.teeth
    assert [len(side) for side in scene.glb] == [teeth, teeth]
    expected = [[_expected_depth(worn, f, k, pieces.flanks[f][k].vertices)
                 for k in range(teeth)] for f in range(2)]
    top = max(float(np.max(d)) for side in expected for d in side)
    assert scene.top_mm == pytest.approx(top, rel=1e-12)
    assert 0.5 * float(np.max(worn.hub_depth_mm)) < top <= float(np.max(worn.hub_depth_mm))
    for f in range(2):
        for k in range(teeth):
            sent = trimesh.load(io.BytesIO(scene.glb[f][k]), file_type="glb", force="mesh")
            patch = pieces.flanks[f][k]
            np.testing.assert_allclose(sent.vertices, patch.vertices, atol=1e-4)
            rgb = np.asarray(sent.visual.vertex_colors)[:, :3].astype(int)
            want = wear_colors(expected[f][k], top).astype(int)
            assert np.max(np.abs(rgb - want)) <= 1, (f, k)
    # the unloaded cw flanks do not wear: grey; the loaded ccw ones reach the top colour
    cw = np.concatenate([np.asarray(trimesh.load(io.BytesIO(b), file_type="glb",
                                                 force="mesh").visual.vertex_colors)[:, :3]
                         for b in scene.glb[0]])
    assert np.all(cw == np.asarray(UNWORN_RGB))
    assert any(np.any(np.all(c == (170, 20, 20), axis=1)) for c in scene.colors[1])


def test_the_static_page_is_self_contained_and_names_the_spec_as_text(worn):
    import dataclasses

    from gearcoupling.viewer.wear import wear_html

    hostile = dataclasses.replace(worn, spec=worn.spec.replace(name="<script>x</script>"))
    page = wear_html(hostile)
    assert "&lt;script&gt;x&lt;/script&gt;: worn hub flanks after 200 h" in page
    assert "<script>x</script>" not in page
    assert "http://" not in page.replace("http://www.w3.org", "")
    with pytest.raises(gc.ArgumentError, match="result"):
        wear_html("renzo-1967")
