"""A still picture of a coupling scene, drawn once without a browser (matplotlib): the
static HTML shows it until WebGL has drawn the interactive view (software WebGL takes
tens of seconds).

The camera is the viewer's starting camera (position ``(-1, -1.45, 1) R``, looking at the
origin, ``+z`` up, 75° vertical field of view); the triangles facing the camera are
shaded by the angle to it and painted far to near. The legend is the scene's; the
contact points are left out (painting cannot hide those behind the sleeve).
"""

from __future__ import annotations

import io
import math

import numpy as np
from numpy.typing import NDArray

from ..numeric import TINY
from ..plots import import_matplotlib
from .assembly import AssemblyScene
from .nodes import HUB_RGB, SLEEVE_RGB, CouplingScene
from .scene import INTERFERENCE_RGB, Patch, flank_colors, hub_rotation, legend, legend_title

CAMERA = (-1.0, -1.45, 1.0)
"""Camera position in pitch radii (the viewer's ``initial_camera``)."""
FOV_DEG = 75.0
"""Vertical field of view (viser's default)."""
SIZE_PX = (800, 560)


def _triangles(patch: Patch, rotation: NDArray, rgb) -> tuple[NDArray, NDArray]:
    tri = (patch.vertices.astype(float) @ rotation.T)[patch.faces]
    return tri, np.broadcast_to(np.asarray(rgb, dtype=float) / 255.0, (len(tri), 3))


def _scene_triangles(scene: CouplingScene) -> tuple[NDArray, NDArray]:
    """Every shown triangle ``(n, 3, 3)`` in screen-world coordinates and its RGB ``(n, 3)``."""
    st, state, meshes = scene.settings, scene.state, scene.meshes
    ground = scene.ground()
    hub = ground @ hub_rotation(st.misalignment_deg, st.psi_deg)
    parts = []
    if st.show_sleeve:
        parts.append(_triangles(meshes.sleeve_cut(st.cutaway), ground, SLEEVE_RGB))
    if st.show_hub and state is not None:
        pieces = meshes.hub_pieces
        colors = flank_colors(state, st.color_mode, scene.color_scale_mm, scene.spec)
        parts.append(_triangles(pieces.body, hub, HUB_RGB))
        parts += [_triangles(patch, hub, colors[f, k])
                  for f in range(2) for k, patch in enumerate(pieces.flanks[f])]
    patch = scene.interference_patch
    if st.show_interference and patch is not None and patch.faces.shape[0]:
        parts.append(_triangles(patch, ground, INTERFERENCE_RGB))
    return np.concatenate([t for t, _ in parts]), np.concatenate([c for _, c in parts])


def _assembly_triangles(scene: AssemblyScene) -> tuple[NDArray, NDArray, NDArray]:
    """The whole coupling's triangles, each part at its placement, their RGB and their
    opacity (the floating member's plain parts translucent, as in the scene)."""
    parts = []
    for patch, placement, rgb, alpha in scene.patches():
        tri, colour = _triangles(patch, placement[:3, :3], rgb)
        parts.append((tri + placement[:3, 3], colour, np.full(len(tri), alpha)))
    return tuple(np.concatenate([p[i] for p in parts]) for i in range(3))  # type: ignore


def _camera(eye: NDArray, target: NDArray) -> tuple[NDArray, NDArray]:
    """Camera position ``(3,)`` and the rows ``(right, up, forward)`` of its frame looking
    from ``eye`` at ``target`` (``+z`` up)."""
    eye = np.asarray(eye, dtype=float)
    fwd = (np.asarray(target, dtype=float) - eye)
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    return eye, np.stack([right, np.cross(right, fwd), fwd])


def still_png(scene: CouplingScene | AssemblyScene, size_px: tuple[int, int] = SIZE_PX
              ) -> bytes:
    """The scene at its pose as PNG bytes (about a second for 30 000 triangles)."""
    import_matplotlib()
    from matplotlib.collections import PolyCollection
    from matplotlib.figure import Figure

    if isinstance(scene, AssemblyScene):
        tri, rgb, alpha = _assembly_triangles(scene)
        eye, frame = _camera(scene.camera_eye, scene.look_at)
    else:
        tri, rgb = _scene_triangles(scene)
        alpha = np.ones(len(tri))
        eye, frame = _camera(np.asarray(CAMERA) * scene.spec.tooth.pitch_radius, np.zeros(3))
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    to_eye = eye - tri.mean(axis=1)
    facing = np.einsum("ij,ij->i", normal, to_eye)
    cosine = facing / np.maximum(np.linalg.norm(normal, axis=1) * np.linalg.norm(to_eye, axis=1),
                                 TINY)
    keep = facing > 0  # closed, outward-wound solids: the back faces are hidden
    cam = (tri[keep] - eye) @ frame.T  # (n, 3, 3): right, up, depth
    shade = np.column_stack([np.clip(rgb[keep] * (0.55 + 0.45 * cosine[keep, None]), 0, 1),
                             alpha[keep]])
    focal = 1.0 / math.tan(math.radians(FOV_DEG) / 2)
    xy = focal * cam[..., :2] / cam[..., 2:3]
    order = np.argsort(-cam[..., 2].mean(axis=1), kind="stable")  # far to near
    w, h = size_px
    fig = Figure(figsize=(w / 100, h / 100), dpi=100)
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    ax.add_collection(PolyCollection(xy[order], facecolors=shade[order],
                                     edgecolors="face", linewidths=0.4, antialiased=False))
    ax.set_xlim(-w / h, w / h)
    ax.set_ylim(-1.0, 1.0)
    ax.set_aspect("equal")
    ax.axis("off")
    _draw_legend(fig, scene)
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


def _draw_legend(fig, scene: CouplingScene | AssemblyScene) -> None:
    """The colour legend at the top right, as in the scene."""
    mode = scene.settings.color_mode
    fig.text(0.66, 0.93, legend_title(mode), fontsize=8)
    for j, (label, rgb) in enumerate(legend(scene.color_scale_mm, mode=mode)):
        y = 0.88 - 0.04 * j
        fig.text(0.67, y, "■", color=np.asarray(rgb) / 255.0, fontsize=10, va="center")
        fig.text(0.69, y, label, fontsize=8, va="center")
