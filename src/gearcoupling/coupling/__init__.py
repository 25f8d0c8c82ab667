"""The whole coupling: two gear meshes on a floating member between two shafts, at the
shafts' parallel offset and angle (docs/coupling.md).

:class:`CouplingLayout` and :class:`ShaftAlignment` describe it; :func:`coupling_geometry`
checks and resolves them (each mesh's angle, tilt axis and frame); :func:`whole_loads`
loads both meshes at one torque with the floating member's balance and the loads on the
machines; :func:`whole_capacity` and :func:`allowable_offset` give the capacity and the
allowable parallel offset; :func:`whole_coupling_data` the mass-elastic data sheet (its
``to_ross`` the pieces of a ROSS train); :func:`coupling_assembly` the parts placed at the
alignment (meshes, glTF, STEP assembly, overlap of each mesh's hub and sleeve).
"""

from .assembly import CouplingAssembly, PlacedPart, annulus_mesh, coupling_assembly
from .beam import Segment, annulus_EI_Nm2, beam_frequencies_Hz, pinned_pinned_Hz
from .capacity import AllowableOffset, WholeCapacity, allowable_offset, whole_capacity
from .geometry import (
    MESHES,
    OFFSET_AT,
    Annulus,
    CouplingGeometry,
    coupling_geometry,
    spec_geometry,
)
from .layout import MAX_SHAFT_ANGLE_DEG, SLEEVES, CouplingLayout, ShaftAlignment
from .loads import (
    LOAD_COLUMNS,
    MACHINE_LOADS,
    WholeLoads,
    default_turn,
    loads_from_results,
    mesh_torque_Nm,
    whole_loads,
)
from .massdata import WholeCouplingData, WholeTorsion, whole_coupling_data
from .ross import RossPieces

__all__ = ["LOAD_COLUMNS", "MACHINE_LOADS", "MAX_SHAFT_ANGLE_DEG", "MESHES", "OFFSET_AT",
           "SLEEVES", "AllowableOffset", "Annulus", "CouplingAssembly", "CouplingGeometry",
           "CouplingLayout", "PlacedPart", "RossPieces", "Segment", "ShaftAlignment",
           "WholeCapacity", "WholeCouplingData", "WholeLoads", "WholeTorsion", "allowable_offset",
           "annulus_EI_Nm2", "annulus_mesh", "beam_frequencies_Hz", "coupling_assembly",
           "coupling_geometry", "default_turn", "loads_from_results", "mesh_torque_Nm",
           "pinned_pinned_Hz", "spec_geometry", "whole_capacity", "whole_coupling_data",
           "whole_loads"]
