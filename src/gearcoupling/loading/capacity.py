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
single-pose solves (:mod:`.models.surface_capacity`: secant steps on log ratio against log torque
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

from ..arguments import GAP_TOLERANCE_MM, MAXIMA, PHASES, SWEEP_GRID, angle_list, choice
from ..clearance import SweepResult, sweep
from ..errors import ArgumentError
from ..geometry import FLANKS
from ..io import write_csv_rows
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec
from ..tables import dataframe
from .api import load_from_sweep
from .inputs import LoadProblem, load_problem
from .limits import CRITERIA, limit_loads
from .models.registry import PoseSearch, load_model, resolve_model


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
    m = resolve_model(problem.spec, model)
    limits = limit_loads(problem.spec, problem.z_mm, problem.r_mm, problem.compliance)
    torques, searches = load_model(m).capacity(problem, limits)
    return _summarise(problem, m, torques, searches)




def _summarise(problem: LoadProblem, model: str, torques: dict[str, float],
               searches: Sequence[PoseSearch] = ()) -> Capacity:
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
    solves += sum(s.solves for s in searches)
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




def turn_phases(spec: CouplingSpec, per_pitch: int = PHASES) -> NDArray:
    """Rotations of a whole turn, ``per_pitch`` per tooth pitch (degrees): with ideal teeth
    the turn holds only ``per_pitch`` distinct poses, which the surface model solves once
    each (a rotation one pitch on is the same pose, its teeth renumbered)."""
    return np.arange(spec.tooth.teeth * per_pitch) * 360.0 / (spec.tooth.teeth * per_pitch)



def default_angles(spec: CouplingSpec, gap_offset_rad, n: int = 25) -> NDArray:
    """Rotations covering every pose: one tooth pitch for ideal teeth (the pattern repeats
    every pitch), a full turn when per-tooth offsets break the periodicity. ``n`` per
    model: its ``LoadModel.rotations`` (the largest tooth load varies by about 2 % over a
    pitch, so the surface model's 8 find the capacity within 0.5 % of 25: bench_surface.py)."""
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
    model : str, optional
        A load model's name (:data:`~gearcoupling.loading.MODELS`); default
        ``spec.load.model``.
    loaded_flank : {"ccw", "cw"}
        The flank the torque loads: ``ccw`` for positive torque, ``cw`` for negative.
    angles_deg : (M,) float, optional
        Rotations searched for the worst pose; default over one tooth pitch (a full turn
        with ``gap_offset_rad``), the model's ``rotations`` (25 for the linear and
        compliance models, 8 for surface).
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
    m = load_model(resolve_model(spec, model))
    if angles_deg is None:
        angles_deg = default_angles(spec, gap_offset_rad, m.rotations)
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
