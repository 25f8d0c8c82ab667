"""Browser 3D viewer of a posed coupling (viser), and its static HTML.

:mod:`.scene` holds the pure logic (meshes split for colouring, poses, clearance colours,
contact points, interference, plot data); :mod:`.nodes` turns it into viser scene nodes;
:mod:`.server` is the live viewer with its GUI; :mod:`.html` writes the static HTML.
viser is imported only when a server is made and is an optional extra
(``pip install 'gearcoupling[viewer]'``).
"""

from .scene import CUTAWAYS, LOD_DIVISORS, PoseState, build_scene_meshes, pose_state


def write_html(spec, path, **kwargs):
    """Write the static HTML of a coupling scene (see :func:`.html.write_html`)."""
    from .html import write_html as _write_html

    return _write_html(spec, path, **kwargs)


def serve(spec, **kwargs):
    """Start the live viewer (see :class:`.server.ViewerApp`)."""
    from .server import serve as _serve

    return _serve(spec, **kwargs)


__all__ = ["CUTAWAYS", "LOD_DIVISORS", "PoseState", "build_scene_meshes", "pose_state", "serve",
           "write_html"]
