"""The whole coupling's scene nodes in a viser server (a double-engagement spec,
docs/coupling.md): every part placed at the shaft alignment, each mesh's hub flanks
coloured by its own clearance (or separation, or contact pressure) at its angle and
rotation. Shared by the live viewer (:mod:`.assembly_app`) and the static HTML.

Node tree (coupling frame = world: shaft A's axis ``+z`` up, hub A's midplane centre at
the origin)::

    /coupling/hub-a               frame placed at hub A's pose
    /coupling/hub-a/body          hub without its flanks
    /coupling/hub-a/flanks/cw/007 one patch per flank and tooth, coloured
    /coupling/sleeve-a            sleeve ring A (with the chosen cutaway)
    /coupling/flange-a ...        the floating member's plain parts, translucent
    /coupling/sleeve-b, /coupling/hub-b
    /legend/...                   colour legend (static HTML only)

Meshes are sent once; :meth:`AssemblyScene.set_pose` moves the part frames and recolours
the flanks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..coupling import annulus_mesh
from ..errors import ArgumentError
from ..geometry import FLANKS
from ..spec import CouplingSpec
from .nodes import HUB_RGB, SLEEVE_RGB, _opacity, add_legend
from .scene import (
    COLOR_MODES,
    CUTAWAYS,
    Patch,
    SceneMeshes,
    build_scene_meshes,
    default_color_scale_mm,
    flank_colors,
    quaternion_wxyz,
)
from .scene.assembly import ALIGNMENT_FIELDS, AssemblyPose, assembly_pose

FLOATING_RGB = (150, 165, 195)


@dataclass
class AssemblySettings:
    """What the whole coupling's viewer shows: the shaft alignment (each field None: the
    spec's ``[alignment]``), the coupling's rotation and the display; the GUI edits these
    and the CLI sets their start values."""

    offset_mm: float | None = None
    offset_azimuth_deg: float | None = None
    angle_deg: float | None = None
    angle_azimuth_deg: float | None = None
    psi_deg: float = 0.0
    cutaway: str = "quarter"
    color_mode: str = "clearance"
    color_scale_mm: float | None = None
    band_mm: float = 0.005
    floating_opacity: float = 0.35

    def __post_init__(self):
        if self.cutaway not in CUTAWAYS:
            raise ArgumentError("cutaway", self.cutaway, f"one of {CUTAWAYS}")
        if self.color_mode not in COLOR_MODES:
            raise ArgumentError("color_mode", self.color_mode, f"one of {COLOR_MODES}")
        if not 0.0 <= self.floating_opacity <= 1.0:
            raise ArgumentError("floating_opacity", self.floating_opacity, "from 0 to 1")

    def changes(self) -> dict[str, float]:
        """The alignment fields given (the rest are the spec's)."""
        return {k: float(getattr(self, k)) for k in ALIGNMENT_FIELDS
                if getattr(self, k) is not None}


def slug(part: str) -> str:
    """A part's node name: ``hub A`` -> ``hub-a``."""
    return part.lower().replace(" ", "-")


class AssemblyScene:
    """The whole coupling of a double-engagement spec as viser scene nodes.

    Parameters
    ----------
    server : viser.ViserServer
    spec : CouplingSpec
        Two engagements.
    settings : AssemblySettings
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (default: the ``coarse`` level of detail).
    legend_in_scene : bool
        Draw the colour legend in the 3D scene (for the static HTML).
    """

    def __init__(self, server, spec: CouplingSpec, settings: AssemblySettings,
                 tolerance_mm: float | None = None, *, legend_in_scene: bool = False):
        self.server, self.spec, self.settings = server, spec, settings
        self.pose: AssemblyPose = self._pose()  # refuses a bad alignment before any node
        geom = self.pose.geometry
        self.meshes: dict[str, SceneMeshes] = {"A": build_scene_meshes(geom.spec_a,
                                                                        tolerance_mm)}
        self.meshes["B"] = self.meshes["A"] if geom.spec_b is geom.spec_a else \
            build_scene_meshes(geom.spec_b, tolerance_mm)
        self.frames: dict[str, Any] = {}  # viser scene handles
        self.sleeves: dict[str, Any] = {}
        self.flanks: dict[str, list[list]] = {}
        self._add_nodes()
        scale = max(geom.span_mm, 4.0 * spec.tooth.pitch_radius)
        self.look_at = np.array([0.0, 0.0, 0.5 * geom.span_mm])
        self.camera_eye = self.look_at + scale * np.array([-0.8, -1.2, 0.25])
        server.scene.set_up_direction("+z")
        server.initial_camera.position = tuple(self.camera_eye)
        server.initial_camera.look_at = tuple(self.look_at)
        server.initial_camera.up = (0.0, 0.0, 1.0)
        if legend_in_scene:
            self._add_legend()
        self.set_pose()

    @property
    def color_scale_mm(self) -> float:
        s = self.settings.color_scale_mm
        return default_color_scale_mm(self.spec) if s is None else s

    def _pose(self) -> AssemblyPose:
        st = self.settings
        return assembly_pose(self.spec, st.psi_deg, st.changes(), band_mm=st.band_mm,
                             pressure=st.color_mode == "pressure")

    def _add_nodes(self) -> None:
        scene, st, geom = self.server.scene, self.settings, self.pose.geometry
        tol = self.meshes["A"].tolerance_mm
        for name, kind in self.pose.kinds.items():
            node = f"/coupling/{slug(name)}"
            frame = scene.add_frame(node, show_axes=False)
            self.frames[name] = frame
            mesh = self.pose.mesh_of(name)
            if kind == "hub":
                assert mesh is not None
                pieces = self.meshes[mesh].hub_pieces
                scene.add_mesh_simple(f"{node}/body", pieces.body.vertices, pieces.body.faces,
                                      color=HUB_RGB)
                self.flanks[mesh] = [
                    [scene.add_mesh_simple(f"{node}/flanks/{flank}/{k:03d}", patch.vertices,
                                           patch.faces, color=HUB_RGB, side="double")
                     for k, patch in enumerate(pieces.flanks[f])]
                    for f, flank in enumerate(FLANKS)]
            elif kind == "sleeve":
                assert mesh is not None
                cut = self.meshes[mesh].sleeve_cut(st.cutaway)
                self.sleeves[mesh] = scene.add_mesh_simple(
                    f"{node}/mesh", cut.vertices, cut.faces, color=SLEEVE_RGB, side="double")
            else:
                part = next(a for a in geom.annuli if a.name == name)
                m = annulus_mesh(part, tol)
                scene.add_mesh_simple(f"{node}/mesh", np.asarray(m.vertices, np.float32),
                                      np.asarray(m.faces, np.uint32), color=FLOATING_RGB,
                                      opacity=_opacity(st.floating_opacity), side="double")

    def set_cutaway(self, cutaway: str) -> None:
        """Show the sleeve rings with another cutaway."""
        if cutaway not in CUTAWAYS:
            raise ArgumentError("cutaway", cutaway, f"one of {CUTAWAYS}")
        self.settings.cutaway = cutaway
        for mesh, handle in list(self.sleeves.items()):
            handle.remove()
            cut = self.meshes[mesh].sleeve_cut(cutaway)
            self.sleeves[mesh] = self.server.scene.add_mesh_simple(
                f"/coupling/sleeve-{mesh.lower()}/mesh", cut.vertices, cut.faces,
                color=SLEEVE_RGB, side="double")

    def set_pose(self) -> AssemblyPose:
        """Place every part at the settings' alignment and rotation and recolour each
        mesh's flanks (no mesh is sent)."""
        pose = self._pose()
        colors = self.colors(pose)
        with self.server.atomic():
            for name, frame in self.frames.items():
                P = pose.placements[name]
                frame.wxyz = quaternion_wxyz(P[:3, :3])
                frame.position = tuple(P[:3, 3])
            for mesh, handles in self.flanks.items():
                for f in range(2):
                    for k, handle in enumerate(handles[f]):
                        handle.color = tuple(int(c) for c in colors[mesh][f, k])
        self.pose = pose
        return pose

    def colors(self, pose: AssemblyPose) -> dict[str, np.ndarray]:
        """Each mesh's flank colours ``(2, N, 3)`` at ``pose``."""
        st, geom = self.settings, pose.geometry
        return {m: flank_colors(pose.states[m], st.color_mode, self.color_scale_mm,
                                geom.spec(m)) for m in geom.meshes}

    def patches(self) -> list[tuple[Patch, np.ndarray, tuple[int, ...], float]]:
        """Every drawn patch with its placement ``(4, 4)``, colour and opacity at the
        current pose (what the still picture paints)."""
        pose, st = self.pose, self.settings
        colors = self.colors(pose)
        tol = self.meshes["A"].tolerance_mm
        out: list[tuple[Patch, np.ndarray, tuple[int, ...], float]] = []
        for name, kind in pose.kinds.items():
            P, mesh = pose.placements[name], pose.mesh_of(name)
            if kind == "hub":
                assert mesh is not None
                pieces = self.meshes[mesh].hub_pieces
                out.append((pieces.body, P, HUB_RGB, 1.0))
                out += [(patch, P, tuple(int(c) for c in colors[mesh][f, k]), 1.0)
                        for f in range(2) for k, patch in enumerate(pieces.flanks[f])]
            elif kind == "sleeve":
                assert mesh is not None
                out.append((self.meshes[mesh].sleeve_cut(st.cutaway), P, SLEEVE_RGB, 1.0))
            else:
                part = next(a for a in pose.geometry.annuli if a.name == name)
                m = annulus_mesh(part, tol)
                out.append((Patch(np.asarray(m.vertices, np.float32),
                                  np.asarray(m.faces, np.uint32)), P, FLOATING_RGB,
                            st.floating_opacity))
        return out

    def _add_legend(self) -> None:
        """Colour legend beside the coupling (the static HTML has no GUI panel)."""
        x = 0.9 * max(self.spec.sleeve.outer_diameter, 2 * self.spec.tooth.pitch_radius)
        add_legend(self.server.scene, self.spec, self.settings.color_mode,
                   self.color_scale_mm, x, self.pose.geometry.span_mm)

    def describe(self) -> str:
        """What the scene shows, in one line."""
        geom, st = self.pose.geometry, self.settings
        a = geom.alignment
        meshes = ", ".join(f"mesh {m} i = {geom.misalignment_deg(m):.4g}°"
                           for m in geom.meshes)
        return (f"{self.spec.name}: offset {a.offset_mm:g} mm at {a.offset_azimuth_deg:g}°, "
                f"shaft angle {a.angle_deg:g}° at {a.angle_azimuth_deg:g}° ({meshes}), "
                f"rotation ψ = {st.psi_deg:g}°, coloured by {st.color_mode}, "
                f"{st.cutaway} cutaway of the sleeve rings")

    def draws(self) -> int:
        """The meshes WebGL draws (hub bodies and flank patches, sleeve rings, plain
        parts)."""
        return sum(1 + 2 * self.pose.geometry.spec(m).tooth.teeth for m in self.flanks) + \
            len(self.pose.kinds) - len(self.flanks)
