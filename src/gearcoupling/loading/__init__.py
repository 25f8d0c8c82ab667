"""Loaded tooth contact: load sharing, contact pressure and capacity (docs/load.md)."""

from __future__ import annotations

from .accuracy import (
    TOOTH_LOAD_RATIO,
    WINDUP_ERROR_PCT,
    springs_name,
    tooth_load_error,
    windup_error,
)
from .api import load, load_from_sweep
from .body import body_windup_rad
from .cantilever import CantileverCompliance
from .capacity import (
    LOAD_GRID,
    PHASES,
    ROTATIONS,
    Capacity,
    CapacityCurve,
    capacity,
    capacity_curve,
    capacity_from_sweep,
    default_angles,
    turn_phases,
    write_capacity_csv,
)
from .fitted import FittedCompliance
from .inputs import resolve_model, resolve_torque_Nm
from .linear import solve_windup
from .linear_model import mesh_stiffness_N_per_mm
from .patchmap import PatchMap, most_loaded, patch_maps
from .plots import (
    plot_capacity,
    plot_loads_over_turn,
    plot_patches,
    plot_q_graph,
    plot_tooth_load,
    plot_vs_misalignment,
    renzo_q,
)
from .result import CSV_COLUMNS, LoadResult
from .sector_check import SectorCheck, sector_check
from .summary import machine_loads, rotation_table

__all__ = [
    "CSV_COLUMNS",
    "LOAD_GRID",
    "PHASES",
    "ROTATIONS",
    "TOOTH_LOAD_RATIO",
    "WINDUP_ERROR_PCT",
    "CantileverCompliance",
    "Capacity",
    "CapacityCurve",
    "FittedCompliance",
    "LoadResult",
    "PatchMap",
    "SectorCheck",
    "body_windup_rad",
    "capacity",
    "capacity_curve",
    "capacity_from_sweep",
    "default_angles",
    "load",
    "load_from_sweep",
    "machine_loads",
    "mesh_stiffness_N_per_mm",
    "most_loaded",
    "patch_maps",
    "plot_capacity",
    "plot_loads_over_turn",
    "plot_patches",
    "plot_q_graph",
    "plot_tooth_load",
    "plot_vs_misalignment",
    "renzo_q",
    "resolve_model",
    "resolve_torque_Nm",
    "rotation_table",
    "sector_check",
    "solve_windup",
    "springs_name",
    "tooth_load_error",
    "turn_phases",
    "windup_error",
    "write_capacity_csv",
]
