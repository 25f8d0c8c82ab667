"""Pictures of a sweep (matplotlib, Agg, written atomically).

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
from pathlib import Path

import numpy as np

from ..geometry.sleeve import sleeve_model
from ..plots import new_figure, save_figure
from .clearance import _Sleeve
from .design import binding_angle_deg, critical_misalignment_deg, min_backlash_rad
from .flank_table import flank_table
from .pose import map_polar
from .result import SweepResult
from .tooth_map import check_misalignment, flank_minima


def plot_clearance(result: SweepResult, path: str | Path) -> Path:
    """Clearance of every tooth against the coupling rotation, per flank."""
    fig, axes = new_figure(2, 2, figsize=(13, 8), sharex=True)
    import matplotlib.pyplot as plt

    colours = plt.cm.twilight(np.linspace(0, 1, result.teeth, endpoint=False))
    psi = result.angles_deg
    order = np.argsort(psi)
    for f, flank in enumerate(("cw", "ccw")):
        for row, (data, label) in enumerate(((result.clearance_mm, "whole flank"),
                                              (result.pitch_clearance_mm, "pitch line"))):
            ax = axes[row, f]
            for k in range(result.teeth):
                ax.plot(psi[order], data[f, k, order] * 1e3, color=colours[k], lw=0.6)
            ax.plot(psi[order], np.min(data[f], axis=0)[order] * 1e3, color="k", lw=1.5,
                    label="contacting tooth")
            ax.set_title(f"{flank} flank, {label} (circumferential)")
            ax.set_ylabel("clearance (µm)")
            ax.legend(fontsize=8, loc="upper right")
    for ax in axes[1]:
        ax.set_xlabel("rotation ψ (deg); one line per tooth")
    fig.suptitle(f"{result.spec_name}: clearance of every tooth at i = "
                 f"{result.misalignment_deg:g}°")
    fig.tight_layout()
    return save_figure(fig, path)


def plot_contact_path(result: SweepResult, spec, path: str | Path) -> Path:
    """Points of first touch on the hub flank (axial position, radius) over the turn."""
    table = flank_table(spec)
    sm = sleeve_model(spec)
    hf = table.half_face
    z = np.linspace(-hf, hf, 201)
    lo, hi = table.radii(z)
    fig, axes = new_figure(1, 2, figsize=(13, 5.5), sharey=True)
    for f, flank in enumerate(("cw", "ccw")):
        ax = axes[f]
        ax.fill_between(z, lo, hi, color="0.92", label="hub flank")
        ax.axhline(sm.r_form, color="0.5", ls="--", lw=0.8, label="sleeve flank starts")
        ax.axhline(spec.tooth.pitch_radius, color="0.5", ls=":", lw=0.8, label="pitch circle")
        th = result.theta_deg
        sc = ax.scatter(result.contact_z_mm[f].ravel(), result.contact_r_mm[f].ravel(),
                        c=th.ravel(), cmap="twilight", s=4, vmin=0, vmax=360)
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
    fig.suptitle(f"{result.spec_name}: contact path at i = {result.misalignment_deg:g}°")
    return save_figure(fig, path)


def clearance_field(spec, misalignment_deg: float, theta_deg: float, nz: int = 121,
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
    circ, _ = _Sleeve(sm).gaps(rq, aq)
    off = (rq < sm.r_form) | (np.abs(zq) > sm.half_face)
    return z, r, np.where(off, np.nan, circ)


def plot_clearance_map(result: SweepResult, spec, path: str | Path) -> Path:
    """Gap over one flank at the contacting tooth's θ and at a swing tooth (θ = 90°)."""
    th = result.contacting_theta_deg("normal")[0]
    fig, axes = new_figure(1, 2, figsize=(13, 5), sharey=True)
    for ax, theta in zip(axes, (th, 90.0), strict=True):
        z, r, c = clearance_field(spec, result.misalignment_deg, theta)
        cs = ax.contourf(z, r, c * 1e3, levels=24, cmap="viridis")
        fig.colorbar(cs, ax=ax, label="circumferential gap (µm)")
        k = np.nanargmin(c)
        ax.plot(z.ravel()[k], r.ravel()[k], "r*", ms=12, label="minimum")
        ax.set_title(f"cw flank at θ = {theta:.1f}°")
        ax.set_xlabel("z (mm)")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("r (mm)")
    fig.suptitle(f"{result.spec_name}: clearance map at i = {result.misalignment_deg:g}° "
                 "(blank: facing the sleeve tip chamfer)")
    return save_figure(fig, path)


def backlash_curve(spec, misalignment_deg, *, steps: int = 8):
    """Smallest backlash over a turn (mm at the pitch radius) at each misalignment."""
    R = spec.tooth.pitch_radius
    return np.array([R * min_backlash_rad(spec, math.radians(a), steps=steps)
                     for a in misalignment_deg])


def plot_backlash(spec, path: str | Path, *, max_deg: float = 6.0, count: int = 25,
                  binding_deg: float | None = None) -> Path:
    """Smallest backlash over a turn against misalignment, with the binding angle."""
    a = np.linspace(0.0, max_deg, count)
    b = backlash_curve(spec, a)
    fig, ax = new_figure(figsize=(8, 5))
    ax.plot(a, b * 1e3, "o-", ms=3, label="smallest backlash over a turn")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.axvline(math.degrees(spec.design_misalignment), color="g", ls="--",
               label="design angle")
    if binding_deg is not None:
        ax.axvline(binding_deg, color="r", ls=":", label=f"binds at {binding_deg:.4f}°")
    ax.set_xlabel("misalignment i (deg)")
    ax.set_ylabel("backlash at the pitch circle (µm)")
    ax.set_title(f"{spec.name}: backlash against misalignment")
    ax.legend(fontsize=8)
    return save_figure(fig, path)


def critical_curve(spec, radius_ratios, *, tolerance_deg: float = 1e-3):
    """Critical misalignment (deg, NaN where none up to 6°) for R_c = ratio * R."""
    R = spec.tooth.pitch_radius
    out = []
    for q in radius_ratios:
        s = spec.replace(**{"hub.crowning.kind": "circular", "hub.crowning.radius": q * R})
        c = critical_misalignment_deg(s, tolerance_deg=tolerance_deg)
        out.append(np.nan if c is None else c)
    return np.array(out)


def plot_critical_vs_radius(spec, path: str | Path, *,
                            radius_ratios=(0.6, 0.8, 1.0, 1.5, 2.0, 3.0)) -> Path:
    """Critical misalignment against the (uniform) crowning radius, with the small-angle
    estimate ``i = b/2 / (R_c cot phi)`` (contact travel reaching the face end)."""
    ratios = np.asarray(radius_ratios, dtype=float)
    crit = critical_curve(spec, ratios)
    R = spec.tooth.pitch_radius
    hf = 0.5 * spec.hub.face_width
    q = np.linspace(ratios.min(), ratios.max(), 100)
    est = np.degrees(hf / (q * R / math.tan(spec.tooth.pressure_angle)))
    fig, ax = new_figure(figsize=(8, 5))
    ax.plot(ratios, crit, "o-", label="sweep (contact reaches the face end)")
    ax.plot(q, est, "--", color="0.4", label="b/2 = R_c cot φ · i (Renzo)")
    ax.set_xlabel("crowning radius R_c / R")
    ax.set_ylabel("critical misalignment (deg)")
    ax.set_title(f"{spec.name}: critical misalignment against crowning radius")
    ax.legend(fontsize=8)
    return save_figure(fig, path)


def plot_generation(spec, misalignment_deg: float, path: str | Path, *,
                    count: int = 721) -> Path:
    """Pitch-line clearance over θ for both generation methods and their difference."""
    i = check_misalignment(misalignment_deg)
    theta = np.linspace(0.0, 2 * np.pi, count)
    fig, axes = new_figure(2, 1, figsize=(9, 7), sharex=True)
    curves = {}
    for gen in ("enveloped", "revolved"):
        s = spec.replace(**{"hub.crowning.generation": gen})
        mins, _ = flank_minima(s, i, theta, tolerance_mm=1e-7)
        curves[gen] = mins
        axes[0].plot(np.degrees(theta), mins["pitch"] * 1e3, label=f"{gen}, pitch line")
        axes[0].plot(np.degrees(theta), mins["clearance"] * 1e3, ls="--",
                     label=f"{gen}, whole flank")
    axes[0].set_ylabel("clearance, cw (µm)")
    axes[0].legend(fontsize=8)
    axes[0].set_title(f"{spec.name}: enveloped (hob) vs revolved crown at i = "
                      f"{misalignment_deg:g}°")
    for key, label in (("pitch", "pitch line"), ("clearance", "whole flank")):
        diff = curves["revolved"][key] - curves["enveloped"][key]
        axes[1].plot(np.degrees(theta), diff * 1e3, label=label)
    axes[1].legend(fontsize=8)
    axes[1].set_ylabel("revolved - enveloped (µm)")
    axes[1].set_xlabel("turning angle θ (deg)")
    return save_figure(fig, path)


def plot_all(result: SweepResult, spec, out_dir: str | Path, *, design: dict | None = None,
             studies: bool = True) -> list[Path]:
    """Every sweep picture into ``out_dir``; ``studies`` adds the backlash, R_c and
    generation studies (several seconds)."""
    out = Path(out_dir)
    paths = [plot_clearance(result, out / "sweep_clearance.png"),
             plot_contact_path(result, spec, out / "sweep_contact_path.png"),
             plot_clearance_map(result, spec, out / "sweep_clearance_map.png")]
    if studies:
        binding = (design or {}).get("binding_angle_deg")
        if binding is None and design is None:
            binding = binding_angle_deg(spec, tolerance_deg=1e-3, steps=8)
        paths.append(plot_backlash(spec, out / "sweep_backlash.png", binding_deg=binding))
        paths.append(plot_critical_vs_radius(spec, out / "sweep_critical_vs_rc.png"))
        paths.append(plot_generation(spec, max(result.misalignment_deg, 0.5),
                                     out / "sweep_generation.png"))
    return paths
