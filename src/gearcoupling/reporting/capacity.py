"""Capacity curves of several specs over one misalignment range (``gearcoupling capacity
--compare`` and the report's capacity section)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import MAXIMA, angle_list, choice
from ..arguments import count as check_count
from ..clearance import critical_misalignment_deg
from ..errors import ArgumentError
from ..forked import ForkedMap, default_workers
from ..loading import CapacityCurve, capacity, model_names
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec

DEFAULT_COUNT = 25
SMALLEST_TOP_DEG = 0.5


@dataclass(frozen=True)
class CapacityComparison:
    """Capacity curves by spec name over the same misalignments, with each spec's critical
    misalignment (None: no face end is reached up to 6°)."""

    misalignments_deg: NDArray[np.float64]
    curves: dict[str, CapacityCurve]
    critical_deg: dict[str, float | None]


def comparison_range(specs: Sequence[CouplingSpec], count: int = DEFAULT_COUNT,
                     top_deg: float | None = None) -> tuple[NDArray, dict[str, float | None]]:
    """``count`` misalignments from 0 to ``top_deg``, by default the largest critical
    misalignment of ``specs`` (where the contact of the pivot teeth reaches a face end;
    the range where crowns differ), at least every design angle and 0.5°, at most 6°;
    and the critical misalignments by spec name."""
    critical = {s.name: critical_misalignment_deg(s) for s in specs}
    if top_deg is None:
        tops = [SMALLEST_TOP_DEG, *(s.design_misalignment_deg for s in specs),
                *(c for c in critical.values() if c is not None)]
        top_deg = min(max(tops), MISALIGNMENT_RANGE_DEG[1])
    if not (isinstance(count, int) and count >= 2):
        raise ArgumentError("count", count, "a whole number >= 2")
    return np.linspace(0.0, float(top_deg), count), critical


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
