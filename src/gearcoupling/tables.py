"""Results as pandas DataFrames: the ``to_dataframe()`` of every result class.

A DataFrame has the columns of the result's CSV file (tidy: one row per observation, units
in the column names), so a notebook and a spreadsheet see the same table. pandas is an
optional extra (``pip install 'gearcoupling[pandas]'``), imported at the first call.
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable, Sequence
from typing import Any

from .errors import BackendError
from .interrupts import reraise as reraise_interrupt


def import_pandas() -> Any:
    """``pandas``, or :class:`~gearcoupling.errors.BackendError` naming the extra."""
    try:
        return importlib.import_module("pandas")
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("DataFrames need pandas: pip install 'gearcoupling[pandas]' "
                           "(or pip install pandas)") from err


def dataframe(columns: Sequence[str], rows: Iterable[Sequence[Any]]) -> Any:
    """A DataFrame of ``rows`` (tuples in ``columns`` order, or dicts keyed by them).

    Columns that hold only numbers and ``None`` become float columns with NaN for
    ``None``, as a CSV reader sees the empty cells the CSV writers leave for ``None``.
    """
    pd = import_pandas()
    records = [[r.get(c) for c in columns] if isinstance(r, dict) else list(r) for r in rows]
    frame = pd.DataFrame.from_records(records, columns=list(columns))
    for name in frame.columns:
        if frame[name].dtype.kind == "O" and all(_number_or_none(v) for v in frame[name]):
            frame[name] = frame[name].astype(float)
    return frame


def _number_or_none(v: Any) -> bool:
    return v is None or (isinstance(v, int | float) and not isinstance(v, bool))
