"""What a wear history runs on: the duty's operating points, the ``[wear]`` settings and the
accuracy knobs, each a frozen dataclass checked when made.

Values from the spec's ``[wear]`` table are refused with a :class:`SpecError` naming
``wear.<key>``; call arguments and command-line options with an :class:`ArgumentError`
naming the argument.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..arguments import ErrorType, count, real, torque_Nm
from ..errors import ArgumentError, SpecError
from ..loading import LOAD_GRID
from ..spec import CouplingSpec, check_misalignment_deg
from .coefficients import DEFAULT_REGIME, REGIMES

MAX_SPEED_RPM = 1e6
MAX_HOURS = 1e7  # a history's hours (over a thousand years)
MAX_FLOAT_MM = 100.0
DEFAULT_LIMIT_FRACTION = 0.1  # wear limit: this share of the tooth thickness (our choice)
DEFAULT_STEP_FRACTION = 0.5  # a step removes at most this share of the elastic approach
DEFAULT_PHASES = 2  # rotations per tooth pitch of a turn
DEFAULT_GRID = LOAD_GRID  # the surface model's cells of a loaded tooth (docs/wear.md)
MAX_PHASES = 64
FLOAT_PHASES = 8  # samples of an axial float's cycle
LIFE_CAP_H = 1e9  # the largest life reported (h); a longer one is reported as this


@dataclass(frozen=True)
class DutyPoint:
    """One duty point: an operating point of a wear duty (not the pipeline's
    :class:`gearcoupling.OperatingPoint`).

    Attributes
    ----------
    misalignment_deg : float
        0-6 degrees.
    torque_Nm : float
        Signed (positive loads the ccw flanks), non-zero.
    speed_rpm : float
        > 0.
    hours : float
        This point's share of the duty (> 0): the duty runs its points interleaved, each
        for its share of the time.
    axial_float_mm : float
        Amplitude of an axial reciprocation of the hub in the sleeve (0: none), ``u = a sin
        phi``, ``float_cycles_per_rev`` cycles per revolution, its phase independent of the
        rotation (every tooth sees every phase at every turning angle).
    """

    misalignment_deg: float
    torque_Nm: float
    speed_rpm: float
    hours: float
    axial_float_mm: float = 0.0
    float_cycles_per_rev: float = 1.0

    @classmethod
    def checked(cls, misalignment_deg: Any, torque: Any, speed_rpm: Any, hours: Any, *,
                axial_float_mm: Any = 0.0, float_cycles_per_rev: Any = 1.0, where: str = ""
                ) -> DutyPoint:
        """A point from call arguments, each refused with an :class:`ArgumentError` naming
        ``where`` + the argument."""
        return cls(check_misalignment_deg(misalignment_deg, f"{where}misalignment_deg",
                                          ArgumentError),
                   torque_Nm(torque, f"{where}torque_Nm", zero=False),
                   real(speed_rpm, f"{where}speed_rpm", 0.0, MAX_SPEED_RPM, open_lo=True,
                        unit="rpm"),
                   real(hours, f"{where}hours", 0.0, MAX_HOURS, open_lo=True, unit="h"),
                   real(axial_float_mm, f"{where}axial_float_mm", 0.0, MAX_FLOAT_MM,
                        unit="mm"),
                   real(float_cycles_per_rev, f"{where}float_cycles_per_rev", 0.0, 1e3,
                        open_lo=True))

    @property
    def revolutions_per_hour(self) -> float:
        return 60.0 * self.speed_rpm


def duty_points(points: Any) -> tuple[DutyPoint, ...]:
    """A duty: a non-empty sequence of :class:`DutyPoint` (or of ``(misalignment_deg,
    torque_Nm, speed_rpm, hours)``), at most 64."""
    if isinstance(points, DutyPoint):
        points = [points]
    if isinstance(points, str | bytes | dict) or not hasattr(points, "__len__") \
            or not 1 <= len(points) <= 64:
        raise ArgumentError("duty", points, "a list of 1 to 64 operating points "
                            "(misalignment_deg, torque_Nm, speed_rpm, hours)")
    out = []
    for i, p in enumerate(points):
        if isinstance(p, DutyPoint):
            p = (p.misalignment_deg, p.torque_Nm, p.speed_rpm, p.hours, p.axial_float_mm,
                 p.float_cycles_per_rev)
        if isinstance(p, str | bytes | dict) or not hasattr(p, "__len__") \
                or not 4 <= len(p) <= 6:
            raise ArgumentError(f"duty[{i}]", p, "(misalignment_deg, torque_Nm, speed_rpm, "
                                "hours[, axial_float_mm[, float_cycles_per_rev]])")
        extra = dict(zip(("axial_float_mm", "float_cycles_per_rev"), p[4:], strict=False))
        out.append(DutyPoint.checked(*p[:4], **extra, where=f"duty[{i}]."))
    return tuple(out)


def gap_offsets(gap_offset_rad: Any, teeth: int) -> NDArray[np.float64] | None:
    """Per-tooth gap offsets as ``load`` takes them, ``(N,)`` (both flanks) or ``(2, N)``
    finite radians, as an array (None stays None)."""
    if gap_offset_rad is None:
        return None
    allowed = f"finite radians shaped ({teeth},) or (2, {teeth})"
    try:
        off = np.asarray(gap_offset_rad, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError("gap_offset_rad", gap_offset_rad, allowed) from None
    if off.shape not in ((teeth,), (2, teeth)) or not np.all(np.isfinite(off)):
        raise ArgumentError("gap_offset_rad", f"shape {off.shape}", allowed)
    return off


@dataclass(frozen=True)
class WearSettings:
    """The ``[wear]`` settings, resolved.

    Attributes
    ----------
    regime : str
        ``oil``, ``grease`` or ``dry`` (:data:`~.coefficients.REGIMES`).
    coefficient_mm3_per_Nm : float
        Archard's dimensional coefficient of the hub flanks (default: the regime's).
    band_mm3_per_Nm : (float, float)
        The coefficients the answer is also given for (default: the regime's range, widened
        to hold the coefficient).
    sleeve_factor : float
        The sleeve flanks' coefficient over the hub's (0: a sleeve that does not wear).
    limit_fraction : float
        The wear limit: a tooth's thickness loss as a share of its thickness.
    required_life_h : float or None
        Judged against the life where given.
    speed_rpm, hours : float or None
        The speed and the hours of running at the pipeline's operating point (its angle
        and torque): where both are given the spec asks for wear, and ``gc.run`` and
        ``gc.report`` compute it (the stage ``wear``); :func:`~.api.wear` takes them as
        its defaults.
    """

    regime: str = DEFAULT_REGIME
    coefficient_mm3_per_Nm: float = REGIMES[DEFAULT_REGIME].nominal
    band_mm3_per_Nm: tuple[float, float] = (REGIMES[DEFAULT_REGIME].low,
                                            REGIMES[DEFAULT_REGIME].high)
    sleeve_factor: float = 1.0
    limit_fraction: float = DEFAULT_LIMIT_FRACTION
    required_life_h: float | None = None
    speed_rpm: float | None = None
    hours: float | None = None
    source: str = field(default=REGIMES[DEFAULT_REGIME].source, compare=False)

    @classmethod
    def from_spec(cls, spec: CouplingSpec, **overrides: Any) -> WearSettings:
        """The spec's ``[wear]`` table (:class:`SpecError` naming ``wear.<key>``), then
        ``overrides`` of the same names (:class:`ArgumentError`)."""
        given = dict(spec.wear)
        bad = sorted(set(overrides) - set(_KEYS))
        if bad:
            raise ArgumentError(bad[0], overrides[bad[0]], f"not a wear setting: one of "
                                f"{', '.join(_KEYS)}")
        values = {k: _check(k, v, "wear.", SpecError) for k, v in given.items()}
        values.update({k: _check(k, v, "", ArgumentError) for k, v in overrides.items()
                       if v is not None})
        regime = REGIMES[values.get("regime", DEFAULT_REGIME)]
        k = values.get("coefficient_mm3_per_Nm", regime.nominal)
        if "coefficient_band_mm3_per_Nm" in values:
            lo, hi = values["coefficient_band_mm3_per_Nm"]
            if not lo <= k <= hi:
                field_ = ("coefficient_band_mm3_per_Nm" if "coefficient_band_mm3_per_Nm"
                          in overrides else "wear.coefficient_band_mm3_per_Nm")
                raise (ArgumentError if not field_.startswith("wear.") else SpecError)(
                    field_, [lo, hi], f"must hold the coefficient {k:g} mm³/(N·m)")
        else:
            lo, hi = min(regime.low, k), max(regime.high, k)
        return cls(regime.name, k, (lo, hi), values.get("sleeve_factor", 1.0),
                   values.get("limit_fraction", DEFAULT_LIMIT_FRACTION),
                   values.get("required_life_h"), values.get("speed_rpm"),
                   values.get("hours"), regime.source)


_KEYS = ("regime", "coefficient_mm3_per_Nm", "coefficient_band_mm3_per_Nm", "sleeve_factor",
         "limit_fraction", "required_life_h", "speed_rpm", "hours")


def _check(key: str, value: Any, prefix: str, error: ErrorType) -> Any:
    """One ``[wear]`` value, or ``error(prefix + key, value, what is allowed)``."""
    name = prefix + key
    if key == "regime":
        if isinstance(value, str) and value in REGIMES:
            return value
        raise error(name, value, f"one of {', '.join(REGIMES)}")
    if key == "coefficient_band_mm3_per_Nm":
        ok = isinstance(value, list | tuple) and len(value) == 2
        band = [real(v, name, 0.0, 1.0, open_lo=True, error=error) for v in value] if ok \
            else []
        if not ok or band[0] > band[1]:
            raise error(name, value, "two coefficients [low, high], 0 < low <= high <= 1 "
                        "mm³/(N·m)")
        return tuple(band)
    if key == "coefficient_mm3_per_Nm":
        return real(value, name, 0.0, 1.0, open_lo=True, unit="mm³/(N·m)", error=error)
    if key == "sleeve_factor":
        return real(value, name, 0.0, 1e3, error=error)
    if key == "limit_fraction":
        return real(value, name, 0.0, 1.0, open_lo=True, open_hi=True, error=error)
    if key == "speed_rpm":
        return real(value, name, 0.0, MAX_SPEED_RPM, open_lo=True, unit="rpm", error=error)
    if key == "hours":
        return real(value, name, 0.0, MAX_HOURS, open_lo=True, unit="h", error=error)
    return real(value, name, 0.0, 1e9, open_lo=True, unit="h", error=error)


@dataclass(frozen=True)
class Accuracy:
    """The accuracy knobs (docs/wear.md measures each one's cost and effect).

    Attributes
    ----------
    step_fraction : float
        A step removes at most this share of the current elastic approach at the most
        worn point, (0, 1].
    grid : (int, int)
        The surface model's cells (along the face, across the depth) of a loaded tooth;
        the depth maps have the same rows and four times the cells along the face.
    phases : int
        Rotations per tooth pitch of a turn, 1-64.
    """

    step_fraction: float = DEFAULT_STEP_FRACTION
    grid: tuple[int, int] = DEFAULT_GRID
    phases: int = DEFAULT_PHASES

    @classmethod
    def checked(cls, step_fraction: Any = DEFAULT_STEP_FRACTION, grid: Any = DEFAULT_GRID,
                phases: Any = DEFAULT_PHASES) -> Accuracy:
        f = real(step_fraction, "step_fraction", 0.0, 1.0, open_lo=True)
        try:
            nf, nd = (count(v, "grid", 4, 512) for v in grid)
        except TypeError:
            raise ArgumentError("grid", grid, "(cells along the face, cells across the "
                                "depth), each 4-512") from None
        return cls(f, (nf, nd), count(phases, "phases", 1, MAX_PHASES))


__all__ = ["DEFAULT_LIMIT_FRACTION", "DEFAULT_PHASES", "DEFAULT_STEP_FRACTION",
           "FLOAT_PHASES", "LIFE_CAP_H", "Accuracy", "DutyPoint", "WearSettings",
           "duty_points", "gap_offsets"]
