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
from .body import annulus_twist_rad, body_windup_rad
from .capacity import (
    PHASES,
    Capacity,
    CapacityCurve,
    capacity,
    capacity_curve,
    capacity_from_sweep,
    default_angles,
    turn_phases,
    write_capacity_csv,
)
from .inputs import resolve_torque_Nm
from .kernels.cantilever import CantileverCompliance
from .kernels.fitted import FittedCompliance
from .kernels.gapfield import GapField, depth_range, face_range, gap_field, lattice_windows
from .kernels.windup import solve_windup
from .models.linear import mesh_stiffness_N_per_mm
from .models.registry import (
    MODELS,
    LoadModel,
    load_model,
    model_names,
    models_help,
    resolve_model,
)
from .models.surface import start_from, surface_solver
from .models.surface_capacity import LOAD_GRID
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
    "MODELS",
    "PHASES",
    "TOOTH_LOAD_RATIO",
    "WINDUP_ERROR_PCT",
    "CantileverCompliance",
    "Capacity",
    "CapacityCurve",
    "FittedCompliance",
    "GapField",
    "LoadModel",
    "LoadResult",
    "PatchMap",
    "SectorCheck",
    "annulus_twist_rad",
    "body_windup_rad",
    "capacity",
    "capacity_curve",
    "capacity_from_sweep",
    "default_angles",
    "depth_range",
    "face_range",
    "gap_field",
    "lattice_windows",
    "load",
    "load_from_sweep",
    "load_model",
    "machine_loads",
    "mesh_stiffness_N_per_mm",
    "model_names",
    "models_help",
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
    "start_from",
    "surface_solver",
    "tooth_load_error",
    "turn_phases",
    "windup_error",
    "write_capacity_csv",
]
