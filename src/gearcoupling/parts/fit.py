"""Least-squares cubic B-splines with the fewest control points that keep the measured
deviation within a tolerance, shared by all the sections of a loft (one knot vector, so
the loft needs no knot insertion). Pure numpy/scipy; OpenCASCADE is not needed here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import GeometryError

DEGREE = 3


@dataclass(frozen=True)
class SectionFit:
    """Poles ``(s, K, d)`` of ``s`` sections on one clamped knot vector.

    ``knots`` are the distinct knots in ``[0, 1]`` and ``mults`` their multiplicities (the
    OpenCASCADE form); ``deviation`` is the largest distance from a data point to its fitted
    point (an upper bound of the distance from the data to the curve).
    """

    poles: NDArray[np.float64]
    knots: NDArray[np.float64]
    mults: NDArray[np.int64]
    deviation: float


def shared_chord_parameters(points: NDArray) -> NDArray[np.float64]:
    """Chord-length parameters in ``[0, 1]`` of ``points (s, m, d)`` averaged over sections."""
    chord = np.linalg.norm(np.diff(points, axis=1), axis=-1)
    cum = np.concatenate([np.zeros((len(points), 1)), np.cumsum(chord, axis=1)], axis=1)
    return np.mean(cum / cum[:, -1:], axis=0)


def _knot_vector(n_poles: int) -> NDArray[np.float64]:
    inner = np.linspace(0.0, 1.0, n_poles - DEGREE + 1)[1:-1]
    return np.concatenate([np.zeros(DEGREE + 1), inner, np.ones(DEGREE + 1)])


def _lsq(points: NDArray, u: NDArray, n_poles: int) -> tuple[NDArray, NDArray, float]:
    """Clamped cubic LSQ fit through both end points of every section."""
    from scipy.interpolate import BSpline

    t = _knot_vector(n_poles)
    basis = BSpline.design_matrix(u, t, DEGREE).toarray()  # (m, K)
    first, last = points[:, :1], points[:, -1:]
    rhs = points - basis[None, :, :1] * first - basis[None, :, -1:] * last  # (s, m, d)
    inner = basis[:, 1:-1]
    s, m, d = points.shape
    sol, *_ = np.linalg.lstsq(inner, rhs.transpose(1, 0, 2).reshape(m, s * d), rcond=None)
    poles = np.concatenate([first, sol.reshape(-1, s, d).transpose(1, 0, 2), last], axis=1)
    fitted = np.einsum("mk,skd->smd", basis, poles)
    return poles, t, float(np.linalg.norm(fitted - points, axis=-1).max())


def fit_sections(points: NDArray, tol: float) -> SectionFit:
    """Fewest-pole clamped cubic B-splines (one knot vector) through the end points of
    ``points (s, m, d)`` whose LSQ fit deviates by at most ``tol`` at every point; with
    ``m`` points at most ``m`` poles (then the fit interpolates them)."""
    points = np.asarray(points, dtype=float)
    m = points.shape[1]
    u = shared_chord_parameters(points)
    if m < DEGREE + 1:
        raise GeometryError(f"a cubic fit needs at least {DEGREE + 1} points per section")
    for n_poles in range(DEGREE + 1, m + 1):
        poles, t, dev = _lsq(points, u, n_poles)
        if dev <= tol:
            break
    knots, mults = np.unique(t, return_counts=True)
    return SectionFit(poles, knots, mults, dev)
