"""Clearance sweeps: clearance, backlash and contact of every tooth over the turn, and the
design angles (critical and binding misalignment); docs/conventions.md."""

from .design import (
    binding_angle_deg,
    contact_travel,
    critical_misalignment_deg,
    design_quantities,
    double_engagement,
    min_backlash_rad,
)
from .kernel import KINDS
from .result import CSV_COLUMNS, SweepResult
from .tooth_map import sweep

__all__ = ["CSV_COLUMNS", "KINDS", "SweepResult", "binding_angle_deg", "contact_travel",
           "critical_misalignment_deg", "design_quantities", "double_engagement",
           "min_backlash_rad", "sweep"]
