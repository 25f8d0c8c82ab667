"""Loaded tooth contact: load sharing, contact pressure and capacity (docs/load.md)."""

from __future__ import annotations

from .api import load, load_from_sweep
from .cantilever import CantileverCompliance
from .capacity import Capacity, capacity, capacity_curve, capacity_from_sweep
from .result import CSV_COLUMNS, LoadResult

__all__ = [
           "CSV_COLUMNS",
           "CantileverCompliance",
           "Capacity",
           "LoadResult",
           "capacity",
           "capacity_curve",
           "capacity_from_sweep",
           "load",
           "load_from_sweep",
]
