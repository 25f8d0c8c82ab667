"""Clearance sweeps: clearance, backlash and contact of every tooth over the turn, and the
design angles (critical and binding misalignment); docs/conventions.md."""

from .design import (
    MeshAngles,
    binding_angle_deg,
    contact_travel,
    critical_misalignment_deg,
    design_quantities,
    double_engagement,
    mesh_angles,
    min_backlash_rad,
    pitch_turning_angles,
)
from .flank_table import flank_table
from .kernel import KINDS
from .plots import (
    backlash_curve,
    plot_all,
    plot_backlash,
    plot_backlash_over_turn,
    plot_clearance,
    plot_clearance_map,
    plot_contact_path,
    sweep_figures,
)
from .result import CSV_COLUMNS, SweepResult
from .tooth_map import check_angles, check_misalignment, flank_minima, sweep

__all__ = [
    "CSV_COLUMNS",
    "KINDS",
    "MeshAngles",
    "SweepResult",
    "backlash_curve",
    "binding_angle_deg",
    "check_angles",
    "check_misalignment",
    "contact_travel",
    "critical_misalignment_deg",
    "design_quantities",
    "double_engagement",
    "flank_minima",
    "flank_table",
    "mesh_angles",
    "min_backlash_rad",
    "pitch_turning_angles",
    "plot_all",
    "plot_backlash",
    "plot_backlash_over_turn",
    "plot_clearance",
    "plot_clearance_map",
    "plot_contact_path",
    "sweep",
    "sweep_figures",
]
