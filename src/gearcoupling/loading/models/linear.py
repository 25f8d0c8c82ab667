"""The ``linear`` model: Renzo's constant mesh stiffness ``C`` per tooth pair."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ...spec import CouplingSpec
from ..contact import contact_estimates
from ..kernels.windup import solve_windup
from ..springs import tooth_compliance


def mesh_stiffness_N_per_mm(spec: CouplingSpec) -> float:
    """Renzo's ``C``: ``[load] mesh_stiffness_N_per_mm``, else the tooth-pair stiffness of
    ``[load] stiffness`` at the pitch point in the midplane (the cantilever's, or the whole
    FE value with the local deformation under its load patch)."""
    if spec.load.mesh_stiffness_N_per_mm is not None:
        return spec.load.mesh_stiffness_N_per_mm
    return float(tooth_compliance(spec).mesh_stiffness_N_per_mm)


def solve_linear(spec: CouplingSpec, gap_rad: NDArray, z_mm: NDArray, r_mm: NDArray,
                 torque_Nmm: float) -> dict[str, NDArray]:
    """Tooth loads ``P_k = C R max(0, dpsi - g_k)`` with ``sum P_k R = T`` exactly.

    Returns a dict of ``(N, M)`` arrays named as in :class:`LoadResult` plus ``windup_rad``
    and ``mesh_stiffness_Nm_per_rad`` ``(M,)``; pressures from :mod:`.contact`.
    """
    R = spec.tooth.pitch_radius
    C = mesh_stiffness_N_per_mm(spec)
    K = C * R * R
    g_min, x = solve_windup(gap_rad, K, torque_Nmm, excess=True)
    windup = g_min + x
    # closure from the gaps above the first (exact differences, no cancellation at tiny T)
    closure = np.maximum(x[None, :] - (gap_rad - g_min[None, :]), 0.0)
    P = C * R * closure
    Fn = P / math.cos(spec.tooth.pressure_angle)
    active = closure > 0
    out = {"windup_rad": windup, "deflection_mm": R * closure, "tangential_force_N": P,
           "normal_force_N": Fn,
           "mesh_stiffness_Nm_per_rad": K * 1e-3 * np.maximum(np.sum(active, axis=0), 1)}
    out.update(contact_estimates(spec, Fn, z_mm, r_mm))
    return out


def linear_capacity_Nmm(spec: CouplingSpec, g: NDArray, W_lim: NDArray) -> float:
    """Closed form: smallest torque (N·mm) at which a tooth of the linear model reaches
    ``W_lim`` (normal load)."""
    R = spec.tooth.pitch_radius
    C = mesh_stiffness_N_per_mm(spec)
    P_lim = W_lim * math.cos(spec.tooth.pressure_angle)
    touch = np.isfinite(g)
    with np.errstate(invalid="ignore"):
        dpsi = np.where(touch & np.isfinite(P_lim), g + P_lim / (C * R), np.inf)  # (N, M)
    # T(dpsi) increases, so at each rotation the first tooth to reach its limit is the one
    # with the smallest dpsi_k; the torque there is sum_j C R² (dpsi - g_j)+
    first = np.min(dpsi, axis=0)  # (M,)
    closure = np.where(touch, np.maximum(first[None, :] - np.where(touch, g, 0.0), 0.0), 0.0)
    with np.errstate(invalid="ignore"):
        T = np.where(np.isfinite(first), C * R * R * np.sum(closure, axis=0), np.inf)
    return float(np.min(T))
