"""One study row: build the sample's spec, evaluate the outputs asked for.

A sample the spec validation (or an evaluation) refuses with a gearcoupling error becomes a
row with ``error`` set to the reason and its outputs empty; other exceptions propagate
(a bug must not look like a result).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import __version__
from ..clearance import (
    binding_angle_deg,
    check_misalignment,
    critical_misalignment_deg,
    flank_minima,
    pitch_turning_angles,
)
from ..errors import GearCouplingError
from ..loading import capacity, load
from ..spec import CouplingSpec
from .file import ANGLE_OUTPUTS, LOAD_OUTPUTS, OUTPUTS, TOLERANCE_OUTPUTS, build_spec, spec_hash
from .tolerance import Tolerances, draw_errors, gap_offsets_rad, tolerance_sample
from .wear import wear_life_h


def _version() -> str:
    return __version__


def angle_outputs(spec: CouplingSpec, misalignment_deg: float, *, steps: int, tolerance_mm: float
                  ) -> dict[str, float]:
    """Smallest backlash over a turn and the axial range of the first-touch point of the
    contacting tooth of each flank, from one clearance map over a tooth pitch (``steps``
    rotations; every tooth, so the whole turn)."""
    i = check_misalignment(misalignment_deg)
    theta = pitch_turning_angles(spec.tooth.teeth, steps)
    mins, _ = flank_minima(spec, i, np.stack([theta, np.pi - theta]), tolerance_mm=tolerance_mm)
    gap = mins["normal"] / spec.tooth.base_radius / mins["rate"]  # (2, N, steps)
    backlash = float(np.min(np.min(gap[0], axis=0) + np.min(gap[1], axis=0)))
    k = np.argmin(gap, axis=1)  # contacting tooth per flank and rotation
    z = np.take_along_axis(mins["z"], k[:, None, :], axis=1)
    return {"min_backlash_mm": backlash * spec.tooth.pitch_radius,
            "contact_z_min_mm": float(np.min(z)), "contact_z_max_mm": float(np.max(z))}


def load_outputs(spec: CouplingSpec,
                 misalignment_deg: float, torque_Nm: float | None, *, angles: int,
                 model: str | None = None) -> dict[str, float | None]:
    """Largest tooth load and q over a turn at the torque (:func:`gearcoupling.loading.load`),
    and the governing capacity (:func:`gearcoupling.loading.capacity.capacity`, times the
    spec's accuracy factor), from the load analysis."""
    psi = np.arange(angles) * 360.0 / angles
    res = load(spec, misalignment_deg, psi, torque_Nm=torque_Nm, model=model)
    cap = capacity(spec, misalignment_deg, model=model)
    return {"max_tooth_load_N": float(np.max(res.tangential_force_N)), "q": float(res.q()),
            "capacity_Nm": cap.capacity_Nm}


def evaluate(payload: dict[str, Any], inputs: dict[str, Any], sample: int = 0) -> dict[str, Any]:
    """The row of one sample: inputs, operating conditions, outputs, spec hash, version.
    ``sample`` (the global index) seeds the tolerance draws."""
    acc = payload["accuracy"]
    wanted = payload["outputs"]
    conditions = payload["conditions"]
    row: dict[str, Any] = dict(inputs)
    names = TOLERANCE_OUTPUTS if payload.get("tolerances") else OUTPUTS
    row.update({k: None for k in names if k in wanted})
    row.update(spec_hash=None, version=_version(), error=None)
    spec_keys = {k: v for k, v in inputs.items()
                 if k not in ("misalignment_deg", "torque_Nm", "draw")}
    try:
        spec = build_spec(payload["base_name"], payload["base_text"],
                          {**payload["fixed"], **spec_keys})
        row["spec_hash"] = spec_hash(spec)
        mis = float(inputs.get("misalignment_deg", conditions.get(
            "misalignment_deg", math.degrees(spec.design_misalignment))))
        torque = inputs.get("torque_Nm", conditions.get("torque_Nm"))
        row["misalignment_deg"] = mis
        row["torque_Nm"] = None if torque is None else float(torque)
        if payload.get("tolerances"):
            row.update(_tolerance_row(payload, spec, mis, torque, sample))
            return row
        if "critical_misalignment_deg" in wanted:
            row["critical_misalignment_deg"] = critical_misalignment_deg(
                spec, tolerance_deg=acc["angle_tolerance_deg"])
        if "binding_angle_deg" in wanted:
            row["binding_angle_deg"] = binding_angle_deg(
                spec, tolerance_deg=acc["angle_tolerance_deg"], steps=int(acc["steps"]))
        if any(k in wanted for k in ANGLE_OUTPUTS):
            got = angle_outputs(spec, mis, steps=int(acc["steps"]),
                                tolerance_mm=acc["tolerance_mm"])
            row.update({k: v for k, v in got.items() if k in wanted})
        if any(k in wanted for k in LOAD_OUTPUTS):
            loads = load_outputs(spec, mis, torque, angles=int(acc["load_angles"]),
                                 model=payload["conditions"].get("load_model"))
            row.update({k: v for k, v in loads.items() if k in wanted})
        if "wear_life_h" in wanted:
            row["wear_life_h"] = wear_life_h(spec, mis, torque, acc)
    except GearCouplingError as err:
        row["error"] = f"{type(err).__name__}: {err}"
        row.update({k: None for k in names if k in wanted})
    return row


def _tolerance_row(payload, spec: CouplingSpec, mis: float, torque, sample: int) -> dict[str, Any]:
    t = payload["tolerances"]
    acc = payload["accuracy"]
    tol = Tolerances(**t["values"])
    out = tolerance_sample(spec, mis, tol, payload["seed"], sample, path=t["path"],
                           torque_Nm=torque, steps=int(acc["steps"]),
                           tolerance_mm=acc["tolerance_mm"], model=t["model"])
    if "wear_life_h" in payload["outputs"]:  # the sample's own draw (seeded as above)
        err = draw_errors(tol, spec.tooth.teeth, np.random.default_rng([payload["seed"],
                                                                        sample]))
        out["wear_life_h"] = wear_life_h(spec, mis, torque, acc, gap_offsets_rad(spec, err))
    return {k: v for k, v in out.items() if k in payload["outputs"]}


def evaluate_chunk(payload: dict[str, Any], chunk: int, items: list[tuple[int, dict]]
                   ) -> list[dict[str, Any]]:
    """Rows of one chunk of samples ``(sample index, inputs)`` (one dask task)."""
    return [{"sample": n, "chunk": chunk, **evaluate(payload, inputs, n)} for n, inputs in items]
