"""Capacity: the torque at which a limit is first reached anywhere over the turn, times K.

Criteria (each skipped when its limit is not set): ``tooth_load`` (Renzo's allowable
tangential tooth load ``P_i``), ``contact_stress`` (interior contact pressure against the
smaller allowable of hub and sleeve), ``bending_stress`` (root bending stress, likewise);
``face_end`` is reported beside them: the torque at which a contact patch first reaches a
face end (not a capacity limit by itself).

Every tooth load grows monotonically with torque, so each criterion is a per-tooth limit
load ``W_lim`` (from the contact and root-stress laws, independent of the torque) and the
capacity the smallest torque at which ``max_k W_k / W_lim,k = 1``: closed form for the
linear model (tooth ``k`` reaches its limit at ``dpsi_k = g_k + P_lim,k / (C R)``, where the
torque is ``sum_j K (dpsi_k - g_j)+``), a bracketed root find (Brent on log torque) for the
compliance model, and the same root find on full solves for the surface model.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SpecError
from .api import contact_points, loaded_gaps, resolve_model, tooth_compliance
from .compliance import first_limit_torque_Nmm
from .contact import contact_model

CRITERIA = ("tooth_load", "contact_stress", "bending_stress")
RTOL = 1e-7  # relative accuracy of a root-found torque (the closed forms are exact)


def limit_loads(spec, z: NDArray, r: NDArray, compliance) -> dict[str, NDArray]:
    """Normal tooth loads (N) at which each criterion is reached at each contact point, and
    ``face_end``: the load at which the patch reaches the face end. ``inf`` = never."""
    cosphi = math.cos(spec.tooth.pressure_angle)
    cm = contact_model(spec)
    geo = cm.geometry(z, r)
    mat = spec.material
    out: dict[str, NDArray] = {}
    if spec.load.allowable_tooth_load_N is not None:
        out["tooth_load"] = np.full(z.shape, spec.load.allowable_tooth_load_N / cosphi)
    p_allow = min(mat.hub.allowable_contact_stress_MPa, mat.sleeve.allowable_contact_stress_MPa)
    out["contact_stress"] = cm.pressure_limit_load(p_allow, geo)
    s_allow = min(mat.hub.allowable_bending_stress_MPa, mat.sleeve.allowable_bending_stress_MPa)
    if hasattr(compliance, "root_stress_MPa"):
        per_N = compliance.root_stress_MPa(np.ones(z.shape), z, r)
        out["bending_stress"] = s_allow / per_N
    room = np.maximum(cm.half_face - np.abs(geo["z"]), 0.0)
    out["face_end"] = np.where(room > 0, cm.half_length_limit_load(room, geo), 0.0)
    return out


def _linear_capacity(spec, g: NDArray, W_lim: NDArray) -> float:
    """Closed form: smallest torque (N·mm) at which a tooth of the linear model reaches
    ``W_lim`` (normal load)."""
    from .linear_model import mesh_stiffness_N_per_mm

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


def _root_torque(ratio, T0: float, *, step: float = 8.0, rtol: float = RTOL) -> float:
    """Smallest torque (N·mm) with ``ratio(T) = 1`` for increasing ``ratio``, bracketed from
    ``T0`` by factors ``step``; inf if none."""
    from scipy.optimize import brentq

    lo, hi = T0, T0
    r_hi = ratio(hi)
    while r_hi < 1.0:
        lo, hi = hi, hi * step
        if hi > 1e18:
            return math.inf
        r_hi = ratio(hi)
    r_lo = ratio(lo)
    while r_lo >= 1.0:
        hi, lo = lo, lo / step
        if lo < 1e-12:
            return 0.0
        r_lo = ratio(lo)
    f = lambda x: math.log(max(ratio(math.exp(x)), 1e-300))  # noqa: E731
    # on log T an absolute tolerance is a relative one on T (brentq's rtol would scale by ln T)
    return math.exp(brentq(f, math.log(lo), math.log(hi), xtol=rtol, rtol=1e-15))


def capacity_from_sweep(spec, sweep_result, *, model: str | None = None,
                        gap_offset_rad: ArrayLike | None = None,
                        sign: int = 1) -> dict[str, Any]:
    """:func:`capacity` on an existing sweep (``sign`` picks the flank: +1 ccw, -1 cw)."""
    m = resolve_model(spec, model)
    flank = 1 if sign >= 0 else 0
    g = loaded_gaps(sweep_result, flank, gap_offset_rad)
    z, r = contact_points(spec, sweep_result, flank)
    comp = tooth_compliance(spec)
    limits = limit_loads(spec, z, r, comp)
    torques: dict[str, float] = {}
    memo: dict[float, Any] = {}  # surface solves shared by the criteria
    for name, W_lim in limits.items():
        if m == "linear":
            T = _linear_capacity(spec, g, W_lim)
        elif m == "compliance":
            T = first_limit_torque_Nmm(spec, g, z, r, W_lim, comp)
        else:
            guess = first_limit_torque_Nmm(spec, g, z, r, W_lim, comp)
            T = _surface_capacity(spec, sweep_result, name, sign, gap_offset_rad, guess, memo)
        torques[name] = T * 1e-3
    return _summarise(spec, sweep_result, m, torques, gap_offset_rad, sign)


SURFACE_RTOL = 1e-3  # relative accuracy of a surface-model capacity (full solves: costly)


def _surface_capacity(spec, sw, name: str, sign: int, gap_offset_rad, guess_Nmm: float,
                      memo: dict) -> float:
    """Root find on full surface-model solves for criterion ``name``, bracketed from the
    compliance model's torque ``guess_Nmm`` (factors of 1.5) to ``SURFACE_RTOL``."""
    from .api import load_from_sweep

    mat = spec.material
    limit = {"tooth_load": spec.load.allowable_tooth_load_N,
             "contact_stress": min(mat.hub.allowable_contact_stress_MPa,
                                   mat.sleeve.allowable_contact_stress_MPa),
             "bending_stress": min(mat.hub.allowable_bending_stress_MPa,
                                   mat.sleeve.allowable_bending_stress_MPa)}

    def ratio(T):
        if T not in memo:
            memo[T] = load_from_sweep(spec, sw, torque_Nm=sign * T * 1e-3, model="surface",
                                      gap_offset_rad=gap_offset_rad)
        res = memo[T]
        if name == "face_end":
            return 2.0 if np.any(res.edge_contact) else 0.5
        field = {"tooth_load": res.tangential_force_N,
                 "contact_stress": res.interior_pressure_MPa,
                 "bending_stress": res.root_stress_MPa}[name]
        return float(np.max(field)) / limit[name]

    start = guess_Nmm if math.isfinite(guess_Nmm) and guess_Nmm > 0 else \
        1e3 * spec.tooth.pitch_radius
    return _root_torque(ratio, start, step=1.5, rtol=SURFACE_RTOL)


def _summarise(spec, sw, model, torques, gap_offset_rad, sign) -> dict[str, Any]:
    K = spec.load.accuracy_factor
    crit = {k: v for k, v in torques.items() if k in CRITERIA}
    gov = min(crit, key=lambda k: crit[k])
    T_gov = crit[gov]
    out: dict[str, Any] = {
        "misalignment_deg": float(sw.misalignment_deg), "model": model,
        "accuracy_factor": K,
        "capacity_Nm": K * T_gov if math.isfinite(T_gov) else None,
        "governing": gov,
        "criteria_Nm": {k: (K * v if math.isfinite(v) else None) for k, v in crit.items()},
        "face_end_torque_Nm": torques["face_end"] if math.isfinite(torques["face_end"])
        else None,
        "aligned_capacity_Nm": None,
    }
    R, N = spec.tooth.pitch_radius, spec.tooth.teeth
    if spec.load.allowable_tooth_load_N is not None:
        out["aligned_capacity_Nm"] = K * N * spec.load.allowable_tooth_load_N * R * 1e-3
    # q at the governing torque (Renzo: T = q N P_max R)
    if math.isfinite(T_gov) and T_gov > 0:
        from .api import load_from_sweep

        res = load_from_sweep(spec, sw, torque_Nm=sign * T_gov, model=model,
                              gap_offset_rad=gap_offset_rad)
        out["q"] = res.q()
        out["load_sharing_factor"] = 1.0 / out["q"]
        out["max_tooth_load_N"] = float(np.max(res.tangential_force_N))
    else:
        out["q"] = out["load_sharing_factor"] = out["max_tooth_load_N"] = None
    return out


def default_angles(spec, gap_offset_rad, n: int = 25) -> NDArray:
    """Rotations covering every pose: one tooth pitch for ideal teeth (the pattern repeats
    every pitch), a full turn when per-tooth offsets break the periodicity."""
    span = 360.0 if gap_offset_rad is not None else 360.0 / spec.tooth.teeth
    return np.linspace(0.0, span, n, endpoint=False)


def capacity(spec, misalignment_deg: float, *, model: str | None = None,
             gap_offset_rad: ArrayLike | None = None, angles: ArrayLike | None = None,
             sign: int = 1, **accuracy: Any) -> dict[str, Any]:
    """Torque capacity at a misalignment, per criterion, with the governing one and q.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
    model : {"linear", "compliance", "surface"}, optional
    gap_offset_rad : (N,) or (2, N) float, optional
    angles : (M,) float, optional
        Rotations (degrees) searched for the worst pose; default 25 over one tooth pitch
        (a full turn with ``gap_offset_rad``).
    sign : {1, -1}
        Torque direction (+1 loads the ccw flanks).
    **accuracy
        Passed to the sweep (``tolerance_mm``, ``grid``).

    Returns
    -------
    dict
        ``capacity_Nm`` (governing, times K), ``governing``, ``criteria_Nm`` (each times K),
        ``face_end_torque_Nm`` (not times K), ``q`` and ``load_sharing_factor`` at the
        governing torque, ``aligned_capacity_Nm`` (``K N P_i R``).
    """
    from ..sweep import sweep

    if sign not in (1, -1):
        raise SpecError("sign", sign, "must be 1 (ccw flanks) or -1 (cw flanks)")
    a = default_angles(spec, gap_offset_rad) if angles is None else angles
    sw = sweep(spec, misalignment_deg, a, **accuracy)
    return capacity_from_sweep(spec, sw, model=model, gap_offset_rad=gap_offset_rad, sign=sign)


def capacity_curve(spec, misalignments_deg: ArrayLike | None = None, *,
                   model: str | None = None, gap_offset_rad: ArrayLike | None = None,
                   angles: ArrayLike | None = None, progress=None,
                   **accuracy: Any) -> list[dict[str, Any]]:
    """:func:`capacity` at each misalignment (default 25 from 0 to the design angle, at
    least 0.5°); ``progress(i, n)`` is called after each."""
    if misalignments_deg is None:
        top = max(math.degrees(spec.design_misalignment), 0.5)
        misalignments_deg = np.linspace(0.0, top, 25)
    mis = np.atleast_1d(np.asarray(misalignments_deg, dtype=float))
    out = []
    for i, m in enumerate(mis):
        out.append(capacity(spec, float(m), model=model, gap_offset_rad=gap_offset_rad,
                            angles=angles, **accuracy))
        if progress is not None:
            progress(i + 1, mis.size)
    return out


CAPACITY_COLUMNS = ("spec", "misalignment_deg", "capacity_Nm", "governing", "tooth_load_Nm",
                    "contact_stress_Nm", "bending_stress_Nm", "face_end_torque_Nm", "q",
                    "load_sharing_factor", "max_tooth_load_N")


def capacity_rows(name: str, curve: list[dict]):
    """CSV rows of one capacity curve in :data:`CAPACITY_COLUMNS` order."""
    for c in curve:
        crit = c["criteria_Nm"]
        yield (name, c["misalignment_deg"], c["capacity_Nm"], c["governing"],
               crit.get("tooth_load"), crit.get("contact_stress"), crit.get("bending_stress"),
               c["face_end_torque_Nm"], c["q"], c["load_sharing_factor"], c["max_tooth_load_N"])


def write_capacity_csv(curves: dict[str, list[dict]], path) -> Path:
    """``capacity.csv``: one row per spec name and misalignment of :func:`capacity_curve`
    results, written atomically."""
    from ..atomic import write_csv_rows

    return write_csv_rows(path, CAPACITY_COLUMNS, (row for name, curve in curves.items()
                                                   for row in capacity_rows(name, curve)))
