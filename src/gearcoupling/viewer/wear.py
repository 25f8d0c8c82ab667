"""The worn hub flanks of a wear history as a heat map in the viewer: the coupling at the
history's angle, each hub flank patch coloured vertex by vertex by its final worn depth
(:mod:`.scene.wear`), as one static, self-contained HTML page."""

from __future__ import annotations

import contextlib
import html
import io
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ArgumentError
from ..geometry import FLANKS
from ..io import writable_file, write_text
from ..wear import WearResult
from .html import free_port
from .nodes import CouplingScene, ViewSettings, add_legend_entries, import_viser
from .scene.wear import hub_flank_depths, wear_colors, wear_legend


class WearScene(CouplingScene):
    """A :class:`~.nodes.CouplingScene` at a wear history's angle whose hub flank patches
    are heat maps of the worn depth (``depths[f][k]`` per vertex, ``colors[f][k]`` their
    RGB, the scale's top ``top_mm`` the deepest point; ``glb[f][k]`` the binary glTF each
    patch is sent as, with its vertex colours), with its legend in the scene."""

    def __init__(self, server, result: Any, settings: ViewSettings,
                 tolerance_mm: float | None = None):
        super().__init__(server, result.spec, settings, tolerance_mm)
        self.result = result
        pieces = self.meshes.hub_pieces
        self.depths = hub_flank_depths(result, pieces)
        self.top_mm = max((float(np.max(d)) for side in self.depths for d in side if d.size),
                          default=0.0)
        self.colors = [[wear_colors(d, self.top_mm) for d in side] for side in self.depths]
        self.heat_maps: list[list] = [[], []]
        self.glb: list[list[bytes]] = [[], []]
        self._paint(pieces)
        self._add_wear_legend()

    def _paint(self, pieces) -> None:
        """Each flank patch again, as a mesh with its vertices' colours."""
        import trimesh

        st = self.settings
        for f, name in enumerate(FLANKS):
            for k, patch in enumerate(pieces.flanks[f]):
                self._flanks[f][k].remove()
                rgba = np.column_stack([self.colors[f][k],
                                        np.full(len(patch.vertices), 255, np.uint8)])
                mesh = trimesh.Trimesh(patch.vertices, patch.faces, vertex_colors=rgba,
                                       process=False)
                glb = bytes(mesh.export(file_type="glb"))  # type: ignore[arg-type]
                self.glb[f].append(glb)
                self.heat_maps[f].append(self.server.scene.add_glb(
                    f"/hub/flanks/{name}/{k:03d}", glb, visible=st.show_hub))
        self._flanks = [[], []]  # the clearance colours no longer apply
        self._contacts.visible = False  # the pose's first-touch points: not the wear's

    def _add_wear_legend(self) -> None:
        bounds = self.meshes.sleeve.bounds
        entries = wear_legend(self.top_mm) if self.top_mm > 0 else wear_legend(1.0)[:1]
        add_legend_entries(self.server.scene, self.spec, "worn depth of the hub flanks "
                           "(along the normal)", entries, 0.9 * bounds[1][0], bounds[1][2])

    def describe(self) -> str:
        """What the page shows, in one line."""
        res, p = self.result, self.result.duty[0]
        duty = "" if len(res.duty) == 1 else f" (the first of {len(res.duty)} duty points)"
        return (f"{res.spec.name}: worn hub flanks after {float(res.hours[-1]):.4g} h at "
                f"i = {p.misalignment_deg:g}°, T = {p.torque_Nm:.4g} N·m, "
                f"{p.speed_rpm:.4g} rpm{duty}; deepest {1e3 * self.top_mm:.3g} µm; rotation "
                f"ψ = {self.settings.psi_deg:g}°, {self.settings.cutaway} cutaway")


def wear_html(result: Any, *, psi_deg: float = 0.0,
              tolerance_mm: float | None = None) -> str:
    """The static HTML of a wear history's worn hub flanks as a heat map: hub and sleeve
    at the history's (first duty point's) misalignment and rotation ``psi_deg``, quarter
    cutaway, each hub flank coloured by its final worn depth (the deepest point dark red,
    unworn grey); one self-contained page.

    Parameters
    ----------
    result : WearResult
        From :func:`gearcoupling.wear` (a single engagement's).
    psi_deg : float
        Rotation shown.
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (default coarse, module / 20).
    """
    if not isinstance(result, WearResult):
        raise ArgumentError("result", str(result)[:60], "a WearResult (gc.wear)")
    viser = import_viser()
    settings = ViewSettings(misalignment_deg=result.duty[0].misalignment_deg,
                            psi_deg=psi_deg)
    with contextlib.redirect_stdout(io.StringIO()):  # viser's banner
        server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        scene = WearScene(server, result, settings, tolerance_mm)
        page = server.get_scene_serializer().as_html(dark_mode=False)
        return _titled(page, scene.describe())
    finally:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()


def _titled(page: str, text: str) -> str:
    """Viser's page with the scene's title and caption (escaped: the spec's name is data)."""
    text = html.escape(text)
    page = page.replace("<title>Viser</title>", f"<title>{text} (gearcoupling viewer)</title>",
                        1)
    style = ('<style>#gc-caption { position: fixed; top: 8px; left: 10px; z-index: 1001; '
             "pointer-events: none; font: 13px/1.3 sans-serif; color: #1d2330; "
             "background: rgba(255,255,255,0.85); padding: 3px 7px; border-radius: 3px; }"
             "</style>")
    page = page.replace("<head>", "<head>" + style, 1)
    return page.replace("<body>", f'<body><div id="gc-caption">{text}</div>', 1)


def write_wear_html(result: Any, path: str | os.PathLike, **options: Any) -> Path:
    """Write :func:`wear_html` to ``path`` atomically (parent folders are created)."""
    writable_file(path, "path")
    return write_text(path, wear_html(result, **options))


__all__ = ["WearScene", "wear_html", "write_wear_html"]
