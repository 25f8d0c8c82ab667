"""Torsional stiffness: the wind-up curve from zero to the capacity, secant and tangent.

The wind-up of the teeth from first touch (the rotation beyond the smallest gap, mean
over the rotations of one pitch) plus the bodies' torsion (``gc.body_windup_rad``, bore
to sleeve outside diameter), at torques from zero to the capacity at the misalignment.
The secant stiffness is the operating torque over that wind-up; the tangent stiffness is
``dT/dchi`` there, the torsion entry of the stiffness matrix (the same difference).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..clearance import SweepResult
from ..errors import ArgumentError
from ..loading import body_windup_rad, load_from_sweep

#: torques on the wind-up curve: placed at ``(i / (n - 1))^2`` of its end, closer where it
#: bends most (near zero), 6 draw it within 2.1 % of its end on the templates, where 11
#: evenly placed drew it within 4.4 % (docs/rotordynamics.md, "Speed and knobs")
DEFAULT_POINTS = 6


@dataclass(frozen=True, eq=False)
class TorsionalStiffness:
    """The wind-up curve and the stiffnesses at the operating torque.

    Attributes
    ----------
    torque_Nm : (n,) float
        From 0 to the curve's end, signed like the operating torque.
    mesh_windup_rad, body_windup_rad : (n,) float
        The teeth's wind-up from first touch (mean over one pitch) and the bodies' torsion,
        signed like the torque; their sum is :attr:`windup_rad`.
    operating_torque_Nm : float
    secant_Nm_per_rad, tangent_Nm_per_rad : float
        At the operating torque, bodies included.
    capacity_Nm : float or None
        The capacity at the misalignment (``None``: no criterion limits it); the curve ends
        there, or at twice the operating torque without a capacity, and never below the
        operating torque.
    """

    torque_Nm: NDArray[np.float64]
    mesh_windup_rad: NDArray[np.float64]
    body_windup_rad: NDArray[np.float64]
    operating_torque_Nm: float
    secant_Nm_per_rad: float
    tangent_Nm_per_rad: float
    capacity_Nm: float | None

    @property
    def windup_rad(self) -> NDArray[np.float64]:
        return self.mesh_windup_rad + self.body_windup_rad

    def rows(self):
        """``(torque_Nm, mesh_windup_rad, body_windup_rad, windup_rad)`` per point."""
        return zip(self.torque_Nm.tolist(), self.mesh_windup_rad.tolist(),
                   self.body_windup_rad.tolist(), self.windup_rad.tolist(), strict=True)

    def as_dict(self) -> dict[str, Any]:
        return {"operating_torque_Nm": self.operating_torque_Nm,
                "secant_Nm_per_rad": self.secant_Nm_per_rad,
                "tangent_Nm_per_rad": self.tangent_Nm_per_rad, "capacity_Nm": self.capacity_Nm,
                "curve": {"torque_Nm": self.torque_Nm.tolist(),
                          "mesh_windup_rad": self.mesh_windup_rad.tolist(),
                          "body_windup_rad": self.body_windup_rad.tolist(),
                          "windup_rad": self.windup_rad.tolist()}}


def mesh_windup_from_touch(sw: SweepResult, torque_Nm: float, model: str | None) -> float:
    """The teeth's wind-up beyond first touch at ``torque_Nm``, mean over the sweep's
    rotations (signed like the torque; 0 at zero torque)."""
    if torque_Nm == 0:
        return 0.0
    return windup_beyond_touch(load_from_sweep(sw, torque_Nm=torque_Nm, model=model))


def windup_beyond_touch(res) -> float:
    """:func:`mesh_windup_from_touch` of a solved load result ``res`` (a ``LoadResult``)."""
    beyond = np.abs(res.windup_rad) - np.min(res.gap_angle_rad, axis=0)
    return math.copysign(float(np.mean(beyond)), res.torque_Nm)


def windup_torques(torque_Nm: float, capacity_Nm: float | None,
                   points: int = DEFAULT_POINTS) -> NDArray[np.float64]:
    """The curve's torques ``(points,)`` or ``(points + 1,)``: from 0 to the capacity (twice
    the torque without one, never below the torque) at ``(i / (points - 1))^2`` of it
    (closer near zero, where the wind-up bends most), the torque among them, signed like
    it."""
    if isinstance(points, bool) or not isinstance(points, int) or not 2 <= points <= 1000:
        raise ArgumentError("points", points, "a whole number of torques from 2 to 1000")
    T = float(torque_Nm)
    top = 2.0 * abs(T) if capacity_Nm is None else max(float(capacity_Nm), abs(T))
    share = np.linspace(0.0, 1.0, points) ** 2
    return np.unique(np.append(share * top, abs(T))) * math.copysign(1.0, T)


def torsion_from_curve(spec, grid: NDArray[np.float64], mesh_windup_rad: ArrayLike,
                       torque_Nm: float, tangent_Nm_per_rad: float,
                       capacity_Nm: float | None) -> TorsionalStiffness:
    """:class:`TorsionalStiffness` of the teeth's wind-up ``mesh_windup_rad`` at the torques
    ``grid`` (:func:`windup_torques`), the bodies' torsion added."""
    T = float(torque_Nm)
    mesh = np.asarray(mesh_windup_rad, float)
    body = np.array([body_windup_rad(spec, t)["body_rad"] for t in grid])
    at = int(np.argmin(np.abs(grid - T)))
    secant = abs(T) / float(abs(mesh[at] + body[at]))
    return TorsionalStiffness(grid, mesh, body, T, secant, float(tangent_Nm_per_rad),
                              capacity_Nm)


__all__ = ["TorsionalStiffness", "mesh_windup_from_touch", "torsion_from_curve",
           "windup_beyond_touch", "windup_torques"]
