"""The surface model's capacity search: a root per rotation from a few single-pose solves
(:func:`surface_torques`: secant steps on log ratio against log torque from the compliance
model's root, each solve warm-started from its nearest solved pose)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import GearCouplingError
from ...geometry import FLANKS
from ..inputs import LoadProblem, nominal_root_stress_MPa
from ..limits import CRITERIA
from .compliance import first_limit_torque_Nmm
from .surface import DEFAULT_GRID, BendingSprings, SurfaceSolver, flank_offsets

SURFACE_RTOL = 1e-3  # relative accuracy of a surface-model capacity torque
INFO_RTOL = 1e-2  # ... of a criterion more than SCREEN_MARGIN above the governing one
FACE_END_RTOL = 3e-2  # the face-end torque (reported, not a capacity)
SOLVE_TOLERANCE = 1e-4  # contact solves of the search (the model's default 1e-6): the
#   capacities move by at most 3e-4 over the templates at 0.5-3° (bench_capacity.py), the
#   criteria of the renzo-1967 report curve by 2e-4, for about 35 % less CPU
LOAD_GRID = (24, 16)  # surface-model cells of the load and bending criteria (bench_surface.py)
PRESSURE_GRID = DEFAULT_GRID  # ... of the contact-pressure criterion
SCREEN_MARGIN = 0.15  # criteria within this of the smallest are screened over the rotations
SLOPE_SPREAD = 0.5  # a rotation's d ln ratio / d ln T within a factor 1.5 of the measured
SCREEN_RANGE = 0.25  # rotations screened: compliance-model root within this of the smallest
SLOPES = {"tooth_load": 1.0, "contact_stress": 0.5, "bending_stress": 1.0,  # d ln f / d ln T
          "face_end": 1.0}  # (face end: its closure; 0.4-1 measured)


def surface_torques(problem: LoadProblem, limits: dict[str, NDArray]
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
        if name in CRITERIA and 0.0 < T < math.inf and (
                T <= (1.0 + SCREEN_MARGIN) * best or search is pressure):
            # to SURFACE_RTOL on its own grid, from the rough root, with the slope the
            # rough search measured (none where the rough search found it over the limit
            # at no torque or never reached)
            T = _rotation_root(search, name, j, T, SURFACE_RTOL if T <= (
                1.0 + SCREEN_MARGIN) * best else INFO_RTOL, _measured_slope(load, name, j, T))
        if name in CRITERIA and T <= (1.0 + SCREEN_MARGIN) * best:
            T = _surface_capacity(search, name, guesses[name], j, T)
        if name in CRITERIA:
            best = min(best, T)
        torques[name] = T * 1e-3
    return torques, [load, pressure]


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
            grid=grid, offsets=flank_offsets(problem.gap_offset_rad, FLANKS.index(flank), N),
            tolerance=SOLVE_TOLERANCE)
        mat = spec.material
        self.limit = {
            "tooth_load": spec.load.allowable_tooth_load_N,
            "contact_stress": min(mat.hub.allowable_contact_stress_MPa,
                                  mat.sleeve.allowable_contact_stress_MPa),
            "bending_stress": min(mat.hub.allowable_bending_stress_MPa,
                                  mat.sleeve.allowable_bending_stress_MPa)}
        self.solved: dict[tuple[int, float], tuple[dict, Any, float]] = {}

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
        key = _key(j, T_Nmm)
        if key not in self.solved:
            load_N = T_Nmm / self.spec.tooth.base_radius
            out, extra, pose = self.solver.solve_pose(j, load_N, self._start(j, T_Nmm))
            self.solved[key] = (out, pose, extra["face_end_closure"])
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
        (face end: the patches' closure of the cells next to a face end,
        :func:`.surface.face_end_closure`, which passes 1 where a patch reaches one)."""
        out = self.out(j, T_Nmm)
        if name == "face_end":
            # nan: no window reaches a face end, so every patch lies inside its window;
            # bounded (a face-end cell at its tooth's smallest gap has a vanishing scale):
            # the secant's steps stay within ln 4
            closure = self.solved[_key(j, T_Nmm)][2]
            return min(max(closure, 0.25), 4.0) if math.isfinite(closure) else 0.5
        if name == "bending_stress":
            value = nominal_root_stress_MPa(self.problem.spec, out["normal_force_N"],
                                            out["contact_z_mm"], out["contact_r_mm"])
        else:
            value = out[{"tooth_load": "tangential_force_N",
                         "contact_stress": "interior_pressure_MPa"}[name]]
        return float(np.max(value)) / self.limit[name]


def _key(j: int, T_Nmm: float) -> tuple[int, float]:
    """A solved pose's key: one pose for a torque that went through N·m."""
    return j, float(f"{T_Nmm:.12g}")


def _first_root(limits: _SurfaceLimits, name: str, guess_Nmm: NDArray,
                rtol: float = SURFACE_RTOL) -> tuple[int, float]:
    """The rotation where the compliance model reaches criterion ``name`` first (from its
    roots ``guess_Nmm (M,)``) and the surface model's root there (N·mm, to ``rtol``),
    started from the pose already solved nearest to it, where there is one (its ratio and
    the criterion's slope give the start, within :data:`MAX_STEP` of it; a ratio of 0: the
    compliance model's root, kept within a step above it), else from the compliance
    model's root."""
    fallback = 1e3 * limits.spec.tooth.pitch_radius
    start = np.where(np.isfinite(guess_Nmm) & (guess_Nmm > 0), guess_Nmm, fallback)
    j = int(np.argmin(start))
    T0 = float(start[j])
    if limits.solved and name in SLOPES:
        k, T = min(limits.solved, key=lambda key: (abs(key[0] - j), abs(math.log(key[1] / T0))))
        ratio = limits.ratio(name, k, T)
        if ratio > 0 and (name != "face_end" or math.isfinite(limits.solved[k, T][2])):
            T0 = min(max(T * ratio ** (-1.0 / SLOPES[name]), T * math.exp(-MAX_STEP)),
                     T * math.exp(MAX_STEP))
        elif ratio == 0.0:  # nothing of it at T (no interior pressure yet): above T, and
            #   within a step of it (the compliance model's root may be absurd there)
            T0 = min(max(T0, T), T * math.exp(MAX_STEP))
    return j, _rotation_root(limits, name, j, T0, rtol)


def _surface_capacity(limits: _SurfaceLimits, name: str, guess_Nmm: NDArray, first: int,
                      best: float) -> float:
    """Smallest torque (N·mm) at which criterion ``name`` reaches its limit on the surface
    model, to :data:`SURFACE_RTOL`, given its root ``best`` at rotation ``first``. Each
    tooth's load grows with the torque, so at each rotation the ratio ``criterion / limit``
    does; the capacity is the smallest of the rotations' roots. Every other rotation whose
    compliance-model root (``guess_Nmm (M,)``) lies within :data:`SCREEN_RANGE` of the
    smallest is screened at ``best`` (a ratio at or below 1: its root is no smaller); those
    above are searched in the order of their estimated roots (``T ratio^(-1/slope)``, the
    slope measured at ``first``, :func:`_measured_slope`; face end: most teeth on a face end
    first). A rotation is left out without a solve where its root, with a slope up to
    :data:`SLOPE_SPREAD` off, stays within :data:`SURFACE_RTOL` above the best so far;
    otherwise it is first checked at the best torque so far."""
    if not math.isfinite(best) or best <= 0.0:  # never reached, or over it at no torque
        return best
    finite = np.isfinite(guess_Nmm) & (guess_Nmm > 0)
    low = np.min(guess_Nmm[finite]) if np.any(finite) else math.inf
    near = ~finite | (guess_Nmm <= (1.0 + SCREEN_RANGE) * low)
    slope = _measured_slope(limits, name, first, best)
    estimate: dict[int, float] = {}
    lowest: dict[int, float] = {}
    for j in map(int, np.flatnonzero(near)):
        if j == first or limits.ratio(name, j, best) <= 1.0:
            continue
        if name == "face_end":
            estimate[j] = -float(np.sum(limits.out(j, best)["edge_contact"]))
            lowest[j] = 0.0
        else:
            drop = math.log(limits.ratio(name, j, best)) / slope
            estimate[j] = best * math.exp(-drop)
            lowest[j] = best * math.exp(-(1.0 + SLOPE_SPREAD) * drop)
    for j in sorted(estimate, key=estimate.__getitem__):
        if lowest[j] >= best * math.exp(-SURFACE_RTOL):
            continue  # its root lies above best, or below it by less than SURFACE_RTOL
        if limits.ratio(name, j, best) > 1.0:
            T0 = best if name == "face_end" else min(estimate[j], best)
            best = min(best, _rotation_root(limits, name, j, T0, slope=slope))
    return best


def _measured_slope(limits: _SurfaceLimits, name: str, j: int, T_Nmm: float) -> float:
    """``d ln ratio / d ln T`` of criterion ``name`` at rotation ``j`` near ``T``: from the
    two poses solved there nearest ``T`` (within 25 %; the worst tooth's share falls as
    more teeth take load, so bending at 1° on renzo-1967 has 0.67, not 1), kept within a
    factor 2 of :data:`SLOPES`; the nominal slope where there are none (face end: 1)."""
    nominal = SLOPES.get(name, 1.0)
    if not 0.0 < T_Nmm < math.inf:
        return nominal
    near = sorted((abs(math.log(T / T_Nmm)), T) for k, T in limits.solved
                  if k == j and abs(math.log(T / T_Nmm)) <= math.log(1.25))
    if name not in SLOPES or len(near) < 2:
        return nominal
    (_, Ta), (_, Tb) = near[:2]
    ra, rb = limits.ratio(name, j, Ta), limits.ratio(name, j, Tb)
    if ra <= 0 or rb <= 0 or Ta == Tb:
        return nominal
    measured = math.log(rb / ra) / math.log(Tb / Ta)
    return min(max(measured, 0.5 * nominal), 2.0 * nominal)


def _rotation_root(limits: _SurfaceLimits, name: str, j: int, T0: float,
                   rtol: float = SURFACE_RTOL, slope: float | None = None) -> float:
    def ratio(T):
        return limits.ratio(name, j, T)

    if name == "face_end":
        rtol = FACE_END_RTOL
    return _secant_root(ratio, T0, SLOPES[name] if slope is None else slope, rtol)


T_MAX, T_MIN = 1e18, 1e-12  # N·mm: a torque never reached, a vanishing one
LOG_T_MAX, LOG_T_MIN = math.log(T_MAX), math.log(T_MIN)
MAX_STEP = 4.0  # ln T: the longest step before a root is bracketed (a factor of 55)


def _secant_root(ratio, T0: float, slope: float, rtol: float = SURFACE_RTOL) -> float:
    """``ratio(T) = 1`` for increasing ``ratio``: secant steps on ``ln ratio`` against
    ``ln T`` (nearly straight: the first step takes the slope ``slope``), kept inside the
    bracket once one is found (bisection where a step leaves it, steps of at most
    :data:`MAX_STEP` outward before); stops when the step is below ``rtol`` (relative), the
    first one (from the slope alone) when it is below ``rtol / 2``: there a true slope from
    half to twice ``slope`` moves the root by less than ``rtol``.

    A ratio of 0 (the criterion's measure is absent at that torque: past the critical
    misalignment the interior pressure, while every patch lies at a face end) is below 1
    but has no logarithm: it bounds the root from below and the secant goes on from the
    last positive ratio. ``inf`` where the ratio stays below 1 up to 1e18 N·mm, 0 where it
    is at or above 1 down to 1e-12 N·mm (binding teeth: loaded at no torque)."""
    lo, hi = -math.inf, math.inf  # ln T: the ratio below 1 at lo, at or above 1 at hi
    last: tuple[float, float] | None = None  # (ln T, ln ratio) of the last positive ratio
    T = min(max(T0, T_MIN), T_MAX)
    x = math.log(T)
    for solve in range(100):
        r = ratio(T)
        if math.isnan(r):
            raise GearCouplingError(f"surface capacity: the model's solve at {T:.6g} N·mm "
                                    "gave no value of the criterion (NaN)")
        if r >= 1.0:
            hi = min(hi, x)
        else:
            lo = max(lo, x)
        if r > 0.0:
            f = math.log(r)
            step = -f / slope if last is None or last[1] == f else \
                -f * (x - last[0]) / (f - last[1])
            last = (x, f)
            if abs(step) <= (0.5 if solve == 0 else 1.0) * rtol:
                return math.exp(x + step)
        else:
            f, step = -math.inf, MAX_STEP  # nothing of the criterion yet: upward
        if hi - lo <= rtol:
            return math.exp(0.5 * (lo + hi))
        if math.isfinite(lo + hi):  # bracketed: the step inside, else bisection
            x = x + step if lo < x + step < hi else 0.5 * (lo + hi)
        elif hi == LOG_T_MIN:  # over the limit at a vanishing torque (binding teeth)
            return 0.0
        elif lo == LOG_T_MAX:  # never reached
            return math.inf
        else:  # outward, toward the side the root lies on (a secant pointing back: the
            #    ratio fell with the torque; the slope's step instead)
            if (step > 0.0) != (hi == math.inf):
                step = -f / slope
            x = min(max(x + min(max(step, -MAX_STEP), MAX_STEP), LOG_T_MIN), LOG_T_MAX)
        T = math.exp(x)
    raise GearCouplingError(f"surface capacity: no root within {rtol:g} after 100 solves")
