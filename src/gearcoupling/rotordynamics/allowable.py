"""The allowable misalignment at a torque and the loads the coupling puts on the shafts there.

The allowable misalignment is the smaller of the critical angle (the pivot teeth's
contact runs onto a face end, :func:`gearcoupling.critical_misalignment_deg`) and the
largest angle at which the capacity still carries the torque (bisection on
:func:`gearcoupling.capacity`, which falls with the angle), within the supported 0-6°.
There the coupling's machine loads over a turn: the bending moment on the hub (normal
and friction forces about ``O``, perpendicular to the hub axis), the thrust along the hub
axis and the radial force (both cancel between opposite teeth for an even tooth count),
and the axial slip force (friction times the tooth normal loads: the thrust that slides
the teeth when the shafts move axially), with their extremes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..clearance import critical_misalignment_deg
from ..loading import capacity, load, machine_loads
from ..spec import MISALIGNMENT_RANGE_DEG
from .stiffness import DATASHEET_MODEL

DEFAULT_TURN_ANGLES = 360
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
                       tolerance_deg: float = ANGLE_TOLERANCE_DEG
                       ) -> tuple[float | None, str | None]:
    """The largest misalignment up to ``top_deg`` whose capacity carries ``|torque_Nm|``
    (``None`` when ``top_deg`` still does) and the criterion that governs there."""
    need = abs(torque_Nm)

    def carries(deg: float) -> tuple[bool, str]:
        c = capacity(spec, deg, model=model)
        return c.capacity_Nm is None or c.capacity_Nm >= need, c.governing

    ok, governing = carries(top_deg)
    if ok:
        return None, None
    ok, _ = carries(0.0)
    if not ok:
        return 0.0, governing
    lo, hi = 0.0, top_deg
    while hi - lo > tolerance_deg:
        mid = 0.5 * (lo + hi)
        ok, g = carries(mid)
        if ok:
            lo = mid
        else:
            hi, governing = mid, g
    return lo, governing


def allowable_loads(spec, torque_Nm: float, *, model: str | None = None,
                    angles: int = DEFAULT_TURN_ANGLES,
                    tolerance_deg: float = ANGLE_TOLERANCE_DEG) -> AllowableLoads:
    """The allowable misalignment at ``torque_Nm`` and the machine loads over a turn there
    (``angles`` rotations; module docstring); ``model`` default
    :data:`~.stiffness.DATASHEET_MODEL`."""
    model = DATASHEET_MODEL if model is None else model
    top = MISALIGNMENT_RANGE_DEG[1]
    critical = critical_misalignment_deg(spec)
    limit, governing = capacity_limit_deg(spec, torque_Nm, critical or top, model=model,
                                          tolerance_deg=tolerance_deg)
    if limit is not None:
        angle, criterion = limit, "capacity"
    elif critical is not None:
        angle, criterion = critical, "critical angle"
    else:
        angle, criterion = top, "range"
    res = load(spec, angle, np.arange(angles) * 360.0 / angles, torque_Nm=torque_Nm,
               model=model)
    ml = machine_loads(res)
    slip = spec.load.friction * np.sum(res.normal_force_N, axis=0)
    return AllowableLoads(float(angle), criterion, critical, limit, governing, float(torque_Nm),
                          np.asarray(res.angles_deg, float), ml["tilting_moment_Nm"],
                          ml["axial_force_N"], ml["radial_force_N"], slip)


__all__ = ["AllowableLoads", "allowable_loads", "capacity_limit_deg"]
