"""The stages that :func:`~gearcoupling.outputs.run` and the design report
(:func:`gearcoupling.report`) share: the sweep over a turn, the critical and binding
angles, the misalignment grids, the backlash curve, Renzo's q points and the misalignment
studies of the loads.

Each stage is computed once per spec and arguments in a process and kept (:func:`stage`):
a report made in the process of a run, or after it (``gc.run`` then ``gc.report``),
reuses what the run computed, and a report alone computes each stage once. The run's
forked workers send the stages they computed back to the parent (:func:`take_new`,
:func:`remember`). Results are shared, not copied: treat them as read-only. The stages of
the loads are in :mod:`.load_stages` (they need :mod:`gearcoupling.loading`, which the
run's parent does not load).
"""

from __future__ import annotations

import functools
import json
from collections import OrderedDict
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, backlash_curve, design_quantities, sweep
from ..errors import ArgumentError
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
