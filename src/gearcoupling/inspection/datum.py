"""Datum axis from the bore: a least-squares cylinder through the scan's bore points."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..spec import CouplingSpec


def bore_datum(points: NDArray[np.float64], spec: CouplingSpec, min_points: int = 200,
               band: float = 0.04) -> dict | None:
    """Axis of the hub bore in the hub frame, from registered scan points.

    Bore points: radius within ``band`` (relative) of the spec's bore radius and ``|z|``
    below 45 % of the body length (the body end faces are left out). The linearised
    cylinder ``r = r_b + x/r (c_x + z t_x) + y/r (c_y + z t_y)`` is solved by least
    squares twice (the second time about the first axis).

    Returns
    -------
    dict or None
        ``centre_mm (2,)`` (axis at z = 0), ``tilt (2,)`` (dx/dz, dy/dz), ``radius_mm``,
        ``rms_mm``, ``points``; ``None`` without a bore or with fewer than ``min_points``.
    """
    rb = 0.5 * spec.hub.body.bore_diameter
    if rb <= 0:
        return None
    sel = (np.abs(np.hypot(points[:, 0], points[:, 1]) - rb) < band * rb) & \
        (np.abs(points[:, 2]) < 0.45 * spec.hub.body.length)
    p = points[sel]
    if len(p) < min_points:
        return None
    c, t = np.zeros(2), np.zeros(2)
    for _ in range(2):
        x = p[:, 0] - c[0] - t[0] * p[:, 2]
        y = p[:, 1] - c[1] - t[1] * p[:, 2]
        r = np.hypot(x, y)
        ux, uy, z = x / r, y / r, p[:, 2]
        A = np.stack([np.ones_like(r), ux, ux * z, uy, uy * z], axis=-1)
        sol, *_ = np.linalg.lstsq(A, r, rcond=None)
        c += sol[[1, 3]]
        t += sol[[2, 4]]
    x = p[:, 0] - c[0] - t[0] * p[:, 2]
    y = p[:, 1] - c[1] - t[1] * p[:, 2]
    res = np.hypot(x, y) - sol[0]
    return {"centre_mm": c, "tilt": t, "radius_mm": float(sol[0]),
            "rms_mm": float(np.sqrt(np.mean(res * res))), "points": len(p)}
