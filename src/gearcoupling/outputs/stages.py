"""The stages that :func:`~gearcoupling.outputs.run` and the design report
(:func:`gearcoupling.report`) share: the sweep over a turn, the critical and binding
angles, the misalignment grids, the backlash curve, Renzo's q points and the misalignment
studies of the loads.

Each stage is computed once per spec and arguments in a process and kept (:func:`stage`):
a report made in the process of a run, or after it (``gc.run`` then ``gc.report``),
reuses what the run computed, and a report alone computes each stage once. The run's
forked workers send the stages they computed back to the parent (:func:`take_new`,
:func:`remember`). Results are shared, not copied: treat them as read-only. The load
stages import :mod:`gearcoupling.loading` at the call (the run's parent needs it not).
"""

from __future__ import annotations

import functools
import json
import math
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, backlash_curve, design_quantities, sweep
from ..errors import ArgumentError
from ..geometry import renzo_z0_mm
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec

MEMO_SIZE = 64  # stage results kept per process (least recently used dropped)
_MEMO: OrderedDict[tuple, Any] = OrderedDict()
_NEW: dict[tuple, Any] = {}  # computed here since the last take_new()

F = TypeVar("F", bound=Callable[..., Any])


def spec_key(spec: CouplingSpec) -> str:
    """The spec as one string: equal for equal specs, however they were made."""
    return json.dumps(spec.to_dict(), sort_keys=True, default=repr)


def remember(entries: dict[tuple, Any]) -> None:
    """Keep stage results (``entries`` from :func:`take_new` of another process)."""
    for key, value in entries.items():
        _MEMO[key] = value
        _MEMO.move_to_end(key)
    while len(_MEMO) > MEMO_SIZE:
        _MEMO.popitem(last=False)


def take_new() -> dict[tuple, Any]:
    """The stage results computed in this process since the last call."""
    new = dict(_NEW)
    _NEW.clear()
    return new


def forget() -> None:
    """Drop every kept stage result."""
    _MEMO.clear()
    _NEW.clear()


def stage(fn: F) -> F:
    """Keep ``fn(spec, *args)`` per spec and (hashable) positional arguments (module
    docstring); keyword arguments (a progress callback) are passed on, not compared."""
    @functools.wraps(fn)
    def kept(spec: CouplingSpec, *args: Any, **kwargs: Any) -> Any:
        key = (fn.__name__, spec_key(spec), args)
        if key in _MEMO:
            _MEMO.move_to_end(key)
            return _MEMO[key]
        value = fn(spec, *args, **kwargs)
        remember({key: value})
        _NEW[key] = value
        if len(_NEW) > MEMO_SIZE:  # bounded where no one takes them (not a run's worker)
            del _NEW[next(iter(_NEW))]
        return value
    return kept  # type: ignore[return-value]


@stage
def turn_sweep(spec: CouplingSpec, misalignment_deg: float, angles: int,
               tolerance_mm: float = GAP_TOLERANCE_MM) -> SweepResult:
    """The sweep of ``angles`` rotations evenly over a turn, checked finite."""
    if angles < 1:
        raise ArgumentError("angles", angles, "at least 1")
    a = np.arange(angles) * 360.0 / angles
    return sweep(spec, misalignment_deg, a, tolerance_mm=tolerance_mm).check_finite()


@stage
def design_point(spec: CouplingSpec, misalignment_deg: float) -> dict[str, Any]:
    """:func:`~gearcoupling.clearance.design_quantities` at the misalignment: the critical
    and binding angles and the contact travel (root finding, a few seconds)."""
    return design_quantities(spec, misalignment_deg)


def study_misalignments(spec: CouplingSpec, top_deg: float | None = None,
                        count: int = 7) -> np.ndarray:
    """Misalignments of the studies and the q graph: ``count`` from ``top / count`` to
    ``top`` (0 left out); ``top`` the design angle by default, at least 0.5°."""
    top = max(spec.design_misalignment_deg if top_deg is None else top_deg, 0.5)
    return np.linspace(top / count, top, count)


def backlash_range_deg(spec: CouplingSpec, binding_deg: float | None,
                       misalignment_deg: float) -> float:
    """The top of the backlash-against-misalignment grid: twice the binding angle (3° when
    it does not bind), at least 1.5 times the misalignment, at most 6°."""
    return min(MISALIGNMENT_RANGE_DEG[1], max(2.0 * (binding_deg or 3.0), 1.5 * misalignment_deg))


@stage
def backlash_grid(spec: CouplingSpec, max_deg: float, count: int = 25
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Misalignments 0 to ``max_deg`` (deg) and the smallest backlash over a turn at each
    (mm at the pitch radius; 8 rotations per tooth pitch)."""
    mis = np.linspace(0.0, max_deg, count)
    return mis, backlash_curve(spec, mis)


@dataclass(frozen=True)
class QPoint:
    """One point of Renzo's q graph: the linear model's tooth-load capacity over the
    aligned capacity at a misalignment, against ``z_c / z0``, with Renzo's eq. 8."""

    misalignment_deg: float
    zc_over_z0: float
    q_linear: float
    q_renzo: float


@stage
def q_points(spec: CouplingSpec, top_deg: float | None = None) -> tuple[QPoint, ...]:
    """Renzo's q graph at :func:`study_misalignments` (needs ``load.allowable_tooth_load``
    and ``load.mesh_stiffness``; empty without them): the linear model on the exact
    geometry, 25 rotations over a tooth pitch at each misalignment."""
    from ..loading import capacity_from_sweep, default_angles, renzo_q

    ld = spec.load
    if ld.allowable_tooth_load_N is None or ld.mesh_stiffness_N_per_mm is None:
        return ()
    zc = ld.allowable_tooth_load_N / ld.mesh_stiffness_N_per_mm
    rc = spec.derived["crowning_radius_midplane_mm"]
    pts = []
    for i in study_misalignments(spec, top_deg):
        c = capacity_from_sweep(sweep(spec, float(i), default_angles(spec, None)),
                                model="linear")
        z0 = renzo_z0_mm(rc, math.radians(i), spec.tooth.pressure_angle)
        T_tooth = c.criteria_Nm.get("tooth_load")
        if 0 < z0 < math.inf and T_tooth and c.aligned_capacity_Nm:
            pts.append(QPoint(float(i), zc / z0, T_tooth / c.aligned_capacity_Nm,
                              renzo_q(zc / z0)))
    return tuple(pts)


@dataclass(frozen=True)
class LoadStudy:
    """The largest tooth load (N) and the mean tilting moment (N·m) over a tooth pitch at
    each misalignment, per torque (Wei Figs. 12-13); keys ``T/2 = ... N·m`` and so on."""

    misalignments_deg: np.ndarray
    peak_N: dict[str, list[float]]
    moment_Nm: dict[str, list[float]]


@stage
def load_study(spec: CouplingSpec, torque_Nm: float, model: str | None,
               top_deg: float | None = None, *,
               progress: Callable[[int, int], None] | None = None) -> LoadStudy:
    """The loads at T/2, T and 2T over one tooth pitch at each of
    :func:`study_misalignments` (at the model's :attr:`~gearcoupling.loading.LoadModel.study`
    rotations and grid); ``progress(done, total)`` after each
    misalignment."""
    from ..loading import default_angles, load_from_sweep, load_model, resolve_model

    mis = study_misalignments(spec, top_deg)
    torques = [0.5 * torque_Nm, torque_Nm, 2.0 * torque_Nm]
    # one curve per factor, also where the torques coincide (0 N·m: three flat curves)
    labels = [f"{f} = {t:.4g} N·m" for f, t in zip(("T/2", "T", "2T"), torques, strict=True)]
    peak: dict[str, list[float]] = {k: [] for k in labels}
    moment: dict[str, list[float]] = {k: [] for k in labels}
    m = load_model(resolve_model(spec, model))
    rotations, grid = m.study or (m.rotations, None)
    for n, i in enumerate(mis):
        sw = sweep(spec, float(i), default_angles(spec, None, rotations))
        for t, key in zip(torques, labels, strict=True):
            res = load_from_sweep(sw, torque_Nm=t, model=model, pressure_grid=grid)
            peak[key].append(float(np.max(res.tangential_force_N)))
            moment[key].append(res.summary()["tilting_moment_Nm"]["mean"])
        if progress:
            progress(n + 1, mis.size)
    return LoadStudy(mis, peak, moment)
