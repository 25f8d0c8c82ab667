"""Plots of a wear history, each a plain matplotlib Figure: the worn depth on the developed
flanks at several times beside the tooth bearing pictures (the largest pressure each point
of the hub flank sees in a turn, the marking a contact pattern leaves), and backlash, q and
pressures against hours."""

from __future__ import annotations

import numpy as np

from ..geometry import FLANKS
from ..io import plot_text
from ..plots import import_matplotlib, new_figure
from .result import WearResult

SNAPSHOTS = 4  # columns of the map figure: the unworn flank, then evenly to the end


def snapshot_states(result: WearResult, count: int = SNAPSHOTS) -> list[int]:
    """States nearest to ``count`` evenly spaced times from 0 to the end of the history."""
    hours = result.hours
    want = np.linspace(0.0, hours[-1], count)
    return sorted({int(np.argmin(np.abs(hours - t))) for t in want})


def worn_flanks(result: WearResult) -> list[int]:
    """The loaded flanks of the duty, ``0`` cw and ``1`` ccw."""
    return sorted({1 if p.torque_Nm > 0 else 0 for p in result.duty})


def plot_wear_maps(result: WearResult):
    """Worn depth of the hub and the sleeve flank (worst tooth) and the tooth bearing
    picture of the hub flank (the largest pressure of a turn over its peak), on the
    developed flank (axial position across, involute arc length up), at
    :data:`SNAPSHOTS` times; a row of each per loaded flank."""
    import_matplotlib()
    from matplotlib.figure import Figure

    states = snapshot_states(result)
    flanks = worn_flanks(result)
    rows = [(f, kind) for f in flanks for kind in ("hub", "sleeve", "bearing")]
    cols = len(states)
    fig = Figure(figsize=(3.3 * cols + 1.0, 2.3 * len(rows) + 0.9))
    axes = np.asarray(fig.subplots(len(rows), cols, squeeze=False))
    for r, (f, kind) in enumerate(rows):
        data, grid, unit, cmap = _panel_data(result, f, kind)
        top = max(float(np.max(data[states])), 1e-12)
        for c, i in enumerate(states):
            ax = axes[r, c]
            title = f"{kind} {FLANKS[f]}, {result.hours[i]:.4g} h"
            if kind == "bearing":  # each picture on its own scale, as a marking would be
                peak = max(float(np.max(data[i])), 1e-12)
                im = ax.pcolormesh(grid.z_mm, grid.s_mm, data[i].T / peak, vmin=0.0, vmax=1.0,
                                   cmap=cmap, shading="nearest")
                title += f", peak {peak:.0f} MPa"
            else:
                im = ax.pcolormesh(grid.z_mm, grid.s_mm, data[i].T, vmin=0.0, vmax=top,
                                   cmap=cmap, shading="nearest")
            ax.set_title(title, fontsize=8)
            ax.tick_params(labelsize=7)
            if c == 0:
                ax.set_ylabel("s (mm)", fontsize=8)
            if r == len(rows) - 1:
                ax.set_xlabel("z (mm)", fontsize=8)
        bar = fig.colorbar(im, ax=list(axes[r]), fraction=0.02, pad=0.01)
        bar.set_label(unit, fontsize=7)
        bar.ax.tick_params(labelsize=7)
    p = result.duty[0]
    several = " (duty of several points)" if len(result.duty) > 1 else ""
    fig.suptitle(f"{plot_text(result.spec.name)}: wear at {p.misalignment_deg:g}°, "
                 f"{p.torque_Nm:.4g} N·m, {p.speed_rpm:.4g} rpm{several}", fontsize=10)
    return fig


def _panel_data(result: WearResult, flank: int, kind: str):
    if kind == "hub":
        return result.hub_maps[:, flank], result.hub_grid, "depth (mm)", "magma"
    if kind == "sleeve":
        return result.sleeve_maps[:, flank], result.sleeve_grid, "depth (mm)", "magma"
    return result.bearing_MPa[:, flank], result.hub_grid, "pressure / its peak", "viridis"


def plot_wear_history(result: WearResult):
    """Against hours: the largest depth and thickness loss with the wear limit, the
    backlash, Renzo's q, and the peak and interior pressure (a line per operating
    point)."""
    fig, axes = new_figure(2, 2, figsize=(10, 6.6), layout="constrained")
    ax = np.ravel(axes)
    h = result.hours
    s = result.settings
    ax[0].plot(h, np.max(result.hub_max_mm, axis=1), label="hub, deepest")
    ax[0].plot(h, np.max(result.sleeve_max_mm, axis=1), label="sleeve, deepest")
    ax[0].plot(h, result.thickness_loss_mm[:, 0], "--", label="hub tooth thinning")
    ax[0].plot(h, result.thickness_loss_mm[:, 1], "--", label="sleeve tooth thinning")
    limit = s.limit_fraction * result.hub_thickness_mm
    ax[0].axhline(limit, color="k", lw=0.8, ls=":", label=f"wear limit (hub, {limit:.3g} mm)")
    ax[0].set_ylabel("mm")
    for j, p in enumerate(result.duty):
        tag = f"{p.misalignment_deg:g}°, {p.torque_Nm:.4g} N·m" if len(result.duty) > 1 else ""
        ax[1].plot(h, result.backlash_mm[:, j], label=tag or None)
        ax[2].plot(h, result.stats["q"][:, j], label=tag or None)
        ax[3].plot(h, result.stats["max_pressure_MPa"][:, j], label=f"peak {tag}".strip())
        ax[3].plot(h, result.stats["max_interior_pressure_MPa"][:, j], "--",
                   label=f"interior {tag}".strip())
    ax[1].set_ylabel("backlash at the pitch circle (mm)")
    ax[2].set_ylabel("load proportion q")
    ax[3].set_ylabel("pressure (MPa)")
    for a in ax:
        a.set_xlabel("hours")
        a.grid(alpha=0.3)
        if result.limit_reached:
            a.axvline(result.life_h, color="r", lw=0.8, ls=":")
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7)
    lo, hi = result.life_band_h
    fig.suptitle(f"{plot_text(result.spec.name)}: life {result.life_h:.4g} h ({result.life_basis}; "
                 f"{lo:.3g}-{hi:.3g} h across the {s.regime} band), k = "
                 f"{s.coefficient_mm3_per_Nm:.3g} mm³/(N·m)", fontsize=10)
    return fig


__all__ = ["SNAPSHOTS", "plot_wear_history", "plot_wear_maps", "snapshot_states"]
