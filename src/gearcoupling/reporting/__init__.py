"""The design report (``gearcoupling report``): one self-contained HTML file, optionally
printed to PDF, that says what the coupling is, what it carries and whether it passes
against the spec's limits (and which limits were not set)."""

from .build import ReportResult, report
from .capacity import CapacityComparison, compare_capacity, comparison_range
from .settings import KNOB_RANGES, ReportSettings
from .verdict import FAIL, Verdict, geometry_verdicts, load_verdicts

__all__ = [
    "FAIL",
    "KNOB_RANGES",
    "CapacityComparison",
    "ReportResult",
    "ReportSettings",
    "Verdict",
    "compare_capacity",
    "comparison_range",
    "geometry_verdicts",
    "load_verdicts",
    "report",
]
