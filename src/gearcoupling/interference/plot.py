"""Plot of an interference check: overlap volume, signed minimum gap and backlash against
the rotation angle. Returns a matplotlib Figure; never switches the matplotlib back-end."""

from __future__ import annotations

from collections.abc import Sequence

from numpy.typing import ArrayLike

from ..errors import ArgumentError
from ..io import plot_text
from ..plots import fixed_layout, new_figure


def plot_interference(result, reference_mm: ArrayLike | None = None,
                      backlash_mm: ArrayLike | None = None, *, ax: Sequence | None = None):
    """Overlap volume, mesh minimum gap (and backlash, when measured) against ψ.

    Parameters
    ----------
    result : InterferenceResult
    reference_mm : (M,) float, optional
        The exact sweep's smallest normal clearance at the same angles.
    backlash_mm : (M,) float, optional
        The sweep's backlash at the same angles.
    ax : sequence of matplotlib Axes, optional
        One Axes per panel (2, or 3 when ``result.backlash_mm`` is set); a new Figure
        (not registered with pyplot) when not given.

    Returns
    -------
    matplotlib.figure.Figure
    """
    rows = 3 if result.backlash_mm is not None else 2
    if ax is None:
        fig, axes = new_figure(rows, 1, figsize=(9, 3.25 * rows), sharex=True)
        fixed_layout(fig, 0.88, 0.15, 0.59, 0.36, hspace=0.074)
    else:
        axes = list(ax)
        if len(axes) != rows:
            raise ArgumentError("ax", f"{len(axes)} axes", f"{rows} axes, one per panel")
        fig = axes[0].figure
    a = result.angles_deg
    ax1, ax2 = axes[0], axes[1]
    ax1.plot(a, result.overlap_volume_mm3, ".-", color="tab:red")
    ax1.set_ylabel("overlap volume (mm³)")
    ax1.set_title(f"{plot_text(result.spec_name)}: "
                  f"i = {result.misalignment_deg:g}°, {result.method}, "
                  f"{result.model}, tolerance {result.tolerance_mm:.4g} mm")
    ax1.grid(alpha=0.3)
    ax2.plot(a, result.min_gap_mm, ".-", label="mesh minimum gap (− depth when overlapping)")
    if reference_mm is not None:
        ax2.plot(a, reference_mm, "--", color="k", lw=1,
                 label="sweep: smallest normal clearance (exact)")
    tol = result.tolerance_mm
    ax2.axhspan(-tol, tol, color="0.85", label="± chordal tolerance")
    ax2.axhline(0.0, color="tab:red", lw=0.8)
    ax2.set_ylabel("gap (mm)")
    ax2.legend(fontsize=8, loc="best")
    ax2.grid(alpha=0.3)
    if rows == 3:
        ax3 = axes[2]
        ax3.plot(a, result.backlash_mm, ".-", color="tab:green", label="mesh backlash")
        if backlash_mm is not None:
            ax3.plot(a, backlash_mm, "--", color="k", lw=1, label="sweep backlash")
        ax3.axhline(0.0, color="tab:red", lw=0.8)
        ax3.set_ylabel("backlash at R (mm)")
        ax3.legend(fontsize=8, loc="best")
        ax3.grid(alpha=0.3)
    axes[-1].set_xlabel("rotation ψ (deg)")
    return fig
