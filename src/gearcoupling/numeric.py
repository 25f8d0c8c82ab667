"""Numeric guards shared by the kernels (numpy only; every layer may import them)."""

from __future__ import annotations

from typing import Any

import numpy as np

#: the floor of a divisor, a logarithm's argument or a square root's that may reach 0:
#: far below any value the kernels compute, so it changes no result above it and turns
#: 0 into a finite quotient instead of a division by zero
TINY = 1e-300


def divide(numerator: Any, denominator: Any) -> Any:
    """``numerator / denominator`` with the (non-negative) denominator floored at
    :data:`TINY`: finite where it is 0; floats or arrays, broadcast as numpy does."""
    if isinstance(denominator, np.ndarray):
        return numerator / np.maximum(denominator, TINY)
    return numerator / max(float(denominator), TINY)
