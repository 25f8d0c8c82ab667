"""The clearance-vs-θ plot: one sweep over a pitch, and the current teeth marked on it."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...clearance import sweep
from ...errors import ArgumentError
from ...spec import CouplingSpec
from .pose import VIEW_SWEEP_TOLERANCE_MM, PoseState, check_pose

DEFAULT_PLOT_SAMPLES = 720


@dataclass(frozen=True)
class ClearanceCurve:
    """Clearance of one tooth against its turning angle at one misalignment.

    Attributes
    ----------
    theta_deg : (n,) float
        Sorted turning angles in ``[0, 360)``.
    clearance_mm : (2, n) float
        Circumferential clearance of the cw and ccw flank.
    """

    misalignment_deg: float
    theta_deg: NDArray[np.float64]
    clearance_mm: NDArray[np.float64]


def clearance_curve(spec: CouplingSpec,
                    misalignment_deg: float, samples: int = DEFAULT_PLOT_SAMPLES, *,
                    tolerance_mm: float = VIEW_SWEEP_TOLERANCE_MM) -> ClearanceCurve:
    """Clearance against θ from one sweep over one pitch (every tooth gives its θ).

    ``samples`` turning angles over 360° (rounded up to a multiple of the tooth count).
    """
    if not (isinstance(samples, int | np.integer) and samples >= 8):
        raise ArgumentError("samples", samples, "must be a whole number >= 8")
    mis, _ = check_pose(misalignment_deg, 0.0)
    n = spec.tooth.teeth
    per_pitch = max(1, math.ceil(samples / n))
    psi = np.arange(per_pitch) * (360.0 / n / per_pitch)
    res = sweep(spec, mis, psi, tolerance_mm=tolerance_mm)
    theta = res.theta_deg.ravel()
    order = np.argsort(theta, kind="stable")
    clear = res.clearance_mm.reshape(2, -1)[:, order]
    return ClearanceCurve(mis, theta[order], clear)


def plot_series(curve: ClearanceCurve, state: PoseState) -> tuple[NDArray, ...]:
    """Plot data ``(x, cw, ccw, cw_now, ccw_now, tooth0)`` on one shared x axis (degrees).

    ``x`` merges the curve's θ with the current θ of every tooth; ``cw``/``ccw`` are the
    curve (interpolated at the merged points, periodic in θ); ``*_now`` hold the exact
    clearance of each tooth at the current pose where ``x`` is that tooth's θ, NaN
    elsewhere (drawn as markers); ``tooth0`` is the smaller of tooth 0's two clearances
    at its θ = ψ (the current angle), NaN elsewhere. Infinite clearances (no contact)
    become NaN (gaps).
    """
    now = np.mod(state.theta_deg, 360.0)
    x = np.concatenate([curve.theta_deg, now])
    order = np.argsort(x, kind="stable")
    x = x[order]
    xp = np.concatenate([curve.theta_deg - 360.0, curve.theta_deg, curve.theta_deg + 360.0])
    out = [x]
    for f in range(2):
        c = curve.clearance_mm[f]
        fp = np.concatenate([c, c, c])
        finite = np.isfinite(fp)
        y = np.interp(x, xp[finite], fp[finite]) if np.any(finite) else np.full(x.shape, np.nan)
        out.append(y)
    blank = np.full(curve.theta_deg.size, np.nan)
    for f in range(2):
        out.append(np.concatenate([blank, state.clearance_mm[f]])[order])
    first = np.full(now.size, np.nan)
    first[0] = np.min(state.clearance_mm[:, 0])
    out.append(np.concatenate([blank, first])[order])
    return tuple(np.where(np.isfinite(a), a, np.nan) for a in out)


def plot_range(series: tuple[NDArray, ...], pad: float = 0.08) -> tuple[float, float]:
    """A fixed y range ``(lo, hi)`` (mm) covering every finite value of the y series.

    The plot sets it explicitly: uPlot's automatic range breaks on a NaN first sample,
    which the marker series have.
    """
    ys = np.concatenate([np.asarray(a, dtype=float).ravel() for a in series[1:]])
    ys = ys[np.isfinite(ys)]
    if ys.size == 0:
        return -1.0, 1.0
    lo, hi = float(ys.min()), float(ys.max())
    span = hi - lo if hi > lo else max(abs(hi), 1e-3)
    return lo - pad * span, hi + pad * span
