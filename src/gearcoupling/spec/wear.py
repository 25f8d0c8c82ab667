"""The spec's ``[wear]`` table: read as text and numbers here, judged by
:mod:`gearcoupling.wear` (its ``WearSettings``, which knows the regimes and the ranges)."""

from __future__ import annotations

from typing import Any

from ..io import Table

#: the keys of ``[wear]``
WEAR_TABLE_KEYS = ("regime", "coefficient_mm3_per_Nm", "coefficient_band_mm3_per_Nm",
                   "sleeve_factor", "limit_fraction", "required_life_h", "speed_rpm", "hours")


def parse_wear(data: Any) -> tuple[tuple[str, Any], ...]:
    """The ``[wear]`` table as ``(key, value)`` pairs in :data:`WEAR_TABLE_KEYS` order:
    ``regime`` a string, the band an array of numbers, the others numbers; unknown keys
    refused. What each value may be is ``gearcoupling.wear``'s to say."""
    t = data if isinstance(data, Table) else Table(data, "wear")
    out: list[tuple[str, Any]] = []
    for key in WEAR_TABLE_KEYS:
        if not t.has(key):
            continue
        if key == "regime":
            out.append((key, t.get(key, str)))
        elif key == "coefficient_band_mm3_per_Nm":
            out.append((key, t.array(key)))
        else:
            out.append((key, t.number(key)))
    t.done(WEAR_TABLE_KEYS)
    return tuple(out)


def wear_table(pairs: tuple[tuple[str, Any], ...]) -> dict[str, Any]:
    """The ``[wear]`` table of the pairs :func:`parse_wear` read (arrays as lists)."""
    return {k: list(v) if isinstance(v, tuple | list) else v for k, v in pairs}
