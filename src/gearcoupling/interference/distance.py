"""The distance engine: closest point pair, collision test and penetration depth.

Choice by measurement (``python benchmarks/bench_interference.py --engines``; the times
are in docs/interference.md): on renzo-1967 at 1°, tolerance 0.0127 mm, the pose of its
smallest clearance, all engines (python-fcl, libigl, manifold3d) find the same distance to
1e-6 mm.

python-fcl is used for the gap because it is the fastest on large meshes, it is exact on
the meshes (triangle-triangle, not only vertex-triangle like libigl), it returns the
closest point pair and the two triangles (hence surface kind and tooth), and its
bounding-volume tree is built once per part and re-posed by a matrix (the libigl call
rebuilds its tree on every query). manifold3d's ``min_gap`` returns 0 as soon as the parts
touch and gives no points. Where the parts overlap a gap has no meaning; the penetration
depth (the largest distance of a hub surface point inside the sleeve to the sleeve
surface, the quantity the sweep's negative normal clearance measures) comes from libigl's
signed distance with pseudo-normals, which is exact for closed meshes and only runs at
overlapping poses, on the few hundred vertices of a window.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import BackendError
from ..geometry import rot_z
from ..interrupts import reraise as reraise_interrupt
from .posed import PreparedPart


def _igl():
    try:
        import igl
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("penetration depths need libigl: pip install "
                           "'gearcoupling[interference]'") from err
    return igl


@dataclass(frozen=True)
class Closest:
    """Closest point pair of a posed hub and the sleeve (sleeve/window frame, mm).

    ``hub_face`` and ``sleeve_face`` index the parts' :attr:`PreparedPart.faces`.
    """

    distance_mm: float
    hub_point: NDArray[np.float64]
    sleeve_point: NDArray[np.float64]
    hub_face: int
    sleeve_face: int


def closest_pair(hub: PreparedPart, matrix: NDArray, sleeve: PreparedPart,
                 flank: str | None = None) -> Closest:
    """Minimum distance between the hub shell posed by ``matrix`` and the sleeve shell.

    Exact on the meshes (python-fcl, triangle-triangle). Zero when they intersect. With
    ``flank`` (``"cw"``/``"ccw"``) only that flank side of both parts (the surfaces that
    close when the hub turns toward that side).
    """
    import fcl

    req = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=False)
    res = fcl.DistanceResult()
    d = fcl.distance(hub.fcl_object(matrix, flank), sleeve.fcl_object(None, flank), req, res)
    p, q = (np.asarray(x, dtype=float) for x in res.nearest_points)
    return Closest(max(float(d), 0.0), p, q, hub.shell_face(res.b1, flank),
                   sleeve.shell_face(res.b2, flank))


def turning_rate(matrix: NDArray, point: NDArray) -> float:
    """Rate of the sleeve polar angle of a posed hub point per unit turn of the hub about
    its own axis (1 when aligned).

    Parameters
    ----------
    matrix : (3, 3) float
        Hub pose; its third column is the hub axis in the sleeve frame.
    point : (3,) float
        The point in the sleeve frame.
    """
    k = np.asarray(matrix, dtype=float)[:, 2]
    q = np.asarray(point, dtype=float)
    v = np.cross(k, q)
    r2 = q[0] ** 2 + q[1] ** 2
    return float((v[1] * q[0] - v[0] * q[1]) / r2)


def collide(hub: PreparedPart, matrix: NDArray, sleeve: PreparedPart) -> bool:
    """Whether the hub shell posed by ``matrix`` intersects the sleeve shell (python-fcl)."""
    import fcl

    return bool(fcl.collide(hub.fcl_object(matrix), sleeve.fcl_object(),
                            fcl.CollisionRequest(), fcl.CollisionResult()))


def penetration(points: NDArray, sleeve: PreparedPart):
    """Signed distance of points to the closed sleeve mesh (negative inside), libigl.

    Parameters
    ----------
    points : (n, 3) float
        In the sleeve (window) frame.

    Returns
    -------
    depth : (n,) float
        Distance inside the sleeve (> 0 inside, <= 0 outside), mm.
    foot : (n, 3) float
        Closest sleeve surface point of each.
    """
    igl = _igl()
    s, _, foot, _ = igl.signed_distance(
        np.ascontiguousarray(points, dtype=float), sleeve.vertices, sleeve.faces,
        igl.SIGNED_DISTANCE_TYPE_PSEUDONORMAL)
    return -np.asarray(s, dtype=float), np.asarray(foot, dtype=float)


def surface_distance(points: NDArray, sleeve: PreparedPart):
    """Unsigned distance of points ``(n, 3)`` to the sleeve surface (mm) and the closest
    sleeve points ``(n, 3)``, libigl."""
    igl = _igl()
    d2, _, foot = igl.point_mesh_squared_distance(np.ascontiguousarray(points, dtype=float),
                                                  sleeve.vertices, sleeve.faces)
    return np.sqrt(np.maximum(np.asarray(d2, dtype=float), 0.0)), np.asarray(foot, dtype=float)


def positive_integral(vertices: NDArray, faces: NDArray, values: NDArray) -> NDArray:
    """Integral over each triangle of ``max(0, f)`` for ``f`` linear between vertex values.

    Parameters
    ----------
    vertices : (n, 3) float
    faces : (m, 3) int
    values : (n,) float

    Returns
    -------
    (m,) float
        Exact for the linear interpolant: the triangle is clipped where ``f`` changes sign.
        With ``f`` the penetration depth this is the overlap volume to first order in the
        depth (a thin lens: depth times area).
    """
    a, b, c = (vertices[faces[:, j]] for j in range(3))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    d = values[faces]
    pos = d > 0
    count = pos.sum(axis=1)
    full = area * d.mean(axis=1)
    out = np.where(count == 3, full, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        # one vertex on the other side: the corner triangle at it has area
        # area * t1 * t2 and integral area * t1 * t2 * d_lone / 3
        lone = np.where(count == 1, np.argmax(pos, axis=1), np.argmin(pos, axis=1))
        rows = np.arange(len(d))
        dl = d[rows, lone]
        d1, d2 = d[rows, (lone + 1) % 3], d[rows, (lone + 2) % 3]
        corner = area * (dl / (dl - d1)) * (dl / (dl - d2)) * dl / 3.0
    out = np.where(count == 1, corner, out)
    out = np.where(count == 2, full - corner, out)
    return np.where(np.isfinite(out), np.maximum(out, 0.0), 0.0)


def closing_speed(matrix: NDArray, pair: Closest, sign: float, fallback: float) -> float:
    """Rate at which the gap of a closest pair shrinks per unit turn of the hub about its
    own axis (``sign`` +1 toward increasing polar angle, -1 the other way): the velocity
    of the hub point along the unit vector to the sleeve point. For involute flanks it
    is ``r_b`` times the turning rate; where the pair does not close at first order the
    ``fallback`` rate is used so that a search keeps moving."""
    k = np.asarray(matrix, dtype=float)[:, 2]
    u = pair.sleeve_point - pair.hub_point
    n = float(np.linalg.norm(u))
    if n == 0.0:
        return fallback
    speed = float(sign * np.cross(k, pair.hub_point) @ u) / n
    return speed if speed > 1e-6 * fallback else fallback


def free_turn(hub: PreparedPart, matrix: NDArray, sleeve: PreparedPart, flank: str,
              fallback: float, tol_angle: float, max_iter: int = 30) -> float:
    """How far the posed hub turns about its own axis toward ``flank`` before that flank
    side touches the sleeve (radians), by distance queries on the meshes.

    Steps by ``gap / closing speed`` (Newton on the first-order gap; exact for parallel
    involutes), bisecting between the last free turn and the first touching one when a
    step overshoots; stops when the remaining step is below ``tol_angle``.
    """
    sign = 1.0 if flank == "ccw" else -1.0
    lo, hi = 0.0, math.inf
    c = closest_pair(hub, matrix, sleeve, flank)
    if c.distance_mm == 0.0:
        return 0.0
    step = c.distance_mm / closing_speed(matrix, c, sign, fallback)
    for _ in range(max_iter):
        trial = lo + step if lo + step < hi else 0.5 * (lo + hi)
        m = matrix @ rot_z(sign * trial)
        c = closest_pair(hub, m, sleeve, flank)
        if c.distance_mm > 0.0:
            lo = trial
            step = c.distance_mm / closing_speed(m, c, sign, fallback)
            if step < tol_angle:
                return min(lo + step, hi)
        else:
            hi = trial
            if hi - lo < tol_angle:
                return lo
    return min(lo + step, hi)
