"""The stage ``check``: the mesh interference check over a turn, with
``interference.csv``, ``interference.json``, ``interference.png`` and the worst posed
meshes."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..clearance import SweepResult, sweep
from ..interference import (
    InterferenceResult,
    check_interference,
    plot_interference,
    posed_meshes,
)
from ..io import atomic_path, plain, write_json
from ..spec import CouplingSpec
from .stage import StageInputs


@dataclass(frozen=True)
class Check:
    """The interference check with the sweep's exact smallest normal clearance and backlash
    at its poses (mm; None where the hub was turned off its pose)."""

    result: InterferenceResult
    reference_mm: NDArray[np.float64] | None
    backlash_mm: NDArray[np.float64] | None


def check(inputs: StageInputs) -> Check:
    """The stage ``check``: ``check_angles`` poses over a turn at the misalignment (less a
    mesh's phase: a double-engagement coupling's meshes as the placed assembly poses
    them)."""
    n, p = inputs.settings.check_angles, inputs.point
    result = check_interference(inputs.spec, p.misalignment_deg,
                                p.rotations(np.arange(n) * 360.0 / n))
    return reference(inputs.spec, result)


def files(found: Check, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``check``'s files."""
    return check_files(found, folder, inputs.settings.dpi)


def reference(spec: CouplingSpec, result: InterferenceResult,
              swept: SweepResult | None = None) -> Check:
    """``result`` with the sweep's exact clearance at its poses (``swept``: a sweep at the
    check's rotations and misalignment to reuse, else one is made) when the hub is on its
    pose."""
    if result.hub_rotation_deg != 0.0:
        return Check(result, None, None)
    if swept is None or not np.array_equal(swept.angles_deg, result.angles_deg):
        swept = sweep(spec, result.misalignment_deg, result.angles_deg)
    swept = swept.check_finite()
    return Check(result, np.min(swept.normal_clearance_mm, axis=(0, 1)), swept.backlash_mm)


def _plot(found: Check, path: Path, dpi: int) -> Path:
    fig = plot_interference(found.result, found.reference_mm, found.backlash_mm)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return Path(path)


def _worst_meshes(result: InterferenceResult, index: int, out: Path) -> list[Path]:
    written = []
    for name, mesh in posed_meshes(result, index).items():
        path = out / f"worst_{name}.stl"
        with atomic_path(path) as tmp:
            mesh.export(tmp, file_type="stl")
        written.append(path)
    return written


def check_files(found: Check, out: Path, dpi: int = 120) -> list[Path]:
    """CSV, JSON (with the sweep's exact clearance beside the meshes' gap), plot and the
    worst posed meshes."""
    result = found.result
    summary = result.summary()
    if found.reference_mm is not None and found.backlash_mm is not None:
        summary["sweep_min_normal_clearance_mm"] = [float(v) for v in found.reference_mm]
        summary["sweep_backlash_mm"] = [float(v) for v in found.backlash_mm]
    # validated before anything is written: no NaN in the CSV or the JSON
    plain(list(result.rows()), "interference.csv")
    plain(summary, "interference.json")
    written = [result.write_csv(out / "interference.csv"),
               write_json(out / "interference.json", summary),
               _plot(found, out / "interference.png", dpi)]
    return written + _worst_meshes(result, int(result.worst(1)[0]), out)


def write_interference(spec: CouplingSpec, result: InterferenceResult, out: Path, *,
                       swept: SweepResult | None = None) -> list[Path]:
    """``gearcoupling check``'s files for ``result`` (:func:`check_files`); ``swept`` as
    :func:`reference`."""
    return check_files(reference(spec, result, swept), out)
