"""The design report (``gearcoupling report``): one self-contained HTML file, optionally
printed to PDF, that says what the coupling is, what it carries and whether it passes
against the spec's limits (and which limits were not set)."""

from .build import ReportResult, report, report_files, section_verdicts
from .sections import SECTIONS
from .settings import KNOB_RANGES, ReportSettings
from .verdict import FAIL, Verdict, capacity_verdict, geometry_verdicts, load_verdicts
from .view import ReportSection, View

__all__ = [
    "FAIL",
    "KNOB_RANGES",
    "SECTIONS",
    "ReportResult",
    "ReportSection",
    "ReportSettings",
    "Verdict",
    "View",
    "capacity_verdict",
    "geometry_verdicts",
    "load_verdicts",
    "report",
    "report_files",
    "section_verdicts",
]
