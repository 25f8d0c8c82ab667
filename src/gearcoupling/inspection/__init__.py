"""Inspection: a measured (or another) hub against the nominal, tooth by tooth.

Reads meshes and point clouds, registers them on the exact nominal flanks (coarse by axis
and tooth indexing, fine by point-to-flank least squares) and reports profile, lead,
crown, pitch, thickness and runout deviations with pass/fail. Uses the geometry kernels;
trimesh is imported only to read mesh files, matplotlib only to plot.
"""

from .compare import STAGES, PartComparison, compare_part
from .heatmap import write_deviation_ply
from .io import load_points
from .iso1328 import GRADES, grade_limits
from .plots import plot_deviation_map, plot_inspection
from .register import Registration, RegistrationError
from .report import LIMITS, InspectionReport, check_limits, verdicts

__all__ = [
    "GRADES",
    "LIMITS",
    "STAGES",
    "InspectionReport",
    "PartComparison",
    "Registration",
    "RegistrationError",
    "check_limits",
    "compare_part",
    "grade_limits",
    "load_points",
    "plot_deviation_map",
    "plot_inspection",
    "verdicts",
    "write_deviation_ply",
]
