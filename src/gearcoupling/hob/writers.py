"""Thin, atomic CSV writer shared by the manufacturing and inspection outputs."""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import SupportsFloat, cast

from ..atomic import write_text
from ..errors import GearCouplingError


def write_csv(path: str | Path, rows: Iterable[Mapping[str, object]],
              comments: Iterable[str] = ()) -> Path:
    """Write dict rows as CSV atomically, after ``# comment`` lines (units, frame).

    Floats are written with 10 significant digits; a non-finite value is refused.
    """
    rows = list(rows)
    buf = io.StringIO()
    for line in comments:
        buf.write(f"# {line}\n")
    if rows:
        w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        for row in rows:
            w.writerow({k: _fmt(k, v) for k, v in row.items()})
    return write_text(path, buf.getvalue())


def _fmt(key: str, value: object) -> object:
    numeric = isinstance(value, float | int) or hasattr(value, "dtype")
    if isinstance(value, bool) or not numeric:
        return value
    v = float(cast(SupportsFloat, value))  # a number or a numpy scalar/0-d array
    if not math.isfinite(v):
        raise GearCouplingError(f"refusing to write a non-finite {key} = {v} to CSV")
    return int(v) if isinstance(value, int) else f"{v:.10g}"
