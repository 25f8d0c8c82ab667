"""Browser 3D viewer of a posed coupling (viser), and its static HTML.

:mod:`.scene` holds the pure logic (meshes split for colouring, poses, clearance colours,
contact points, interference, plot data); :mod:`.nodes` turns it into viser scene nodes;
:mod:`.server` is the live viewer with its GUI; :mod:`.html` writes the static HTML.
viser is imported only when a server is made and is an optional extra
(``pip install 'gearcoupling[viewer]'``).
"""

from .assembly import AssemblyScene, AssemblySettings
from .assembly_app import AssemblyApp
from .html import static_html, write_html
from .nodes import FRAMES, ViewSettings
from .scene import (
    COLOR_MODES,
    CUTAWAYS,
    LOD_DIVISORS,
    AssemblyPose,
    PoseState,
    assembly_pose,
    build_scene_meshes,
    check_pose,
    lod_tolerance,
    pose_state,
)
from .server import ViewerApp, exposure_warning, serve
from .wear import WearScene, wear_html, write_wear_html

__all__ = [
    "COLOR_MODES",
    "CUTAWAYS",
    "FRAMES",
    "LOD_DIVISORS",
    "AssemblyApp",
    "AssemblyPose",
    "AssemblyScene",
    "AssemblySettings",
    "PoseState",
    "ViewSettings",
    "ViewerApp",
    "WearScene",
    "assembly_pose",
    "build_scene_meshes",
    "check_pose",
    "exposure_warning",
    "lod_tolerance",
    "pose_state",
    "serve",
    "static_html",
    "wear_html",
    "write_html",
    "write_wear_html",
]
