"""The distance engine: closest point pair, collision test and penetration depth.

Choice by measurement (``python benchmarks/bench_interference.py --engines``): renzo-1967
at 1°, tolerance 0.0127 mm, the pose of its smallest clearance, 2 cores; all engines find
the same distance to 1e-6 mm:

============  =========  ===============  =================  =============  ==========
model         triangles  fcl distance     libigl both ways   manifold3d     fcl collide
                         (+ setup once)   (vertex-triangle)  ``min_gap``
============  =========  ===============  =================  =============  ==========
tooth pair    968        0.7 ms (+2)      0.8 ms             1.2 ms         0.3 ms
±1 sector     2840       2.2 ms (+5)      2.5 ms             3.3 ms         0.8 ms
full parts    46800      37 ms (+96)      50 ms              60 ms          16 ms
============  =========  ===============  =================  =============  ==========

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

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import BackendError
from .posed import PreparedPart


def _igl():
    try:
        import igl
    except ImportError as err:
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


def closest_pair(hub: PreparedPart, matrix: NDArray, sleeve: PreparedPart) -> Closest:
    """Minimum distance between the hub shell posed by ``matrix`` and the sleeve shell.

    Exact on the meshes (python-fcl, triangle-triangle). Zero when they intersect.
    """
    import fcl

    req = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=False)
    res = fcl.DistanceResult()
    d = fcl.distance(hub.fcl_object(matrix), sleeve.fcl_object(), req, res)
    p, q = (np.asarray(x, dtype=float) for x in res.nearest_points)
    return Closest(max(float(d), 0.0), p, q, hub.shell_face(res.b1), sleeve.shell_face(res.b2))


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
