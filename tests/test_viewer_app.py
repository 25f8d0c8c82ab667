"""The live viewer's controls, driven from the server side (no browser): each GUI change
reaches the scene the way the issue asks."""

from __future__ import annotations

import os
import stat
import time

import numpy as np
import pytest

from gearcoupling.viewer import scene as vs

pytestmark = [pytest.mark.needs_viewer]

viser = pytest.importorskip("viser")


@pytest.fixture
def app(renzo, tmp_path):
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.nodes import ViewSettings
    from gearcoupling.viewer.server import ViewerApp

    a = ViewerApp(renzo, port=free_port(), settings=ViewSettings(misalignment_deg=1.0),
                  html_path=tmp_path / "shared" / "viewer.html")
    yield a
    a.stop()


def test_controls_reach_the_scene(app, renzo):
    sc = app.scene
    # sleeve cutaway: the half through the tilt axis keeps y >= 0
    app.panel.cutaway.value = "half"
    app.apply({"cutaway"})
    assert sc.settings.cutaway == "half"
    assert np.asarray(sc.sleeve.vertices)[:, 1].min() >= -1e-4

    # level of detail: a finer mesh, same pose
    coarse = sc.meshes.triangles
    app.panel.lod.value = "medium"
    app.apply({"lod"})
    assert sc.meshes.tolerance_mm == pytest.approx(renzo.tooth.module / 100)
    assert sc.meshes.triangles > coarse
    assert "tolerance 0.0254 mm" in app.panel.mesh_info.content

    # show/hide and transparency of the hub
    app.panel.show_hub.value = False
    app.panel.hub_opacity.value = 0.5
    app.apply({"display"})
    hub_nodes = [sc.hub_body, *sc._flanks[0], *sc._flanks[1]]
    assert all(not h.visible and h.opacity == 0.5 for h in hub_nodes)

    # colour scale: legend and flank colours follow
    app.panel.scale.value = 0.02
    app.apply({"scale"})
    assert "0.0200 mm" in app.panel.legend.content
    cols = vs.clearance_colors(sc.state.clearance_mm, 0.02)
    assert tuple(sc._flanks[0][3].color) == tuple(int(c) for c in cols[0, 3])
    app.panel.color_mode.value = "separation"
    app.apply({"scale"})
    assert "separation" in app.panel.legend.content
    cols = vs.clearance_colors(vs.flank_values(sc.state, "separation"), 0.02)
    k = int(np.argmin(sc.state.clearance_mm[1]))  # first contact: the touching colour
    assert tuple(sc._flanks[1][k].color) == tuple(int(c) for c in cols[1, k]) == (255, 215, 0)

    # pose: misalignment 3° at psi 45° interferes; status, plot and red solid follow
    app.panel.misalignment.value = 3.0
    app.panel.rotation.value = 45.0
    app.apply({"misalignment"})
    assert (sc.state.misalignment_deg, sc.state.psi_deg) == (3.0, 45.0)
    assert sc.state.interfering.any() and sc.interference_volume_mm3 > 0
    assert "interference volume" in app.panel.status.content
    x, *_, ring = app.panel.plot.data
    assert x[np.isfinite(ring)][0] == pytest.approx(45.0)
    lo, hi = app.panel.plot.scales["y"]["range"]
    assert lo < sc.state.clearance_mm.min() and hi > 0


def test_ground_frame_turns_both_members(app):
    """Ground frame: the sleeve turns by Rz(psi), the hub by Rx(i) Rz(psi) (docs/conventions.md,
    Frames
    seen from the ground: Rz(psi) Rz(-psi) Rx(i) Rz(psi))."""
    from scipy.spatial.transform import Rotation

    app.panel.frame.value = "ground"
    app.panel.misalignment.value = 2.0
    app.panel.rotation.value = 70.0
    app.apply({"pose"})
    sc = app.scene

    def quat(rot):
        x, y, z, w = rot.as_quat()
        q = np.array([w, x, y, z])
        return q if w >= 0 else -q

    hub = Rotation.from_euler("x", 2.0, degrees=True) * Rotation.from_euler("z", 70.0,
                                                                             degrees=True)
    np.testing.assert_allclose(sc.hub_frame.wxyz, quat(hub), atol=1e-12)
    np.testing.assert_allclose(sc.sleeve.wxyz, quat(Rotation.from_euler("z", 70.0,
                                                                         degrees=True)),
                               atol=1e-12)
    app.panel.frame.value = "sleeve"
    app.apply({"pose"})
    np.testing.assert_allclose(sc.sleeve.wxyz, [1, 0, 0, 0], atol=1e-12)


def test_play_turns_the_coupling_and_pause_stops_it(app):
    """Event-driven: wait for worker iterations, not for wall-clock sleeps."""
    app.panel.speed.value = 60.0
    psi0, updates = app.panel.rotation.value, app.pose_updates
    start = time.monotonic()
    app._toggle_play()
    assert app.panel.play.label == "Pause"
    assert app.wait_ticks(4)
    app._toggle_play()
    assert app.panel.play.label == "Play"
    assert app.wait_ticks(2)  # the iteration running at the pause, then one that sees it
    elapsed = time.monotonic() - start
    psi = app.panel.rotation.value
    assert app.pose_updates >= updates + 3
    turned = (psi - psi0) % 360.0
    assert 0.0 < turned <= 60.0 * elapsed + 1e-9  # at most the speed times the time played
    assert app.wait_ticks(3)
    assert app.panel.rotation.value == psi  # paused: further iterations leave it


def test_save_button_writes_a_shareable_html(app):
    app.apply({"save"})
    path = app.html_path
    text = path.read_text()
    assert text.startswith("<!doctype html>") and "__VISER_EMBED_DATA__" in text
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~mask  # as the umask allows
    assert str(path) in app.panel.saved.content


def test_bad_tolerance_is_refused_and_frees_the_port(renzo):
    import socket

    from gearcoupling.errors import ArgumentError
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.server import ViewerApp

    port = free_port()
    with pytest.raises(ArgumentError, match="tolerance_mm"):
        ViewerApp(renzo, port=port, tolerance_mm=50.0)
    with socket.socket() as s:  # the server was stopped: the port binds again
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(("127.0.0.1", port))
