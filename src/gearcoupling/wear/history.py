"""The wear history: steps in wear exposure, each removing the depth its turns' rates give,
the loads solved again on the worn flanks after each (docs/wear.md, Stepping in time).

The state is a function of the **exposure** ``X = k t`` (coefficient times hours) alone:
the depth rate is linear in ``k`` and the loads depend only on the depths, so the history
is stepped in ``X`` and a coefficient ``k`` reads it at ``t = X / k``. A history with
``2k`` over ``t / 2`` is the history with ``k`` over ``t``, and the life at every
coefficient of the band comes from one history.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import GearCouplingError
from ..spec import CouplingSpec
from .kernels import exposure_step, limit_crossing
from .model import PointSolver, Turn, WearMaps, flank_grids
from .result import POINT_STATS, WearResult, thicknesses_mm
from .settings import Accuracy, DutyPoint, WearSettings

MAX_STEPS = 5000  # a history stops with an error past this many steps
MIN_STEP = 1e-5  # the smallest step, as a share of the history's exposure
#: the share of a step's own wear taken implicitly (docs/wear.md, Stepping in time): a
#: cell-sized bump shrinks by 1 - 1/IMPLICIT (-2/3) per step however long, the smooth part
#: of the history is near the midpoint rule's second order (1/2 would be it exactly, and
#: leave the cell-sized bumps undamped)
IMPLICIT = 0.6
SPREAD_CELLS = 2  # map cells a step's wear per MPa is spread to (:func:`spread`)


def tooth_losses(spec: CouplingSpec, maps: WearMaps) -> tuple[NDArray, NDArray]:
    """Thickness loss of every hub tooth and every sleeve tooth ``(T,)`` (mm, as an arc at
    the pitch circle): the largest over the flank of its two flanks' depths at one flank
    point, times ``R / r_b`` (a normal depth ``h`` thins a tooth by ``h R / r_b`` there).
    Sleeve tooth ``k`` lies between space ``k`` (its ccw-loaded flank) and space ``k + 1``
    (its cw-loaded flank)."""
    factor = spec.tooth.pitch_radius / spec.tooth.base_radius
    hub = np.max(maps.hub[0] + maps.hub[1], axis=(1, 2))
    sleeve = np.max(maps.sleeve[1] + np.roll(maps.sleeve[0], -1, axis=0), axis=(1, 2))
    return factor * hub, factor * sleeve


def spread(maps: NDArray, cells: int = SPREAD_CELLS) -> NDArray:
    """``maps (..., nz, ns)`` spread to their neighbours: the largest value within
    ``cells`` map cells either way along the face and the profile. The wear per MPa a
    step gives a cell is known from the last turn's loaded cells; a patch that grows in
    the step loads cells next to them, which then take their neighbours' value rather
    than none (a cell with none would draw the load of the step's worn ones to itself)."""
    out = maps.copy()
    for axis in (-2, -1):
        src = out.copy()
        n = src.shape[axis]
        for k in range(1, cells + 1):
            if k >= n:
                break
            lo = [slice(None)] * src.ndim
            hi = [slice(None)] * src.ndim
            lo[axis], hi[axis] = slice(0, n - k), slice(k, n)
            out[tuple(lo)] = np.maximum(out[tuple(lo)], src[tuple(hi)])
            out[tuple(hi)] = np.maximum(out[tuple(hi)], src[tuple(lo)])
    return out


def _wear_ratio(spec: CouplingSpec, maps: WearMaps) -> NDArray:
    """Every tooth's thickness loss over its thickness, hub teeth then sleeve teeth."""
    th, ts = thicknesses_mm(spec)
    hub, sleeve = tooth_losses(spec, maps)
    return np.concatenate([hub / th, sleeve / ts])


def _loss_points(spec: CouplingSpec, before: WearMaps, after: WearMaps
                 ) -> tuple[NDArray, NDArray]:
    """The thickness loss over the thickness at every flank point of every tooth, before
    and after a step (each linear in the step, so :func:`.kernels.limit_crossing` finds
    the largest one's crossing exactly)."""
    th, ts = thicknesses_mm(spec)
    factor = spec.tooth.pitch_radius / spec.tooth.base_radius

    def points(m: WearMaps) -> NDArray:
        hub = (m.hub[0] + m.hub[1]) * (factor / th)
        sleeve = (m.sleeve[1] + np.roll(m.sleeve[0], -1, axis=0)) * (factor / ts)
        return np.concatenate([hub.ravel(), sleeve.ravel()])

    return points(before), points(after)


class History:
    """The records of a history as it runs (one per state: the depths and the loads solved
    on them)."""

    def __init__(self, spec: CouplingSpec, solvers: list[PointSolver]):
        self.spec, self.solvers = spec, solvers
        self.rows: dict[str, list[Any]] = {}
        self.fields: list[dict] = [{} for _ in solvers]
        self.kept: list[tuple[float, list]] = []

    def add(self, exposure: float, maps: WearMaps, turns: list[Turn], step: float = 0.0
            ) -> None:
        hub_loss, sleeve_loss = tooth_losses(self.spec, maps)
        rec: dict[str, Any] = {
            "exposure": exposure,
            "hub_max_mm": np.max(maps.hub, axis=(1, 2, 3)),
            "hub_mean_mm": np.mean(maps.hub, axis=(1, 2, 3)),
            "sleeve_max_mm": np.max(maps.sleeve, axis=(1, 2, 3)),
            "sleeve_mean_mm": np.mean(maps.sleeve, axis=(1, 2, 3)),
            "thickness_loss_mm": np.array([np.max(hub_loss), np.max(sleeve_loss)]),
            "wear_ratio": float(np.max(_wear_ratio(self.spec, maps))),
            "hub_maps": np.max(maps.hub, axis=1),
            "sleeve_maps": np.max(maps.sleeve, axis=1),
            "bearing_MPa": _bearings(maps, turns),
            "backlash_mm": np.array([s.backlash_mm(maps, f)
                                     for s, f in zip(self.solvers, self.fields, strict=True)]),
        }
        for name in POINT_STATS:
            rec[name] = np.array([t.stats[name] for t in turns])
        for key, value in rec.items():
            self.rows.setdefault(key, []).append(value)
        if any(t.fields for t in turns):
            self.kept.append((step, [t.fields for t in turns]))

    def arrays(self) -> dict[str, NDArray]:
        return {k: np.asarray(v) for k, v in self.rows.items()}


def _bearings(maps: WearMaps, turns: list[Turn]) -> NDArray:
    """The tooth bearing picture of each loaded flank ``(2, nz, ns)``: the largest pressure
    every hub flank cell saw over the turns (worst tooth)."""
    g = maps.hub_grid
    out = np.zeros((2, g.nz, g.ns))
    for t in turns:
        out[t.flank] = np.maximum(out[t.flank], np.max(t.bearing_MPa, axis=0))
    return out


def rates(turns: list[Turn], duty: tuple[DutyPoint, ...], like: WearMaps,
          sleeve_factor: float, slide: bool = False) -> WearMaps:
    """Depth per unit exposure (mm per mm³/(N·m)·h) of every map, ``(2, T, nz, ns)``: each
    point's depth per revolution times its revolutions per hour and its share of the
    duty's time; the sleeve's times ``sleeve_factor``. ``slide``: the same per MPa of a
    loaded cell's own pressure (the implicit part of a step)."""
    total_h = sum(p.hours for p in duty)
    hub, sleeve = np.zeros_like(like.hub), np.zeros_like(like.sleeve)
    for t, p in zip(turns, duty, strict=True):
        w = p.hours / total_h * p.revolutions_per_hour
        hub[t.flank] += w * (t.hub_slide if slide else t.hub_rate)
        sleeve[t.flank] += w * sleeve_factor * (t.sleeve_slide if slide else t.sleeve_rate)
    return WearMaps(hub, sleeve, like.hub_grid, like.sleeve_grid)


def run_history(spec: CouplingSpec, duty: tuple[DutyPoint, ...], settings: WearSettings,
                accuracy: Accuracy, hours: float, *, gap_offset_rad: Any = None,
                progress: Callable[[int, int], None] | None = None,
                keep: bool = False) -> WearResult:
    """The wear history over ``hours`` (or up to the wear limit) at ``settings``'
    coefficient (arguments as :func:`gearcoupling.wear.wear`). ``keep``: the result keeps
    every step's exposure and solved poses (``steps_kept``: the turns the step's wear came
    from; for checks)."""
    N = spec.tooth.teeth
    hub_grid, sleeve_grid = flank_grids(spec, duty, accuracy.grid)
    T = N if gap_offset_rad is not None and np.ptp(np.asarray(gap_offset_rad, float)) > 0 \
        else 1
    maps = WearMaps(np.zeros((2, T, hub_grid.nz, hub_grid.ns)),
                    np.zeros((2, T, sleeve_grid.nz, sleeve_grid.ns)), hub_grid, sleeve_grid)
    solvers = [PointSolver(spec, p, accuracy, maps, gap_offset_rad) for p in duty]
    k = settings.coefficient_mm3_per_Nm
    sf = settings.sleeve_factor
    end = k * hours
    history = History(spec, solvers)
    turns = [s.turn(maps, None, keep) for s in solvers]
    history.add(0.0, maps, turns)
    x, steps, life = 0.0, 0, None
    step_floor = MIN_STEP * end
    while x < end * (1 - 1e-12) and life is None:
        if steps >= MAX_STEPS:
            raise GearCouplingError(f"wear: {MAX_STEPS} steps did not reach {hours:g} h; "
                                    "raise step_fraction")
        # the step from the last turn's rates; its wear from a turn solved with IMPLICIT of
        # each cell's own wear over the step in series (implicit in the stiff local part)
        start = rates(turns, duty, maps, sf)
        approach = min(t.stats["approach_mm"] for t in turns)
        top = max(float(np.max(start.hub)), float(np.max(start.sleeve)))
        full = exposure_step(approach, top, accuracy.step_fraction, step_floor, end - x)
        dx = min(full, end - x)
        # the implicit part at the rule's step even where the history's end cuts it
        # short: the loads of every step are solved alike
        slide = rates(turns, duty, maps, sf, slide=True)
        c = IMPLICIT * full
        local = WearMaps(c * spread(slide.hub), c * spread(slide.sleeve), maps.hub_grid,
                         maps.sleeve_grid)
        turns = [s.turn(maps, local, keep) for s in solvers]
        rate = rates(turns, duty, maps, sf)
        new = maps.advanced(rate.hub, rate.sleeve, dx)
        lam = limit_crossing(*_loss_points(spec, maps, new), settings.limit_fraction)
        if lam is not None:
            dx *= lam
            new = maps.advanced(rate.hub, rate.sleeve, dx)
            life = x + dx
        maps, x = new, x + dx
        steps += 1
        history.add(x, maps, turns, dx)
        if progress is not None:
            progress(round(1000 * min(x / end, 1.0)), 1000)
    return WearResult.from_history(spec, duty, settings, accuracy, hours, history.arrays(),
                                   maps, life, _extrapolated(history, settings),
                                   len(solvers) * (steps + 1), history.kept)


def _extrapolated(history: History, settings: WearSettings) -> float:
    """The exposure at the wear limit by the last step's rate of the largest wear ratio
    (where the history ended before it): ``inf`` where nothing wears."""
    x = history.rows["exposure"]
    r = history.rows["wear_ratio"]
    if len(x) < 2 or not x[-1] > x[-2]:
        return math.inf
    slope = (r[-1] - r[-2]) / (x[-1] - x[-2])
    if not slope > 0:
        return math.inf
    return x[-1] + (settings.limit_fraction - r[-1]) / slope


__all__ = ["MAX_STEPS", "History", "rates", "run_history", "tooth_losses"]
