"""Misalignment sweeps: clearance, backlash and contact of every tooth (DESIGN.md §2, §5)."""

from .clearance import KINDS
from .result import CSV_COLUMNS, SweepResult
from .tooth_map import sweep

__all__ = ["CSV_COLUMNS", "KINDS", "SweepResult", "sweep"]
