"""Measured part vs nominal (:func:`compare_part`) and part vs part (geometry regression)."""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import cast, overload

import numpy as np

from ..arguments import choice, count, positive
from ..errors import ArgumentError
from ..hob import measuring_charts
from ..spec import CouplingSpec, as_spec
from ..tables import dataframe
from .datum import bore_datum
from .io import UNIT_SCALE, check_magnitude, load_points
from .iso1328 import grade_limits
from .register import RegistrationError, register
from .report import FLANK_NAMES, InspectionReport, check_limits, evaluate, pass_fail
from .surface import deviation, flank_table

SAMPLE = 200_000  # points kept in the report for the deviation map
STAGES = 2  # progress stages per part (register, evaluate), plus reading and the table


@dataclass(frozen=True)
class PartComparison:
    """Two parts inspected against the same nominal; ``rows`` are B - A per tooth."""

    a: InspectionReport
    b: InspectionReport

    def rows(self) -> list[dict[str, object]]:
        ra = {r["tooth"]: r for r in self.a.rows()}
        out = []
        for rb in self.b.rows():
            if rb["tooth"] not in ra:
                continue
            row: dict[str, object] = {"tooth": rb["tooth"]}
            for key, vb in rb.items():
                va = ra[rb["tooth"]].get(key)
                if key.endswith("_mm") and isinstance(vb, float) and isinstance(va, float):
                    row[f"{key[:-3]}_diff_mm"] = vb - va
            out.append(row)
        return out

    def to_dataframe(self):
        """:meth:`rows` (B - A per tooth) as a pandas DataFrame with the columns of
        ``comparison.csv`` (the ``pandas`` extra)."""
        rows = self.rows()
        return dataframe(list(rows[0]) if rows else [], rows)

    def summary(self) -> dict:
        rows = self.rows()
        worst: dict[str, float] = {}
        for row in rows:
            for key, v in row.items():
                if key != "tooth":  # the others are the float differences of rows()
                    worst[key] = max(worst.get(key, 0.0), abs(cast(float, v)))
        return {"a": self.a.summary(), "b": self.b.summary(),
                "common_teeth": [r["tooth"] for r in rows], "max_abs_diff": worst}


def _points(source, units: str):
    if isinstance(source, str | os.PathLike):
        return load_points(Path(source), units), str(source)
    try:
        pts = np.asarray(source)
    except ValueError:  # a ragged nesting
        pts = np.asarray(None)
    if pts.dtype.kind not in "iuf":
        raise ArgumentError("source", source, "a scan file path or an (n, 3) array of "
                            "point coordinates")
    pts = pts.astype(float)
    if pts.ndim != 2 or pts.shape[1] != 3 or len(pts) == 0:
        raise ArgumentError("points", f"array of shape {pts.shape}", "an (n, 3) array, n >= 1")
    if not np.all(np.isfinite(pts)):
        raise ArgumentError("points", "array with NaN/inf", "finite coordinates only")
    pts = pts * UNIT_SCALE[units]
    check_magnitude(pts, "points", f"array of shape {pts.shape}")
    return pts, "array"


@overload
def compare_part(spec: CouplingSpec, source, other: None = None, *, units: str = "mm",
                 limits=None, grade: int | None = None, coarse: str = "auto",
                 fit_points: int = 20_000, grid: tuple[int, int] = (61, 41),
                 outlier_mm: float | None = None, min_points: int = 30,
                 progress: Callable[[int, int], None] | None = None) -> InspectionReport: ...


@overload
def compare_part(spec: CouplingSpec, source, other: str | Path | np.ndarray, *,
                 units: str = "mm", limits=None, grade: int | None = None,
                 coarse: str = "auto", fit_points: int = 20_000,
                 grid: tuple[int, int] = (61, 41), outlier_mm: float | None = None,
                 min_points: int = 30, progress: Callable[[int, int], None] | None = None
                 ) -> PartComparison: ...


def compare_part(spec: CouplingSpec, source, other=None, *, units: str = "mm", limits=None,
                 grade: int | None = None, coarse: str = "auto", fit_points: int = 20_000,
                 grid: tuple[int, int] = (61, 41), outlier_mm: float | None = None,
                 min_points: int = 30, progress: Callable[[int, int], None] | None = None
                 ) -> InspectionReport | PartComparison:
    """Inspect a measured hub against the spec's nominal, tooth by tooth.

    Parameters
    ----------
    spec : CouplingSpec
    source : path or (n, 3) float array
        Mesh (STL/PLY/OBJ: vertices) or point cloud (CSV/PLY/XYZ) of the hub, any placement.
    other : path or array, optional
        A second part: both are inspected and compared (:class:`PartComparison`, B - A).
    units : {"mm", "in", "m"}
        Unit of the file coordinates (a scan in other units than given is detected by
        its size and refused with the reason).
    limits : dict, optional
        Tolerances in mm, keys of :data:`~gearcoupling.inspection.report.LIMITS`; they
        override ``grade`` and the spec's ``[inspection]`` limits. A quantity without a
        limit is reported "not judged", never passed.
    grade : int, optional
        ISO 1328-1:2013 flank tolerance class (1-11) whose limits (``fpt``, ``Fp``,
        ``Fr``, ``f_Halpha``, ``f_Hbeta``, :func:`~.iso1328.grade_limits`) override the
        spec's.
    coarse : {"auto", "none"}
        ``none`` keeps the file's frame (part coordinates; partial scans).
    fit_points : int
        Points used by the fine registration (accuracy knob; all points are evaluated).
    grid : (int, int)
        ``(z, r)`` grid of the tabulated exact flank (accuracy knob).
    outlier_mm : float, optional
        Points farther than this from the nominal are outliers (default 0.1 module).
    min_points : int
        A flank with fewer band points (or covering less than half of the evaluation
        ranges) is not reported; a tooth is reported when both flanks are.
    progress : callable, optional
        ``progress(done, total)`` after each stage (``STAGES`` per part, plus two).

    Returns
    -------
    InspectionReport or PartComparison
    """
    spec = as_spec(spec)
    if source is None:
        raise ArgumentError("source", None, "a scan file path or an (n, 3) array of points")
    choice(units, "units", ("mm", "in", "m"))
    choice(coarse, "coarse", ("auto", "none"))
    count(fit_points, "fit_points", 100)
    count(min_points, "min_points", 1, 1_000_000)
    if not (isinstance(grid, tuple | list) and len(grid) == 2):
        raise ArgumentError("grid", grid, "(z, r) counts of the flank table, each 5-1001")
    grid = (count(grid[0], "grid", 5, 1001), count(grid[1], "grid", 5, 1001))
    if outlier_mm is not None:
        positive(outlier_mm, "outlier_mm")
    if limits is not None and not isinstance(limits, dict):
        raise ArgumentError("limits", limits, "a dict of limit name -> mm")
    graded = {} if grade is None else grade_limits(spec, grade)
    lim = check_limits({**spec.inspection.as_dict(), **graded, **dict(limits or {})})
    parts = [_points(src, units) for src in (source, other) if src is not None]
    total, done = 2 + STAGES * len(parts), [0]

    def step(_label: str) -> None:
        done[0] += 1
        if progress is not None:
            progress(done[0], total)

    step(f"read {', '.join(f'{len(p):,}' for p, _ in parts)} points")
    table = flank_table(spec, grid)
    charts = measuring_charts(spec)
    step("nominal flank table")
    args = (table, charts, lim, coarse, fit_points, outlier_mm, min_points, step)
    reports = [_inspect(spec, pts, name, *args) for pts, name in parts]
    return reports[0] if other is None else PartComparison(*reports)


def _inspect(spec: CouplingSpec, pts, name, table, charts, lim, coarse, fit_points, outlier_mm,
             min_points, step) -> InspectionReport:
    reg = register(pts, table, coarse=coarse, fit_points=fit_points, outlier_mm=outlier_mm)
    step(f"registered (rms {1e3 * reg.rms_mm:.2f} um)")
    hub = reg.apply(pts)
    dev = deviation(table, hub)
    outlier = 0.2 * table.model.R / table.model.teeth if outlier_mm is None else outlier_mm
    keep = np.abs(dev.d) <= outlier
    dev = type(dev)(*(getattr(dev, f)[keep] for f in dev.__dataclass_fields__))
    datum = bore_datum(hub, spec)
    ev = evaluate(table, charts, dev, min_points=min_points,
                  datum_centre=None if datum is None else datum["centre_mm"])
    if not len(ev["teeth"]):
        raise RegistrationError(
            f"{name}: no tooth has both flanks measured: a flank needs {min_points} points "
            f"in the band |z| <= {table.half_lead:.4g} mm, r = {table.r_lo:.5g} .. "
            f"{table.r_hi:.5g} mm covering half of it ({len(dev.d)} band points in all)")
    step("evaluated")
    ok, checks = pass_fail(ev, lim)
    ev["part"].update(checks)
    ev["part"]["outliers"] = int((~keep).sum())
    ev["part"]["runout_datum"] = "teeth best-fit axis" if datum is None else "bore axis"
    if datum is not None:
        ev["part"]["bore"] = {k: (v.tolist() if hasattr(v, "tolist") else v)
                              for k, v in datum.items()}
    take = np.linspace(0, len(dev.d) - 1, min(SAMPLE, len(dev.d))).astype(np.intp)
    rb = table.model.R * math.cos(table.model.phi)
    sample = {"points": hub[dev.index[take]],
              "tooth": dev.tooth[take], "flank": dev.flank[take], "z": dev.z[take],
              "xi": np.sqrt(np.maximum(dev.r[take] ** 2 - rb**2, 0.0)), "d": dev.d[take]}
    nominal = {f: {k: charts.values[f][k] for k in ("C_beta_mm", "f_Hbeta_mm",
                                                    "lead_radius_mm")} for f in FLANK_NAMES}
    nominal["lead_evaluation_mm"] = {"L_beta": 2 * table.half_lead}
    nominal["band_mm"] = {"r_lo": table.r_lo, "r_hi": table.r_hi}
    return InspectionReport(spec.name, name, len(pts), reg, table.table_error_mm, ev["teeth"],
                            ev["flank"], ev["tooth"], ev["part"], lim, ok, sample, nominal)
