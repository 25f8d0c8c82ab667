"""Measuring-machine charts of the nominal hub flank: profile and lead traces.

A gear measuring machine plots a flank as its deviation from the unmodified involute
helicoid (here: the spur involute of the midplane section, base radius
``r_b = R cos(phi)``, through the midplane pitch point), measured along the base tangent
in the transverse plane, positive = material excess. For tooth 0's cw flank at polar
angle ``theta(z, r)`` the deviation is ``r_b (theta_ref(r) - theta)``, for ccw
``r_b (theta - theta_ref_ccw(r))``, with ``theta_ref`` the midplane involute.

Traces and evaluation ranges (ISO 1328-1 / VDI 2607 style, defaults adjustable):

* profile traces at the midplane and at both ends of the lead evaluation range, against
  the roll length ``xi = sqrt(r^2 - r_b^2)``; evaluation range ``L_alpha`` from the form
  diameter over ``1 - tip_exclusion`` (92 %) of the length to the tip;
* lead traces at mid depth (the middle of ``L_alpha`` in the midplane) against ``z``;
  evaluation range ``L_beta`` = face width less ``min(5 % b, module)`` at each end.

Derived values: ``C_beta`` (crown height) and ``f_Hbeta`` (lead slope) from the
least-squares parabola ``a + b z + c z^2`` of the lead trace over ``L_beta``:
``C_beta = -c (L_beta/2)^2``, ``f_Hbeta = b L_beta``; ``f_Halpha`` (profile slope) from
the least-squares line of the profile trace over ``L_alpha``: slope times ``L_alpha``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..arguments import count, real
from ..geometry import FLANKS, HubModel, form_radius, hub_flank_model, hub_model, inv, tip_radius
from ..io import plot_text, write_csv_records
from ..plots import figure_axes, fixed_layout
from ..spec import CouplingSpec, as_spec

_EPS = 1e-9


@dataclass(frozen=True)
class Trace:
    """One nominal trace of tooth 0.

    Attributes
    ----------
    kind : {"profile", "lead"}
    flank : {"cw", "ccw"}
    position_mm : float
        ``z`` of a profile trace, ``r`` of a lead trace.
    x_mm : (n,) float
        Abscissa: roll length ``xi`` (profile) or ``z`` (lead).
    deviation_mm : (n,) float
        Design deviation from the midplane involute (+ = material excess).
    points, normals : (n, 3) float
        Hub-frame points and unit outward normals.
    evaluation_mm : (2,) float
        Evaluation range on the abscissa.
    """

    kind: str
    flank: str
    position_mm: float
    x_mm: NDArray[np.float64] = field(repr=False)
    deviation_mm: NDArray[np.float64] = field(repr=False)
    points: NDArray[np.float64] = field(repr=False)
    normals: NDArray[np.float64] = field(repr=False)
    evaluation_mm: tuple[float, float] = (0.0, 0.0)

    @property
    def name(self) -> str:
        where = "z" if self.kind == "profile" else "r"
        return f"{self.kind} {self.flank} {where}={self.position_mm:+.4f}"

    def in_range(self) -> NDArray[np.bool_]:
        lo, hi = self.evaluation_mm
        return (self.x_mm >= lo - _EPS) & (self.x_mm <= hi + _EPS)


@dataclass(frozen=True)
class MeasuringCharts:
    """Nominal traces and derived values; see :func:`measuring_charts`."""

    spec_name: str
    base_radius_mm: float
    lead_evaluation_mm: float
    traces: list[Trace] = field(repr=False)
    values: dict[str, dict[str, float]] = field(default_factory=dict)

    def summary(self) -> dict:
        """Evaluation ranges and derived values per flank (``charts.json``)."""
        return {"spec": self.spec_name, "base_radius_mm": self.base_radius_mm,
                "lead_evaluation_mm": self.lead_evaluation_mm,
                "reference": "midplane spur involute; deviation along the base tangent, "
                             "+ = material excess",
                "flanks": self.values}

    def rows(self) -> list[dict[str, object]]:
        """Every trace point with its normal: the nominal for a measuring machine."""
        out: list[dict[str, object]] = []
        for tr in self.traces:
            inside = tr.in_range()
            for i in range(len(tr.x_mm)):
                p, n = tr.points[i], tr.normals[i]
                out.append({"trace": tr.name, "kind": tr.kind, "flank": tr.flank, "tooth": 0,
                            "point": i, "x_mm": p[0], "y_mm": p[1], "z_mm": p[2],
                            "nx": n[0], "ny": n[1], "nz": n[2],
                            "r_mm": math.hypot(p[0], p[1]),
                            "roll_length_mm": math.sqrt(max(p[0] ** 2 + p[1] ** 2
                                                            - self.base_radius_mm ** 2, 0.0)),
                            "deviation_mm": tr.deviation_mm[i],
                            "in_evaluation": int(inside[i])})
        return out


def _reference_angle(m: HubModel, flank: str, r) -> NDArray[np.float64]:
    """Polar angle of the midplane spur involute of ``flank`` at radius ``r``."""
    rb = m.R * math.cos(m.phi)
    pts, _, _ = hub_flank_model(m, "cw", 0.0, m.R)
    theta_p = math.atan2(pts[1], pts[0])
    alpha = np.arccos(np.clip(rb / np.asarray(r, dtype=float), -1.0, 1.0))
    cw = theta_p + (inv(alpha) - inv(m.phi))
    return cw if flank == "cw" else -cw


def flank_deviation(m: HubModel, flank: str, points: NDArray[np.float64]) -> NDArray[np.float64]:
    """Base-tangent deviation of tooth-0 flank points from the midplane involute.

    Parameters
    ----------
    points : (n, 3) float
    Returns
    -------
    (n,) float
        ``r_b (theta_ref - theta)`` (cw) or ``r_b (theta - theta_ref)`` (ccw).
    """
    rb = m.R * math.cos(m.phi)
    r = np.hypot(points[..., 0], points[..., 1])
    d = np.arctan2(points[..., 1], points[..., 0]) - _reference_angle(m, flank, r)
    return rb * (-d if flank == "cw" else d)


def _trace(m: HubModel, kind: str, flank: str, pos: float, z, r, x, rng) -> Trace:
    pts, nrm, _ = hub_flank_model(m, flank, z, r)
    return Trace(kind, flank, float(pos), np.asarray(x, dtype=float),
                 flank_deviation(m, flank, pts), pts, nrm, (float(rng[0]), float(rng[1])))


def evaluation_ranges(spec: CouplingSpec, tip_exclusion: float = 0.08):
    """``(half_lead, profile, r_lead)``: the lead evaluation half length (mm; shortened where
    a tip sphere cuts the lead radius), a function ``z -> (r_start, r_end)`` of the profile
    evaluation range in plane ``z`` and the lead trace radius (middle of ``L_alpha`` in
    the midplane)."""
    m = hub_model(spec)
    b = 2.0 * m.half_face
    half_lead = m.half_face - min(0.05 * b, spec.tooth.module)
    rb = m.R * math.cos(m.phi)

    def profile(z: float) -> tuple[float, float]:
        r0 = max(float(form_radius(m, z)), rb * (1 + 1e-12))
        r1 = float(tip_radius(m, z))
        x0, x1 = math.sqrt(r0**2 - rb**2), math.sqrt(r1**2 - rb**2)
        x_end = x0 + (1.0 - tip_exclusion) * (x1 - x0)
        return r0, math.sqrt(rb**2 + x_end**2)

    r0, r1 = profile(0.0)
    x_mid = 0.5 * (math.sqrt(r0**2 - rb**2) + math.sqrt(r1**2 - rb**2))
    r_lead = math.sqrt(rb**2 + x_mid**2)
    return min(half_lead, lead_reach(m, r_lead)), profile, r_lead


def lead_reach(m: HubModel, r: float) -> float:
    """Largest ``|z|`` (up to the face end) where radius ``r`` is still below the tip
    surface (a tip sphere cuts the corners of short, small hubs)."""
    if float(tip_radius(m, m.half_face)) >= r:
        return m.half_face
    return math.sqrt(max(m.tip_radius**2 - r * r, 0.0)) * (1.0 - 1e-12)


def measuring_charts(spec: CouplingSpec,
                     points: int = 101, tip_exclusion: float = 0.08) -> MeasuringCharts:
    """Nominal profile and lead traces of both flanks, with ``C_beta``, ``f_Hbeta``, ``f_Halpha``.

    Parameters
    ----------
    spec : CouplingSpec
    points : int
        Points per trace (5 to ``MAXIMA["points"]``, 10 001); the traces are exact
        (``hub_flank``) at every point.
    tip_exclusion : float
        Share of the profile length from the form diameter to the tip left out of
        ``L_alpha`` at the tip end (0 to 0.5).
    """
    spec = as_spec(spec)
    count(points, "points", 5)
    real(tip_exclusion, "tip_exclusion", 0.0, 0.5, unit="(a share of the profile)")
    m = hub_model(spec)
    rb = m.R * math.cos(m.phi)
    half_lead, profile_range, r_lead = evaluation_ranges(spec, tip_exclusion)
    traces: list[Trace] = []
    values: dict[str, dict[str, float]] = {}
    for flank in FLANKS:
        vals: dict[str, float] = {}
        for z in (-half_lead, 0.0, half_lead):
            lo, hi = profile_range(z)
            r_form, r_tip = float(form_radius(m, z)), float(tip_radius(m, z))
            r = np.linspace(r_form, r_tip, points)
            x = np.sqrt(np.maximum(r * r - rb * rb, 0.0))
            tr = _trace(m, "profile", flank, z, z, r, x,
                        (math.sqrt(lo**2 - rb**2), math.sqrt(hi**2 - rb**2)))
            traces.append(tr)
            key = {-half_lead: "z_minus", 0.0: "mid", half_lead: "z_plus"}[z]
            vals[f"f_Halpha_{key}_mm"] = profile_slope(tr.x_mm, tr.deviation_mm,
                                                        tr.evaluation_mm)
        reach = lead_reach(m, r_lead)
        z = np.linspace(-reach, reach, points)
        tr = _trace(m, "lead", flank, r_lead, z, r_lead, z, (-half_lead, half_lead))
        traces.append(tr)
        c_beta, f_hb, apex = lead_values(tr.x_mm, tr.deviation_mm, half_lead)
        vals.update({"C_beta_mm": c_beta, "f_Hbeta_mm": f_hb, "crown_position_mm": apex,
                     "lead_radius_mm": r_lead,
                     "L_alpha_mid_mm": float(np.diff(traces[-3].evaluation_mm)[0])})
        values[flank] = vals
    return MeasuringCharts(spec.name, rb, 2.0 * half_lead, traces, values)


def profile_slope(x, d, rng) -> float:
    """``f_Halpha``: the least-squares line of ``d(x)`` over ``rng``, rise over the range."""
    x, d = np.asarray(x), np.asarray(d)
    sel = (x >= rng[0] - _EPS) & (x <= rng[1] + _EPS)
    slope = np.polyfit(x[sel], d[sel], 1)[0]
    return float(slope * (rng[1] - rng[0]))


def lead_values(z, d, half_lead: float) -> tuple[float, float, float]:
    """``(C_beta, f_Hbeta, crown position)`` of a lead trace ``d(z)`` over ``|z| <= half_lead``.

    The least-squares parabola ``a + b z + c z^2``: ``C_beta = -c half_lead^2``,
    ``f_Hbeta = 2 b half_lead``, crown position ``-b / (2c)`` (0 without crown).
    """
    z, d = np.asarray(z), np.asarray(d)
    sel = np.abs(z) <= half_lead + _EPS
    A = np.stack([np.ones(sel.sum()), z[sel], z[sel] ** 2], axis=-1)
    _, b, c = np.linalg.lstsq(A, d[sel], rcond=None)[0]
    apex = float(-b / (2.0 * c)) if abs(c) * half_lead**2 > 1e-12 else 0.0
    return float(-c * half_lead**2), float(2.0 * b * half_lead), apex


def plot_measuring_charts(charts: MeasuringCharts, ax=None):
    """Measuring-machine charts: profile (left) and lead (right) traces per flank.

    Parameters
    ----------
    ax : sequence of 4 matplotlib Axes, optional
        ``(profile cw, lead cw, profile ccw, lead ccw)``; a new figure when omitted.

    Returns
    -------
    matplotlib.figure.Figure
    """
    own = ax is None
    fig, axes = figure_axes(ax, (2, 2), figsize=(11, 8))
    axes = list(np.ravel(axes))
    for row, flank in enumerate(FLANKS):
        vals = charts.values[flank]
        pa, la = axes[2 * row], axes[2 * row + 1]
        for tr in (t for t in charts.traces if t.flank == flank):
            target = pa if tr.kind == "profile" else la
            label = f"z = {tr.position_mm:+.2f} mm" if tr.kind == "profile" else \
                f"r = {tr.position_mm:.3f} mm"
            target.plot(tr.x_mm, 1e3 * tr.deviation_mm, label=label)
            for edge in tr.evaluation_mm:
                target.axvline(edge, color="grey", lw=0.6, ls=":")
        pa.set_title(f"{flank} profile: f_Hα(mid) = {1e3 * vals['f_Halpha_mid_mm']:.2f} µm, "
                     f"ends {1e3 * vals['f_Halpha_z_minus_mm']:.2f} / "
                     f"{1e3 * vals['f_Halpha_z_plus_mm']:.2f} µm", fontsize=9)
        pa.set_xlabel("roll length ξ (mm)")
        la.set_title(f"{flank} lead: Cβ = {1e3 * vals['C_beta_mm']:.2f} µm, "
                     f"f_Hβ = {1e3 * vals['f_Hbeta_mm']:.2f} µm", fontsize=9)
        la.set_xlabel("z (mm)")
        for a in (pa, la):
            a.set_ylabel("deviation from midplane involute (µm, + material)")
            a.legend(fontsize=7, loc="best")
            a.grid(True, lw=0.3)
    fig.suptitle(f"{plot_text(charts.spec_name)}: "
                 "nominal measuring charts (evaluation ranges dotted)")
    if own:
        fixed_layout(fig, 0.83, 0.15, 0.59, 0.66, wspace=0.2, hspace=0.261)
    return fig


def write_nominal_csv(charts: MeasuringCharts, path: str | Path) -> Path:
    """The nominal traces as a CSV a measuring machine can load (points + normals)."""
    return write_csv_records(path, charts.rows(), [
        f"gearcoupling nominal measuring traces, spec {charts.spec_name}",
        "units: mm (coordinates, roll length, deviation); normals: unit vectors out of the "
        "tooth material",
        "frame: hub, origin at the axis in the tooth midplane, z along the axis, tooth 0 "
        "centred on +x; tooth k = rotation by 360 k / N deg about z",
        "deviation: from the midplane spur involute along the base tangent, + = material "
        "excess; in_evaluation = 1 inside L_alpha / L_beta",
    ])
