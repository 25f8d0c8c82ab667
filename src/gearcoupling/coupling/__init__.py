"""The whole coupling (docs/coupling.md)."""

from .capacity import AllowableOffset, WholeCapacity, allowable_offset, whole_capacity
from .geometry import MESHES, OFFSET_AT, Annulus, CouplingGeometry, coupling_geometry
from .layout import MAX_SHAFT_ANGLE_DEG, SLEEVES, CouplingLayout, ShaftAlignment
from .loads import LOAD_COLUMNS, MACHINE_LOADS, WholeLoads, whole_loads

__all__ = ["LOAD_COLUMNS", "MACHINE_LOADS", "MAX_SHAFT_ANGLE_DEG", "MESHES", "OFFSET_AT",
           "SLEEVES", "AllowableOffset", "Annulus", "CouplingGeometry", "CouplingLayout",
           "ShaftAlignment", "WholeCapacity", "WholeLoads", "allowable_offset",
           "coupling_geometry", "whole_capacity", "whole_loads"]
