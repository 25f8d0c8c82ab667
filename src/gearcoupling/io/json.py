"""JSON files with one rule for non-finite numbers.

Every JSON file gearcoupling writes goes through :func:`plain`: numpy scalars and arrays
become Python numbers and lists, an infinite float becomes the string ``"inf"`` or
``"-inf"`` (as TOML spells it, and as the CSV files print it: a clearance of a flank that
faces nothing, a straight crown's radius), and NaN is refused, so a file never holds a
value that a JSON reader cannot parse or that hides a fault.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import GearCouplingError
from .atomic import write_text


class NonFiniteError(GearCouplingError, ValueError):
    """A NaN in data about to be written: a fault in gearcoupling (nothing is written)."""


def plain(data: Any, what: str = "data", key: str = "") -> Any:
    """``data`` as plain JSON data: dicts, lists, str, bool, int, float, None; ``±inf`` as
    ``"inf"``/``"-inf"``. NaN raises :class:`NonFiniteError` naming ``what`` and the key."""
    if isinstance(data, dict):
        return {k: plain(v, what, f"{key}.{k}" if key else str(k)) for k, v in data.items()}
    if isinstance(data, list | tuple | np.ndarray):
        return [plain(v, what, f"{key}[{j}]") for j, v in enumerate(list(data))]
    if isinstance(data, bool | np.bool_):
        return bool(data)
    if isinstance(data, int | np.integer):
        return int(data)
    if isinstance(data, float | np.floating):
        x = float(data)
        if math.isnan(x):
            raise NonFiniteError(f"{what}: {key or 'a value'} is NaN (a fault: please report "
                                 "the spec); nothing was written")
        return x if math.isfinite(x) else ("inf" if x > 0 else "-inf")
    return data


def write_json(path: str | os.PathLike, data: Any) -> Path:
    """Write ``data`` (after :func:`plain`) as indented JSON, atomically."""
    text = json.dumps(plain(data, Path(path).name), indent=2, allow_nan=False)
    return write_text(path, text + "\n")
