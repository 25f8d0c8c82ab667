"""Arguments checked one way: numbers, counts, tolerances, angle lists and torques, with the
documented maximum of every size-like argument in one table (:data:`MAXIMA`).

A number argument is an ``int``, a ``float`` or a numpy number: never ``bool`` and never
text (``"100"`` is refused wherever a number is wanted). Text from the command line is
read by :func:`parse_number` and :func:`parse_count`, which take digits as a person writes
them: ``0_5``, ``1,5``, ``0x10``, non-ASCII digits, ``nan`` and ``inf`` are refused.
Errors are :class:`~gearcoupling.errors.ArgumentError` (a call argument) or, with
``error=SpecError``, a spec or study value; each names the field, the value as given and
what is allowed.
"""

from __future__ import annotations

import math
import numbers
import re
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .errors import ArgumentError, SpecError

ErrorType = type[ArgumentError] | type[SpecError]

#: the largest value of every size-like argument (each costs time or memory in
#: proportion); the docs (docs/spec-and-cli.md, "Ranges") list the same
MAXIMA: dict[str, int] = {
    "angles": 100_000,         # rotations per turn of a sweep or load
    "grid": 1_000,             # coarse planes over the face width in the sweep kernel
    "steps": 1_000,            # rotations per tooth pitch of the design searches
    "points": 10_001,          # points of a measuring chart or a hob table
    "misalignments": 200,      # misalignments of a capacity curve
    "poses": 3_600,            # poses of a mesh interference check
    "samples": 1_000_000,      # samples of a study (each is a sweep or more)
    "fit_points": 1_000_000,   # scan points of a registration
}

#: |torque| of a loaded coupling in N·m, the same for every entry point (load, report,
#: capacity, FE, ``[load] torque_Nm``): far beyond any coupling at the top (the contact
#: laws overflow past ~1e150), and below the bottom the loads underflow. 0 is unloaded.
TORQUE_RANGE_NM = (1e-9, 1e9)

#: accuracy of a clearance minimum in mm (the sweep kernel and its flank table): below
#: the bottom the rounding of the coordinates dominates
SWEEP_TOLERANCE_RANGE_MM = (1e-12, 0.1)

#: the default accuracy of every clearance minimum and of the flank table in mm (sweep,
#: design angles, load, studies, report, command line): one value everywhere
GAP_TOLERANCE_MM = 1e-7

#: the default rotations per tooth pitch of a turn's loads (``loading.turn_phases``): with
#: ideal teeth a turn holds only these poses
PHASES = 8

#: the default coarse planes over the face width of the sweep kernel
SWEEP_GRID = 17

#: tolerances of the design-angle searches in degrees (bisection and Brent's method);
#: below the bottom they cost more than the geometry is worth, above the top they are
#: no answer
ANGLE_TOLERANCE_RANGE_DEG = (1e-9, 0.5)

_NUMBER = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_WHOLE = re.compile(r"[+-]?[0-9]+")

def parse_number(text: str, field: str, *, nonfinite: bool = False,
                 error: ErrorType = ArgumentError) -> float:
    """A number written on the command line: optional sign, ASCII digits, an optional
    point and exponent (``-1.5e3``); ``inf``/``-inf`` only with ``nonfinite``. Anything
    else (``0_5``, ``1,5``, ``0x10``, ``nan``, ``١``) is ``error(field, text, ...)``."""
    t = text.strip()
    if _NUMBER.fullmatch(t):
        value = float(t)
        if math.isfinite(value):
            return value
        raise error(field, text, "too large for a number")
    if nonfinite and t.lower() in ("inf", "+inf", "-inf", "infinity", "+infinity",
                                   "-infinity"):
        return float(t)
    raise error(field, text, "not a number as written by hand (digits, an optional "
                "sign, point and exponent, e.g. 0.5 or 2e3" + (", or inf" if nonfinite else "")
                + ")")


def parse_count(text: str, field: str, *, error: ErrorType = ArgumentError) -> int:
    """A whole number written on the command line (ASCII digits, optional sign)."""
    t = text.strip()
    if not _WHOLE.fullmatch(t):
        raise error(field, text, "not a whole number (digits only, e.g. 12)")
    return int(t)


def is_real(value: Any) -> bool:
    """Whether ``value`` is a real number of Python or numpy (not ``bool``, not text)."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)


def real(value: Any, field: str, lo: float = -math.inf, hi: float = math.inf, *,
         open_lo: bool = False, open_hi: bool = False, unit: str = "",
         nonfinite: bool = False, error: ErrorType = ArgumentError) -> float:
    """``value`` as a float when it is a real number in the range (finite unless
    ``nonfinite``; NaN never); else ``error(field, value, what is allowed)``."""
    ok = is_real(value) and not math.isnan(value) and (nonfinite or math.isfinite(value))
    if ok:
        v = float(value)
        ok = (lo < v if open_lo else lo <= v) and (v < hi if open_hi else v <= hi)
        if ok:
            return v
    raise error(field, value, f"must be a {'' if nonfinite else 'finite '}number"
                + _range_text(lo, hi, open_lo, open_hi, unit))


def _range_text(lo: float, hi: float, open_lo: bool, open_hi: bool, unit: str) -> str:
    u = f" {unit}" if unit else ""
    if math.isinf(lo) and math.isinf(hi):
        return f"{' in ' + unit if unit else ''}"
    if math.isinf(hi):
        return f" {'>' if open_lo else '>='} {lo:g}{u}"
    if math.isinf(lo):
        return f" {'<' if open_hi else '<='} {hi:g}{u}"
    return f" in {'(' if open_lo else '['}{lo:g}, {hi:g}{')' if open_hi else ']'}{u}"


def positive(value: Any, field: str, hi: float = math.inf, *, unit: str = "mm",
             error: ErrorType = ArgumentError) -> float:
    """A finite number > 0 (a length, tolerance or size), at most ``hi``."""
    return real(value, field, 0.0, hi, open_lo=True, unit=unit, error=error)


def count(value: Any, field: str, lo: int = 1, hi: int | None = None, *,
          error: ErrorType = ArgumentError) -> int:
    """A whole number (``int`` or numpy integer, not ``bool``) from ``lo`` to ``hi``
    (default: :data:`MAXIMA` ``[field]`` where the field is listed there)."""
    top = MAXIMA.get(field) if hi is None else hi
    if isinstance(value, numbers.Integral) and not isinstance(value, bool | np.bool_):
        v = int(value)
        if lo <= v and (top is None or v <= top):
            return v
    raise error(field, value, f"must be a whole number from {lo}"
                + (f" to {top}" if top is not None else " up"))


def angle_list(values: Any, field: str = "angles_deg", *, lo: float = -math.inf,
               hi: float = math.inf, most: int | None = None, unit: str = "degrees",
               error: ErrorType = ArgumentError) -> NDArray[np.float64]:
    """A non-empty 1-D list of finite numbers (at most ``most``, default
    :data:`MAXIMA` ``["angles"]``) as a float array; text, nested lists, NaN or too
    many are ``error(field, ...)``."""
    most = MAXIMA["angles"] if most is None else most
    allowed = (f"a non-empty 1-D list of at most {most} finite numbers"
               + _range_text(lo, hi, False, False, unit))
    if isinstance(values, str | bytes | dict) or values is None:
        raise error(field, values, allowed)
    if isinstance(values, range | list | tuple) and len(values) > most:
        raise error(field, f"{type(values).__name__} of {len(values)}", allowed)
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError):
        raise error(field, values, allowed) from None
    if raw.dtype.kind not in "iuf" or raw.dtype.kind == "b":
        raise error(field, values, allowed)
    a = np.atleast_1d(raw.astype(float))
    if a.ndim != 1 or not 1 <= a.size <= most:
        raise error(field, f"{a.size} values of shape {raw.shape}", allowed)
    if not (np.all(np.isfinite(a)) and np.all(a >= lo) and np.all(a <= hi)):
        bad = a[~(np.isfinite(a) & (a >= lo) & (a <= hi))][0]
        raise error(field, float(bad), allowed)
    return a


def torque_Nm(value: Any, field: str = "torque_Nm", *, zero: bool = True,
              error: ErrorType = ArgumentError) -> float:
    """A signed torque in N·m (the sign picks the loaded flank): a magnitude in
    :data:`TORQUE_RANGE_NM`, or 0 (unloaded) where ``zero``."""
    lo, hi = TORQUE_RANGE_NM
    if is_real(value) and math.isfinite(value) and (
            lo <= abs(float(value)) <= hi or (zero and value == 0)):
        return float(value)
    raise error(field, value, f"must be a torque in N·m of magnitude {lo:g} to {hi:g}"
                + (", or 0 (unloaded)" if zero else "") + "; the sign picks the loaded flank")


def resolve_torque_Nm(spec: Any, torque: Any, field: str = "torque_Nm", *,
                      zero: bool = True) -> float:
    """The torque in N·m a call applies, by one rule for every entry point: the argument
    ``torque`` (checked by :func:`torque_Nm`, an :class:`ArgumentError` naming
    ``field``), else the spec's ``[load] torque_Nm`` (checked by the spec against the same
    range), else a :class:`SpecError`. ``zero=False`` refuses 0 from either."""
    if torque is not None:
        return torque_Nm(torque, field, zero=zero)
    if spec.load.torque_Nm is None:
        raise SpecError("load.torque_Nm", None, "no torque: give [load] torque_Nm (or "
                        "torque_lbf_in) in the spec or torque_Nm= / --torque")
    return torque_Nm(spec.load.torque_Nm, "load.torque_Nm", zero=zero, error=SpecError)


def angle_tolerance_deg(value: Any, field: str = "tolerance_deg") -> float:
    """A design-angle search tolerance in :data:`ANGLE_TOLERANCE_RANGE_DEG` degrees."""
    lo, hi = ANGLE_TOLERANCE_RANGE_DEG
    return real(value, field, lo, hi, unit="degrees")


def sweep_tolerance_mm(value: Any, field: str = "tolerance_mm",
                       error: ErrorType = ArgumentError) -> float:
    """A clearance accuracy in :data:`SWEEP_TOLERANCE_RANGE_MM` mm."""
    lo, hi = SWEEP_TOLERANCE_RANGE_MM
    return real(value, field, lo, hi, unit="mm", error=error)


def flag(value: Any, field: str) -> bool:
    """A ``bool`` (or numpy bool) argument."""
    if isinstance(value, bool | np.bool_):
        return bool(value)
    raise ArgumentError(field, value, "True or False")


def choice(value: Any, field: str, options: tuple[str, ...] | list[str],
           error: ErrorType = ArgumentError) -> str:
    """``value`` when it is one of the strings ``options``."""
    if isinstance(value, str) and value in options:
        return value
    raise error(field, value, f"one of {', '.join(map(repr, options))}")


def keywords(given: dict[str, Any], allowed: tuple[str, ...] | list[str], field: str) -> None:
    """Refuse keyword arguments outside ``allowed`` (of a call taking ``**kwargs``)."""
    unknown = sorted(set(given) - set(allowed))
    if unknown:
        raise ArgumentError(unknown[0], given[unknown[0]], f"not a keyword of {field}: "
                            f"the keywords are {', '.join(allowed) or 'none'}")
