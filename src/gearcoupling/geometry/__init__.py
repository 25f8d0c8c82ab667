"""Pure numpy/scipy geometry kernels: involutes, feed paths, hub and sleeve surfaces, sections.

Nothing here imports a mesh, CAD or viewer library.
"""

from .feedpath import (
    CrowningLike,
    FeedPath,
    arc_path,
    curvature_table_path,
    drop_table_path,
    end_round_path,
    feed_path,
    vari_crown_path,
)
from .hub import (
    FLANKS,
    HubModel,
    envelope,
    flank_depth,
    flank_u,
    form_radius,
    hub_flank,
    hub_flank_model,
    hub_model,
    plane_rack,
    radius_squared,
    root_radius,
    round_point,
    tip_radius,
)
from .involute import developed_arc, inv, inv_inverse
from .pose import hub_to_sleeve, map_polar, rot_z, turning_angles
from .renzo import renzo_z0_mm
from .section import PARTS, sleeve_space_outline, transverse_section
from .sleeve import SleeveModel, flank_point, sleeve_flank, sleeve_model
from .speclike import SpecLike

__all__ = [
    "FLANKS",
    "PARTS",
    "CrowningLike",
    "FeedPath",
    "HubModel",
    "SleeveModel",
    "SpecLike",
    "arc_path",
    "curvature_table_path",
    "developed_arc",
    "drop_table_path",
    "end_round_path",
    "envelope",
    "feed_path",
    "flank_depth",
    "flank_point",
    "flank_u",
    "form_radius",
    "hub_flank",
    "hub_flank_model",
    "hub_model",
    "hub_to_sleeve",
    "inv",
    "inv_inverse",
    "map_polar",
    "plane_rack",
    "radius_squared",
    "renzo_z0_mm",
    "root_radius",
    "rot_z",
    "round_point",
    "sleeve_flank",
    "sleeve_model",
    "sleeve_space_outline",
    "tip_radius",
    "transverse_section",
    "turning_angles",
    "vari_crown_path",
]
