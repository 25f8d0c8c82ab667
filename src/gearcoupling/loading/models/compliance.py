"""The ``compliance`` model: bending (cantilever or FE table) + non-linear contact per pair.

Tooth ``k`` at a rotation closes by the normal approach ``d_k = r_b (dpsi - g_k)``; its
normal load ``W_k`` solves ``c_k W + delta_c,k(W) = d_k`` (``c_k`` the pair's bending +
foundation compliance at the load centre: the middle of the active profile at the contact's
face position, where a patch spread across the depth acts, as the ``surface`` model puts
its springs at the pressure centre; ``delta_c`` the contact approach of
:class:`~.contact.ContactModel`, concave and increasing), and the wind-up solves
``r_b sum_k W_k = T``. Both are monotone: the inner solve is Newton on a concave increasing
function (globally convergent, monotone after the first step), the outer Newton on the
convex increasing torque from the bracket's upper end ``min_k (g_k + d_k(T / r_b) / r_b)``
(one tooth carrying everything), so it decreases monotonically to the root. All rotations
are solved together.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentError, SpecError
from ...numeric import TINY, divide
from ...spec import CouplingSpec
from ..contact import contact_model, patch_centre_radius
from ..inputs import nominal_root_stress_MPa

INNER_ITER, OUTER_ITER = 60, 100


def _solve_load(d: NDArray, c: NDArray, law, W0: NDArray | None = None,
                tol: float = 1e-14) -> tuple[NDArray, NDArray]:
    """Normal loads ``W`` with ``c W + delta(W) = d`` (``d >= 0``) and ``dW/dd``; ``W0`` a
    start at or above the root (default ``d / c``: ``delta >= 0`` makes it one). A tooth
    that ``W0`` leaves unloaded starts from ``d / c`` too: at ``W = 0`` the contact law's
    slope is infinite and Newton would not leave it."""
    W = d / c if W0 is None else np.where(W0 > 0, np.minimum(W0, d / c), d / c)
    for _ in range(INNER_ITER):
        delta, s = law(W)
        step = (c * W + delta - d) / (c + s)
        W = np.maximum(W - step, 0.05 * W)  # an overshoot below 0 becomes a damped step
        if np.all(np.abs(step) <= tol * np.maximum(W, TINY)):
            break
    _, s = law(W)
    return W, np.where(d > 0, 1.0 / (c + s), 0.0)


def pair_laws(spec: CouplingSpec, z_mm, r_mm, compliance):
    """Normal bending compliance ``c`` (mm/N) and contact law ``law(W) -> (delta, slope)`` of
    every contact, with the contact model and its geometry."""
    cphi = math.cos(spec.tooth.pressure_angle)
    cm = contact_model(spec)
    r_load = patch_centre_radius(*cm.depth_limits(z_mm))
    c = compliance.pair_compliance_mm_per_N(z_mm, r_load) * cphi**2  # normal mm/N
    if not np.all(np.isfinite(c) & (c > 0)):
        raise SpecError("load.stiffness", float(np.min(c)), "tooth compliance must be "
                        "positive and finite")
    geo = cm.geometry(z_mm, r_mm)
    constants = cm.laws(geo)

    def law(W):
        return cm.approach_mm(W, constants)

    return c, law, cm, geo


def first_limit_torque_Nmm(spec: CouplingSpec, gap_rad: NDArray, z_mm: NDArray, r_mm: NDArray,
                           W_lim: NDArray, compliance) -> float:
    """Smallest torque (N·mm) over all rotations at which a tooth reaches its normal load
    ``W_lim``, without iteration on the torque: each tooth's load depends on the wind-up
    alone, so tooth k reaches its limit at ``dpsi_k = g_k + (c W_lim + delta(W_lim)) / r_b``;
    the first (smallest) one per rotation fixes the wind-up, one load solve gives the torque.
    """
    r_b = spec.tooth.base_radius
    c, law, _, _ = pair_laws(spec, z_mm, r_mm, compliance)
    g = np.asarray(gap_rad, dtype=float)
    touch = np.isfinite(g) & np.isfinite(W_lim)
    Wl = np.where(touch, W_lim, 0.0)
    dpsi = np.where(touch, g + (c * Wl + law(Wl)[0]) / r_b, np.inf)
    first = np.min(dpsi, axis=0)  # (M,)
    ok = np.isfinite(first)
    if not np.any(ok):
        return math.inf
    at = np.where(ok, first, -np.inf)  # rotations where no tooth has a limit carry nothing
    with np.errstate(invalid="ignore"):
        d = np.where(np.isfinite(g), r_b * np.maximum(at[None, :] - g, 0.0), 0.0)
    W, _ = _solve_load(d, c, law)
    T = r_b * np.sum(W, axis=0)
    return float(np.min(T[ok]))


def solve_compliance(spec: CouplingSpec,
                     gap_rad: NDArray, z_mm: NDArray, r_mm: NDArray, torque_Nmm: float,
                     compliance) -> dict[str, NDArray]:
    """Wind-up and tooth loads of every rotation; dict as :func:`.linear.solve_linear`.

    Parameters
    ----------
    gap_rad, z_mm, r_mm : (N, M) float
        Gap angles and first-touch points of the loaded flank.
    torque_Nmm : float
        Torque magnitude (N·mm), >= 0.
    compliance : object with ``pair_compliance_mm_per_N(z, r)``
    """
    t = spec.tooth
    R, r_b, cphi = t.pitch_radius, t.base_radius, math.cos(t.pressure_angle)
    g = np.asarray(gap_rad, dtype=float)
    touch = np.isfinite(g)
    if not np.all(np.any(touch, axis=0)):
        raise ArgumentError("misalignment_deg", None, "no tooth can touch at some rotation")
    c, law, cm, geo = pair_laws(spec, z_mm, r_mm, compliance)

    g_min = np.min(np.where(touch, g, np.inf), axis=0)
    gr = np.where(touch, g - g_min[None, :], np.inf)  # gaps above the first, exact at 0
    T = float(torque_Nmm)
    x = np.zeros(g_min.shape)  # wind-up beyond g_min
    W: NDArray | None  # None: _solve_load's own start
    W = dW = np.zeros(g.shape)
    if T > 0:
        # bracket top: each tooth alone carrying T; the smallest is an upper bound
        Wall = np.full(g.shape, T / r_b)
        x = np.min(np.where(touch, gr + (c * Wall + law(Wall)[0]) / r_b, np.inf), axis=0)
        W = None
        for _ in range(OUTER_ITER):
            d = np.where(touch, r_b * np.maximum(x[None, :] - gr, 0.0), 0.0)
            W, dW = _solve_load(d, c, law, W)
            resid = r_b * np.sum(W, axis=0) - T
            slope = r_b * r_b * np.sum(dW, axis=0)
            x = np.maximum(x - divide(resid, slope), 0.0)
            if np.all(np.abs(resid) <= 1e-12 * T):
                break
        d = np.where(touch, r_b * np.maximum(x[None, :] - gr, 0.0), 0.0)
        W, dW = _solve_load(d, c, law, W)
        resid = np.abs(r_b * np.sum(W, axis=0) - T)
        if not np.all(resid <= 1e-9 * T):
            raise ArgumentError("torque_Nm", T * 1e-3, f"load sharing did not converge (torque "
                            f"error {float(np.max(resid)) / T:.2e} relative)")
    closure = np.where(touch, np.maximum(x[None, :] - gr, 0.0), 0.0)
    out = {"windup_rad": g_min + x, "deflection_mm": R * closure,
           "tangential_force_N": W * cphi, "normal_force_N": W,
           "mesh_stiffness_Nm_per_rad": r_b * r_b * np.sum(dW, axis=0) * 1e-3}
    out.update(cm.estimates(W, geo))
    out["root_stress_MPa"] = nominal_root_stress_MPa(spec, W, z_mm, r_mm)
    return out
