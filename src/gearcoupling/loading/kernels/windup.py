"""Renzo's linear load-sharing model solved exactly (piecewise linear in the wind-up).

Tooth ``k`` carries the torque ``K_k max(0, dpsi - g_k)`` (``K_k = C R²`` for Renzo's
mesh stiffness ``C``); the wind-up ``dpsi`` of each rotation solves
``sum_k K_k max(0, dpsi - g_k) = T``. Sorting the gaps makes the left side a known
piecewise-linear function, so the root is found exactly (no iteration).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentError, SpecError


def solve_windup(gap_rad: NDArray[np.float64],
                 stiffness_Nmm_per_rad: NDArray[np.float64] | float,
                 torque_Nmm: float, *, excess: bool = False):
    """Exact wind-up of each rotation for linear tooth stiffnesses.

    Parameters
    ----------
    gap_rad : (N, M) float
        Gap angle of every tooth at every rotation (``inf`` = never touches).
    stiffness_Nmm_per_rad : (N, M) or broadcastable float
        Torsional stiffness ``K_k`` of each tooth pair (N·mm/rad), > 0.
    torque_Nmm : float
        Torque magnitude ``T >= 0`` (N·mm).

    excess : bool
        Return ``(min_k g_k, dpsi - min_k g_k)`` instead: the excess keeps its full relative
        precision at tiny torques.

    Returns
    -------
    (M,) float
        ``dpsi`` with ``sum_k K_k max(0, dpsi - g_k) = T``; ``min_k g_k`` at ``T = 0``.
    """
    g = np.asarray(gap_rad, dtype=float)
    K = np.broadcast_to(np.asarray(stiffness_Nmm_per_rad, dtype=float), g.shape)
    if not np.all(np.isfinite(K) & (K > 0)):
        raise SpecError("load.mesh_stiffness_N_per_mm", float(np.min(K)),
                        "tooth stiffness must be positive and finite")
    if not (np.isfinite(torque_Nmm) and torque_Nmm >= 0):
        raise ArgumentError("torque_Nm", torque_Nmm / 1e3, "must be a finite torque")
    if not np.all(np.any(np.isfinite(g), axis=0)):
        raise ArgumentError("misalignment_deg", None, "no tooth can touch at some rotation")
    g_min = np.min(g, axis=0)
    if torque_Nmm == 0:
        return (g_min, np.zeros_like(g_min)) if excess else g_min
    order = np.argsort(g, axis=0)
    gs = np.take_along_axis(g, order, axis=0) - g_min  # exact 0 for the first: no cancellation
    Ks = np.where(np.isfinite(gs), np.take_along_axis(K, order, axis=0), 0.0)
    gs0 = np.where(np.isfinite(gs), gs, 0.0)
    cum_K = np.cumsum(Ks, axis=0)            # stiffness of the first n+1 teeth
    cum_Kg = np.cumsum(Ks * gs0, axis=0)
    # torque when dpsi reaches the gap of the next tooth (n+1 teeth active before it)
    with np.errstate(invalid="ignore"):
        t_next = np.where(np.isfinite(gs[1:]), gs[1:] * cum_K[:-1] - cum_Kg[:-1], np.inf)
    n = np.sum(t_next < torque_Nmm, axis=0)  # teeth beyond the first that are active
    cols = np.arange(g.shape[1])
    x = (torque_Nmm + cum_Kg[n, cols]) / cum_K[n, cols]
    return (g_min, x) if excess else g_min + x
