"""The default model's capacity over the whole supported range, 0-6°: the seeded specs and
the checks of one point (used by ``tests/test_capacity_range.py`` and
``benchmarks/bench_capacity_range.py``).

At each misalignment a point is ``gc.capacity(spec, angle)`` and the load at three
torques (:func:`torques`: the spec's, else the capacity there; a tenth of it and ten times
it) on the default model; :func:`problems` lists what is wrong with a point (an empty list:
every returned number finite, the governing criterion named, the loads carrying their
torque), :func:`jumps` where a capacity curve changes by more than :data:`JUMP` between
neighbouring angles without a change of regime: of its governing criterion, or of whether
a patch reaches a face end at the capacity (the capacity falls steeply where it starts to:
the root stress of a load at the face end is higher, and fewer teeth share).
"""

from __future__ import annotations

import itertools
import math

import numpy as np

import gearcoupling as gc
from gearcoupling.arguments import TORQUE_RANGE_NM
from gearcoupling.loading.limits import CRITERIA
from random_specs import STRATA, random_spec_data

ANGLES = tuple(0.5 * k for k in range(13))  # 0, 0.5, ..., 6 degrees
SEED = 38  # of the random specs (issue 38)
LOAD_ANGLES = (0.0,)  # rotations of each load (one pose: the load is checked, not searched)
BALANCE_RTOL = 1e-6  # the tooth loads carry the torque (the surface model's own balance)
JUMP = 3.0  # neighbouring angles 0.5° apart: a capacity changing by more in one regime is
#   a finding (measured over the benchmark: see docs/safety.md)
LOAD_FIELDS = ("tangential_force_N", "normal_force_N", "deflection_mm", "windup_rad",
               "max_pressure_MPa", "interior_pressure_MPa", "edge_load_share",
               "patch_length_mm", "root_stress_MPa", "mesh_stiffness_Nm_per_rad")


def range_specs(count: int, seed: int = SEED, most_teeth: int | None = None) -> list:
    """The first ``count`` accepted specs drawn with ``seed`` (spec ``i`` of stratum
    ``STRATA[i % 20]``, as ``benchmarks/bench_random_specs.py`` draws), named
    ``random-<i>-<stratum>``; with ``most_teeth`` only those of at most that many teeth."""
    out = []
    for i in range(100 * count):
        if len(out) == count:
            break
        stratum = STRATA[i % len(STRATA)]
        data = random_spec_data(np.random.default_rng([seed, i]), *stratum)
        if most_teeth is not None and data["tooth"]["teeth"] > most_teeth:
            continue
        data["name"] = f"random-{i}-{'-'.join(stratum)}"
        try:
            out.append(gc.spec_from_dict(data))
        except gc.SpecError:
            continue
    return out


def torques(spec, capacity_Nm: float | None) -> tuple[float, ...]:
    """The three torques (N·m) a point's loads are solved at: a reference (the spec's
    torque, else the capacity at the angle, else 1 N per tooth at the pitch radius) times
    0.1, 1 and 10, within the allowed range."""
    lo, hi = TORQUE_RANGE_NM
    ref = spec.load.torque_Nm
    if ref is None:
        ref = capacity_Nm if capacity_Nm else 1e-3 * spec.tooth.pitch_radius * spec.tooth.teeth
    return tuple(min(max(f * ref, lo), hi) for f in (0.1, 1.0, 10.0))


def point(spec, angle: float):
    """``(capacity, loads)`` at ``angle``: :func:`gc.capacity` and the load at each of
    :func:`torques` (default model, one pose: :func:`gc.load_from_sweep` on one sweep)."""
    c = gc.capacity(spec, angle)
    sw = gc.sweep(spec, angle, LOAD_ANGLES)
    return c, [gc.load_from_sweep(sw, torque_Nm=T) for T in torques(spec, c.capacity_Nm)]


def _finite(v) -> bool:
    return v is not None and math.isfinite(v)


def problems(c, loads) -> list[str]:
    """What is wrong with one point: [] where the capacity is a finite number >= 0 with its
    governing criterion named and equal to that criterion's torque, every other reported
    number finite or None (not reached), q in (0, 1] where the capacity is positive, and
    each load finite, carrying its torque to :data:`BALANCE_RTOL` with q in (0, 1]."""
    out = []
    if not (_finite(c.capacity_Nm) and c.capacity_Nm >= 0):
        out.append(f"capacity {c.capacity_Nm}")
    if c.governing not in CRITERIA or c.criteria_Nm.get(c.governing) != c.capacity_Nm:
        out.append(f"governing {c.governing!r} of {c.criteria_Nm}")
    numbers = {**{f"criteria_Nm[{k}]": v for k, v in c.criteria_Nm.items()},
               "face_end_torque_Nm": c.face_end_torque_Nm,
               "aligned_capacity_Nm": c.aligned_capacity_Nm}
    out += [f"{k} {v}" for k, v in numbers.items() if v is not None and not (_finite(v) and v >= 0)]
    if _finite(c.capacity_Nm) and c.capacity_Nm > 0:
        for k in ("q", "load_sharing_factor", "max_tooth_load_N"):
            if not (_finite(getattr(c, k)) and getattr(c, k) > 0):
                out.append(f"{k} {getattr(c, k)}")
        if _finite(c.q) and c.q > 1 + 1e-9:
            out.append(f"q {c.q}")
    for res in loads:
        T = res.torque_Nm
        out += [f"load at {T:.6g} N·m: {f} not finite" for f in LOAD_FIELDS
                if not np.all(np.isfinite(getattr(res, f)))]
        carried = res.tangential_force_N.sum(axis=0) * res.spec.tooth.pitch_radius * 1e-3
        if not np.allclose(carried, abs(T), rtol=BALANCE_RTOL, atol=0.0):
            out.append(f"load at {T:.6g} N·m carries {carried.tolist()}")
        q = res.summary()["q"]
        if not (_finite(q) and 0 < q <= 1 + 1e-9):
            out.append(f"load at {T:.6g} N·m: q {q}")
    return out


def curve_point(c) -> tuple[float, float | None, str, bool]:
    """A capacity's point on its curve: ``(angle, capacity_Nm, governing, edge)``, ``edge``
    where a patch reaches a face end at or below the governing torque (the face-end
    torque at most ``capacity / K``)."""
    fe, cap = c.face_end_torque_Nm, c.capacity_Nm
    edge = fe is not None and cap is not None and fe <= cap / c.accuracy_factor
    return c.misalignment_deg, cap, c.governing, edge


def changes(points) -> list[tuple[float, float, float, bool]]:
    """``(angle, next angle, factor, regime changed)`` of neighbouring :func:`curve_point`
    ``points`` (ascending angles) under the same governing criterion, both capacities
    positive: the factor by which the capacity changes between them (at least 1), and
    whether the patch reaches a face end at the capacity at one angle and not the other."""
    out = []
    for (a, ca, ga, ea), (b, cb, gb, eb) in itertools.pairwise(points):
        if ga == gb and _finite(ca) and _finite(cb) and ca > 0 and cb > 0:
            out.append((a, b, max(ca, cb) / min(ca, cb), ea != eb))
    return out


def jumps(points) -> list[str]:
    """The :func:`changes` of a capacity curve by more than a factor :data:`JUMP` without a
    change of regime (governing criterion, face end reached at the capacity or not)."""
    return [f"{a:g}° -> {b:g}°: x{f:.3g}" for a, b, f, moved in changes(points)
            if f > JUMP and not moved]
