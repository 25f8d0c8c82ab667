"""Where the hub loft puts its sections: the planes of the tolerance grid spaced as widely
as keeps the cubic interpolation in ``z`` within ``Z_SHARE`` of the tolerance, split where
the feed-path curvature jumps. Pure numpy/scipy; the solids are :mod:`.solid`'s.
"""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
from numpy.typing import NDArray

from ..numeric import TINY
from ..spec import CouplingSpec

Z_SHARE = 0.45
"""Share of the tolerance the cubic interpolation between loft sections may deviate."""



def sampling_tolerance(spec: CouplingSpec, tol: float) -> float:
    """Chord tolerance of the hub grid whose planes are the candidate loft sections.

    A cubic through sections is far closer to the crowned surface than chords between the
    same planes, so the grid is sized for ``min(10 tol, module / 20)``;
    :func:`loft_sections` then measures which spacing keeps the tolerance.
    """
    return max(tol, min(10.0 * tol, spec.tooth.module / 20.0))


def curvature_breaks(m) -> NDArray[np.float64]:
    """Axial positions ``z > 0`` inside the face where the feed-path curvature jumps."""
    out = []
    for sb in m.path.breaks[1:-1]:
        if not np.isfinite(sb):
            continue
        eps = 1e-6 * max(sb, 1.0)
        k = m.path.evaluate(sb + np.array([-eps, eps, -1e-3 * eps, 1e-3 * eps]))[0]
        wide, narrow = abs(k[1] - k[0]), abs(k[3] - k[2])
        jump = wide > 1e-9 * max(abs(k).max(), 1e-12) and narrow > 0.5 * wide  # not a slope
        z = float(m.path.evaluate(sb)[3])
        if jump and 0 < z < m.half_face * (1 - 1e-6):
            out.append(z)
    return np.array(sorted(out))


def _pieces(z_all: NDArray, edges: NDArray, half_face: float) -> list[NDArray]:
    """Section planes of each loft piece between consecutive ``edges`` (cut planes)."""
    rows = []
    for z0, z1 in pairwise(edges):
        inside = z_all[(z_all > z0 + 1e-9 * half_face) & (z_all < z1 - 1e-9 * half_face)]
        z_rows = np.concatenate([[z0], inside, [z1]])
        rows.append(np.linspace(z0, z1, 3) if len(z_rows) == 2 else z_rows)
    return rows


def _every(z: NDArray, stride: int) -> NDArray:
    """Every ``stride``-th plane of ``z`` spread evenly, at least 4 (a cubic), with both ends."""
    count = max(4, math.ceil((len(z) - 1) / stride) + 1)
    if len(z) <= count:
        return z
    return z[np.round(np.linspace(0, len(z) - 1, count)).astype(int)]


def _polyline_distance(points: NDArray, line: NDArray) -> NDArray:
    """Distance ``(k,)`` from 2-D ``points (k, 2)`` to the polyline ``line (q, 2)``."""
    a, d = line[:-1], np.diff(line, axis=0)
    rel = points[:, None, :] - a[None]
    dd = np.maximum(np.einsum("qi,qi->q", d, d), TINY)
    t = np.clip(np.einsum("kqi,qi->kq", rel, d) / dd, 0.0, 1.0)
    gap = rel - t[..., None] * d[None]
    return np.sqrt(np.einsum("kqi,kqi->kq", gap, gap).min(axis=1))


def interpolation_deviation(rows: list[NDArray], dense, refine: int = 8) -> float:
    """Largest distance (mm) from the cubic interpolation in ``z`` (through the planes
    ``rows`` of each piece) of the exact profile points of ``dense`` (a hub layout) to the
    exact profile on its grid planes: what the loft adds to the profile fit (the fit is
    linear in the points and the loft interpolates the poles across the sections). The
    exact profile is the dense points refined ``refine`` times by a cubic through them."""
    from scipy.interpolate import make_interp_spline

    worst = 0.0
    for z_rows in rows:
        z = dense.grid.z[(dense.grid.z >= z_rows[0]) & (dense.grid.z <= z_rows[-1])]
        if z.size == 0:
            continue
        across = make_interp_spline(z_rows, dense.grid.points(z_rows), k=min(3, len(z_rows) - 1))
        exact = dense.grid.points(z)  # (nz, m, 2)
        m = exact.shape[1]
        fine = np.linspace(0, m - 1, refine * (m - 1) + 1)
        lines = make_interp_spline(np.arange(m), exact, k=3, axis=1)(fine)
        for guess, line in zip(across(z), lines, strict=True):  # per plane: bounded memory
            worst = max(worst, float(_polyline_distance(guess, line).max()))
    return worst


def loft_sections(z_grid: NDArray, edges: NDArray, dense, tol: float) -> list[NDArray]:
    """Section planes per loft piece: the widest spacing (every 3rd, 2nd or every plane of
    the sampling grid ``z_grid``) whose cubic interpolation in ``z`` keeps the exact profile
    points within ``tol`` (:func:`interpolation_deviation`)."""
    half = float(edges[-1])
    for stride in (3, 2):
        rows = _pieces(_every(z_grid, stride), edges, half)
        if interpolation_deviation(rows, dense) <= tol:
            return rows
    return _pieces(z_grid, edges, half)
