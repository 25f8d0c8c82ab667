"""``gc.report``: the design report of a spec, one self-contained HTML file (and a PDF)."""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from .. import __version__
from ..arguments import flag
from ..browser import browser_backend
from ..errors import ArgumentError
from ..hob import check_hob_diameter
from ..inspection import check_limits, grade_limits, load_points
from ..io import output_folder, require_file, writable_targets, write_text
from ..outputs import (
    REPORT,
    REPORT_PDF,
    Results,
    Scope,
    compute,
    default_workers,
    run_folders,
    settings_from,
    stage_files,
)
from ..spec import CouplingSpec, as_spec
from . import sections as registry
from .document import Note, Section, Table, render
from .pdf import print_pdf
from .settings import ReportSettings
from .verdict import COLUMNS, Verdict, overall
from .view import ReportSection, View


@dataclass(frozen=True)
class ReportResult:
    """What :func:`report` wrote: the HTML, the PDF (or None), the data files, the verdict
    (``pass``, ``fail`` or ``open`` when something was not judged, with its sentence) and
    each stage's seconds."""

    html: Path
    pdf: Path | None
    files: tuple[Path, ...]
    verdict: str
    verdict_text: str
    seconds: dict[str, float]
    wall_seconds: float


def report(spec: CouplingSpec, out: str | os.PathLike, *, pdf: bool = False,
           progress: Callable[[int, int], None] | None = None,
           settings: ReportSettings | None = None, workers: int | None = None,
           **options: Any) -> ReportResult:
    """Write the design report of ``spec`` into the folder ``out``.

    ``report.html`` is self-contained (figures inline, the 3D viewer embedded, no network)
    and holds: the verdict table against the spec's limits (saying which are not set), the
    spec and its derived values, clearance, backlash and contact over the turn, the
    critical and binding angles with Renzo's estimates, the loads (tooth load, q,
    pressure, root stress, machine loads, contact patches), capacity per criterion against
    misalignment, the data sheet, the interference check, the hob program and measuring
    charts, a measured part when ``scan`` is given, and the 3D view. Its sections show the
    results of the pipeline's stages (:data:`~gearcoupling.outputs.STAGES`), whose files
    (each figure's data, the programs, the data sheet) are written beside it; each figure
    states the model and accuracy settings it was made with.

    Parameters
    ----------
    spec : CouplingSpec
    out : path-like
        Output folder (created).
    pdf : bool
        Also print ``report.pdf`` through headless chromium (the ``browser`` extra and
        Debian's chromium; the 3D view becomes a picture).
    progress : callable, optional
        ``progress(done, total)`` as the stages finish.
    settings : ReportSettings, optional
        Inputs and accuracy knobs; or give them as keyword arguments (``torque_Nm``,
        ``misalignment_deg``, ``scan``, ``angles``, ...; see :class:`ReportSettings`).
    workers : {1, 2}, optional
        Processes the stages run in (:func:`gearcoupling.run`).

    Returns
    -------
    ReportResult
    """
    spec = as_spec(spec)
    output_folder(out, "out", create=False)
    s = settings_from(settings, options, ReportSettings, "report")
    flag(pdf, "pdf")
    engagements = spec.coupling.engagements
    writable_targets(out, report_files(s, pdf, engagements, spec), run_folders(engagements),
                     field="out")
    n = default_workers(workers)
    t0 = time.perf_counter()
    s.resolve(spec)
    s = _check_inputs(spec, s)
    if pdf:
        browser_backend()
    created = not Path(out).exists()
    folder = output_folder(out, "out")
    shown = [sec for sec in registry.SECTIONS if sec.applies(s, engagements, spec)]
    written: list[Path] = []
    try:
        results = compute(spec, s, report_stages(s, engagements, spec), folder=folder,
                          workers=n, progress=progress, written=written)
        return _render(spec, s, results, folder, shown, pdf, t0)
    except BaseException:  # an error or an interruption: no partial report is left
        _discard(folder, written, created)
        raise


def report_stages(settings: ReportSettings, engagements: int = 1,
                  spec: CouplingSpec | None = None) -> list[str]:
    """The stages a report with these settings shows on a spec of ``engagements`` (on
    ``spec`` where given: without it, also those a spec may ask for, the wear history)."""
    return [n for sec in registry.SECTIONS if sec.applies(settings, engagements, spec)
            for n in sec.stages]


def report_files(settings: ReportSettings, pdf: bool = False, engagements: int = 1,
                 spec: CouplingSpec | None = None) -> list[str]:
    """The files :func:`report` may write on a spec of ``engagements`` (``spec``: as
    :func:`report_stages`): those of its stages (a double-engagement coupling's meshes'
    in ``mesh-a/``, ``mesh-b/``), ``report.html`` and, with ``pdf``, ``report.pdf``."""
    return [*stage_files(report_stages(settings, engagements, spec), engagements), REPORT,
            *([REPORT_PDF] if pdf else [])]


def _views(spec: CouplingSpec, s: ReportSettings, results: Results, folder: Path
           ) -> tuple[View, list[View]]:
    """The report's view (the spec at the root) and each mesh's of a double-engagement
    coupling (none for one engagement)."""
    scopes: dict[str, Scope] = s.scopes(spec)
    root = scopes.pop("")
    view = View(spec, s, root.point, results, folder)
    return view, [View(sc.spec, s, sc.point, results.scope(name), folder / name, name)
                  for name, sc in scopes.items()]


def _sections(sec: ReportSection, view: View, meshes: list[View]) -> list[Section]:
    """A section as rendered: once, or once per mesh (its title saying which)."""
    if sec.level != "mesh" or not meshes:
        return [Section(sec.key, sec.title, sec.render(view))]
    return [Section(f"{sec.key}-{m.scope}", f"{sec.title}: mesh {m.point.mesh} "
                    f"(i = {m.point.misalignment_deg:.4g}°)", sec.render(m)) for m in meshes]


def _verdicts(sec: ReportSection, view: View, meshes: list[View]) -> list[Verdict]:
    """A section's verdicts: once, or per mesh (each check saying which)."""
    if sec.verdicts is None:
        return []
    if sec.level != "mesh" or not meshes:
        return sec.verdicts(view)
    return [replace(row, check=f"mesh {m.point.mesh}: {row.check}") for m in meshes
            for row in sec.verdicts(m)]


def section_verdicts(spec: CouplingSpec, settings: ReportSettings, results: Results,
                     folder: Path, keys: Sequence[str]) -> list[Verdict]:
    """The verdicts of the report's sections ``keys`` on these results (a double-engagement
    coupling's mesh sections once per mesh, each check saying which): what a command
    prints of its findings."""
    view, meshes = _views(spec, settings, results, folder)
    return [row for sec in registry.SECTIONS if sec.key in keys
            for row in _verdicts(sec, view, meshes)]


def _render(spec: CouplingSpec, s: ReportSettings, results: Results, folder: Path,
            shown: list[ReportSection], pdf: bool, t0: float) -> ReportResult:
    view, meshes = _views(spec, s, results, folder)
    point = view.point
    sections = [one for sec in shown for one in _sections(sec, view, meshes)]
    engagements = spec.coupling.engagements
    verdicts = [row for sec in registry.SECTIONS
                if sec.level != {1: "whole", 2: "single"}[engagements]
                for row in _verdicts(sec, view, meshes)]
    cls, text = overall(verdicts)
    head = Section("verdict", "Verdict against the spec's limits", [
        Table(COLUMNS, [v.row() for v in verdicts], "pass / fail only against a limit; "
              "not judged where the spec sets no limit or an input is missing (the reason "
              "says which key or option sets it).", verdict_column=4)])
    data = tuple(results.all_files(list(results.files)))
    wall = time.perf_counter() - t0
    sections.append(_provenance(view, data, wall))
    html_path = folder / REPORT
    title = f"Gear coupling design report: {spec.name}"
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    torque = point.torque_Nm
    sub = (_where(view, meshes) + ", "
           + (f"T = {torque:.4g} N·m" if torque is not None else "no torque")
           + f", {point.model} load model · gearcoupling {__version__} · {when}")
    write_text(html_path, render(title, sub, (cls, text), [head, *sections]))
    pdf_path = print_pdf(html_path, folder / REPORT_PDF) if pdf else None
    return ReportResult(html_path, pdf_path, data, cls, text, dict(results.seconds),
                        time.perf_counter() - t0)


def _where(view: View, meshes: list[View]) -> str:
    """The misalignment of the subtitle: the angle, or a double-engagement coupling's
    alignment and mesh angles."""
    if not meshes:
        return f"i = {view.point.misalignment_deg:g}°"
    a = view.point.coupling.alignment if view.point.coupling is not None else None
    shafts = "" if a is None else (f"offset {a.offset_mm:g} mm at {a.offset_azimuth_deg:g}°, "
                                   f"shaft angle {a.angle_deg:g}° at "
                                   f"{a.angle_azimuth_deg:g}°: ")
    return shafts + ", ".join(f"mesh {m.point.mesh} i = {m.point.misalignment_deg:.4g}°"
                              for m in meshes)


def _discard(folder: Path, written: list[Path], created: bool) -> None:
    """Remove what this report wrote (and its folder when it is left empty and was made
    now)."""
    for path in [*written, folder / REPORT, folder / REPORT_PDF]:
        path.unlink(missing_ok=True)
    if created:
        with contextlib.suppress(OSError):  # not empty: other files were there before
            folder.rmdir()


def _check_inputs(spec: CouplingSpec, s: ReportSettings) -> ReportSettings:
    """Inputs that would fail late, checked before anything is computed: the scan (read
    and checked here: the settings returned carry its points, in mm), the inspection
    limits and class, the hob diameter."""
    if s.scan is not None and not isinstance(s.scan, np.ndarray):
        require_file(s.scan, "scan", "a scan or mesh file (STL/PLY/OBJ, CSV/XYZ)", ArgumentError)
        try:
            points = load_points(Path(s.scan), s.scan_units)
        except ArgumentError as err:
            raise ArgumentError("scan", str(s.scan), getattr(err, "allowed", str(err))) from None
        s = replace(s, scan=points, scan_units="mm")
    if s.grade is not None:
        grade_limits(spec, s.grade)
    check_limits(s.limits)
    if s.hob_diameter_mm is not None:
        check_hob_diameter(spec, s.hob_diameter_mm)
    return s


def _provenance(view: View, files: tuple[Path, ...], wall: float) -> Section:
    p = view.point
    used = {"misalignment_deg": p.misalignment_deg, "torque_Nm": p.torque_Nm,
            "model": p.model}
    if p.coupling is not None:  # the alignment the meshes' angles come from
        a = p.coupling.alignment
        used = {"offset_mm": a.offset_mm, "offset_azimuth_deg": a.offset_azimuth_deg,
                "shaft_angle_deg": a.angle_deg, "angle_azimuth_deg": a.angle_azimuth_deg,
                "torque_Nm": p.torque_Nm, "model": p.model}
    settings = []
    for k, v in view.settings.as_dict(view.spec.coupling.engagements).items():
        if k in used:
            k, v = f"{k} (used)", used[k]
        elif isinstance(v, dict):
            v = ", ".join(f"{a}={b:g}" for a, b in v.items()) or "–"
        settings.append((k, v))
    timing = [(k, round(v, 2)) for k, v in view.results.seconds.items()]
    timing.append(("all stages, wall", round(wall, 2)))
    listing = [(p.relative_to(view.folder).as_posix(), p.stat().st_size) for p in files
               if p.exists()]
    return Section("settings", "Settings, timing and files", [
        Table(("setting", "value"), settings, "Inputs and accuracy knobs of this report "
              "(gc.report keyword arguments; gearcoupling report options)."),
        Table(("stage", "seconds"), timing, "CPU time of each stage (in one of two worker "
              "processes where the machine has two cores) and the wall time of them all, "
              "on the machine that made the report."),
        Table(("data file", "bytes"), listing, "Beside report.html: each figure's data, the "
              "hob program and the data sheet."),
        Note("Conventions (frames, signs, units) are those of docs/conventions.md; the models "
             "and their validations are described in docs/load.md and docs/load-surface.md.")])
