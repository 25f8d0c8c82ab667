"""Loaded tooth contact: load sharing, contact pressure and capacity (issue 10, DESIGN.md §6).

``gearcoupling.load`` is both this package and, called, :func:`load` (so ``gc.load(spec, ...)``
works whether the attribute resolves to the package or to the function).
"""

from __future__ import annotations

from .._callable import make_callable
from .api import load, load_from_sweep
from .cantilever import CantileverCompliance
from .capacity import capacity, capacity_curve, capacity_from_sweep
from .result import CSV_COLUMNS, LoadResult

__all__ = ["CSV_COLUMNS", "CantileverCompliance", "LoadResult", "capacity", "capacity_curve",
           "capacity_from_sweep", "load", "load_from_sweep"]

make_callable(__name__, load)
