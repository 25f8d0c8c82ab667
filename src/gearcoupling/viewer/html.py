"""Static, self-contained HTML of a coupling scene (viser's scene serializer).

The file embeds viser's client and the scene (meshes, colours at one pose, contact
points, interference solid, a colour legend); it opens from disk in a browser without a
server or network. It is written atomically. Its title and a caption name the spec, the
misalignment and the rotation; a still picture of the scene (:func:`.still.still_png`)
covers the 3D view until WebGL has drawn it and the picture has settled, or until it is
clicked.
"""

from __future__ import annotations

import base64
import contextlib
import html
import io
import os
import socket
from pathlib import Path

from ..errors import ArgumentError
from ..io import writable_file, write_text
from ..spec import CouplingSpec, as_spec
from .assembly import AssemblyScene, AssemblySettings
from .nodes import CouplingScene, ViewSettings, import_viser
from .still import still_png

Scene = CouplingScene | AssemblyScene


def free_port(host: str = "127.0.0.1") -> int:
    """A TCP port that is free on ``host`` right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((host, 0))
        return int(s.getsockname()[1])


def scene_html(scene: Scene, *, dark_mode: bool = False) -> str:
    """The current scene of a running viewer as one HTML document, titled and captioned,
    with its still picture shown until WebGL draws."""
    page = scene.server.get_scene_serializer().as_html(dark_mode=dark_mode)
    return dress(page, scene)


def describe(scene: Scene) -> str:
    """What the scene shows, in one line: spec, misalignment (or a double-engagement
    coupling's alignment and mesh angles), rotation, colours, cutaway."""
    if isinstance(scene, AssemblyScene):
        return scene.describe()
    st = scene.settings
    return (f"{scene.spec.name}: misalignment i = {st.misalignment_deg:g}°, rotation "
            f"ψ = {st.psi_deg:g}° ({st.frame} frame still), coloured by {st.color_mode}, "
            f"{st.cutaway} cutaway")


_STYLE = """<style>
#gc-caption { position: fixed; top: 8px; left: 10px; z-index: 1001; pointer-events: none;
  font: 13px/1.3 sans-serif; color: #1d2330; background: rgba(255,255,255,0.85);
  padding: 3px 7px; border-radius: 3px; }
#gc-still { position: fixed; inset: 0; width: 100%; height: 100%; object-fit: contain;
  background: #fff; z-index: 1000; cursor: pointer; }
#gc-still-note { position: fixed; bottom: 8px; left: 0; right: 0; text-align: center;
  z-index: 1001; pointer-events: none; font: 12px sans-serif; color: #555; }
</style>"""

# keeps the WebGL drawing buffer (so it can be read at any time) and counts draw calls
# per animation frame; once a frame has drawn at least the coupling's meshes, it reads a
# small copy of the view every half second and removes the still picture when the view
# is drawn (pixels off the background) and settled (two copies alike: viser fades the
# scene in, and software WebGL takes tens of seconds to show it)
_SCRIPT = """<script>(function () {
  var need = %d, draws = 0, gl = null, last = null;
  var getContext = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function (type, attrs) {
    if (/webgl/.test(type)) attrs = Object.assign({}, attrs, {preserveDrawingBuffer: true});
    return getContext.call(this, type, attrs);
  };
  ["WebGLRenderingContext", "WebGL2RenderingContext"].forEach(function (name) {
    var proto = window[name] && window[name].prototype;
    if (!proto) return;
    ["drawElements", "drawArrays", "drawElementsInstanced", "drawArraysInstanced"]
      .forEach(function (m) {
        var f = proto[m];
        if (f) proto[m] = function () { draws++; gl = this; return f.apply(this, arguments); };
      });
  });
  var probe = document.createElement("canvas");
  probe.width = 64; probe.height = 48;
  var copy = probe.getContext("2d", {willReadFrequently: true});
  function hide() {
    ["gc-still", "gc-still-note"].forEach(function (id) {
      var e = document.getElementById(id); if (e) e.remove();
    });
  }
  function settled() {
    copy.clearRect(0, 0, 64, 48);
    copy.drawImage(gl.canvas, 0, 0, 64, 48);
    var px = copy.getImageData(0, 0, 64, 48).data, drawn = 0, moved = 0;
    for (var i = 0; i < px.length; i += 4) {
      var off = 0;
      for (var c = 0; c < 4; c++) {
        off = Math.max(off, Math.abs(px[i + c] - px[c]));
        if (last) moved = Math.max(moved, Math.abs(px[i + c] - last[i + c]));
      }
      if (off > 40) drawn++;
    }
    var ok = last !== null && drawn > 0.05 * px.length / 4 && moved <= 8;
    last = px;
    return ok;
  }
  function poll() {
    if (!document.getElementById("gc-still")) return;
    if (settled()) hide(); else setTimeout(poll, 500);
  }
  function frame() {
    if (draws >= need) { setTimeout(poll, 500); return; }
    draws = 0;
    requestAnimationFrame(frame);
  }
  requestAnimationFrame(frame);
  document.addEventListener("click", function (e) {
    if (e.target && e.target.id === "gc-still") hide();
  });
})();</script>"""


def dress(page: str, scene: Scene) -> str:
    """Viser's HTML ``page`` with the scene's title, caption and still picture."""
    text = html.escape(describe(scene))
    if isinstance(scene, AssemblyScene):
        meshes = scene.draws()
    else:
        st = scene.settings
        meshes = int(st.show_sleeve) + int(st.show_hub) * (1 + 2 * scene.spec.tooth.teeth)
    src = "data:image/png;base64," + base64.b64encode(still_png(scene)).decode("ascii")
    head = _STYLE + _SCRIPT % max(meshes, 1)
    body = (f'<div id="gc-caption">{text}</div>'
            f'<img id="gc-still" src="{src}" alt="still picture: {text}">'
            '<div id="gc-still-note">A still picture until the interactive 3D view has '
            "drawn (software WebGL can take a minute); click to use the view now.</div>")
    title = f"<title>{text} (gearcoupling viewer)</title>"
    page = page.replace("<title>Viser</title>", "", 1)
    page = page.replace("<head>", "<head>" + title + head, 1)
    return page.replace("<body>", "<body>" + body, 1)


def save_html(scene: Scene, path: str | os.PathLike) -> Path:
    """Write the current scene's HTML atomically (usual file mode, to be shared)."""
    return write_text(path, scene_html(scene))


def write_html(spec: CouplingSpec, path: str | os.PathLike, *,
               settings: ViewSettings | AssemblySettings | None = None,
               tolerance_mm: float | None = None) -> Path:
    """Write the static HTML of a coupling scene (:func:`static_html`) to ``path`` (parent
    folders are created; written atomically)."""
    writable_file(path, "path")
    return write_text(path, static_html(spec, settings=settings, tolerance_mm=tolerance_mm))


def static_html(spec: CouplingSpec, *, settings: ViewSettings | AssemblySettings | None = None,
                tolerance_mm: float | None = None) -> str:
    """The static HTML of a coupling scene, one self-contained page.

    Parameters
    ----------
    spec : CouplingSpec
        A double-engagement spec shows the whole coupling: every part placed at the
        shaft alignment, each mesh coloured at its own angle and rotation.
    settings : ViewSettings or AssemblySettings, optional
        Pose and display; default: the spec's design misalignment (the spec's
        ``[alignment]`` for two engagements: :class:`AssemblySettings`), rotation 0,
        quarter cutaway.
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (default coarse, module / 20). Most of the page
        is viser's client; the scene's meshes add to it in proportion to their triangles
        (``benchmarks/bench_viewer.py``).
    """
    spec = as_spec(spec)
    double = spec.coupling.engagements == 2
    kind = AssemblySettings if double else ViewSettings
    if settings is not None and not isinstance(settings, kind):
        raise ArgumentError("settings", str(settings)[:60], f"a {kind.__name__}"
                            + (" (a double-engagement spec)" if double else ""))
    viser = import_viser()
    if settings is None:
        settings = AssemblySettings() if double else \
            ViewSettings(misalignment_deg=_design_deg(spec))
    # a private server on a free local port: the serializer needs one; no client connects.
    # viser prints its address banner to stdout: keep it out of the caller's output
    with contextlib.redirect_stdout(io.StringIO()):
        server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        if isinstance(settings, AssemblySettings):
            return scene_html(AssemblyScene(server, spec, settings, tolerance_mm,
                                            legend_in_scene=True))
        return scene_html(CouplingScene(server, spec, settings, tolerance_mm,
                                        legend_in_scene=True))
    finally:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()


def _design_deg(spec: CouplingSpec) -> float:
    import math

    return math.degrees(spec.design_misalignment)
