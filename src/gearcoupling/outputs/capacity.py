"""Capacity against misalignment: the stage ``capacity`` (one spec, to its critical
misalignment, through the operating point) and the curves of several specs over one range
(``gearcoupling capacity --compare``)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import MAXIMA, angle_list, choice
from ..arguments import count as check_count
from ..clearance import critical_misalignment_deg
from ..errors import ArgumentError
from ..forked import ForkedMap, default_workers
from ..io import write_json
from ..loading import Capacity, CapacityCurve, capacity, model_names, plot_capacity
from ..loading import write_capacity_csv as write_curves_csv
from ..plots import save_figure
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec
from .stage import StageInputs
from .sweep import DesignPoint

DEFAULT_COUNT = 25
SMALLEST_TOP_DEG = 0.5


@dataclass(frozen=True)
class CapacityComparison:
    """Capacity curves by spec name over the same misalignments, with each spec's critical
    misalignment (None: no face end is reached up to 6°)."""

    misalignments_deg: NDArray[np.float64]
    curves: dict[str, CapacityCurve]
    critical_deg: dict[str, float | None]


@dataclass(frozen=True)
class Rating:
    """The stage ``rating``: the capacity at the operating point on its loaded flank, and
    the torque judged against it (``torque_Nm`` None: no torque given, nothing judged)."""

    capacity: Capacity
    torque_Nm: float | None

    @property
    def holds(self) -> bool | None:
        """Whether the capacity carries the torque (None: no torque, or no criterion
        reaches its limit, which carries any torque)."""
        cap = self.capacity.capacity_Nm
        if self.torque_Nm is None:
            return None
        return True if cap is None else abs(self.torque_Nm) <= cap

    def summary(self) -> dict[str, Any]:
        """``rating.json``: the capacity (times K) and its governing criterion, K, the
        torque and the margin (% of the capacity; negative: over it)."""
        c = self.capacity
        margin = None if c.capacity_Nm is None or self.torque_Nm is None else \
            100.0 * (c.capacity_Nm - abs(self.torque_Nm)) / c.capacity_Nm
        return {"misalignment_deg": c.misalignment_deg, "model": c.model,
                "loaded_flank": c.loaded_flank, "capacity_Nm": c.capacity_Nm,
                "governing": c.governing, "accuracy_factor": c.accuracy_factor,
                "torque_Nm": self.torque_Nm, "margin_pct": margin, "holds": self.holds}

    def sentence(self) -> str:
        """The finding in one line."""
        c = self.capacity
        where = f"at {c.misalignment_deg:g}° ({c.model} model, {c.loaded_flank} flanks)"
        if c.capacity_Nm is None:
            return f"capacity {where}: no criterion reaches its limit"
        text = (f"capacity {where} {c.capacity_Nm:.4g} N·m = K × "
                f"{c.capacity_Nm / c.accuracy_factor:.4g} N·m ({c.governing.replace('_', ' ')}"
                f" governs, K = {c.accuracy_factor:g})")
        if self.torque_Nm is None:
            return text
        T = abs(self.torque_Nm)
        verdict = "carries" if self.holds else "is UNDER"
        return (f"{text}: it {verdict} the torque {T:.4g} N·m (margin "
                f"{self.summary()['margin_pct']:+.1f} %)")


def rating(inputs: StageInputs) -> Rating:
    """The stage ``rating``."""
    p = inputs.point
    return Rating(capacity(inputs.spec, p.misalignment_deg, model=p.model,
                           loaded_flank=p.flank), p.torque_Nm)


def rating_files(result: Rating, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``rating``'s ``rating.json``."""
    return [write_json(folder / "rating.json", result.summary())]


@dataclass(frozen=True)
class CapacityAgainstMisalignment:
    """The stage ``capacity``: the capacity curve of one spec (ccw flanks) from 0 to
    ``top_deg``, its critical misalignment, and the capacity at the operating point on its
    loaded flank (:attr:`at_point`, the rating's)."""

    curve: CapacityCurve
    critical_deg: float | None
    top_deg: float
    at_point: Capacity

    @property
    def misalignments_deg(self) -> NDArray[np.float64]:
        return np.array([c.misalignment_deg for c in self.curve])


def comparison_range(specs: Sequence[CouplingSpec], count: int = DEFAULT_COUNT,
                     top_deg: float | None = None,
                     critical: dict[str, float | None] | None = None
                     ) -> tuple[NDArray, dict[str, float | None]]:
    """``count`` misalignments from 0 to ``top_deg``, by default the largest critical
    misalignment of ``specs`` (where the contact of the pivot teeth reaches a face end;
    the range where crowns differ), at least every design angle and 0.5°, at most 6°;
    and the critical misalignments by spec name (``critical``: those already known)."""
    critical = critical or {s.name: critical_misalignment_deg(s) for s in specs}
    if top_deg is None:
        tops = [SMALLEST_TOP_DEG, *(s.design_misalignment_deg for s in specs),
                *(c for c in critical.values() if c is not None)]
        top_deg = min(max(tops), MISALIGNMENT_RANGE_DEG[1])
    if not (isinstance(count, int) and count >= 2):
        raise ArgumentError("count", count, "a whole number >= 2")
    return np.linspace(0.0, float(top_deg), count), critical


def through(grid: NDArray, point_deg: float) -> NDArray:
    """The misalignments ``grid`` through ``point_deg``, so that one search gives the
    operating point's capacity and the curve's point: it takes the place of the nearest
    interior point of ``grid`` (0 and the top stay), else it is added."""
    inside = grid[1:-1]
    out = grid.copy()
    if inside.size and grid[0] < point_deg < grid[-1]:
        out[1 + int(np.argmin(np.abs(inside - point_deg)))] = point_deg
    else:
        out = np.append(out, point_deg)
    return np.unique(out)


@dataclass(frozen=True)
class CapacityPlan:
    """The stage ``capacity``'s searches: one per misalignment of the curve, and one at
    the operating point where its flank is cw."""

    grid: NDArray[np.float64]
    critical_deg: float | None
    at_point: Capacity
    known: int | None  # the grid's index of the operating point, searched by the rating
    tasks: tuple[Callable[[], Capacity], ...]

    def combine(self, found: Sequence[Capacity]) -> CapacityAgainstMisalignment:
        found = list(found)
        if self.known is not None:
            found.insert(self.known, self.at_point)
        return CapacityAgainstMisalignment(CapacityCurve(found), self.critical_deg,
                                           float(self.grid[-1]), self.at_point)


def plan(inputs: StageInputs) -> CapacityPlan:
    """The stage ``capacity``: ``capacity_count`` misalignments from 0 to the critical
    misalignment (:func:`comparison_range`), on the ccw flanks through the operating point,
    whose capacity the rating searched already."""
    spec, p = inputs.spec, inputs.point
    critical = inputs.get("design", DesignPoint).critical_deg
    at = inputs.get("rating", Rating).capacity
    grid, _ = comparison_range([spec], inputs.settings.capacity_count,
                               critical={spec.name: critical})
    known = None
    if p.flank == "ccw":
        grid = through(grid, p.misalignment_deg)
        known = int(np.searchsorted(grid, p.misalignment_deg))
    tasks = [partial(capacity, spec, float(m), model=p.model) for j, m in enumerate(grid)
             if j != known]
    return CapacityPlan(grid, critical, at, known, tuple(tasks))


def files(result: CapacityAgainstMisalignment, inputs: StageInputs, folder: Path
          ) -> list[Path]:
    """The stage ``capacity``'s ``capacity.csv`` and ``capacity.png``."""
    name = inputs.spec.name
    curves = {name: result.curve}
    return [write_curves_csv(curves, folder / "capacity.csv"),
            save_figure(plot_capacity(curves, critical_deg={name: result.critical_deg}),
                        folder / "capacity.png", inputs.settings.dpi)]


def compare_capacity(specs: Sequence[CouplingSpec], misalignments_deg: ArrayLike | None = None,
                     *, model: str | None = None, count: int = DEFAULT_COUNT,
                     progress: Callable[[int, int], None] | None = None,
                     workers: int | None = None) -> CapacityComparison:
    """Capacity curves of ``specs`` over the same misalignments (default
    :func:`comparison_range`); ``progress(done, total)`` after each point. Every argument
    is checked before any work: each spec a CouplingSpec, template name or TOML path, each
    with its own name. ``workers``: 1 computes every point in this process, 2 (the default
    where the machine has two cores and forking is safe) splits them over two forked
    processes while this one waits; interrupted, the workers are killed first
    (:func:`~gearcoupling.forked.fork_map`)."""
    started = StartedComparison(specs, misalignments_deg, model=model, count=count,
                                workers=workers)
    try:
        return started.result(progress)
    finally:
        started.stop()


class StartedComparison:
    """:func:`compare_capacity` started now (its points in forked workers where it forks)
    and collected later by :meth:`result`; :meth:`stop` in a ``finally`` kills the workers
    still running (the report starts its capacity curve before its first section).
    ``known_range``: :func:`comparison_range` of ``specs`` where the caller has it (it
    searches each spec's critical misalignment)."""

    def __init__(self, specs: Sequence[CouplingSpec],
                 misalignments_deg: ArrayLike | None = None, *, model: str | None = None,
                 count: int = DEFAULT_COUNT, workers: int | None = None,
                 known_range: tuple[NDArray, dict[str, float | None]] | None = None):
        if isinstance(specs, str | bytes) or not isinstance(specs, Sequence) or not specs:
            raise ArgumentError("specs", specs, "a non-empty list of specs (CouplingSpec, "
                                "template names or TOML paths)")
        specs = [as_spec(s, "specs") for s in specs]
        names = [s.name for s in specs]
        if len(set(names)) < len(names):
            raise ArgumentError("specs", names, "each compared spec needs its own name (a "
                                "spec compared with itself is the same curve)")
        check_count(count, "count", 2, MAXIMA["misalignments"])
        if workers is not None and (workers not in (1, 2) or isinstance(workers, bool)):
            raise ArgumentError("workers", workers, "1 or 2")
        if model is not None:
            choice(model, "model", model_names())
        lo, hi = MISALIGNMENT_RANGE_DEG
        given = None if misalignments_deg is None else np.unique(angle_list(
            misalignments_deg, "misalignments_deg", lo=lo, hi=hi,
            most=MAXIMA["misalignments"]))
        auto, self.critical = (comparison_range(specs, count) if known_range is None
                               else known_range)
        self.top_deg = float(auto[-1])  # the automatic range's end
        self.mis = auto if given is None else given
        self.specs = specs
        points = [(spec, float(m)) for spec in specs for m in self.mis]
        self.map = ForkedMap(lambda p: capacity(p[0], p[1], model=model), points,
                             default_workers() if workers is None else workers)

    def result(self, progress: Callable[[int, int], None] | None = None
               ) -> CapacityComparison:
        n, total = self.mis.size, len(self.map.items)
        found = self.map.results(None if progress is None else (lambda k: progress(k, total)))
        curves = {spec.name: CapacityCurve(found[k * n:(k + 1) * n])
                  for k, spec in enumerate(self.specs)}
        return CapacityComparison(self.mis, curves, self.critical)

    def stop(self) -> None:
        self.map.stop()
