"""Static, self-contained HTML of a coupling scene (viser's scene serializer).

The file embeds viser's client and the scene (meshes, colours at one pose, contact
points, interference solid, a colour legend); it opens from disk in a browser without a
server or network. It is written atomically.
"""

from __future__ import annotations

import contextlib
import io
import os
import socket
from pathlib import Path

from ..io import writable_file, write_text
from ..spec import CouplingSpec
from .nodes import CouplingScene, ViewSettings, import_viser


def free_port(host: str = "127.0.0.1") -> int:
    """A TCP port that is free on ``host`` right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((host, 0))
        return int(s.getsockname()[1])


def scene_html(scene: CouplingScene, *, dark_mode: bool = False) -> str:
    """The current scene of a running viewer as one HTML document."""
    return scene.server.get_scene_serializer().as_html(dark_mode=dark_mode)


def save_html(scene: CouplingScene, path: str | os.PathLike) -> Path:
    """Write the current scene's HTML atomically (usual file mode, to be shared)."""
    return write_text(path, scene_html(scene))


def write_html(spec: CouplingSpec, path: str | os.PathLike, *, settings: ViewSettings | None = None,
               tolerance_mm: float | None = None) -> Path:
    """Write the static HTML of a coupling scene.

    Parameters
    ----------
    spec : CouplingSpec
    path : path-like
        Output file (parent folders are created; written atomically).
    settings : ViewSettings, optional
        Pose and display; default: the spec's design misalignment, rotation 0, quarter
        cutaway.
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (default coarse, module / 20). Most of the file
        is viser's client (0.8 MB); renzo-1967's scene adds 0.2 MB coarse (30k
        triangles) and 0.6 MB at module / 400 (105k triangles), compressed
        (``benchmarks/bench_viewer.py``).

    Returns
    -------
    Path
    """
    writable_file(path, "path")
    viser = import_viser()
    if settings is None:
        settings = ViewSettings(misalignment_deg=_design_deg(spec))
    # a private server on a free local port: the serializer needs one; no client connects.
    # viser prints its address banner to stdout: keep it out of the caller's output
    with contextlib.redirect_stdout(io.StringIO()):
        server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        scene = CouplingScene(server, spec, settings, tolerance_mm, legend_in_scene=True)
        return save_html(scene, path)
    finally:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()


def _design_deg(spec: CouplingSpec) -> float:
    import math

    return math.degrees(spec.design_misalignment)
