"""``gc.report``: the design report of a spec, one self-contained HTML file (and a PDF)."""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, fields
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from .. import __version__
from ..arguments import flag, keywords
from ..browser import browser_backend
from ..errors import ArgumentError
from ..hob import check_hob_diameter
from ..inspection import check_limits, grade_limits, load_points
from ..io import output_folder, require_file, writable_targets, write_text
from ..spec import CouplingSpec, as_spec
from . import sections as sec
from .datasheet import datasheet, start_datasheet
from .document import Note, Section, Table, render
from .pdf import print_pdf
from .settings import ReportSettings
from .verdict import (
    COLUMNS,
    geometry_verdicts,
    inspection_verdicts,
    interference_verdict,
    load_verdicts,
    overall,
)

REPORT = "report.html"


@dataclass(frozen=True)
class ReportResult:
    """What :func:`report` wrote: the HTML, the PDF (or None), the data files, the verdict
    (``pass``, ``fail`` or ``open`` when something was not judged, with its sentence) and
    each section's seconds."""

    html: Path
    pdf: Path | None
    files: tuple[Path, ...]
    verdict: str
    verdict_text: str
    seconds: dict[str, float]
    wall_seconds: float


def _steps(settings: ReportSettings) -> list[tuple[str, Callable[[sec.Context], Section]]]:
    steps: list[tuple[str, Callable[[sec.Context], Section]]] = [
        ("coupling", sec.coupling), ("clearance", sec.clearance),
             ("design angles", sec.design_angles), ("loads", sec.loads),
             ("capacity", sec.capacity_section), ("data sheet", datasheet),
             ("interference", sec.interference),
             ("manufacturing", sec.manufacturing)]
    if not settings.datasheet:
        steps.remove(("data sheet", datasheet))
    if settings.scan is not None:
        steps.append(("measured part", sec.measured))
    if settings.viewer:
        steps.append(("3D view", sec.view3d))
    return steps


def _computed_order(steps: list[tuple[str, Callable[[sec.Context], Section]]]
                    ) -> list[tuple[str, Callable[[sec.Context], Section]]]:
    """The steps in the order they are computed: the data sheet last, so that the sections
    after it in the report are built while its workers run."""
    return sorted(steps, key=lambda item: item[1] is datasheet)


def report(spec: CouplingSpec, out: str | os.PathLike, *, pdf: bool = False,
           progress: Callable[[int, int], None] | None = None,
           settings: ReportSettings | None = None, **options: Any) -> ReportResult:
    """Write the design report of ``spec`` into the folder ``out``.

    ``report.html`` is self-contained (figures inline, the 3D viewer embedded, no network)
    and holds: the verdict table against the spec's limits (saying which are not set), the
    spec and its derived values, clearance, backlash and contact over the turn, the
    critical and binding angles with Renzo's estimates, the loads (tooth load, q,
    pressure, root stress, machine loads, contact patches), capacity per criterion against
    misalignment, the interference check, the hob program and measuring charts, a measured
    part when ``scan`` is given, and the 3D view. Each figure's data is a CSV file in
    ``out/report-data/`` and its model and accuracy settings are written under it.

    Parameters
    ----------
    spec : CouplingSpec
    out : path-like
        Output folder (created).
    pdf : bool
        Also print ``report.pdf`` through headless chromium (the ``browser`` extra and
        Debian's chromium; the 3D view becomes a picture).
    progress : callable, optional
        ``progress(done, total)`` after each section.
    settings : ReportSettings, optional
        Inputs and accuracy knobs; or give them as keyword arguments (``torque_Nm``,
        ``misalignment_deg``, ``scan``, ``angles``, ...; see :class:`ReportSettings`).

    Returns
    -------
    ReportResult
    """
    spec = as_spec(spec)
    output_folder(out, "out", create=False)
    writable_targets(out, report_files(pdf), [sec.DATA_DIR], "out")
    if settings is not None and not isinstance(settings, ReportSettings):
        raise ArgumentError("settings", settings, "a ReportSettings")
    keywords(options, [f.name for f in fields(ReportSettings)], "report")
    flag(pdf, "pdf")
    s = settings if settings is not None else ReportSettings(**options)
    t0 = time.perf_counter()
    mis, torque, model = sec.resolve(spec, s)
    scan_points = _check_inputs(spec, s)
    if pdf:
        browser_backend()
    created = not Path(out).exists()
    folder = output_folder(out, "out")
    ctx = sec.Context(spec, s, folder, mis, torque, model, scan_points=scan_points)
    try:
        return _build(ctx, pdf, progress, t0)
    except BaseException:  # an error or an interruption: no partial report is left
        _discard(ctx, created)
        raise


def report_files(pdf: bool = False) -> list[str]:
    """The files :func:`report` writes beside its data folder (``report-data/``, a folder
    of its own): ``report.html``, and ``report.pdf`` with ``pdf``."""
    return ["report.html", *(["report.pdf"] if pdf else [])]


def _build(ctx: sec.Context, pdf: bool, progress: Callable[[int, int], None] | None,
           t0: float) -> ReportResult:
    spec, s, folder, mis, torque, model = (ctx.spec, ctx.settings, ctx.out,
                                           ctx.misalignment_deg, ctx.torque_Nm, ctx.model)
    steps = _steps(s)
    total = len(steps) + 1 + (1 if pdf else 0)
    built: dict[str, Section] = {}
    seconds: dict[str, float] = {}
    files: dict[str, list[Path]] = {}
    sec.start_capacity(ctx)  # its workers run while the sections before it are built
    try:
        for n, (name, step) in enumerate(_computed_order(steps)):
            t, ahead = time.perf_counter(), len(ctx.files)
            section = step(ctx)
            section.seconds = seconds[name] = (time.perf_counter() - t
                                               + seconds.get(name, 0.0))
            built[name], files[name] = section, ctx.files[ahead:]
            if step is sec.capacity_section and s.datasheet:
                t = time.perf_counter()  # its start counts as the data sheet's time
                start_datasheet(ctx)  # its workers run while the sections after it are built
                seconds["data sheet"] = time.perf_counter() - t
            if progress is not None:
                progress(n + 1, total)
    finally:
        ctx.capacity_curve.stop()
        if not (ctx.datasheet_run is None or isinstance(ctx.datasheet_run, str)):
            ctx.datasheet_run.stop()
    ctx.files[:] = [p for name, _ in steps for p in files[name]]  # in the report's order
    seconds = {name: seconds[name] for name, _ in steps}
    sections = [built[name] for name, _ in steps]
    verdicts = _verdicts(ctx)
    cls, text = overall(verdicts)
    head = Section("verdict", "Verdict against the spec's limits", [
        Table(COLUMNS, [v.row() for v in verdicts], "pass / fail only against a limit; "
              "not judged where the spec sets no limit or an input is missing (the reason "
              "says which key or option sets it).", verdict_column=4)])
    wall = time.perf_counter() - t0
    sections.append(_provenance(ctx, seconds, wall))
    html_path = folder / "report.html"
    title = f"Gear coupling design report: {spec.name}"
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    sub = (f"i = {mis:g}°, " + (f"T = {torque:.4g} N·m" if torque is not None else "no torque")
           + f", {model} load model · gearcoupling {__version__} · {when}")
    ctx.files.append(html_path)
    write_text(html_path, render(title, sub, (cls, text), [head, *sections]))
    if progress is not None:
        progress(len(steps) + 1, total)
    pdf_path = None
    if pdf:
        ctx.files.append(folder / "report.pdf")
        pdf_path = print_pdf(html_path, folder / "report.pdf")
        if progress is not None:
            progress(total, total)
    data = tuple(p for p in ctx.files if p not in (html_path, pdf_path))
    return ReportResult(html_path, pdf_path, data, cls, text, seconds,
                        time.perf_counter() - t0)


def _discard(ctx: sec.Context, created: bool) -> None:
    """Remove what this report wrote (its data folder and the folder itself when they are
    left empty and were made now)."""
    for path in ctx.files:
        path.unlink(missing_ok=True)
    for folder in (ctx.data_dir, *([ctx.out] if created else [])):
        with contextlib.suppress(OSError):  # not empty: other files were there before
            folder.rmdir()


def _check_inputs(spec: CouplingSpec, s: ReportSettings):
    """Inputs that would fail late, checked before anything is computed: the scan (read
    and checked here; its points are returned), the inspection limits and class, the hob
    diameter."""
    points = None
    if s.scan is not None:
        require_file(s.scan, "scan", "a scan or mesh file (STL/PLY/OBJ, CSV/XYZ)", ArgumentError)
        try:
            points = load_points(Path(s.scan), s.scan_units)
        except ArgumentError as err:
            raise ArgumentError("scan", str(s.scan), getattr(err, "allowed", str(err))) from None
    if s.grade is not None:
        grade_limits(spec, s.grade)
    check_limits(s.limits)
    if s.hob_diameter_mm is not None:
        check_hob_diameter(spec, s.hob_diameter_mm)
    return points


def _verdicts(ctx: sec.Context):
    f = ctx.found
    rows = geometry_verdicts(ctx.misalignment_deg, f["min_backlash_mm"], f.get("critical_deg"),
                             f.get("binding_deg"))
    rows += load_verdicts(ctx.spec, f.get("load"), f.get("capacity"))
    rows.append(interference_verdict(*f.get("interference", (None, "not run"))))
    rows += inspection_verdicts(f.get("inspection"))
    return rows


def _provenance(ctx: sec.Context, seconds: dict[str, float], wall: float) -> Section:
    used = {"misalignment_deg": ctx.misalignment_deg, "torque_Nm": ctx.torque_Nm,
            "model": ctx.model}
    settings = []
    for k, v in ctx.settings.as_dict().items():
        if k in used:
            k, v = f"{k} (used)", used[k]
        elif isinstance(v, dict):
            v = ", ".join(f"{a}={b:g}" for a, b in v.items()) or "–"
        settings.append((k, v))
    timing = [(k, round(v, 2)) for k, v in seconds.items()] + [("all sections", round(wall, 2))]
    files = [(str(p.relative_to(ctx.out)), p.stat().st_size) for p in ctx.files if p.exists()]
    return Section("settings", "Settings, timing and files", [
        Table(("setting", "value"), settings, "Inputs and accuracy knobs of this report "
              "(gc.report keyword arguments; gearcoupling report options)."),
        Table(("section", "seconds"), timing, "Wall time on the machine that made the report."),
        Table(("data file", "bytes"), files, "Beside report.html: each figure's data."),
        Note("Conventions (frames, signs, units) are those of docs/conventions.md; the models "
             "and their validations are described in docs/load.md and docs/load-surface.md.")])
