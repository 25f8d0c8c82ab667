"""A load model against the misaligned finite-element sector at one pose.

The model (:func:`gearcoupling.load`) solves the pose at the torque; the finite-element
sector (:func:`gearcoupling.fea.fe_sector_at_loads`, which runs the FE) is then centred on
the model's most loaded tooth and turned by the model's wind-up plus the bodies' torsion
(:func:`body_windup_rad`), the same total the aligned reference measures. Equal wind-up,
since a sector cannot be given its share of the torque: the share is the answer sought.
The teeth at least two pitches from a cut are the compared ones (their loads change by
little when the sector grows: docs/fea.md has the measured figure).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from ..arguments import TORQUE_RANGE_NM, real
from ..clearance import sweep
from ..errors import ArgumentError
from ..fea import FESectorResult, check_sector, fe_sector_at_loads
from ..spec import CouplingSpec, as_spec, check_misalignment_deg
from .api import load, load_from_sweep
from .body import body_windup_rad
from .inputs import resolve_torque_Nm
from .models.registry import resolve_model


@dataclass(frozen=True)
class SectorCheck:
    """A model and the FE sector at one pose. Lists follow ``fe.teeth``; ``compared``
    indexes the teeth far enough from the cuts; ``ratio`` is FE / model tooth load there."""

    model: str
    stiffness: str
    torque_Nm: float
    model_windup_rad: float
    body_rad: float
    model_tangential_force_N: list[float]
    model_peak_pressure_MPa: list[float]
    compared: list[int]
    ratio: list[float]
    fe: FESectorResult

    def to_dict(self) -> dict:
        """Plain values, for ``fea_contact.json``."""
        return asdict(self)


def sector_check(spec: CouplingSpec, misalignment_deg: float, *, rotation_deg: float = 0.0,
                 torque_Nm: float | None = None, model: str | None = None, sector: int = 5,
                 size_mm: float | None = None, workdir=None) -> SectorCheck:
    """Compare ``model`` with the FE sector at one misaligned pose (module docstring).

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg, rotation_deg : float
        The pose, as in :func:`gearcoupling.load`.
    torque_Nm : float, optional
        Default the spec's load torque.
    model : str, optional
        Default the spec's load model; its tooth springs are the spec's ``load.stiffness``.
    sector : int
        Teeth in the FE sector, at least 5 (the accuracy knob of the cut conditions).
    size_mm : float, optional
        FE element size on the teeth (default module / 4).
    workdir : path, optional
        Keep the solver's deck, log and printout here.
    """
    spec = as_spec(spec)
    check_sector(spec, sector)
    T = resolve_torque_Nm(spec, torque_Nm)
    check_misalignment_deg(misalignment_deg, error=ArgumentError)
    real(rotation_deg, "rotation_deg", unit="degrees")
    resolve_model(spec, model)
    if not T > 0:
        raise ArgumentError("torque_Nm", T, "a torque above 0 N·m: unloaded, nothing touches")
    res = load(spec, misalignment_deg, [rotation_deg], torque_Nm=T, model=model)
    W = res.tangential_force_N[:, 0]
    body = body_windup_rad(spec, T)["body_rad"]
    fe, compared, ratio = fe_sector_at_loads(
        spec, W, misalignment_deg=misalignment_deg, rotation_deg=rotation_deg,
        windup_rad=float(res.windup_rad[0]) + body, sector=sector, size_mm=size_mm,
        workdir=workdir)
    return SectorCheck(model=res.model, stiffness=spec.load.stiffness, torque_Nm=T,
                       model_windup_rad=float(res.windup_rad[0]), body_rad=body,
                       model_tangential_force_N=[float(W[t]) for t in fe.teeth],
                       model_peak_pressure_MPa=[float(res.max_pressure_MPa[t, 0])
                                                for t in fe.teeth],
                       compared=compared, ratio=ratio, fe=fe)


def loads_at_windup(spec: CouplingSpec, misalignment_deg: float, rotation_deg: float,
                    windup_rad: float, *, model: str | None = None,
                    rtol: float = 1e-4) -> tuple[float, np.ndarray]:
    """The torque (N m) at which ``model`` plus the bodies' torsion winds up by
    ``windup_rad`` at one pose, and its tangential tooth loads ``(N,)`` there: a model
    compared with the FE sector at equal wind-up (module docstring). ``rtol``: the
    torque's relative tolerance."""
    if not (isinstance(windup_rad, int | float) and math.isfinite(windup_rad)):
        raise ArgumentError("windup_rad", windup_rad, "a finite turn in rad")

    sw = sweep(spec, misalignment_deg, [rotation_deg])  # the pose's gaps: one sweep

    def excess(T: float) -> float:
        res = load_from_sweep(sw, torque_Nm=T, model=model)
        return float(res.windup_rad[0]) + body_windup_rad(spec, T)["body_rad"] - windup_rad

    t_min, t_max = TORQUE_RANGE_NM
    lo = hi = min(max(abs(spec.load.torque_Nm or 1000.0), t_min), t_max)
    f_lo = f_hi = excess(lo)
    while f_lo > 0 or f_hi < 0:  # bracket the root by halving and doubling, within the range
        if f_lo > 0:
            if lo == t_min:
                raise ArgumentError("windup_rad", windup_rad, "a turn beyond the pose's first "
                                    f"touch (reached at {t_min:g} N·m)")
            lo = max(lo / 2.0, t_min)
            f_lo = excess(lo)
        else:
            if hi == t_max:
                raise ArgumentError("windup_rad", windup_rad, f"a turn reached below "
                                    f"{t_max:g} N·m")
            hi = min(hi * 2.0, t_max)
            f_hi = excess(hi)
    from scipy.optimize import brentq  # at the call: `import gearcoupling` stays light

    T = float(brentq(excess, lo, hi, rtol=rtol)) if lo < hi else lo
    return T, load_from_sweep(sw, torque_Nm=T, model=model).tangential_force_N[:, 0]
