"""Hub and sleeve solids as meshes and STEP files, with ``parts.json``."""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from importlib.util import find_spec
from pathlib import Path
from typing import Any

from ..errors import BackendError
from ..export import export_part
from ..io import write_json
from ..parts import build_part, check_part, check_tolerance, measure_deviation
from ..spec import CouplingSpec
from .files import PART_NAMES, file_stem


def write_parts(spec: CouplingSpec, out: Path, parts: Sequence[str] = PART_NAMES,
                formats: Sequence[str] = ("stl",), tolerance_mm: float | None = None,
                teeth: Sequence[int] | None = None,
                progress: Callable[[int, int], None] | None = None
                ) -> tuple[list[Path], dict[str, Any]]:
    """Build the parts, write every format and ``parts.json``; returns the files and the
    report (triangles, volume, validity, measured deviation and files of each part).
    ``progress(done, total)`` after each part and each file."""
    tol = check_tolerance(spec, tolerance_mm)
    total, done = len(parts) * (1 + len(formats)), 0
    written: list[Path] = []
    report: dict[str, Any] = {"spec": spec.name, "tolerance_mm": tol,
                              "teeth": None if teeth is None else list(teeth), "parts": {}}
    for part in parts:
        mesh = build_part(spec, part, tolerance_mm=tol, teeth=teeth)
        check = check_part(mesh)
        done += 1
        if progress:
            progress(done, total)
        files = []
        for ext in formats:
            path = export_part(spec, part, out / f"{file_stem(part, teeth)}.{ext}",
                               tolerance_mm=tol, teeth=teeth, mesh=mesh)
            files.append(path.name)
            written.append(path)
            done += 1
            if progress:
                progress(done, total)
        report["parts"][part] = {
            "triangles": len(mesh.faces), "volume_mm3": float(mesh.volume),
            "area_mm2": float(mesh.area), "valid": check.ok, "problems": check.problems(),
            "genus": check.genus, "build_seconds": mesh.metadata["build_seconds"],
            "measured_deviation_mm": measure_deviation(spec, mesh, samples=500)["max"],
            "files": files,
        }
    written.append(write_json(out / "parts.json", report))
    return written, report


def write_step_files(spec: CouplingSpec, out: Path) -> list[Path]:
    """Hub and sleeve STEP solids (the ``step`` extra); adds them to the files of each part
    in ``parts.json`` when :func:`write_parts` wrote it. Without OpenCASCADE a
    :class:`~gearcoupling.errors.BackendError` names the extra."""
    if find_spec("OCP") is None:
        raise BackendError("STEP files need OpenCASCADE: pip install 'gearcoupling[step]'")
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
