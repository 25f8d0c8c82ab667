"""CSV files: one writer for every table gearcoupling writes. Every text cell, header and
comment line goes out through :mod:`.text` (one line each, never a formula)."""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import GearCouplingError
from .atomic import atomic_path
from .text import csv_cell, csv_comment


def _cell(column: str, v: Any, digits: int, finite: bool) -> Any:
    if type(v) is not float:  # a Python float, the common case, goes straight to the number
        if v is None:
            return ""
        if isinstance(v, bool | str) or not (isinstance(v, float | int) or hasattr(v, "dtype")):
            return str(v).lower() if isinstance(v, bool) else csv_cell(v)
        if isinstance(v, int):
            return v
    x = float(v)
    if finite and not math.isfinite(x):
        raise GearCouplingError(f"refusing to write a non-finite {column} = {x} to CSV")
    return f"{x:.{digits}g}"


def write_csv_rows(path: str | os.PathLike, columns: Sequence[str],
                   rows: Iterable[Sequence[Any]], *, comments: Iterable[str] = (),
                   digits: int = 9, finite: bool = False) -> Path:
    """A CSV written atomically: ``# comment`` lines (units, frame), a header of
    ``columns``, then ``rows`` (sequences in column order). Floats with ``digits``
    significant digits (``inf`` for infinity, or refused with ``finite``), booleans
    ``true``/``false``, None empty, text as :func:`~gearcoupling.io.csv_cell` makes it
    (comments as :func:`~gearcoupling.io.csv_comment`)."""
    return _write(path, columns, ([_cell(c, v, digits, finite)
                                   for c, v in zip(columns, row, strict=True)]
                                  for row in rows), comments)


def _write(path: str | os.PathLike, columns: Sequence[str], rows: Iterable[Sequence[Any]],
           comments: Iterable[str]) -> Path:
    """``# comment`` lines, the header and the formatted ``rows``, atomically."""
    with atomic_path(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as fh:
        fh.writelines(csv_comment(line) + "\n" for line in comments)
        w = csv.writer(fh, lineterminator="\n")
        w.writerow([csv_cell(c) for c in columns])
        w.writerows(rows)
    return Path(path)


def _column(column: str, values: Any, digits: int, finite: bool) -> list[Any]:
    """The cells of one column as :func:`_cell` makes them, a float array at once."""
    if not (isinstance(values, np.ndarray) and values.dtype.kind == "f"):
        return [_cell(column, v, digits, finite) for v in values]
    if finite and not np.all(np.isfinite(values)):
        bad = values[~np.isfinite(values)][0]
        raise GearCouplingError(f"refusing to write a non-finite {column} = {bad} to CSV")
    form = f".{digits}g"
    return [format(x, form) for x in values.tolist()]


def write_csv_columns(path: str | os.PathLike, columns: Sequence[str],
                      data: Sequence[Any], *, comments: Iterable[str] = (),
                      digits: int = 9, finite: bool = False) -> Path:
    """:func:`write_csv_rows` of a table given by columns: ``data[i]`` the values of
    ``columns[i]``, all of one length (a numpy array of floats is formatted at once): the
    same file as the rows would give."""
    cells = [_column(c, v, digits, finite) for c, v in zip(columns, data, strict=True)]
    if len({len(c) for c in cells}) > 1:
        raise GearCouplingError(f"CSV columns of unequal length: {[len(c) for c in cells]}")
    return _write(path, columns, zip(*cells, strict=True), comments)


def write_csv_records(path: str | os.PathLike, rows: Iterable[dict[str, Any]],
                      comments: Iterable[str] = ()) -> Path:
    """Dict rows (keys as columns, from the first row) as :func:`write_csv_rows` with 10
    significant digits, refusing a non-finite number: the manufacturing and inspection
    tables that go to a machine."""
    rows = list(rows)
    columns = list(rows[0]) if rows else []
    return write_csv_rows(path, columns, ([r[c] for c in columns] for r in rows),
                          comments=comments, digits=10, finite=True)
