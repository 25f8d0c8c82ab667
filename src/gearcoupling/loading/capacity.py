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
torque is ``sum_j K (dpsi_k - g_j)+``), the compliance model's own root (one load solve at
the first tooth's limit), and for the surface model a root per rotation from a few
single-pose solves (:func:`_surface_capacity`: secant steps on log ratio against log torque
from the compliance model's root, each solve warm-started from its nearest solved pose).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from ..arguments import GAP_TOLERANCE_MM, MAXIMA, SWEEP_GRID, angle_list, choice
from ..clearance import SweepResult, sweep
from ..errors import ArgumentError, GearCouplingError
from ..geometry import FLANKS
from ..io import write_csv_rows
from ..loadspec import LOAD_MODELS
from ..numeric import TINY
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec
from ..tables import dataframe
from .api import load_from_sweep
from .compliance import first_limit_torque_Nmm
from .contact import contact_model
from .inputs import LoadProblem, load_problem, nominal_root_stress_MPa, resolve_model
from .linear_model import mesh_stiffness_N_per_mm
from .surface import DEFAULT_GRID, BendingSprings, SurfaceSolver, flank_offsets

CRITERIA = ("tooth_load", "contact_stress", "bending_stress")
RTOL = 1e-7  # relative accuracy of a root-found torque (the closed forms are exact)


def limit_loads(spec: CouplingSpec, z: NDArray, r: NDArray, compliance) -> dict[str, NDArray]:
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
    per_N = nominal_root_stress_MPa(spec, np.ones(z.shape), z, r)
    out["bending_stress"] = s_allow / per_N
    room = np.maximum(cm.half_face - np.abs(geo["z"]), 0.0)
    out["face_end"] = np.where(room > 0, cm.half_length_limit_load(room, geo), 0.0)
    return out


def _linear_capacity(spec: CouplingSpec, g: NDArray, W_lim: NDArray) -> float:
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


def _root_torque(ratio, T0: float, *, step: float = 8.0, rtol: float = RTOL) -> float:
    """Smallest torque (N·mm) with ``ratio(T) = 1`` for increasing ``ratio``, bracketed from
    ``T0`` by factors ``step``; inf if none."""
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
    f = lambda x: math.log(max(ratio(math.exp(x)), TINY))  # noqa: E731
    # on log T an absolute tolerance is a relative one on T (brentq's rtol would scale by ln T)
    return math.exp(brentq(f, math.log(lo), math.log(hi), xtol=rtol, rtol=1e-15))


@dataclass(frozen=True, eq=False)
class Capacity:
    """Torque capacity at one misalignment, per criterion (torques in N·m, magnitudes).

    ``capacity_Nm`` is the governing criterion's torque times the accuracy factor K
    (``None``: no limit is reached); ``criteria_Nm`` each criterion's (times K);
    ``face_end_torque_Nm`` the torque at which a patch reaches a face end (not times K);
    ``q``, ``load_sharing_factor`` and ``max_tooth_load_N`` at the governing torque;
    ``aligned_capacity_Nm`` Renzo's ``K N P_i R``; ``solves`` the model solves used: one
    per load solve of all rotations (linear, compliance), one per single pose (surface: its
    search, and each rotation of the solve for q).
    """

    spec: Any = field(repr=False)
    misalignment_deg: float
    model: str
    loaded_flank: str
    accuracy_factor: float
    capacity_Nm: float | None
    governing: str
    criteria_Nm: dict[str, float | None]
    face_end_torque_Nm: float | None
    aligned_capacity_Nm: float | None
    q: float | None
    load_sharing_factor: float | None
    max_tooth_load_N: float | None
    solves: int = 0

    def as_dict(self) -> dict[str, Any]:
        """Plain data (JSON) with the field names as keys, the spec by name."""
        names = [f for f in self.__dataclass_fields__ if f != "spec"]
        return {"spec": self.spec.name, **{k: getattr(self, k) for k in names}}

    def to_dataframe(self):
        """This result as a one-row pandas DataFrame with the columns of ``capacity.csv``
        (:data:`CAPACITY_COLUMNS`; the ``pandas`` extra)."""
        return dataframe(CAPACITY_COLUMNS, [self.row()])

    def row(self) -> tuple:
        """This result as a row of :data:`CAPACITY_COLUMNS`."""
        crit = self.criteria_Nm
        return (self.spec.name, self.misalignment_deg, self.capacity_Nm, self.governing,
                crit.get("tooth_load"), crit.get("contact_stress"), crit.get("bending_stress"),
                self.face_end_torque_Nm, self.q, self.load_sharing_factor, self.max_tooth_load_N)


class CapacityCurve(list):
    """The :class:`Capacity` results of :func:`capacity_curve`, one per misalignment (a
    list, with :meth:`to_dataframe`)."""

    def to_dataframe(self):
        """One row per misalignment, the columns of ``capacity.csv`` (the ``pandas``
        extra)."""
        return dataframe(CAPACITY_COLUMNS, [c.row() for c in self])


def _flank_problem(sweep_result: SweepResult, loaded_flank: str,
                   gap_offset_rad: ArrayLike | None,
                   pressure_grid: tuple[int, int] | None = None) -> LoadProblem:
    """The load problem of ``loaded_flank`` (a unit torque of that sign picks the flank)."""
    if loaded_flank not in FLANKS:
        raise ArgumentError("loaded_flank", loaded_flank, "'ccw' (positive torque) or 'cw' "
                            "(negative torque)")
    return load_problem(sweep_result, 1.0 if loaded_flank == "ccw" else -1.0, gap_offset_rad,
                        pressure_grid)


def capacity_from_sweep(sweep_result: SweepResult, *, model: str | None = None,
                        gap_offset_rad: ArrayLike | None = None,
                        loaded_flank: str = "ccw",
                        pressure_grid: tuple[int, int] | None = None) -> Capacity:
    """:func:`capacity` on an existing sweep (its spec gives the limits)."""
    problem = _flank_problem(sweep_result, loaded_flank, gap_offset_rad, pressure_grid)
    spec, g, z, r, comp = (problem.spec, problem.gap_rad, problem.z_mm, problem.r_mm,
                           problem.compliance)
    m = resolve_model(spec, model)
    limits = limit_loads(spec, z, r, comp)
    torques: dict[str, float] = {}
    if m == "surface":
        torques, search = _surface_torques(problem, limits)
        return _summarise(problem, m, torques, search)
    for name, W_lim in limits.items():
        if m == "linear":
            T = _linear_capacity(spec, g, W_lim)
        else:
            T = first_limit_torque_Nmm(spec, g, z, r, W_lim, comp)
        torques[name] = T * 1e-3
    return _summarise(problem, m, torques)


def _surface_torques(problem: LoadProblem, limits: dict[str, NDArray]
                     ) -> tuple[dict[str, float], list[_SurfaceLimits]]:
    """Each criterion's torque (N·m) on the surface model and the searches (load grid
    first) that found them.

    Every criterion is first solved at the rotation where the compliance model reaches it
    first (its root there, :func:`_rotation_root`). In the order of those torques, a
    criterion within :data:`SCREEN_MARGIN` of the smallest so far is then screened on the
    other rotations (:func:`_surface_capacity`); one further above cannot govern and keeps
    its first root (which may stand up to the rotations' spread above its own smallest,
    a few per cent), as does the face end (reported, not a capacity; 0 without a search
    where the first touch lies on a face end). Loads, bending and the face end are solved
    on the load grid, the contact pressure on the pressure grid, started from the load
    grid's root (:data:`LOAD_GRID`, :data:`PRESSURE_GRID`; one grid for all where the
    problem names one)."""
    spec, g, z, r, comp = (problem.spec, problem.gap_rad, problem.z_mm, problem.r_mm,
                           problem.compliance)
    grids = (LOAD_GRID, PRESSURE_GRID) if problem.pressure_grid is None else \
        (problem.pressure_grid,) * 2
    load = _SurfaceLimits(problem, grids[0])
    pressure = _SurfaceLimits(problem, grids[1], coarser=load)
    guesses, first = {}, {}
    for name, W_lim in sorted(limits.items(), key=lambda kv: kv[0] != "bending_stress"):
        guesses[name] = np.array([first_limit_torque_Nmm(spec, g[:, j:j + 1], z[:, j:j + 1],
                                                         r[:, j:j + 1], W_lim[:, j:j + 1], comp)
                                  for j in range(g.shape[1])])
        if name == "face_end" and np.any(guesses[name] == 0.0):
            first[name] = (0, 0.0)  # the first touch lies on a face end: at any torque
            continue
        # roughly (INFO_RTOL) on the load grid first: the order of the criteria
        first[name] = _first_root(load, name, guesses[name], INFO_RTOL)
    torques: dict[str, float] = {}
    best = math.inf
    for name in sorted(first, key=lambda k: first[k][1]):
        j, T = first[name]
        search = pressure if name == "contact_stress" else load
        if name in CRITERIA and (T <= (1.0 + SCREEN_MARGIN) * best or search is pressure):
            # to SURFACE_RTOL on its own grid, from the rough root
            T = _rotation_root(search, name, j, T, SURFACE_RTOL if T <= (
                1.0 + SCREEN_MARGIN) * best else INFO_RTOL)
        if name in CRITERIA and T <= (1.0 + SCREEN_MARGIN) * best:
            T = _surface_capacity(search, name, guesses[name], j, T)
        if name in CRITERIA:
            best = min(best, T)
        torques[name] = T * 1e-3
    return torques, [load, pressure]


SURFACE_RTOL = 1e-3  # relative accuracy of a surface-model capacity torque
INFO_RTOL = 1e-2  # ... of a criterion more than SCREEN_MARGIN above the governing one
FACE_END_RTOL = 3e-2  # the face-end torque (reported, not a capacity) by bisection
LOAD_GRID = (24, 16)  # surface-model cells of the load and bending criteria (bench_surface.py)
PRESSURE_GRID = DEFAULT_GRID  # ... of the contact-pressure criterion
SCREEN_MARGIN = 0.15  # criteria within this of the smallest are screened over the rotations
SCREEN_RANGE = 0.25  # rotations screened: compliance-model root within this of the smallest
SLOPES = {"tooth_load": 1.0, "contact_stress": 0.5, "bending_stress": 1.0}  # d ln f / d ln T


class _SurfaceLimits:
    """The surface model's criterion ratios per rotation and torque (single poses: each
    solve warm-started from the nearest solved one, kept for the other criteria)."""

    def __init__(self, problem: LoadProblem, grid: tuple[int, int],
                 coarser: _SurfaceLimits | None = None):
        spec = problem.spec
        self.coarser = coarser  # a search on a coarser grid whose poses may start this one
        self.problem = problem
        self.spec = spec
        t = spec.tooth
        flank = problem.loaded_flank
        N = problem.gap_rad.shape[0]
        self.solver = SurfaceSolver(
            spec, problem.sweep, flank, BendingSprings(problem.compliance, t.base_radius,
                                                       t.pitch_radius),
            grid=grid, offsets=flank_offsets(problem.gap_offset_rad, FLANKS.index(flank), N))
        mat = spec.material
        self.limit = {
            "tooth_load": spec.load.allowable_tooth_load_N,
            "contact_stress": min(mat.hub.allowable_contact_stress_MPa,
                                  mat.sleeve.allowable_contact_stress_MPa),
            "bending_stress": min(mat.hub.allowable_bending_stress_MPa,
                                  mat.sleeve.allowable_bending_stress_MPa)}
        self.solved: dict[tuple[int, float], tuple[dict, Any]] = {}

    @property
    def solves(self) -> int:
        return len(self.solved)

    def _start(self, j: int, T: float):
        """The solved pose nearest to ``(j, T)``: the same rotation at the nearest torque,
        else the nearest rotation; with none solved, the coarser search's (None: cold)."""
        if not self.solved:
            return None if self.coarser is None else self.coarser._start(j, T)
        key = min(self.solved, key=lambda k: (abs(k[0] - j), abs(math.log(k[1] / T))))
        return self.solved[key][1]

    def out(self, j: int, T_Nmm: float) -> dict:
        key = (j, float(f"{T_Nmm:.12g}"))  # one pose for a torque that went through N·m
        if key not in self.solved:
            load_N = T_Nmm / self.spec.tooth.base_radius
            out, _, pose = self.solver.solve_pose(j, load_N, self._start(j, T_Nmm))
            self.solved[key] = (out, pose)
        return self.solved[key][0]

    def peak_load_N(self, T_Nmm: float, within: float = 0.1) -> float:
        """The largest tangential tooth load at torque ``T`` over the rotations: from each
        rotation's pose solved nearest ``T`` (within ``within``, relative), scaled to ``T``
        (the load grows about linearly with the torque there); the rotations without one
        are those the compliance model puts well below the worst, unless none has one:
        then the rotation of the pose solved nearest ``T`` is solved at ``T``."""
        near: dict[int, float] = {}
        for j, T in self.solved:
            if abs(math.log(T / T_Nmm)) <= math.log1p(within) and (
                    j not in near or abs(math.log(T / T_Nmm)) < abs(math.log(near[j] / T_Nmm))):
                near[j] = T
        if not near:
            j, _ = min(self.solved, key=lambda k: abs(math.log(k[1] / T_Nmm)))
            near[j] = T_Nmm
        return max(float(np.max(self.out(j, T)["tangential_force_N"])) * T_Nmm / T
                   for j, T in near.items())

    def ratio(self, name: str, j: int, T_Nmm: float) -> float:
        """``max over the teeth of criterion / limit`` at rotation ``j`` and torque ``T``
        (face end: 2 with a patch on a face end, else 0.5)."""
        out = self.out(j, T_Nmm)
        if name == "face_end":
            return 2.0 if np.any(out["edge_contact"]) else 0.5
        if name == "bending_stress":
            value = nominal_root_stress_MPa(self.problem.spec, out["normal_force_N"],
                                            out["contact_z_mm"], out["contact_r_mm"])
        else:
            value = out[{"tooth_load": "tangential_force_N",
                         "contact_stress": "interior_pressure_MPa"}[name]]
        return float(np.max(value)) / self.limit[name]


def _first_root(limits: _SurfaceLimits, name: str, guess_Nmm: NDArray,
                rtol: float = SURFACE_RTOL) -> tuple[int, float]:
    """The rotation where the compliance model reaches criterion ``name`` first (from its
    roots ``guess_Nmm (M,)``) and the surface model's root there (N·mm, to ``rtol``),
    started from the pose already solved nearest to it, where there is one (its ratio and
    the criterion's slope give the start), else from the compliance model's root."""
    fallback = 1e3 * limits.spec.tooth.pitch_radius
    start = np.where(np.isfinite(guess_Nmm) & (guess_Nmm > 0), guess_Nmm, fallback)
    j = int(np.argmin(start))
    T0 = float(start[j])
    if limits.solved and name in SLOPES:
        k, T = min(limits.solved, key=lambda key: (abs(key[0] - j), abs(math.log(key[1] / T0))))
        ratio = limits.ratio(name, k, T)
        if ratio > 0:
            T0 = T * ratio ** (-1.0 / SLOPES[name])
    return j, _rotation_root(limits, name, j, T0, rtol)


def _surface_capacity(limits: _SurfaceLimits, name: str, guess_Nmm: NDArray, first: int,
                      best: float) -> float:
    """Smallest torque (N·mm) at which criterion ``name`` reaches its limit on the surface
    model, to :data:`SURFACE_RTOL`, given its root ``best`` at rotation ``first``. Each
    tooth's load grows with the torque, so at each rotation the ratio ``criterion / limit``
    does; the capacity is the smallest of the rotations' roots. Every other rotation whose
    compliance-model root (``guess_Nmm (M,)``) lies within :data:`SCREEN_RANGE` of the
    smallest is screened at ``best`` (a ratio at or below 1: its root is no smaller); those
    above are searched in the order of their estimated roots (``T ratio^(-1/slope)``; face
    end: most teeth on a face end first), each first checked at the best torque so far."""
    if not math.isfinite(best) or best <= 0.0:  # never reached, or over it at no torque
        return best
    finite = np.isfinite(guess_Nmm) & (guess_Nmm > 0)
    low = np.min(guess_Nmm[finite]) if np.any(finite) else math.inf
    near = ~finite | (guess_Nmm <= (1.0 + SCREEN_RANGE) * low)
    estimate: dict[int, float] = {}
    for j in map(int, np.flatnonzero(near)):
        if j == first or limits.ratio(name, j, best) <= 1.0:
            continue
        if name == "face_end":
            estimate[j] = -float(np.sum(limits.out(j, best)["edge_contact"]))
        else:
            estimate[j] = best * limits.ratio(name, j, best) ** (-1.0 / SLOPES[name])
    for j in sorted(estimate, key=estimate.__getitem__):
        if limits.ratio(name, j, best) > 1.0:
            T0 = best if name == "face_end" else min(estimate[j], best)
            best = min(best, _rotation_root(limits, name, j, T0))
    return best


def _rotation_root(limits: _SurfaceLimits, name: str, j: int, T0: float,
                   rtol: float = SURFACE_RTOL) -> float:
    def ratio(T):
        return limits.ratio(name, j, T)

    if name == "face_end":
        return _bisect_root(ratio, T0, FACE_END_RTOL)
    return _secant_root(ratio, T0, SLOPES[name], rtol)


LOG_T_MAX = math.log(1e18)  # N·mm: a torque never reached
LOG_T_MIN = math.log(1e-12)


def _secant_root(ratio, T0: float, slope: float, rtol: float = SURFACE_RTOL) -> float:
    """``ratio(T) = 1`` for increasing ``ratio``: secant steps on ``ln ratio`` against
    ``ln T`` (nearly straight: the first step takes the slope ``slope``), kept inside the
    bracket once one is found (bisection where a step leaves it, doubling steps outward
    before); stops when the step is below ``rtol`` (relative)."""
    x0, f0 = math.log(T0), math.log(max(ratio(T0), TINY))
    lo, hi = (-math.inf, x0) if f0 >= 0 else (x0, math.inf)
    x1 = x0 - f0 / slope
    for _ in range(100):
        if x1 > LOG_T_MAX:
            return math.inf
        if x1 < LOG_T_MIN:  # over the limit at a vanishing torque (binding teeth)
            return 0.0
        f1 = math.log(max(ratio(math.exp(x1)), TINY))
        if f1 >= 0:
            hi = min(hi, x1)
        else:
            lo = max(lo, x1)
        step = -f1 * (x1 - x0) / (f1 - f0) if f1 != f0 else -f1 / slope
        if abs(step) <= rtol:
            return math.exp(x1 + step)
        if hi - lo <= rtol:
            return math.exp(0.5 * (lo + hi))
        x2 = x1 + step
        if not lo < x2 < hi:
            x2 = 0.5 * (lo + hi) if math.isfinite(lo + hi) else x1 + math.copysign(2.0, step)
        x0, f0, x1 = x1, f1, x2
    raise GearCouplingError(f"surface capacity: no root within {rtol:g} after 100 solves")


def _bisect_root(ratio, T0: float, rtol: float = SURFACE_RTOL) -> float:
    """The torque where the increasing step ``ratio`` passes 1, by bisection on ``ln T``
    from ``T0`` (bracketed by factors of 2) to ``rtol``."""
    lo = hi = math.log(T0)
    if ratio(T0) >= 1.0:
        while ratio(math.exp(lo)) >= 1.0:
            hi, lo = lo, lo - math.log(2.0)
            if lo < LOG_T_MIN:
                return 0.0
    else:
        while ratio(math.exp(hi)) < 1.0:
            lo, hi = hi, hi + math.log(2.0)
            if hi > LOG_T_MAX:
                return math.inf
    while hi - lo > rtol:
        mid = 0.5 * (lo + hi)
        if ratio(math.exp(mid)) >= 1.0:
            hi = mid
        else:
            lo = mid
    return math.exp(hi)


def _summarise(problem: LoadProblem, model: str, torques: dict[str, float],
               searches: list[_SurfaceLimits] | None = None) -> Capacity:
    """The :class:`Capacity` of the criteria's torques (N·m); q at the governing torque from
    a load solve of every rotation (the surface model: the first search's single poses)."""
    spec, sw = problem.spec, problem.sweep
    K = spec.load.accuracy_factor
    crit = {k: v for k, v in torques.items() if k in CRITERIA}
    gov = min(crit, key=lambda k: crit[k])
    T_gov = crit[gov]
    R, N = spec.tooth.pitch_radius, spec.tooth.teeth
    P_i = spec.load.allowable_tooth_load_N
    q = P_max = None
    solves = 0
    if math.isfinite(T_gov) and T_gov > 0:  # q at the governing torque (T = q N P_max R)
        if searches:
            P_max = searches[0].peak_load_N(1e3 * T_gov)
            q = 1e3 * T_gov / (R * N * P_max)
        else:
            sign = 1.0 if problem.torque_Nm >= 0 else -1.0
            res = load_from_sweep(sw, torque_Nm=sign * T_gov, model=model,
                                  gap_offset_rad=problem.gap_offset_rad)
            q, P_max = res.q(), float(np.max(res.tangential_force_N))
            solves = 1
    solves += sum(s.solves for s in searches or ())
    return Capacity(
        spec=spec, misalignment_deg=float(sw.misalignment_deg), model=model,
        loaded_flank=problem.loaded_flank, accuracy_factor=K,
        capacity_Nm=_finite_or_none(K * T_gov), governing=gov,
        criteria_Nm={k: _finite_or_none(K * v) for k, v in crit.items()},
        face_end_torque_Nm=_finite_or_none(torques["face_end"]),
        aligned_capacity_Nm=None if P_i is None else K * N * P_i * R * 1e-3,
        q=q, load_sharing_factor=None if q is None else 1.0 / q, max_tooth_load_N=P_max,
        solves=solves)


def _finite_or_none(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


ROTATIONS = {"linear": 25, "compliance": 25, "surface": 8}  # default rotations per pitch
PHASES = 8  # rotations per tooth pitch of a turn's default load (turn_phases)


def turn_phases(spec: CouplingSpec, per_pitch: int = PHASES) -> NDArray:
    """Rotations of a whole turn, ``per_pitch`` per tooth pitch (degrees): with ideal teeth
    the turn holds only ``per_pitch`` distinct poses, which the surface model solves once
    each (a rotation one pitch on is the same pose, its teeth renumbered)."""
    return np.arange(spec.tooth.teeth * per_pitch) * 360.0 / (spec.tooth.teeth * per_pitch)



def default_angles(spec: CouplingSpec, gap_offset_rad, n: int = 25) -> NDArray:
    """Rotations covering every pose: one tooth pitch for ideal teeth (the pattern repeats
    every pitch), a full turn when per-tooth offsets break the periodicity. ``n`` per
    model: :data:`ROTATIONS` (the largest tooth load varies by about 2 % over a pitch, so
    the surface model's 8 find the capacity within 0.5 % of 25: bench_surface.py)."""
    span = 360.0 if gap_offset_rad is not None else 360.0 / spec.tooth.teeth
    return np.linspace(0.0, span, n, endpoint=False)


def capacity(spec: CouplingSpec, misalignment_deg: float, *, model: str | None = None,
             loaded_flank: str = "ccw", angles_deg: ArrayLike | None = None,
             gap_offset_rad: ArrayLike | None = None,
             pressure_grid: tuple[int, int] | None = None,
             tolerance_mm: float = GAP_TOLERANCE_MM, grid: int = SWEEP_GRID,
             periodic: bool = True) -> Capacity:
    """Torque capacity at a misalignment, per criterion, with the governing one and q.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
    model : {"linear", "compliance", "surface"}, optional
        Default ``spec.load.model``.
    loaded_flank : {"ccw", "cw"}
        The flank the torque loads: ``ccw`` for positive torque, ``cw`` for negative.
    angles_deg : (M,) float, optional
        Rotations searched for the worst pose; default over one tooth pitch (a full turn
        with ``gap_offset_rad``), 25 for the linear and compliance models, 8 for surface.
    gap_offset_rad : (N,) or (2, N) float, optional
    pressure_grid : (int, int), optional
        The surface model's cells per loaded tooth; default 24 x 16 for the load and
        bending criteria and 48 x 32 for the contact pressure (:data:`LOAD_GRID`,
        :data:`PRESSURE_GRID`).
    tolerance_mm, grid, periodic
        The sweep's accuracy (:func:`gearcoupling.sweep`).

    Returns
    -------
    Capacity
    """
    spec = as_spec(spec)
    choice(loaded_flank, "loaded_flank", FLANKS)
    if model is not None:
        choice(model, "model", LOAD_MODELS)
    if angles_deg is None:
        angles_deg = default_angles(spec, gap_offset_rad, ROTATIONS[resolve_model(spec, model)])
    sw = sweep(spec, misalignment_deg, angles_deg, tolerance_mm=tolerance_mm, grid=grid,
               periodic=periodic)
    return capacity_from_sweep(sw, model=model, gap_offset_rad=gap_offset_rad,
                               loaded_flank=loaded_flank, pressure_grid=pressure_grid)


def capacity_curve(spec: CouplingSpec, misalignments_deg: ArrayLike | None = None, *,
                   model: str | None = None, loaded_flank: str = "ccw",
                   angles_deg: ArrayLike | None = None, gap_offset_rad: ArrayLike | None = None,
                   progress=None, tolerance_mm: float = GAP_TOLERANCE_MM,
                   grid: int = SWEEP_GRID, periodic: bool = True) -> CapacityCurve:
    """:func:`capacity` at each misalignment (default 25 from 0 to the design angle, at
    least 0.5°; at most ``MAXIMA["misalignments"]``); ``progress(done, total)`` is called
    after each; the other arguments as :func:`capacity`."""
    spec = as_spec(spec)
    if misalignments_deg is None:
        top = max(math.degrees(spec.design_misalignment), 0.5)
        misalignments_deg = np.linspace(0.0, top, 25)
    lo, hi = MISALIGNMENT_RANGE_DEG
    mis = angle_list(misalignments_deg, "misalignments_deg", lo=lo, hi=hi,
                     most=MAXIMA["misalignments"])
    out = CapacityCurve()
    for i, m in enumerate(mis):
        out.append(capacity(spec, float(m), model=model, loaded_flank=loaded_flank,
                            angles_deg=angles_deg, gap_offset_rad=gap_offset_rad,
                            tolerance_mm=tolerance_mm, grid=grid, periodic=periodic))
        if progress is not None:
            progress(i + 1, mis.size)
    return out


CAPACITY_COLUMNS = ("spec", "misalignment_deg", "capacity_Nm", "governing", "tooth_load_Nm",
                    "contact_stress_Nm", "bending_stress_Nm", "face_end_torque_Nm", "q",
                    "load_sharing_factor", "max_tooth_load_N")


def write_capacity_csv(curves: Mapping[str, Sequence[Capacity]], path) -> Path:
    """``capacity.csv``: one row per spec name and misalignment of :func:`capacity_curve`
    results, written atomically."""
    return write_csv_rows(path, CAPACITY_COLUMNS, ((name, *c.row()[1:])
                                                   for name, curve in curves.items()
                                                   for c in curve))
