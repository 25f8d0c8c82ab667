"""Viewer scene logic without a browser: poses, hub split, colours, contact points,
interference, cutaways, plot data, the HTML writer and the CLI."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.errors import ArgumentError, BackendError
from gearcoupling.geometry.sleeve import sleeve_flank, sleeve_model
from gearcoupling.viewer import scene as vs

TOL = 0.127  # coarse viewing tolerance of renzo-1967 (module / 20)


@pytest.fixture(scope="module")
def meshes(renzo):
    return vs.build_scene_meshes(renzo)


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


@pytest.mark.parametrize(("mis", "psi"), [(0.0, 0.0), (1.0, 37.0), (6.0, 250.0), (3.0, -90.0)])
def test_hub_rotation_is_design_pose_and_quaternion_matches(mis, psi):
    rot = vs.hub_rotation(mis, psi)
    i, p = math.radians(mis), math.radians(psi)
    np.testing.assert_allclose(rot, _rz(-p) @ _rx(i) @ _rz(p), atol=1e-14)
    # the hub axis is tilted by exactly i from the sleeve axis
    assert math.degrees(math.acos(np.clip(rot[2, 2], -1, 1))) == pytest.approx(mis, abs=1e-9)
    # rotate vectors with the quaternion formula v' = v + 2w (q x v) + 2 q x (q x v)
    w, *q = vs.quaternion_wxyz(rot)
    q = np.array(q)
    assert w >= 0 and w * w + q @ q == pytest.approx(1.0, abs=1e-14)
    for v in np.eye(3):
        t = 2 * np.cross(q, v)
        np.testing.assert_allclose(v + w * t + np.cross(q, t), rot @ v, atol=1e-12)


def test_split_hub_partitions_faces_and_patches_sit_on_their_tooth(renzo, meshes):
    hub, pieces = meshes.hub, meshes.hub_pieces
    N = renzo.tooth.teeth
    n_patch = sum(len(p.faces) for fl in pieces.flanks for p in fl)
    assert len(pieces.body.faces) + n_patch == len(hub.faces)
    area = 0.0
    for f, sign in ((0, -1.0), (1, 1.0)):  # cw flank at decreasing polar angle (y < 0)
        assert len(pieces.flanks[f]) == N
        for k, patch in enumerate(pieces.flanks[f]):
            v = patch.vertices.astype(float)
            assert patch.faces.max() < len(v) and len(patch.faces) > 0
            rel = np.angle(np.exp(1j * (np.arctan2(v[:, 1], v[:, 0]) - 2 * np.pi * k / N)))
            assert np.all(sign * rel > 0) and np.all(np.abs(rel) < np.pi / N)
            tri = v[patch.faces]
            area += 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0],
                                                  tri[:, 2] - tri[:, 0]), axis=1).sum()
    kind = np.asarray(hub.face_attributes["kind"])
    codes = [gc.parts.SURFACE_KINDS.index(k) for k in ("flank_cw", "flank_ccw")]
    assert area == pytest.approx(hub.area_faces[np.isin(kind, codes)].sum(), rel=1e-5)


def test_clearance_colors_and_legend():
    s = 0.08
    c = vs.clearance_colors([-1e-6, 0.0, s, 10 * s, np.inf], s)
    assert tuple(c[0]) == vs.INTERFERENCE_RGB
    assert tuple(c[1]) == (255, 215, 0)  # touching: the first stop
    assert tuple(c[2]) == tuple(c[3]) == (40, 80, 200)  # the scale and above: the last stop
    assert tuple(c[4]) == vs.NO_CONTACT_RGB
    # continuous: a 1/1000 step of the scale moves no channel by more than 1
    x = np.linspace(0, s, 1001)
    steps = np.abs(np.diff(vs.clearance_colors(x, s).astype(int), axis=0))
    assert steps.max() <= 1
    for (label, rgb), value in zip(vs.legend(s)[1:-1], np.linspace(0, s, 5), strict=True):
        assert f"{value:.4f}" in label
        assert rgb == tuple(int(v) for v in vs.clearance_colors(value, s))
    with pytest.raises(ArgumentError, match="color_scale_mm"):
        vs.clearance_colors([0.0], 0.0)


def test_pose_state_contact_points_have_the_reported_gap(renzo):
    """Independent check of the contact points: posed into the sleeve frame, their gap to
    the sleeve flank (kernel ``sleeve_flank``) along its normal is the normal clearance."""
    st = vs.pose_state(renzo, 1.0, 12.0, band_mm=0.002)
    N, r_b = renzo.tooth.teeth, renzo.tooth.base_radius
    assert st.clearance_mm.shape == (2, N) and np.all(np.isfinite(st.clearance_mm))
    assert st.contact_points.shape[0] >= 2 and not st.interfering.any()
    rot = vs.hub_rotation(1.0, 12.0)
    sm = sleeve_model(renzo)
    checked = 0
    for p, f, k in zip(st.contact_points, st.contact_flank, st.contact_tooth, strict=True):
        q = _rz(-2 * np.pi * k / N) @ rot @ p  # into space 0's frame
        rq, aq = math.hypot(q[0], q[1]), math.atan2(q[1], q[0])
        if not (sm.r_form < rq < sm.r_fillet and abs(q[2]) <= sm.half_face):
            continue
        s, _ = sleeve_flank(renzo, ("cw", "ccw")[f], q[2], rq)
        beta = math.atan2(s[1], s[0])
        gap = r_b * ((aq - beta) if f == 0 else (beta - aq))
        assert gap == pytest.approx(st.normal_clearance_mm[f, k], abs=2e-5)
        checked += 1
    assert checked >= 2
    # both flanks have a tooth in contact within the band of their own minimum
    assert set(st.contact_flank.tolist()) == {0, 1}
    assert "backlash" in st.summary()


def test_aligned_coupling_has_constant_clearance_half_the_backlash(renzo):
    """Aligned, every flank has the same clearance; along the normal it is half the
    aligned backlash times r_b / R (involutes of one base circle are parallel)."""
    curve = vs.clearance_curve(renzo, 0.0, samples=100)
    assert np.all(np.diff(curve.theta_deg) > 0) and curve.theta_deg.size >= 100
    np.testing.assert_allclose(curve.clearance_mm, curve.clearance_mm[0, 0], atol=1e-7)
    st = vs.pose_state(renzo, 0.0, 5.0)
    half = 0.5 * renzo.derived["aligned_backlash_mm"]
    np.testing.assert_allclose(st.normal_clearance_mm, half * math.cos(
        renzo.tooth.pressure_angle), atol=1e-6)
    np.testing.assert_allclose(st.clearance_mm, curve.clearance_mm[0, 0], atol=1e-7)
    # circumferentially r * dalpha: smallest at the lowest active radius, below R
    # (the sweep's 1e-7 mm clearance tolerance moves r_star by R * 1e-7 / half < 1e-4 mm)
    r_star = curve.clearance_mm[0, 0] / half * renzo.tooth.pitch_radius
    assert sleeve_model(renzo).r_form - 1e-4 <= r_star < renzo.tooth.pitch_radius


def test_plot_series_marks_every_tooth_at_its_theta(renzo):
    curve = vs.clearance_curve(renzo, 1.0, samples=200)
    st = vs.pose_state(renzo, 1.0, 33.0)
    x, cw, ccw, cw_now, ccw_now, first = vs.plot_series(curve, st)
    assert x.shape == cw.shape == ccw.shape == cw_now.shape == ccw_now.shape == first.shape
    ring = np.flatnonzero(np.isfinite(first))
    assert ring.size == 1 and x[ring[0]] == pytest.approx(33.0)
    assert first[ring[0]] == pytest.approx(st.clearance_mm[:, 0].min())
    assert np.all(np.diff(x) >= 0)
    for now, f in ((cw_now, 0), (ccw_now, 1)):
        marks = np.isfinite(now)
        assert marks.sum() == renzo.tooth.teeth
        np.testing.assert_allclose(np.sort(now[marks]), np.sort(st.clearance_mm[f]))
    # the curve through the markers: interpolation between 200 samples misses the exact
    # clearance by far less than the colour resolution (1/255 of the scale)
    marks = np.isfinite(cw_now)
    assert np.max(np.abs(cw[marks] - cw_now[marks])) < vs.default_color_scale_mm(renzo) / 255


def test_interference_volume_matches_the_sweep(renzo, meshes):
    free = vs.pose_state(renzo, 1.0, 10.0)
    assert not free.interfering.any()
    _, v_free = vs.interference_mesh(meshes, vs.hub_rotation(1.0, 10.0))
    assert v_free == 0.0
    bad = vs.pose_state(renzo, 3.0, 10.0)
    assert bad.interfering.any()
    rot = vs.hub_rotation(3.0, 10.0)
    _, v_all = vs.interference_mesh(meshes, rot)
    patch, v = vs.interference_mesh(meshes, rot, bad.interfering)
    assert 0 < v <= v_all and len(patch.faces) > 0
    # the overlap sits at the teeth the sweep calls interfering (polar angle of its
    # vertices within half a pitch of one of them)
    N = renzo.tooth.teeth
    teeth = np.flatnonzero(bad.interfering.any(axis=0))
    ang = np.arctan2(patch.vertices[:, 1], patch.vertices[:, 0])
    d = np.angle(np.exp(1j * (ang[:, None] - 2 * np.pi * teeth[None, :] / N)))
    assert np.all(np.min(np.abs(d), axis=1) < np.pi / N)


def test_interference_pieces_outside_the_sweep_need_more_than_chord_depth(renzo, meshes):
    """With no flank interfering per the sweep, only pieces thicker than the chordal
    tolerance (which chord error cannot make) are kept."""
    none = np.zeros((2, renzo.tooth.teeth), dtype=bool)
    _, v3 = vs.interference_mesh(meshes, vs.hub_rotation(3.0, 10.0), none)
    assert v3 == 0.0  # 0.14 mm deep at most: thinner than 0.127 mm on average
    _, v6 = vs.interference_mesh(meshes, vs.hub_rotation(6.0, 10.0), none)
    _, v6_all = vs.interference_mesh(meshes, vs.hub_rotation(6.0, 10.0))
    assert 0 < v6 < v6_all  # 0.49 mm deep: the thick pieces stay, the slivers go


@pytest.mark.parametrize(("cutaway", "fraction"), [("none", 1.0), ("half", 0.5),
                                                   ("midplane", 0.5), ("quarter", 0.75)])
def test_cutaways_remove_their_share_of_the_sleeve(meshes, cutaway, fraction):
    full = meshes.sleeve_manifold.volume()
    patch = meshes.sleeve_cut(cutaway)
    tri = patch.vertices.astype(float)[patch.faces]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6
    # 50 teeth do not split evenly into quarters: one tooth pitch of slack
    assert volume == pytest.approx(fraction * full, rel=0.02 if cutaway == "quarter" else 1e-3)
    v = patch.vertices
    if cutaway == "half":
        assert v[:, 1].min() >= -1e-4
    if cutaway == "midplane":
        assert v[:, 2].max() <= 1e-4
    if cutaway == "quarter":
        assert not np.any((v[:, 0] < -1e-3) & (v[:, 1] < -1e-3))


def test_bad_input_is_refused_clearly(renzo):
    with pytest.raises(ArgumentError, match="misalignment_deg"):
        vs.pose_state(renzo, 7.0, 0.0)
    with pytest.raises(ArgumentError, match="psi_deg"):
        vs.pose_state(renzo, 1.0, float("nan"))
    with pytest.raises(ArgumentError, match="band_mm"):
        vs.pose_state(renzo, 1.0, 0.0, band_mm=-1.0)
    with pytest.raises(ArgumentError, match="tolerance_mm"):
        vs.build_scene_meshes(renzo, tolerance_mm=100.0)
    with pytest.raises(ValueError, match="cutaway"):
        vs.cut_sleeve(None, "sideways")


@pytest.mark.parametrize(("overrides", "mis"), [
    ({"hub.crowning.kind": "none"}, 0.0),
    ({"hub.crowning.kind": "none"}, 6.0),
    ({}, 6.0),
])
def test_extreme_poses_stay_finite(overrides, mis):
    spec = gc.load_spec("industrial-m2", **overrides)
    st = vs.pose_state(spec, mis, 45.0)
    assert np.all(np.isfinite(st.clearance_mm) | (st.clearance_mm == np.inf))
    assert np.all(np.isfinite(st.contact_points))
    c = vs.clearance_colors(st.clearance_mm, vs.default_color_scale_mm(spec))
    assert c.shape == (2, spec.tooth.teeth, 3)


# ---------------------------------------------------------------- viser, no browser


@pytest.fixture(scope="module")
def viser():
    return pytest.importorskip("viser")


def test_pose_change_sends_no_mesh(renzo, viser):
    """A new pose moves the hub and recolours: no mesh message is sent again."""
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.nodes import CouplingScene, ViewSettings

    server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        scene = CouplingScene(server, renzo, ViewSettings(misalignment_deg=1.0), TOL)
        sent = []
        queue = server._websock_server.queue_message
        server._websock_server.queue_message = lambda m: (sent.append(m), queue(m))[1]
        before = scene.hub_frame.wxyz.copy()
        state = scene.set_pose(1.0, 45.0)
        names = {type(m).__name__ for m in sent}
        assert "MeshMessage" not in names
        assert not np.allclose(scene.hub_frame.wxyz, before)
        np.testing.assert_allclose(scene.hub_frame.wxyz,
                                   vs.quaternion_wxyz(vs.hub_rotation(1.0, 45.0)))
        cols = vs.clearance_colors(state.clearance_mm, scene.color_scale_mm)
        assert tuple(scene._flanks[1][7].color) == tuple(int(c) for c in cols[1, 7])
        # an interfering pose adds only the interference solid
        sent.clear()
        scene.set_pose(3.0, 45.0)
        meshes = [m for m in sent if type(m).__name__ == "MeshMessage"]
        assert [m.name for m in meshes] == ["/interference"]
        assert scene.interference_volume_mm3 > 0
    finally:
        server.stop()


def test_write_html_is_self_contained(renzo, tmp_path, viser):
    from gearcoupling.viewer.html import write_html

    path = write_html(renzo, tmp_path / "sub" / "v.html", tolerance_mm=TOL)
    text = path.read_text()
    assert text.startswith("<!doctype html>") and "__VISER_EMBED_DATA__" in text
    # named: spec, misalignment (the design angle, 1°) and rotation; a still picture inside
    assert "<title>renzo-1967: misalignment i = 1°, rotation ψ = 0°" in text
    assert text.count('id="gc-still" src="data:image/png;base64,iVBORw0KGgo') == 1
    assert "http://" not in text.split("__VISER_EMBED_DATA__")[1][:200]
    assert [p.name for p in path.parent.iterdir()] == ["v.html"]  # no temporary left


def test_cli_view_html_and_bad_input(tmp_path, capsys, viser):
    out = tmp_path / "scene.html"
    assert main(["view", "renzo-1967", "--html", str(out), "--misalignment", "2",
                 "--cutaway", "half", "--color-by", "separation", "--frame", "ground"]) == 0
    assert out.stat().st_size > 100_000 and "MB" in capsys.readouterr().out
    assert main(["view", "renzo-1967", "--html", str(out), "--misalignment", "9"]) == 2
    assert "--misalignment = 9.0" in capsys.readouterr().err


def test_missing_viser_names_the_extra(monkeypatch):
    import importlib

    from gearcoupling.viewer import nodes

    real = importlib.import_module

    def fake(name, *a, **k):
        if name == "viser":
            raise ImportError("No module named 'viser'")
        return real(name, *a, **k)

    monkeypatch.setattr(nodes.importlib, "import_module", fake)
    with pytest.raises(BackendError, match=r"gearcoupling\[viewer\]"):
        nodes.import_viser()


def test_plot_range_covers_every_finite_value():
    x = np.arange(5.0)
    y = np.array([np.nan, -0.1, 0.05, np.inf, np.nan])
    lo, hi = vs.plot_range((x, y, np.array([0.2, np.nan, np.nan, np.nan, np.nan])))
    assert lo < -0.1 and hi > 0.2 and hi - lo < 0.4
    assert vs.plot_range((x, np.full(5, np.nan))) == (-1.0, 1.0)
    lo, hi = vs.plot_range((x, np.full(5, 0.07)))
    assert lo < 0.07 < hi


def test_separation_colours_zero_on_first_contact(renzo):
    st = vs.pose_state(renzo, 1.0, 12.0)
    sep = vs.flank_values(st, "separation")
    np.testing.assert_allclose(sep.min(axis=1), 0.0, atol=1e-12)
    np.testing.assert_allclose(sep, st.clearance_mm - st.clearance_mm.min(axis=1, keepdims=True),
                               atol=1e-12)
    bad = vs.pose_state(renzo, 3.0, 12.0)
    sep = vs.flank_values(bad, "separation")
    assert np.array_equal(sep < 0, bad.interfering)  # interference stays red
    assert np.all(sep[~bad.interfering] >= 0)
    with pytest.raises(ValueError, match="color mode"):
        vs.flank_values(st, "temperature")
