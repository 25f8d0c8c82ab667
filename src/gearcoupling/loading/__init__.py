"""Loaded tooth contact: load sharing, contact pressure and capacity (docs/load.md)."""

from __future__ import annotations

from .api import load, load_from_sweep
from .cantilever import CantileverCompliance
from .capacity import (
    Capacity,
    CapacityCurve,
    capacity,
    capacity_curve,
    capacity_from_sweep,
    default_angles,
    write_capacity_csv,
)
from .inputs import resolve_torque_Nm
from .linear import solve_windup
from .linear_model import mesh_stiffness_N_per_mm
from .plots import plot_capacity, plot_patches, plot_q_graph, plot_tooth_load, plot_vs_misalignment
from .result import CSV_COLUMNS, LoadResult

__all__ = [
    "CSV_COLUMNS",
    "CantileverCompliance",
    "Capacity",
    "CapacityCurve",
    "LoadResult",
    "capacity",
    "capacity_curve",
    "capacity_from_sweep",
    "default_angles",
    "load",
    "load_from_sweep",
    "mesh_stiffness_N_per_mm",
    "plot_capacity",
    "plot_patches",
    "plot_q_graph",
    "plot_tooth_load",
    "plot_vs_misalignment",
    "resolve_torque_Nm",
    "solve_windup",
    "write_capacity_csv",
]
