"""Per tooth and flank evaluation of a registered scan, tolerances, and the report.

Each flank's deviations ``d`` (mm, + material) over the band are fitted by least squares
with ``a0 + a1 (xi - xi_ref) + a2 z + a3 z^2`` (``xi`` roll length, ``xi_ref`` at the lead
trace radius, :mod:`gearcoupling.hob.charts`), giving

* ``offset`` ``a0``: normal deviation of the flank at the reference point;
* ``f_Halpha`` ``a1 L_alpha`` and ``f_Hbeta`` ``a2 L_beta``: profile and lead slope
  deviations over the evaluation ranges;
* ``C_beta``: nominal crown height minus ``a3 (L_beta / 2)^2``, and the crown position
  (apex of the nominal crown plus the fitted lead terms);
* ``form_rms``: rms of the fit residual (form deviation and noise).

Pitch: a flank's position along the pitch circle ``u = -+ a0 R / (r_ref |n_t|)`` (arc at
``R``, + toward increasing polar angle); single pitch deviation ``f_pt = u_k - u_(k-1)``,
cumulative ``F_pk = u_k - mean(u)``, ``F_p`` its range. Thickness deviation (arc at ``R``)
``(a0_cw + a0_ccw) R / (r_ref |n_t|)``. Runout of a ball in space ``k`` (between teeth
``k`` and ``k+1``): ``(a0_ccw,k + a0_cw,k+1) / (2 sin phi)`` less its mean; ``F_r`` its
range. Registration fits all six rigid degrees of freedom to the flanks, so pitch is
relative to the teeth's own best-fit axis; runout is relative to the bore axis when the
scan has bore points (:mod:`.datum`), else to that best-fit axis too (an eccentric tooth
ring is then centred by the fit, not reported as runout).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..arguments import is_real
from ..errors import ArgumentError
from ..geometry import hub_flank_model
from ..hob import MeasuringCharts
from ..tables import dataframe
from .register import Registration
from .surface import FlankTable, PointDeviation

LIMITS = {
    "fpt": "single pitch deviation |f_pt| per flank (mm)",
    "Fp": "total cumulative pitch deviation F_p (mm, part)",
    "Fr": "runout F_r (mm, part)",
    "f_Halpha": "profile slope deviation |f_Halpha| (mm)",
    "f_Hbeta": "lead slope deviation |f_Hbeta| (mm)",
    "C_beta": "crown height deviation |C_beta - nominal| (mm)",
    "thickness": "tooth thickness deviation |ds| at the pitch circle (mm)",
}
FLANK_NAMES = ("cw", "ccw")


def check_limits(limits) -> dict[str, float]:
    """Validated tolerance limits (mm); keys from :data:`LIMITS`."""
    if limits is not None and not isinstance(limits, dict):
        raise ArgumentError("limits", limits, "a dict of limit name -> mm")
    out = {}
    for key, value in (limits or {}).items():
        if key not in LIMITS:
            raise ArgumentError(f"limits.{key}", value, f"a known limit: {', '.join(LIMITS)}")
        v = float(value) if is_real(value) else math.nan  # text is read by the caller
        if not (math.isfinite(v) and v > 0):
            raise ArgumentError(f"limits.{key}", value, "a positive length in mm")
        out[key] = v
    return out


@dataclass(frozen=True)
class InspectionReport:
    """Result of :func:`gearcoupling.compare_part` for one scan."""

    spec_name: str
    source: str
    points: int
    registration: Registration
    table_error_mm: float
    teeth: NDArray[np.intp]
    flank: dict[str, dict[str, NDArray[np.float64]]] = field(repr=False)
    tooth: dict[str, NDArray[np.float64]] = field(repr=False)
    part: dict[str, Any] = field(default_factory=dict)
    limits: dict[str, float] = field(default_factory=dict)
    passed: NDArray[np.bool_] | None = field(default=None, repr=False)
    sample: dict[str, NDArray] = field(default_factory=dict, repr=False)
    nominal: dict[str, dict[str, float]] = field(default_factory=dict)

    def rows(self) -> list[dict[str, object]]:
        """One row per measured tooth (``inspection.csv``)."""
        out = []
        for i, k in enumerate(self.teeth):
            row: dict[str, object] = {"tooth": int(k)}
            for f in FLANK_NAMES:
                for key, arr in self.flank[f].items():
                    col = f"{key[:-3]}_{f}_mm" if key.endswith("_mm") else f"{key}_{f}"
                    row[col] = _clean(arr[i])
            for key, arr in self.tooth.items():
                row[key] = _clean(arr[i])
            if self.passed is not None:
                row["pass"] = bool(self.passed[i])
            out.append(row)
        return out

    def to_dataframe(self):
        """:meth:`rows` as a pandas DataFrame with the columns of ``inspection.csv`` (the
        ``pandas`` extra)."""
        rows = self.rows()
        return dataframe(list(rows[0]) if rows else [], rows)

    def summary(self) -> dict:
        """Registration, part values, limits and per-tooth pass/fail (``inspection.json``)."""
        return {
            "spec": self.spec_name, "source": self.source, "points": self.points,
            "registration": self.registration.summary(),
            "table_error_mm": self.table_error_mm,
            "teeth_measured": [int(k) for k in self.teeth],
            "nominal": self.nominal, "part": self.part, "limits": self.limits,
            "failed_teeth": [] if self.passed is None else
            [int(k) for k, ok in zip(self.teeth, self.passed, strict=True) if not ok],
            "tooth_numbering": "tooth k centred at 360 k / N deg after registration; the "
                               "tooth nearest the scan's coarse +x is 0",
        }


def _clean(v):
    return float(v)


def _group_fit(g, B, d, n_groups):
    """Per-group least squares ``d ~ B x`` by normal equations; returns ``(x, rms, count)``."""
    k = B.shape[1]
    A = np.zeros((n_groups, k, k))
    b = np.zeros((n_groups, k))
    for i in range(k):
        b[:, i] = np.bincount(g, B[:, i] * d, n_groups)
        for j in range(i, k):
            A[:, i, j] = A[:, j, i] = np.bincount(g, B[:, i] * B[:, j], n_groups)
    count = np.bincount(g, minlength=n_groups)
    x = np.full((n_groups, k), np.nan)
    ok = count >= 2 * k
    ok[ok] &= np.linalg.cond(A[ok]) < 1e12
    x[ok] = np.linalg.solve(A[ok], b[ok][..., None])[..., 0]
    res = d - np.einsum("ij,ij->i", B, np.nan_to_num(x[g]))
    rms = np.sqrt(np.bincount(g, res * res, n_groups) / np.maximum(count, 1))
    return x, rms, count


def evaluate(table: FlankTable, charts: MeasuringCharts, dev: PointDeviation, *,
             min_points: int = 30, min_cover: float = 0.5,
             datum_centre: NDArray[np.float64] | None = None) -> dict:
    """Per tooth and flank values from the band deviations of a registered scan.

    ``datum_centre``: the datum (bore) axis at ``z = 0`` in the hub frame; runout is then
    relative to it (the tooth ring's offset from the datum adds its radial component at
    each space), else relative to the teeth's best-fit axis.
    """
    m = table.model
    N = m.teeth
    rb = m.R * math.cos(m.phi)
    half = table.half_lead
    cw_vals = charts.values["cw"]
    r_ref = cw_vals["lead_radius_mm"]
    xi_ref = math.sqrt(r_ref**2 - rb**2)
    L_alpha = math.sqrt(table.r_hi**2 - rb**2) - math.sqrt(table.r_lo**2 - rb**2)
    # exact normal at the reference point: its tangential part turns normal into arc
    pts, nrm, _ = hub_flank_model(m, "cw", 0.0, r_ref)
    n_t = (-nrm[0] * pts[1] + nrm[1] * pts[0]) / r_ref
    factor = m.R / (r_ref * abs(float(n_t)))
    xi = np.sqrt(np.maximum(dev.r**2 - rb**2, 0.0)) - xi_ref
    zn = dev.z / half
    B = np.stack([np.ones_like(xi), xi / L_alpha, zn, zn * zn], axis=-1)
    g = dev.tooth * 2 + dev.flank
    x, rms, count = _group_fit(g, B, dev.d, 2 * N)
    # coverage of each flank: axial and profile spread of its points
    zspan = _span(g, dev.z, 2 * N) / (2 * half)
    xspan = _span(g, xi, 2 * N) / L_alpha
    good = (count >= min_points) & (zspan >= min_cover) & (xspan >= min_cover) & \
        np.all(np.isfinite(x), axis=1)
    good2 = good.reshape(N, 2)
    teeth = np.flatnonzero(good2.all(axis=1))
    x2 = x.reshape(N, 2, 4)
    flank: dict[str, dict[str, NDArray[np.float64]]] = {}
    u = np.zeros((N, 2))
    for fi, f in enumerate(FLANK_NAMES):
        a = x2[teeth, fi]
        c_nom = charts.values[f]["C_beta_mm"]
        c_tot = -c_nom + a[:, 3]  # total lead curvature term in units of (z / half)^2
        with np.errstate(divide="ignore", invalid="ignore"):
            apex = np.where(np.abs(c_tot) > 1e-9, -a[:, 2] * half / (2 * c_tot), np.nan)
        sign = -1.0 if f == "cw" else 1.0
        u[:, fi] = sign * x2[:, fi, 0] * factor
        flank[f] = {
            "points": count.reshape(N, 2)[teeth, fi].astype(float),
            "offset_mm": a[:, 0], "f_Halpha_mm": a[:, 1], "f_Hbeta_mm": 2 * a[:, 2],
            "C_beta_mm": c_nom - a[:, 3], "C_beta_dev_mm": -a[:, 3],
            "crown_position_mm": apex, "form_rms_mm": rms.reshape(N, 2)[teeth, fi],
        }
    have = np.zeros(N, bool)
    have[teeth] = True
    prev = np.roll(np.arange(N), 1)
    for fi, f in enumerate(FLANK_NAMES):
        uk = u[teeth, fi]
        mean = float(np.mean(uk)) if len(uk) else 0.0
        fpt = np.where(have[prev[teeth]], u[teeth, fi] - u[prev[teeth], fi], np.nan)
        flank[f]["fpt_mm"] = fpt
        flank[f]["Fpk_mm"] = uk - mean
    nxt = (teeth + 1) % N
    run = np.where(have[nxt], (x2[teeth, 1, 0] + x2[nxt, 0, 0]) / (2 * math.sin(m.phi)), np.nan)
    if datum_centre is not None:  # the ring sits at -centre from the datum axis
        ang = 2 * math.pi * (teeth + 0.5) / N
        run = run - (datum_centre[0] * np.cos(ang) + datum_centre[1] * np.sin(ang))
    run_valid = run[np.isfinite(run)]
    run = run - (float(np.mean(run_valid)) if len(run_valid) else 0.0)
    tooth = {"thickness_dev_mm": (x2[teeth, 0, 0] + x2[teeth, 1, 0]) * factor,
             "runout_mm": run}
    Fp = max((float(np.ptp(flank[f]["Fpk_mm"])) if len(teeth) else 0.0) for f in FLANK_NAMES)
    part = {"teeth_measured": len(teeth), "F_p_mm": Fp,
            "F_r_mm": float(np.ptp(run_valid)) if len(run_valid) else None,
            "f_pt_max_mm": _absmax(flank, "fpt_mm"),
            "thickness_dev_mean_mm": float(np.mean(tooth["thickness_dev_mm"]))
            if len(teeth) else None,
            "C_beta_dev_mean_mm": float(np.mean(np.concatenate(
                [flank[f]["C_beta_dev_mm"] for f in FLANK_NAMES]))) if len(teeth) else None,
            "band_points": len(dev.d), "pitch_factor": factor}
    return {"teeth": teeth, "flank": flank, "tooth": tooth, "part": part}


def _span(g, v, n):
    hi = np.full(n, -np.inf)
    lo = np.full(n, np.inf)
    np.maximum.at(hi, g, v)
    np.minimum.at(lo, g, v)
    return np.where(np.isfinite(hi - lo), hi - lo, 0.0)


def _absmax(flank, key):
    vals = np.concatenate([flank[f][key] for f in FLANK_NAMES])
    vals = vals[np.isfinite(vals)]
    return float(np.max(np.abs(vals))) if len(vals) else None


PER_TOOTH = {"fpt": "fpt_mm", "f_Halpha": "f_Halpha_mm", "f_Hbeta": "f_Hbeta_mm",
             "C_beta": "C_beta_dev_mm"}  # per flank; "thickness" is per tooth


def worst_values(ev: dict) -> dict[str, float | None]:
    """The largest measured value of each limit of :data:`LIMITS` (mm; None: not measured)."""
    out: dict[str, float | None] = {k: _absmax(ev["flank"], col) for k, col in PER_TOOTH.items()}
    part = ev["part"]
    out["Fp"], out["Fr"] = part["F_p_mm"], part["F_r_mm"]
    ds = np.abs(ev["tooth"]["thickness_dev_mm"])
    ds = ds[np.isfinite(ds)]
    out["thickness"] = float(np.max(ds)) if len(ds) else None
    return {k: out[k] for k in LIMITS}


def verdicts(worst: dict[str, float | None], limits: dict[str, float]) -> list[dict]:
    """One row per limit of :data:`LIMITS`: what it bounds, the worst measured value, the
    limit and ``pass``, ``fail`` or ``not judged`` (no limit set, or nothing measured)."""
    rows = []
    for key, what in LIMITS.items():
        value, limit = worst.get(key), limits.get(key)
        if limit is None:
            verdict = "not judged"
            why = "no limit set"
        elif value is None:
            verdict, why = "not judged", "not measured"
        else:
            verdict, why = ("pass" if value <= limit else "fail"), ""
        rows.append({"limit": key, "what": what, "measured_mm": value, "limit_mm": limit,
                     "verdict": verdict, "reason": why})
    return rows


def pass_fail(ev: dict, limits: dict[str, float]):
    """Per-tooth pass/fail and part-level checks against ``limits``.

    Returns ``(ok, checks)``: ``ok`` per measured tooth (``None`` when no per-tooth limit
    is set: nothing was judged), ``checks`` with ``pass`` (``None`` when no limit is set at
    all), ``F_p_pass``/``F_r_pass`` where those limits are set, ``verdicts`` (see
    :func:`verdicts`) and ``not_judged``, the limits that were not set.
    """
    teeth = ev["teeth"]
    ok = np.ones(len(teeth), bool)
    for key, col in PER_TOOTH.items():
        if key in limits:
            for f in FLANK_NAMES:
                v = np.abs(ev["flank"][f][col])
                ok &= ~(v > limits[key])  # NaN (a neighbour tooth missing) is not a failure
    if "thickness" in limits:
        ok &= np.abs(ev["tooth"]["thickness_dev_mm"]) <= limits["thickness"]
    part = ev["part"]
    checks: dict[str, object] = {}
    if "Fp" in limits:
        checks["F_p_pass"] = part["F_p_mm"] <= limits["Fp"]
    if "Fr" in limits and part["F_r_mm"] is not None:
        checks["F_r_pass"] = part["F_r_mm"] <= limits["Fr"]
    rows = verdicts(worst_values(ev), limits)
    judged = [r for r in rows if r["verdict"] != "not judged"]
    per_tooth = any(k in limits for k in (*PER_TOOTH, "thickness"))
    checks["pass"] = (bool(ok.all()) and all(r["verdict"] == "pass" for r in judged)
                      if judged else None)
    checks["verdicts"] = rows
    checks["not_judged"] = [r["limit"] for r in rows if r["verdict"] == "not judged"]
    return (ok if per_tooth else None), checks
