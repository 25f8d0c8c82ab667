"""The allowable misalignment at a torque and the loads the coupling puts on the shafts there.

The allowable misalignment is the smaller of the critical angle (the pivot teeth's
contact runs onto a face end, :func:`gearcoupling.critical_misalignment_deg`) and the
largest angle at which the capacity still carries the torque (regula falsi on
:func:`gearcoupling.capacity`, which falls with the angle), within the supported 0-6°.
There the coupling's machine loads over a turn: the bending moment on the hub (normal
and friction forces about ``O``, perpendicular to the hub axis), the thrust along the hub
axis and the radial force (both cancel between opposite teeth for an even tooth count),
and the axial slip force (friction times the tooth normal loads: the thrust that slides
the teeth when the shafts move axially), with their extremes.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..clearance import critical_misalignment_deg
from ..errors import ArgumentError
from ..loading import Capacity, capacity, load, machine_loads, resolve_model, turn_phases
from ..numeric import TINY
from ..spec import MISALIGNMENT_RANGE_DEG

ANGLE_TOLERANCE_DEG = 0.01


@dataclass(frozen=True, eq=False)
class AllowableLoads:
    """The allowable misalignment, what limits it, and the machine loads over a turn there.

    ``criterion`` is ``"critical angle"`` (contact onto a face end), ``"capacity"`` (the
    capacity's governing criterion falls to the torque: ``capacity_criterion``) or
    ``"range"`` (neither within 6°). Per-rotation arrays ``(M,)`` are magnitudes except
    the thrust, signed along the hub axis.
    """

    misalignment_deg: float
    criterion: str
    critical_misalignment_deg: float | None
    capacity_misalignment_deg: float | None
    capacity_criterion: str | None
    torque_Nm: float
    angles_deg: NDArray[np.float64]
    bending_moment_Nm: NDArray[np.float64]
    axial_force_N: NDArray[np.float64]
    radial_force_N: NDArray[np.float64]
    axial_slip_force_N: NDArray[np.float64]

    def loads(self) -> dict[str, NDArray[np.float64]]:
        """The per-rotation loads by name (units in the names)."""
        return {"bending_moment_Nm": self.bending_moment_Nm, "axial_force_N": self.axial_force_N,
                "radial_force_N": self.radial_force_N,
                "axial_slip_force_N": self.axial_slip_force_N}

    def extremes(self) -> dict[str, dict[str, float]]:
        """Min, mean and max of each load over the turn."""
        return {k: {"min": float(np.min(v)), "mean": float(np.mean(v)), "max": float(np.max(v))}
                for k, v in self.loads().items()}

    def rows(self):
        """``(psi_deg, *loads)`` per rotation, in the order of :meth:`loads`."""
        return zip(self.angles_deg.tolist(), *(v.tolist() for v in self.loads().values()),
                   strict=True)

    def as_dict(self) -> dict[str, Any]:
        return {"misalignment_deg": self.misalignment_deg, "criterion": self.criterion,
                "critical_misalignment_deg": self.critical_misalignment_deg,
                "capacity_misalignment_deg": self.capacity_misalignment_deg,
                "capacity_criterion": self.capacity_criterion, "torque_Nm": self.torque_Nm,
                "angles": int(self.angles_deg.size), "over_turn": self.extremes()}


def capacity_limit_deg(spec, torque_Nm: float, top_deg: float, *, model: str | None = None,
                       tolerance_deg: float = ANGLE_TOLERANCE_DEG,
                       known: Sequence[Capacity] = (),
                       step: Callable[[], Any] | None = None
                       ) -> tuple[float | None, str | None]:
    """The largest misalignment up to ``top_deg`` whose capacity carries ``|torque_Nm|``
    (``None`` when ``top_deg`` still does), within ``tolerance_deg``, and the criterion
    that governs just beyond it.

    The capacity falls with the angle, about exponentially: the search is regula falsi
    (Illinois) on ``ln(capacity / torque)`` in a bracket that shrinks by at least
    ``tolerance_deg`` / 2 a step, and stops when the bracket or the secant's step from its
    low end is within the tolerance. ``known``: capacities of this spec and model (ccw
    flank) already computed, e.g. the report's capacity curve; they narrow the first
    bracket and are not solved again (one below the torque above the largest that carries
    it: ``top_deg`` is not solved).
    ``step()`` after each capacity solved.
    """
    need = abs(torque_Nm)
    model = resolve_model(spec, model)
    seen = known_capacities(spec, model, known)

    def margin(deg: float) -> tuple[float, str]:
        if deg not in seen:
            seen[deg] = capacity(spec, deg, model=model)
            if step is not None:
                step()
        c = seen[deg]
        cap = math.inf if c.capacity_Nm is None else max(c.capacity_Nm, TINY)
        return math.log(cap / need), c.governing

    # the capacity falls with the angle: a known one below the torque above the largest
    # known to carry it brackets the angle, and says top_deg does not carry it either
    lo, above = _bracket(seen, top_deg, need)
    if above is None:
        f_hi, governing = margin(top_deg)
        if f_hi >= 0:
            return None, None
        lo, above = _bracket(seen, top_deg, need)
    hi = top_deg if above is None else above  # top_deg does not carry the torque
    f_lo, g = margin(lo)
    if f_lo < 0:
        return 0.0, g
    f_hi, governing = margin(hi)
    w_lo, w_hi, kept = f_lo, f_hi, 0  # Illinois: the end kept twice counts half
    while hi - lo > tolerance_deg and not (
            math.isfinite(f_lo) and (hi - lo) * f_lo / (f_lo - f_hi) <= 0.5 * tolerance_deg):
        x = 0.5 * (lo + hi) if math.isinf(w_lo) else lo + (hi - lo) * w_lo / (w_lo - w_hi)
        x = min(max(x, lo + 0.5 * tolerance_deg), hi - 0.5 * tolerance_deg)
        f, g = margin(x)
        if f >= 0:
            lo, f_lo, w_lo = x, f, f
            w_hi = w_hi / 2 if kept == 1 else w_hi
            kept = 1
        else:
            hi, f_hi, w_hi, governing = x, f, f, g
            w_lo = w_lo / 2 if kept == -1 else w_lo
            kept = -1
    return lo, governing


def known_capacities(spec, model: str, known: Sequence[Capacity]) -> dict[float, Capacity]:
    """``known`` by misalignment, each checked to be of ``spec`` and ``model``, ccw flank."""
    out = {}
    for c in known:
        if not (isinstance(c, Capacity) and c.spec == spec and c.model == model
                and c.loaded_flank == "ccw"):
            raise ArgumentError("known", c, f"capacities of this spec ({spec.name}) with the "
                                f"{model} model on the ccw flank")
        out[c.misalignment_deg] = c
    return out


def _bracket(seen: dict[float, Capacity], top_deg: float, need: float
             ) -> tuple[float, float | None]:
    """The narrowest ``(lo, hi)`` within 0 to ``top_deg`` that the capacities ``seen`` give:
    ``lo`` the largest angle known to carry ``need`` (else 0), ``hi`` the smallest known
    angle above it that does not (None: none known)."""
    carries = sorted(d for d, c in seen.items() if 0 <= d <= top_deg
                     and (c.capacity_Nm is None or c.capacity_Nm >= need))
    lo = carries[-1] if carries else 0.0
    hi = min((d for d, c in seen.items() if lo < d <= top_deg and c.capacity_Nm is not None
              and c.capacity_Nm < need), default=None)
    return lo, hi


def allowable_misalignment(spec, torque_Nm: float, *, model: str | None = None,
                           tolerance_deg: float = ANGLE_TOLERANCE_DEG,
                           known: Sequence[Capacity] = (),
                           step: Callable[[], Any] | None = None
                           ) -> tuple[float, str, float | None, float | None, str | None]:
    """The allowable misalignment at ``torque_Nm`` (module docstring) as ``(angle_deg,
    criterion, critical_deg, capacity_limit_deg, capacity_criterion)``: ``criterion``
    ``"capacity"``, ``"critical angle"`` or ``"range"`` as :class:`AllowableLoads`;
    ``step`` as :func:`capacity_limit_deg`."""
    top = MISALIGNMENT_RANGE_DEG[1]
    critical = critical_misalignment_deg(spec)
    limit, governing = capacity_limit_deg(spec, torque_Nm, critical or top, model=model,
                                          tolerance_deg=tolerance_deg, known=known,
                                          step=step)
    if limit is not None:
        return limit, "capacity", critical, limit, governing
    if critical is not None:
        return critical, "critical angle", critical, limit, governing
    return top, "range", critical, limit, governing


def allowable_loads(spec, torque_Nm: float, *, model: str | None = None,
                    angles: int | None = None,
                    tolerance_deg: float = ANGLE_TOLERANCE_DEG,
                    known: Sequence[Capacity] = (),
                    step: Callable[[], Any] | None = None) -> AllowableLoads:
    """The allowable misalignment at ``torque_Nm`` and the machine loads over a turn there
    (module docstring): ``angles`` rotations evenly over the turn, default
    :data:`~gearcoupling.loading.PHASES` per tooth pitch
    (:func:`~gearcoupling.loading.turn_phases`: with ideal teeth as many distinct poses;
    360 rotations hold 360 / gcd(360, N) poses a pitch, 2 on 180 teeth, 360 on 37). The
    loads summed over the teeth hardly move within a pitch: their max and mean over the
    turn are within 0.13 % of a turn of 72 a pitch on 11 specs, 0.01 % on even tooth
    counts (docs/rotordynamics.md). ``model`` default the spec's; ``known`` as
    :func:`capacity_limit_deg`, ``step`` too."""
    model = resolve_model(spec, model)
    angle, criterion, critical, limit, governing = allowable_misalignment(
        spec, torque_Nm, model=model, tolerance_deg=tolerance_deg, known=known, step=step)
    turn = turn_phases(spec) if angles is None else np.arange(angles) * 360.0 / angles
    res = load(spec, angle, turn, torque_Nm=torque_Nm, model=model)
    ml = machine_loads(res)
    slip = spec.load.friction * np.sum(res.normal_force_N, axis=0)
    return AllowableLoads(float(angle), criterion, critical, limit, governing, float(torque_Nm),
                          np.asarray(res.angles_deg, float), ml["tilting_moment_Nm"],
                          ml["axial_force_N"], ml["radial_force_N"], slip)


__all__ = ["ANGLE_TOLERANCE_DEG", "AllowableLoads", "allowable_loads",
           "allowable_misalignment", "capacity_limit_deg", "known_capacities"]
