"""Inspection: a measured (or another) hub against the nominal, tooth by tooth.

Reads meshes and point clouds, registers them on the exact nominal flanks (coarse by axis
and tooth indexing, fine by point-to-flank least squares) and reports profile, lead,
crown, pitch, thickness and runout deviations with pass/fail. Uses the geometry kernels;
trimesh is imported only to read mesh files, matplotlib only to plot.
"""

from .compare import PartComparison, compare_part
from .io import load_points
from .register import Registration, RegistrationError
from .report import LIMITS, InspectionReport

__all__ = ["LIMITS", "InspectionReport", "PartComparison", "Registration",
           "RegistrationError", "compare_part", "load_points"]
