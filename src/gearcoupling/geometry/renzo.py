"""Renzo, Kaufman & De Rocker (1967): the closed-form separation of a crowned coupling."""

from __future__ import annotations

import math


def renzo_z0_mm(crown_radius_mm: float, misalignment_rad: float,
                pressure_angle_rad: float) -> float:
    """Renzo's eq. (4): the largest separation ``z0 = R_c cot(phi) tan^2(i) / 2`` of a flank
    along its pitch line, measured normal to the flank (mm); 0 when aligned, ``inf`` for a
    straight tooth (``R_c = inf``) at a misalignment.

    >>> round(renzo_z0_mm(2.5 * 25.4, math.radians(1.0), math.radians(20.0)) / 25.4, 5)
    0.00105
    """
    if misalignment_rad == 0.0:
        return 0.0
    return 0.5 * crown_radius_mm * math.tan(misalignment_rad) ** 2 / math.tan(pressure_angle_rad)
