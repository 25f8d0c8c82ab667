"""Inspection plots: pitch, runout, thickness and crown per tooth; the deviation map."""

from __future__ import annotations

from typing import cast

import numpy as np

from ..io import plot_text
from ..plots import figure_axes
from .report import FLANK_NAMES, InspectionReport


def plot_inspection(report: InspectionReport, ax=None):
    """Per-tooth bars: cumulative pitch, single pitch, runout + thickness, crown height.

    Parameters
    ----------
    ax : sequence of 4 matplotlib Axes, optional
    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = figure_axes(ax, (2, 2), figsize=(12, 8))
    axes = list(np.ravel(axes))
    k = report.teeth
    um = 1e3
    w = 0.4
    for i, f in enumerate(FLANK_NAMES):
        fl = report.flank[f]
        axes[0].bar(k + (i - 0.5) * w, um * fl["Fpk_mm"], w, label=f)
        axes[1].bar(k + (i - 0.5) * w, um * np.nan_to_num(fl["fpt_mm"]), w, label=f)
        axes[3].bar(k + (i - 0.5) * w, um * fl["C_beta_mm"], w, label=f"{f} C_beta")
    axes[2].bar(k - 0.5 * w, um * np.nan_to_num(report.tooth["runout_mm"]), w,
                label="runout (space after tooth)")
    axes[2].bar(k + 0.5 * w, um * report.tooth["thickness_dev_mm"], w, label="thickness dev.")
    cnom = report.nominal["cw"]["C_beta_mm"]
    axes[3].axhline(um * cnom, color="k", lw=0.8, label="nominal C_beta")
    F_p = cast(float, report.part["F_p_mm"])
    F_r = cast("float | None", report.part["F_r_mm"])
    titles = [f"cumulative pitch F_pk (F_p = {um * F_p:.2f} µm)",
              "single pitch f_pt", "runout / tooth thickness deviation"
              + (f" (F_r = {um * F_r:.2f} µm)" if F_r is not None else ""),
              "crown height C_beta"]
    limits = {0: "Fp", 1: "fpt"}
    for i, a in enumerate(axes):
        a.set_title(titles[i], fontsize=9)
        a.set_xlabel("tooth")
        a.set_ylabel("µm")
        a.grid(True, lw=0.3)
        if i in limits and limits[i] in report.limits:
            lim = um * report.limits[limits[i]]
            a.axhline(lim, color="r", lw=0.8, ls="--")
            a.axhline(-lim if i == 1 else 0, color="r", lw=0.8, ls="--")
        a.legend(fontsize=7, loc="best")
    if report.passed is not None and len(k):
        for kk in k[~report.passed]:
            axes[0].axvspan(kk - 0.5, kk + 0.5, color="r", alpha=0.12)
    fig.suptitle(f"{plot_text(report.spec_name)}: inspection of {plot_text(report.source)} "
                 f"(registration rms {um * report.registration.rms_mm:.2f} µm)")
    fig.tight_layout()
    return fig


def plot_deviation_map(report: InspectionReport, ax=None, limit_mm: float | None = None):
    """Developed heat map of the deviations: every tooth side by side, per flank.

    ``x`` = tooth + axial position across the face, ``y`` = roll length; colour = normal
    deviation (µm, + material). ``ax``: sequence of 2 Axes (cw, ccw), optional.
    """
    fig, axes = figure_axes(ax, (2, 1), figsize=(14, 7), sharex=True)
    axes = list(np.ravel(axes))
    s = report.sample
    half = 0.5 * report.nominal["lead_evaluation_mm"]["L_beta"]
    d = 1e3 * s["d"]
    lim = 1e3 * limit_mm if limit_mm else float(np.percentile(np.abs(d), 99.5)) if len(d) else 1
    sc = None
    for i, f in enumerate(FLANK_NAMES):
        sel = s["flank"] == i
        x = s["tooth"][sel] + 0.45 * s["z"][sel] / half
        sc = axes[i].scatter(x, s["xi"][sel], c=d[sel], s=1, cmap="RdBu_r", vmin=-lim,
                             vmax=lim, rasterized=True)
        axes[i].set_ylabel(f"{f}: roll length ξ (mm)")
    axes[-1].set_xlabel("tooth (each tooth spans its face width)")
    if sc is not None:
        fig.colorbar(sc, ax=axes, label="deviation from nominal (µm, + material)")
    fig.suptitle(f"{plot_text(report.spec_name)}: flank deviation map")
    return fig
