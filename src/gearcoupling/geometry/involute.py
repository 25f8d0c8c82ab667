"""Involute function and its stable inverse.

All functions take and return arrays of any shape (broadcasting) in radians.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ArgumentError
from ..numeric import TINY

_SERIES_LIMIT = 1e-2  # below this |a| the series avoids the cancellation in tan(a) - a


def inv(a: ArrayLike) -> NDArray[np.float64]:
    """Involute function ``inv(a) = tan(a) - a``.

    Uses its Taylor series for ``|a| < 0.01``, where ``tan(a) - a`` would lose up to
    eight digits to cancellation.

    Parameters
    ----------
    a : (...) float
        Angle in radians, ``|a| < pi/2``.
    """
    a = real_array(a, "a")
    if not np.all(np.abs(a) < 0.5 * np.pi):
        raise ArgumentError("a", float(a[~(np.abs(a) < 0.5 * np.pi)].flat[0]),
                            "angles in radians with |a| < pi/2")
    a2 = a * a
    series = a * a2 * (1 / 3 + a2 * (2 / 15 + a2 * (17 / 315 + a2 * (62 / 2835))))
    return np.where(np.abs(a) < _SERIES_LIMIT, series, np.tan(a) - a)


def inv_inverse(y: ArrayLike, *, rtol: float = 1e-15,
                max_iter: int = 60) -> NDArray[np.float64]:
    """Inverse of :func:`inv`: the angle ``a`` in ``(-pi/2, pi/2)`` with ``inv(a) = y``.

    Newton's method on the convex function ``tan a - a`` started above the root
    (``(3y)^(1/3)`` for small ``y``, ``pi/2 - 1/(y + pi/2)`` for large ``y``) converges
    monotonically; typically 3-6 iterations reach ``rtol``.

    Parameters
    ----------
    y : (...) float
        Involute values, any finite real (odd extension for ``y < 0``).
    """
    y = real_array(y, "y")
    if not np.all(np.isfinite(y)):
        raise ArgumentError("y", float(y[~np.isfinite(y)].flat[0]), "finite involute values")
    sign = np.sign(y)
    ay = np.abs(y)
    a = np.where(ay < 0.5, np.cbrt(3.0 * ay), np.pi / 2 - 1.0 / (ay + np.pi / 2))
    for _ in range(max_iter):
        t = np.tan(a)
        f = inv(a) - ay
        step = np.divide(f, t * t, out=np.zeros_like(a), where=t != 0)
        a = a - step
        if np.all(np.abs(step) <= rtol * np.maximum(np.abs(a), TINY)):
            break
    return sign * a


def real_array(values: ArrayLike, field: str) -> NDArray[np.float64]:
    """``values`` (numbers of any shape) as a float array; text, objects or ``bool`` are an
    :class:`ArgumentError` naming ``field``."""
    try:
        raw = np.asarray(values) if not isinstance(values, str | bytes) else np.asarray([values])
    except ValueError:  # a ragged nesting
        raw = np.asarray([None])
    if raw.dtype.kind not in "iuf":
        raise ArgumentError(field, str(values)[:60], "numbers (a float or an array of them)")
    return raw.astype(float)


def developed_arc(r: ArrayLike, r_base: float) -> NDArray[np.float64]:
    """Arc length of the involute of base radius ``r_base`` from the base circle to radius
    ``r``: ``(r² - r_b²) / (2 r_b)`` (the developed flank's depth co-ordinate)."""
    r = np.asarray(r, dtype=float)
    return (r * r - r_base * r_base) / (2.0 * r_base)


def roll_angle(r: ArrayLike, r_base: float) -> NDArray[np.float64]:
    """Pressure angle ``arccos(r_base / r)`` at radius ``r`` of an involute of base ``r_base``."""
    r = np.asarray(r, dtype=float)
    return np.arccos(np.clip(r_base / r, -1.0, 1.0))
