"""Misalignment sweeps: clearance, backlash and contact of every tooth (docs/conventions.md).

``gearcoupling.sweep`` is both this package and, called, :func:`sweep`.
"""

from .._callable import make_callable
from .clearance import KINDS
from .design import (
    binding_angle_deg,
    contact_travel,
    critical_misalignment_deg,
    design_quantities,
    double_engagement,
    min_backlash_rad,
)
from .result import CSV_COLUMNS, SweepResult
from .tooth_map import sweep

__all__ = ["CSV_COLUMNS", "KINDS", "SweepResult", "binding_angle_deg", "contact_travel",
           "critical_misalignment_deg", "design_quantities", "double_engagement",
           "min_backlash_rad", "sweep"]

make_callable(__name__, sweep)
