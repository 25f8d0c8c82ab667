"""Study plots: an output against a varied key, one line per group of other keys."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..plots import new_figure, save_figure


def plot_study(rows: list[dict[str, Any]], x: str, y: str, group: list[str] | tuple = (), *,
               title: str | None = None, ax=None):
    """Line plot of ``y`` against ``x`` from study rows, one line per value of ``group``;
    rows with an error or an empty ``y`` are left out (a gap, not a zero). Returns the
    Figure."""
    if ax is None:
        fig, ax = new_figure(figsize=(7, 4.5))
    else:
        fig = ax.figure
    lines: dict[tuple, list[tuple[float, float]]] = {}
    for r in rows:
        if r.get("error") is None and r.get(y) is not None:
            lines.setdefault(tuple(r[g] for g in group), []).append((r[x], r[y]))
    for key, pts in sorted(lines.items(), key=lambda kv: str(kv[0])):
        pts.sort()
        label = ", ".join(f"{g} = {v:g}" if isinstance(v, float) else f"{g} = {v}"
                          for g, v in zip(group, key, strict=True))
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, label=label or None)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    if title:
        ax.set_title(title)
    if group:
        ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)
    return fig


def study_plots(study, rows: list[dict[str, Any]], out: Path) -> list[Path]:
    """The plots a study file asks for (``[[plot]]``), as PNG files in ``out``."""
    paths = []
    for k, p in enumerate(study.plots):
        fig = plot_study(rows, p["x"], p["y"], p.get("group", []), title=p.get("title"))
        paths.append(save_figure(fig, out / f"plot-{k}-{p['y']}.png"))
    return paths


def plot_k_histogram(rows: list[dict[str, Any]], summary: dict[str, Any], *, ax=None):
    """Histogram of the accuracy factor K of a tolerance study, mean and its bounds marked."""
    if ax is None:
        fig, ax = new_figure(figsize=(7, 4.5))
    else:
        fig = ax.figure
    k = [r["K"] for r in rows if r.get("K") is not None]
    ax.hist(k, bins=max(10, min(60, len(k) // 10)), color="0.6")
    for name, style in (("K_mean", "-"), ("K_mean_low", ":"), ("K_mean_high", ":"),
                        ("K_p05", "--")):
        ax.axvline(summary[name], color="C3", ls=style, label=f"{name} = {summary[name]:.4f}")
    ax.set_xlabel("accuracy factor K = capacity with errors / without")
    ax.set_ylabel("samples")
    ax.set_title(f"{summary['samples']} samples, {summary['path']} path")
    ax.legend(fontsize=7, loc="best")
    return fig
