"""What the viewer draws, as plain arrays: no viser here (the server and the HTML writer
turn these into scene nodes), and no load solve (loads come from the caller).

- :mod:`.meshes`: hub and sleeve meshed once per level of detail, the hub split into a
  body and one patch per (flank, tooth), sleeve cutaways;
- :mod:`.pose`: the hub's rotation at a pose and :func:`pose_state`, the exact clearance
  of every tooth and flank there, the contact points and interfering teeth;
- :mod:`.colors`: clearance, separation and pressure colours and their legend;
- :mod:`.curves`: the clearance-vs-θ plot;
- :mod:`.interference`: the hub ∩ sleeve volume at a pose (manifold3d);
- :mod:`.assembly`: a double-engagement coupling's parts placed at the shaft alignment and
  each mesh's pose state.
"""

from .assembly import ALIGNMENT_FIELDS, AssemblyPose, assembly_pose
from .colors import (
    COLOR_MODES,
    INTERFERENCE_RGB,
    NO_CONTACT_RGB,
    clearance_colors,
    default_color_scale_mm,
    flank_colors,
    flank_values,
    legend,
    legend_markdown,
    legend_title,
    pressure_colors,
)
from .curves import ClearanceCurve, clearance_curve, plot_range, plot_series
from .interference import interference_mesh
from .meshes import (
    CUTAWAYS,
    LOD_DIVISORS,
    HubPieces,
    Patch,
    SceneMeshes,
    build_scene_meshes,
    cut_sleeve,
    lod_tolerance,
    split_hub,
    submesh,
    view_tolerance,
)
from .pose import (
    VIEW_SWEEP_TOLERANCE_MM,
    PoseState,
    check_pose,
    hub_rotation,
    pose_pressure,
    pose_state,
    quaternion_wxyz,
)

__all__ = [
    "ALIGNMENT_FIELDS",
    "COLOR_MODES",
    "CUTAWAYS",
    "INTERFERENCE_RGB",
    "LOD_DIVISORS",
    "NO_CONTACT_RGB",
    "VIEW_SWEEP_TOLERANCE_MM",
    "AssemblyPose",
    "ClearanceCurve",
    "HubPieces",
    "Patch",
    "PoseState",
    "SceneMeshes",
    "assembly_pose",
    "build_scene_meshes",
    "check_pose",
    "clearance_colors",
    "clearance_curve",
    "cut_sleeve",
    "default_color_scale_mm",
    "flank_colors",
    "flank_values",
    "hub_rotation",
    "interference_mesh",
    "legend",
    "legend_markdown",
    "legend_title",
    "lod_tolerance",
    "plot_range",
    "plot_series",
    "pose_pressure",
    "pose_state",
    "pressure_colors",
    "quaternion_wxyz",
    "split_hub",
    "submesh",
    "view_tolerance",
]
