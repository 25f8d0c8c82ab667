"""The entry point :func:`wear`: a wear history of a coupling over its life."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..arguments import flag, real, resolve_torque_Nm
from ..errors import ArgumentError
from ..spec import CouplingSpec, as_spec
from .history import run_history
from .result import WearResult
from .settings import (
    DEFAULT_PHASES,
    DEFAULT_STEP_FRACTION,
    MAX_HOURS,
    Accuracy,
    DutyPoint,
    WearSettings,
    duty_points,
    gap_offsets,
)


def wear(spec: CouplingSpec | str, misalignment_deg: float | None = None,
         torque_Nm: float | None = None, speed_rpm: float | None = None,
         hours: float | None = None, *, duty: Any = None,
         coefficient_mm3_per_Nm: float | None = None, regime: str | None = None,
         limit_fraction: float | None = None, sleeve_factor: float | None = None,
         axial_float_mm: float = 0.0, gap_offset_rad: Any = None,
         step_fraction: float = DEFAULT_STEP_FRACTION, grid: tuple[int, int] | None = None,
         phases: int = DEFAULT_PHASES,
         progress: Callable[[int, int], None] | None = None,
         keep: bool = False) -> WearResult:
    """The wear of the flanks of every tooth over ``hours`` of running, and the life to the
    wear limit (docs/wear.md).

    Archard wear (depth rate ``k p |v|``, ``v`` the sliding velocity) on the hub and the
    sleeve flanks, integrated over a turn of the surface model's pressure at every rotation,
    removed along the flank normal; the loads are solved again on the worn flanks after
    every step, and a step removes at most ``step_fraction`` of the elastic approach.

    Parameters
    ----------
    spec : CouplingSpec or str
        A spec, template name or TOML path; its ``[wear]`` table gives the coefficient,
        the band, the sleeve factor, the wear limit and a required life.
    misalignment_deg, torque_Nm, speed_rpm, hours : float, optional
        One operating point: 0-6°, a non-zero signed torque (default the spec's
        ``[load]`` torque; positive loads the ccw flanks), speed > 0 and hours > 0 (default
        the spec's ``[wear]`` ``speed_rpm`` and ``hours``). The misalignment defaults to the
        spec's design angle.
    duty : sequence, optional
        Instead: several operating points, each a :class:`DutyPoint` or
        ``(misalignment_deg, torque_Nm, speed_rpm, hours)``, run interleaved, each for its
        share of the time (torques of both signs wear both flanks); ``hours`` then
        defaults to their sum.
    coefficient_mm3_per_Nm, regime, limit_fraction, sleeve_factor : optional
        Override the spec's ``[wear]`` values (docs/wear.md, The coefficient).
    axial_float_mm : float
        Amplitude of an axial float of the hub in the sleeve, once per revolution (0:
        none), for the single operating point.
    gap_offset_rad : (N,) or (2, N) float, optional
        Per-tooth gap offsets (index errors): the teeth then wear each on its own (every
        rotation of the turn is solved: ``phases`` costs N times more).
    step_fraction, grid, phases
        The accuracy knobs (:class:`Accuracy`; docs/wear.md measures them).
    progress : callable, optional
        ``progress(done, 1000)`` as the history advances.
    keep : bool
        Keep every step's solved poses (``WearResult.steps_kept``: for checks; memory
        grows with the steps).

    Returns
    -------
    WearResult

    Examples
    --------
    A short history at 1° on a coarse grid: the flanks wear, the backlash grows, and the
    life to the wear limit comes with its band across the grease regime:

    >>> import gearcoupling as gc
    >>> res = gc.wear("renzo-1967", 1.0, 2000.0, 1800.0, 100.0, grid=(16, 8), phases=1)
    >>> bool(res.backlash_mm[-1, 0] > res.backlash_mm[0, 0])
    True
    >>> lo, hi = res.life_band_h
    >>> bool(lo < res.life_h < hi)
    True
    """
    spec = as_spec(spec)
    settings = WearSettings.from_spec(spec, coefficient_mm3_per_Nm=coefficient_mm3_per_Nm,
                                      regime=regime, limit_fraction=limit_fraction,
                                      sleeve_factor=sleeve_factor)
    accuracy = Accuracy.checked(step_fraction, grid if grid is not None else
                                Accuracy().grid, phases)
    if duty is not None:
        for name, value in (("misalignment_deg", misalignment_deg), ("torque_Nm", torque_Nm),
                            ("speed_rpm", speed_rpm)):
            if value is not None:
                raise ArgumentError(name, value, "give the duty or one operating point, not "
                                    "both")
        points = duty_points(duty)
        total = sum(p.hours for p in points)
    else:
        torque = resolve_torque_Nm(spec, torque_Nm, zero=False)
        mis = misalignment_deg if misalignment_deg is not None else \
            spec.design_misalignment_deg
        speed = speed_rpm if speed_rpm is not None else settings.speed_rpm
        if speed is None:
            raise ArgumentError("speed_rpm", None, "a speed > 0 rpm (or the spec's [wear] "
                                "speed_rpm)")
        points = (DutyPoint.checked(mis, torque, speed, hours if hours is not None else
                                    settings.hours, axial_float_mm=axial_float_mm),)
        total = points[0].hours
    run = real(hours if hours is not None else total, "hours", 0.0, MAX_HOURS,
               open_lo=True, unit="h")
    return run_history(spec, points, settings, accuracy, run,
                       gap_offset_rad=gap_offsets(gap_offset_rad, spec.tooth.teeth),
                       progress=progress, keep=flag(keep, "keep"))


__all__ = ["wear"]
