"""The ranges of a spec's numbers and the value checks every part of a spec uses; each
refusal is a :class:`~gearcoupling.errors.SpecError` naming the field, the value and what
is allowed."""

from __future__ import annotations

import math
import numbers

from ..errors import ArgumentError, SpecError

MM_PER_INCH = 25.4
UNITS = {"mm": 1.0, "in": MM_PER_INCH}
TEETH_RANGE = (6, 300)
MODULE_RANGE_MM = (0.2, 60.0)
PRESSURE_ANGLE_RANGE_DEG = (14.5, 30.0)
MISALIGNMENT_RANGE_DEG = (0.0, 6.0)
MAX_NAME_CHARS = 200
_ROUNDING_DEG = 1e-9  # slack for degree <-> radian round trips (6° -> 6.000000000000001)


def check_misalignment_deg(value: object, field_name: str = "misalignment_deg",
                           error: type[SpecError] | type[ArgumentError] = SpecError) -> float:
    """A misalignment in degrees, validated once for every caller (0-6°).

    Values within ``1e-9°`` outside the range (a degree-radian round trip) are clamped
    onto it; anything else outside, non-numeric or non-finite raises ``error``: a
    :class:`SpecError` for a spec value, an :class:`ArgumentError` for an argument.
    """
    lo, hi = MISALIGNMENT_RANGE_DEG
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (
            math.isfinite(value) and lo - _ROUNDING_DEG <= float(value) <= hi + _ROUNDING_DEG):
        raise error(field_name, value, f"must be a finite angle from {lo} to {hi} degrees")
    return min(max(float(value), lo), hi)


def _check(ok: bool, field_name: str, value: object, allowed: str) -> None:
    """Refuse ``value`` of ``field_name`` unless ``ok``."""
    if not ok:
        raise SpecError(field_name, value, allowed)


def _positive(path: str, value: float, *, finite: bool = True) -> None:
    """Refuse a length that is not positive (and finite, unless ``finite`` is false)."""
    good = value > 0 and (math.isfinite(value) or not finite) and not math.isnan(value)
    _check(good, path, value, "must be a positive finite length in mm" if finite else
           "must be positive (inf allowed)")
