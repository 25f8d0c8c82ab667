"""``interference.csv``, ``interference.json``, ``interference.png`` and the worst posed
meshes of a mesh interference check."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..clearance import SweepResult, sweep
from ..interference import (
    InterferenceResult,
    check_interference,
    plot_interference,
    posed_meshes,
)
from ..io import atomic_path, plain, write_json
from ..spec import CouplingSpec


def _plot(result: InterferenceResult, reference_mm, path: Path, backlash_mm=None) -> Path:
    fig = plot_interference(result, reference_mm, backlash_mm)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=120)
    return Path(path)


def _worst_meshes(result: InterferenceResult, index: int, out: Path) -> list[Path]:
    written = []
    for name, mesh in posed_meshes(result, index).items():
        path = out / f"worst_{name}.stl"
        with atomic_path(path) as tmp:
            mesh.export(tmp, file_type="stl")
        written.append(path)
    return written


def write_interference(spec: CouplingSpec, result: InterferenceResult, out: Path, *,
                       swept: SweepResult | None = None) -> list[Path]:
    """CSV, JSON (with the sweep's exact clearance beside the meshes' gap), plot and the
    worst posed meshes. ``swept``: a sweep at the check's rotations and misalignment to
    reuse (else one is made when the hub is not turned off its pose)."""
    reference = backlash = None
    if result.hub_rotation_deg == 0.0:
        if swept is None or not np.array_equal(swept.angles_deg, result.angles_deg):
            swept = sweep(spec, result.misalignment_deg, result.angles_deg)
        swept = swept.check_finite()
        reference = np.min(swept.normal_clearance_mm, axis=(0, 1))
        backlash = swept.backlash_mm
    summary = result.summary()
    if reference is not None and backlash is not None:
        summary["sweep_min_normal_clearance_mm"] = [float(v) for v in reference]
        summary["sweep_backlash_mm"] = [float(v) for v in backlash]
    # validated before anything is written: no NaN in the CSV or the JSON
    plain(list(result.rows()), "interference.csv")
    plain(summary, "interference.json")
    written = [result.write_csv(out / "interference.csv"),
               write_json(out / "interference.json", summary),
               _plot(result, reference, out / "interference.png", backlash)]
    return written + _worst_meshes(result, int(result.worst(1)[0]), out)


def write_check(spec: CouplingSpec, out: Path, misalignment_deg: float,
                angles_deg) -> list[Path]:
    """:func:`~gearcoupling.interference.check_interference` at the rotations
    ``angles_deg`` with its defaults, written by :func:`write_interference`."""
    return write_interference(spec, check_interference(spec, misalignment_deg, angles_deg),
                              out)
