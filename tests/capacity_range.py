"""The default model's capacity over the whole supported range, 0-6°: the seeded specs and
the checks of one point (used by ``tests/test_capacity_range.py`` and
``benchmarks/bench_capacity_range.py``).

At each misalignment a point is ``gc.capacity(spec, angle)`` and ``gc.load`` at three
torques (:func:`torques`: the spec's, else the capacity there; a tenth of it and ten times
it) on the default model; :func:`problems` lists what is wrong with a point (an empty list:
every returned number finite, the governing criterion named, the loads carrying their
torque), :func:`jumps` where a capacity curve changes by more than :data:`JUMP` between
neighbouring angles without a change of its governing criterion.
"""

from __future__ import annotations

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
JUMP = 3.0  # neighbouring angles 0.5° apart: a capacity changing by more, under the same
#   governing criterion, is a finding (measured over the benchmark: see docs/safety.md)
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
    """``(capacity, loads)`` at ``angle``: :func:`gc.capacity` and :func:`gc.load` at each
    of :func:`torques` (default model, one pose)."""
    c = gc.capacity(spec, angle)
    loads = [gc.load(spec, angle, LOAD_ANGLES, torque_Nm=T) for T in torques(spec, c.capacity_Nm)]
    return c, loads


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


def jumps(curve) -> list[str]:
    """Neighbouring points of a capacity curve (ascending angles) whose capacities differ
    by more than a factor :data:`JUMP` under the same governing criterion."""
    out = []
    for a, b in zip(curve, curve[1:], strict=False):
        ca, cb = a.capacity_Nm, b.capacity_Nm
        if a.governing != b.governing or not (_finite(ca) and _finite(cb)):
            continue
        if max(ca, cb) > JUMP * min(ca, cb):
            out.append(f"{a.misalignment_deg:g}° -> {b.misalignment_deg:g}°: {ca:.6g} -> "
                       f"{cb:.6g} N·m ({a.governing})")
    return out
