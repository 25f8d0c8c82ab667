"""CalculiX/Abaqus input decks: the number and id lines both INP writers use (the surface
mesh export and the FE volume mesh). Lines stay within the 132 characters CalculiX reads."""

from __future__ import annotations

import io

import numpy as np
from numpy.typing import ArrayLike

LINE = 132  # characters CalculiX reads of a line
MAX_PER_LINE = 16  # data items per line (the Abaqus limit)


def inp_number(x: float) -> str:
    """A number field of at most 20 characters that round-trips to 1e-12 relative."""
    return f"{x:.12e}" if x != 0 else "0.0"


def _lines(array: np.ndarray, fmt) -> list[str]:
    buf = io.StringIO()
    np.savetxt(buf, array, fmt=fmt, delimiter=", ")
    return buf.getvalue().splitlines()


def inp_id_lines(ids: ArrayLike) -> list[str]:
    """Ids (1-based) as ``*NSET``/``*ELSET`` data lines, as many to a line as fit."""
    a = np.asarray(ids, dtype=np.int64).ravel()
    if a.size == 0:
        return []
    per = max(1, min(MAX_PER_LINE, LINE // (len(str(int(a.max()))) + 2)))
    full = a.size - a.size % per
    lines = _lines(a[:full].reshape(-1, per), "%d") if full else []
    if full < a.size:
        lines.append(", ".join(map(str, a[full:])))
    return lines


def inp_node_lines(points: ArrayLike, nset: str = "NALL") -> list[str]:
    """``*NODE`` lines of ``points`` ``(n, 3)`` (mm), numbered from 1."""
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    ids = np.arange(1, len(pts) + 1)
    return [f"*NODE, NSET={nset}", *_lines(np.column_stack([ids, pts]),
                                            ["%d", "%.12e", "%.12e", "%.12e"])]


def inp_element_lines(connectivity: ArrayLike, element_type: str,
                      elset: str = "EALL") -> list[str]:
    """``*ELEMENT`` lines of 0-based ``connectivity`` ``(m, k)``, numbered from 1."""
    conn = np.asarray(connectivity, dtype=np.int64)
    ids = np.arange(1, len(conn) + 1)
    return [f"*ELEMENT, TYPE={element_type}, ELSET={elset}",
            *_lines(np.column_stack([ids, conn + 1]), "%d")]
