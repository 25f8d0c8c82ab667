"""The one rule that attributes an overlap (or any point) to a tooth and a flank.

Used by the interference check and by the viewer's interference display. Tooth ``k`` is
centred on the polar angle ``2 pi k / N`` (docs/conventions.md, Loaded analysis); a point belongs
to the nearest
tooth centre, and to the ``ccw`` flank when its polar angle is beyond that centre
(counter-clockwise), to ``cw`` otherwise.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..geometry import FLANKS

__all__ = ["FLANKS", "flank_index", "nearest_tooth"]


def nearest_tooth(points: NDArray, teeth: int) -> NDArray[np.int64]:
    """Index ``(...)`` of the tooth centre nearest to the polar angle of ``points (..., 3)``,
    unwrapped (``-N/2 .. N/2``; take ``% teeth`` for ``0 .. N-1``)."""
    ang = np.arctan2(points[..., 1], points[..., 0])
    return np.rint(ang / (2.0 * math.pi / teeth)).astype(np.int64)


def flank_index(points: NDArray, tooth: ArrayLike, teeth: int) -> NDArray[np.int64]:
    """``1`` (ccw) where ``points (..., 3)`` lie counter-clockwise of the centre of
    ``tooth (...)``, else ``0`` (cw)."""
    ang = np.arctan2(points[..., 1], points[..., 0]) - 2.0 * math.pi * np.asarray(tooth) / teeth
    ang = np.remainder(ang + math.pi, 2.0 * math.pi) - math.pi
    return (ang > 0).astype(np.int64)
