"""Pictures of a sweep (matplotlib).

Every ``plot_*`` function returns a :class:`matplotlib.figure.Figure` and accepts ``ax=``:
an Axes for the one-panel plots, a sequence of Axes (as many as its panels) for the others;
without it a new Figure is made (not through pyplot: the user's back-end is never
switched). :func:`plot_all` writes them as PNG files, atomically.

- :func:`plot_clearance` - clearance of every tooth against rotation (Renzo Fig. 10, Wei
  Fig. 5), both flanks, whole flank and pitch line;
- :func:`plot_contact_path` - where each tooth touches on the flank (Wei Fig. 9);
- :func:`plot_clearance_map` - the gap over one flank at the contacting tooth (Wei Fig. 6);
- :func:`plot_backlash` - smallest backlash over a turn against misalignment;
- :func:`plot_critical_vs_radius` - critical misalignment against R_c (Wei Fig. 14);
- :func:`plot_generation` - pitch-line clearance of the enveloped and revolved crowns and
  their difference (Renzo Fig. 7).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..arguments import GAP_TOLERANCE_MM
from ..geometry import map_polar, sleeve_model
from ..io import atomic_path, plot_text
from ..plots import figure_axes, fixed_layout
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec
from .design import binding_angle_deg, critical_misalignment_deg, min_backlash_rad
from .flank_table import flank_table
from .kernel import sleeve_gaps
from .result import SweepResult
from .tooth_map import check_misalignment, flank_minima


def _colours(name: str, count: int):
    import matplotlib

    return matplotlib.colormaps[name](np.linspace(0, 1, count, endpoint=False))


def save_png(fig, path: str | Path, dpi: int = 130) -> Path:
    """Write ``fig`` as PNG atomically."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return Path(path)


def plot_clearance(result: SweepResult, *, ax=None):
    """Clearance of every tooth against the coupling rotation, per flank (2 x 2 panels)."""
    from matplotlib.collections import LineCollection

    own = ax is None
    fig, axes = figure_axes(ax, (2, 2), figsize=(13, 8), sharex=True)
    colours = _colours("twilight", result.teeth)
    psi = result.angles_deg
    order = np.argsort(psi)
    for f, flank in enumerate(("cw", "ccw")):
        for row, (data, label) in enumerate(((result.clearance_mm, "whole flank"),
                                              (result.pitch_clearance_mm, "pitch line"))):
            ax = axes[row, f]
            y = np.where(np.isfinite(data[f][:, order]), data[f][:, order] * 1e3, np.nan)
            segments = np.stack(np.broadcast_arrays(psi[order][None, :], y), axis=-1)
            ax.add_collection(LineCollection(list(segments), colors=colours, lw=0.6))  # per tooth
            ax.plot(psi[order], np.min(data[f], axis=0)[order] * 1e3, color="k", lw=1.5,
                    label="contacting tooth")
            ax.set_title(f"{flank} flank, {label} (circumferential)")
            ax.set_ylabel("clearance (µm)")
            ax.legend(fontsize=8, loc="upper right")
    for ax in axes[1]:
        ax.set_xlabel("rotation ψ (deg); one line per tooth")
    fig.suptitle(f"{plot_text(result.spec_name)}: clearance of every tooth at i = "
                 f"{result.misalignment_deg:g}°")
    if own:
        fixed_layout(fig, 0.72, 0.15, 0.59, 0.68, wspace=0.12, hspace=0.13)
    return fig


def plot_contact_path(result: SweepResult, spec: CouplingSpec, *, ax=None):
    """Points of first touch on the hub flank (axial position, radius) over the turn
    (2 panels: cw, ccw)."""
    table = flank_table(spec)
    sm = sleeve_model(spec)
    hf = table.half_face
    z = np.linspace(-hf, hf, 201)
    lo, hi = table.radii(z)
    fig, axes = figure_axes(ax, (1, 2), figsize=(13, 5.5), sharey=True)
    for f, flank in enumerate(("cw", "ccw")):
        ax = axes[f]
        ax.fill_between(z, lo, hi, color="0.92", label="hub flank")
        ax.axhline(sm.r_form, color="0.5", ls="--", lw=0.8, label="sleeve flank starts")
        ax.axhline(spec.tooth.pitch_radius, color="0.5", ls=":", lw=0.8, label="pitch circle")
        pz, pr, th = _last_of_each_point(result, f)
        sc = ax.scatter(pz, pr, c=th, cmap="twilight", s=4, vmin=0, vmax=360)
        j = np.argmin(result.normal_clearance_mm[f], axis=0)
        cols = np.arange(result.angles_deg.size)
        ax.plot(result.contact_z_mm[f][j, cols], result.contact_r_mm[f][j, cols], "k.",
                ms=5, label="contacting tooth")
        ax.set_title(f"{flank} flank: point of first touch\n(colour: θ of the tooth, deg)",
                     fontsize=10)
        ax.set_xlabel("z on the hub flank (mm)")
        ax.set_xlim(-1.05 * hf, 1.05 * hf)
        ax.legend(fontsize=7, loc="lower center")
    axes[0].set_ylabel("radius on the hub flank (mm)")
    fig.colorbar(sc, ax=axes, shrink=0.8)
    fig.suptitle(f"{plot_text(result.spec_name)}: contact path at i = {result.misalignment_deg:g}°")
    return fig


def _last_of_each_point(result: SweepResult, f: int) -> tuple[NDArray, NDArray, NDArray]:
    """Contact points ``z, r`` of flank ``f`` with the tooth's ``theta_deg``, one per
    place: of points at one place only the one drawn last, which covers the others. Where
    the teeth turn through the same angles (renzo-1967: 360 rotations, 50 teeth) each
    point repeats once per tooth with the same colour; one of each halves the drawing."""
    touch = np.isfinite(result.normal_clearance_mm[f])  # "no contact" has no point
    z, r = result.contact_z_mm[f][touch], result.contact_r_mm[f][touch]
    th = result.theta_deg[touch]
    _, first = np.unique(np.stack([z, r], axis=1)[::-1], axis=0, return_index=True)
    keep = np.sort(z.size - 1 - first)
    return z[keep], r[keep], th[keep]


def clearance_field(spec: CouplingSpec, misalignment_deg: float, theta_deg: float, nz: int = 121,
                    nt: int = 41):
    """Gap of tooth 0's cw flank over its ``(z, r)`` at turning angle ``theta_deg``.

    Returns ``z (nz, nt), r (nz, nt), circumferential (nz, nt)`` in mm; points facing no
    sleeve flank (below its tip edge, beyond its face) are NaN for plotting.
    """
    i = check_misalignment(misalignment_deg)
    table = flank_table(spec)
    sm = sleeve_model(spec)
    hf = table.half_face
    z = np.linspace(-hf, hf, nz)[:, None] * np.ones((1, nt))
    t = np.ones((nz, 1)) * np.linspace(0.0, 1.0, nt)[None, :]
    r, alpha = table.evaluate(z, t)
    rq, aq, zq = map_polar(r, alpha, z, i, math.radians(theta_deg))
    circ, _ = sleeve_gaps(sm, rq, aq)
    off = (rq < sm.r_form) | (np.abs(zq) > sm.half_face)
    return z, r, np.where(off, np.nan, circ)


def plot_clearance_map(result: SweepResult, spec: CouplingSpec, *, ax=None):
    """Gap over one flank at the contacting tooth's θ and at a swing tooth (θ = 90°)
    (2 panels); a flank that faces no sleeve flank (tilted out of the sleeve face at large
    misalignment) is said so instead of drawn."""
    th = result.contacting_theta_deg("normal")[0]
    fig, axes = figure_axes(ax, (1, 2), figsize=(13, 5), sharey=True)
    for ax_, theta in zip(axes, (th, 90.0), strict=True):
        z, r, c = clearance_field(spec, result.misalignment_deg, theta)
        ax_.set_title(f"cw flank at θ = {theta:.1f}°")
        ax_.set_xlabel("z (mm)")
        if not np.any(np.isfinite(c)):
            ax_.text(0.5, 0.5, "no point faces the sleeve flank", ha="center",
                     va="center", transform=ax_.transAxes)
            continue
        cs = ax_.contourf(z, r, np.where(np.isfinite(c), c * 1e3, np.nan), levels=24,
                          cmap="viridis")
        fig.colorbar(cs, ax=ax_, label="circumferential gap (µm)")
        k = np.nanargmin(c)
        ax_.plot(z.ravel()[k], r.ravel()[k], "r*", ms=12, label="minimum")
        ax_.legend(fontsize=8, loc="best")
    axes[0].set_ylabel("r (mm)")
    fig.suptitle(f"{plot_text(result.spec_name)}: "
                 f"clearance map at i = {result.misalignment_deg:g}° "
                 "(blank: facing the sleeve tip chamfer)")
    return fig


def plot_backlash_over_turn(result: SweepResult, *, ax=None):
    """Backlash (free turning of the hub, µm at the pitch circle) against the rotation, with
    the aligned backlash for reference."""
    own = ax is None
    fig, ax = figure_axes(ax, (1, 1), figsize=(9, 3.4))
    if own:
        fixed_layout(fig, 0.7, 0.05, 0.48, 0.24)
    order = np.argsort(result.angles_deg)
    ax.plot(result.angles_deg[order], result.backlash_mm[order] * 1e3, "-", lw=1.5,
            label=f"at i = {result.misalignment_deg:g}°")
    ax.axhline(result.aligned_backlash_mm * 1e3, color="0.4", ls="--", lw=1,
               label="aligned (i = 0)")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlim(0, 360)
    ax.set_xlabel("rotation ψ (deg)")
    ax.set_ylabel("backlash at the pitch circle (µm)")
    ax.set_title(f"{plot_text(result.spec_name)}: "
                 f"backlash over a turn at i = {result.misalignment_deg:g}°",
                 fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return fig


def backlash_curve(spec: CouplingSpec, misalignment_deg, *, steps: int = 8):
    """Smallest backlash over a turn (mm at the pitch radius) at each misalignment."""
    R = spec.tooth.pitch_radius
    return np.array([R * min_backlash_rad(spec, a, steps=steps)
                     for a in misalignment_deg])


def plot_backlash(spec: CouplingSpec, *, max_deg: float = MISALIGNMENT_RANGE_DEG[1],
                  count: int = 25, binding_deg: float | None = None, ax=None, curve=None):
    """Smallest backlash over a turn against misalignment, with the binding angle.
    ``curve``: ``(misalignments_deg, backlash_mm)`` already computed (:func:`backlash_curve`)
    in place of ``count`` misalignments from 0 to ``max_deg``."""
    if curve is None:
        a = np.linspace(0.0, max_deg, count)
        b = backlash_curve(spec, a)
    else:
        a, b = (np.asarray(v, dtype=float) for v in curve)
    fig, ax = figure_axes(ax, (1, 1), figsize=(8, 5))
    ax.plot(a, b * 1e3, "o-", ms=3, label="smallest backlash over a turn")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.axvline(math.degrees(spec.design_misalignment), color="g", ls="--",
               label="design angle")
    if binding_deg is not None:
        ax.axvline(binding_deg, color="r", ls=":", label=f"binds at {binding_deg:.4f}°")
    ax.set_xlabel("misalignment i (deg)")
    ax.set_ylabel("backlash at the pitch circle (µm)")
    ax.set_title(f"{plot_text(spec.name)}: backlash against misalignment")
    ax.legend(fontsize=8, loc="best")
    return fig


def critical_curve(spec: CouplingSpec, radius_ratios, *, tolerance_deg: float = 1e-3):
    """Critical misalignment (deg, NaN where none up to 6°) for R_c = ratio * R."""
    R = spec.tooth.pitch_radius
    out = []
    for q in radius_ratios:
        s = spec.replace(**{"hub.crowning.kind": "circular", "hub.crowning.radius": q * R})
        c = critical_misalignment_deg(s, tolerance_deg=tolerance_deg)
        out.append(np.nan if c is None else c)
    return np.array(out)


def plot_critical_vs_radius(spec: CouplingSpec,
                            *, radius_ratios=(0.6, 0.8, 1.0, 1.5, 2.0, 3.0), ax=None):
    """Critical misalignment against the (uniform) crowning radius, with the small-angle
    estimate ``i = b/2 / (R_c cot phi)`` (contact travel reaching the face end)."""
    ratios = np.asarray(radius_ratios, dtype=float)
    crit = critical_curve(spec, ratios)
    R = spec.tooth.pitch_radius
    hf = 0.5 * spec.hub.face_width
    q = np.linspace(ratios.min(), ratios.max(), 100)
    est = np.degrees(hf / (q * R / math.tan(spec.tooth.pressure_angle)))
    fig, ax = figure_axes(ax, (1, 1), figsize=(8, 5))
    ax.plot(ratios, crit, "o-", label="sweep (contact reaches the face end)")
    ax.plot(q, est, "--", color="0.4", label="b/2 = R_c cot φ · i (Renzo)")
    ax.set_xlabel("crowning radius R_c / R")
    ax.set_ylabel("critical misalignment (deg)")
    ax.set_title(f"{plot_text(spec.name)}: critical misalignment against crowning radius")
    ax.legend(fontsize=8, loc="best")
    return fig


def plot_generation(spec: CouplingSpec, misalignment_deg: float, *, count: int = 721, ax=None):
    """Pitch-line clearance over θ for both generation methods and their difference
    (2 panels)."""
    i = check_misalignment(misalignment_deg)
    theta = np.linspace(0.0, 2 * np.pi, count)
    fig, axes = figure_axes(ax, (2, 1), figsize=(9, 7), sharex=True)
    curves = {}
    for gen in ("enveloped", "revolved"):
        s = spec.replace(**{"hub.crowning.generation": gen})
        mins, _ = flank_minima(s, i, theta, tolerance_mm=GAP_TOLERANCE_MM)
        curves[gen] = mins
        axes[0].plot(np.degrees(theta), mins["pitch"] * 1e3, label=f"{gen}, pitch line")
        axes[0].plot(np.degrees(theta), mins["clearance"] * 1e3, ls="--",
                     label=f"{gen}, whole flank")
    axes[0].set_ylabel("clearance, cw (µm)")
    axes[0].legend(fontsize=8, loc="best")
    axes[0].set_title(f"{plot_text(spec.name)}: enveloped (hob) vs revolved crown at i = "
                      f"{misalignment_deg:g}°")
    for key, label in (("pitch", "pitch line"), ("clearance", "whole flank")):
        diff = curves["revolved"][key] - curves["enveloped"][key]
        axes[1].plot(np.degrees(theta), diff * 1e3, label=label)
    axes[1].legend(fontsize=8, loc="best")
    axes[1].set_ylabel("revolved - enveloped (µm)")
    axes[1].set_xlabel("turning angle θ (deg)")
    return fig


def sweep_figures(result: SweepResult, spec: CouplingSpec, *, design: dict | None = None,
                  studies: bool = True, backlash=None) -> dict[str, Callable[[], Any]]:
    """Every sweep picture by file name, each drawn when called; ``studies`` adds the
    backlash, R_c and generation studies (several seconds); ``backlash``: the backlash curve
    to draw (``curve`` of :func:`plot_backlash`), else one 0-6° is computed."""
    figures: dict[str, Callable[[], Any]] = {
        "sweep_clearance.png": lambda: plot_clearance(result),
        "sweep_backlash_over_turn.png": lambda: plot_backlash_over_turn(result),
        "sweep_contact_path.png": lambda: plot_contact_path(result, spec),
        "sweep_clearance_map.png": lambda: plot_clearance_map(result, spec)}
    if studies:
        binding = (design or {}).get("binding_angle_deg")
        if binding is None and design is None:
            binding = binding_angle_deg(spec, tolerance_deg=1e-3, steps=8)
        figures["sweep_backlash.png"] = lambda: plot_backlash(spec, binding_deg=binding,
                                                              curve=backlash)
        figures["sweep_critical_vs_rc.png"] = lambda: plot_critical_vs_radius(spec)
        figures["sweep_generation.png"] = lambda: plot_generation(
            spec, max(result.misalignment_deg, 0.5))
    return figures


def plot_all(result: SweepResult, spec: CouplingSpec,
             out_dir: str | Path, *, design: dict | None = None,
             studies: bool = True, backlash=None) -> list[Path]:
    """Every sweep picture (:func:`sweep_figures`) into ``out_dir`` as PNG."""
    out = Path(out_dir)
    return [save_png(make(), out / name) for name, make in
            sweep_figures(result, spec, design=design, studies=studies,
                          backlash=backlash).items()]
