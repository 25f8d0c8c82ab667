"""The stages ``parts`` and ``step``: hub and sleeve solids as meshes and STEP files, with
``parts.json``."""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from importlib.util import find_spec
from pathlib import Path
from typing import Any

from ..errors import BackendError
from ..export import export_part
from ..io import write_json
from ..parts import build_part, check_part, check_tolerance, measure_deviation
from ..spec import CouplingSpec
from .files import PART_NAMES, file_stem
from .stage import StageInputs


@dataclass(frozen=True)
class Parts:
    """Built parts: the meshes by part name and the report of each (triangles, volume,
    validity, measured deviation), at one chordal tolerance."""

    tolerance_mm: float
    teeth: tuple[int, ...] | None
    meshes: dict[str, Any] = field(repr=False)
    report: dict[str, dict[str, Any]]


@dataclass(frozen=True)
class StepParts:
    """The STEP solids to write (the stage ``step`` writes them; OpenCASCADE found)."""

    parts: tuple[str, ...]


def build(inputs: StageInputs) -> Parts:
    """The stage ``parts``: hub and sleeve at the default tolerance."""
    return build_parts(inputs.spec)


def files(result: Parts, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``parts``'s STL files and ``parts.json``."""
    return parts_files(inputs.spec, result, folder)[0]


def step(inputs: StageInputs) -> StepParts:
    """The stage ``step`` (its files are the work); without OpenCASCADE a
    :class:`~gearcoupling.errors.BackendError` names the extra."""
    _need_ocp()
    return StepParts(PART_NAMES)


def step_files(result: StepParts, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``step``'s files (:func:`write_step_files`)."""
    return write_step_files(inputs.spec, folder)


def build_parts(spec: CouplingSpec, parts: Sequence[str] = PART_NAMES,
                tolerance_mm: float | None = None, teeth: Sequence[int] | None = None,
                progress: Callable[[], None] | None = None) -> Parts:
    """Build and check the ``parts``; ``progress()`` after each."""
    tol = check_tolerance(spec, tolerance_mm)
    meshes, report = {}, {}
    for part in parts:
        mesh = build_part(spec, part, tolerance_mm=tol, teeth=teeth)
        check = check_part(mesh)
        meshes[part] = mesh
        report[part] = {
            "triangles": len(mesh.faces), "volume_mm3": float(mesh.volume),
            "area_mm2": float(mesh.area), "valid": check.ok, "problems": check.problems(),
            "genus": check.genus, "build_seconds": mesh.metadata["build_seconds"],
            "measured_deviation_mm": measure_deviation(spec, mesh, samples=500)["max"]}
        if progress:
            progress()
    return Parts(tol, None if teeth is None else tuple(teeth), meshes, report)


def parts_files(spec: CouplingSpec, built: Parts, out: Path, formats: Sequence[str] = ("stl",),
                progress: Callable[[], None] | None = None
                ) -> tuple[list[Path], dict[str, Any]]:
    """Every format of each built part and ``parts.json`` (the report with each part's
    files); returns the paths and the report. ``progress()`` after each file."""
    written: list[Path] = []
    listing: dict[str, Any] = {"spec": spec.name, "tolerance_mm": built.tolerance_mm,
                               "teeth": None if built.teeth is None else list(built.teeth),
                               "parts": {}}
    for part, mesh in built.meshes.items():
        names = []
        for ext in formats:
            path = export_part(spec, part, out / f"{file_stem(part, built.teeth)}.{ext}",
                               tolerance_mm=built.tolerance_mm, teeth=built.teeth, mesh=mesh)
            names.append(path.name)
            written.append(path)
            if progress:
                progress()
        listing["parts"][part] = {**built.report[part], "files": names}
    written.append(write_json(out / "parts.json", listing))
    return written, listing


def write_parts(spec: CouplingSpec, out: Path, parts: Sequence[str] = PART_NAMES,
                formats: Sequence[str] = ("stl",), tolerance_mm: float | None = None,
                teeth: Sequence[int] | None = None,
                progress: Callable[[int, int], None] | None = None
                ) -> tuple[list[Path], dict[str, Any]]:
    """Build the parts, write every format and ``parts.json``; returns the files and the
    report (triangles, volume, validity, measured deviation and files of each part).
    ``progress(done, total)`` after each part and each file."""
    total, done = len(parts) * (1 + len(formats)), 0

    def tick() -> None:
        nonlocal done
        done += 1
        if progress:
            progress(done, total)

    return parts_files(spec, build_parts(spec, parts, tolerance_mm, teeth, tick), out,
                       formats, tick)


def _need_ocp() -> None:
    if find_spec("OCP") is None:
        raise BackendError("STEP files need OpenCASCADE: pip install 'gearcoupling[step]'")


def write_step_files(spec: CouplingSpec, out: Path) -> list[Path]:
    """Hub and sleeve STEP solids (the ``step`` extra); adds them to the files of each part
    in ``parts.json`` when :func:`write_parts` wrote it. Without OpenCASCADE a
    :class:`~gearcoupling.errors.BackendError` names the extra."""
    _need_ocp()
    written = [export_part(spec, part, out / f"{part}.step") for part in PART_NAMES]
    listing = out / "parts.json"
    if listing.is_file():
        report = json.loads(listing.read_text())
        for part, path in zip(PART_NAMES, written, strict=True):
            files = report["parts"].setdefault(part, {}).setdefault("files", [])
            if path.name not in files:
                files.append(path.name)
        write_json(listing, report)
    return written
