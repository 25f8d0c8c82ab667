"""The design report (``gearcoupling report``): one self-contained HTML file, optionally
printed to PDF, that says what the coupling is, what it carries and whether it passes."""

from .capacity import CapacityComparison, compare_capacity, comparison_range

__all__ = ["CapacityComparison", "compare_capacity", "comparison_range"]
