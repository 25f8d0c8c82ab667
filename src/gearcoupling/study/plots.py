"""Study plots: an output against a varied key, one line per group of other keys."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..plots import new_figure, save_figure
from ..spec import MISALIGNMENT_RANGE_DEG
from .file import SPEC_OUTPUTS, build_spec

#: each line its own marker and dash, cycled: lines that lie on each other stay visible
#: (hollow markers growing line by line, dashes that show the line beneath)
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")
DASHES = ("-", "--", "-.", ":")

#: units by the end of a key's name (the spec's and the outputs' units in names)
SUFFIX_UNITS = (("_N_per_mm", "N/mm"), ("_lbf_per_in", "lbf/in"), ("_kg_per_m3", "kg/m³"),
                ("_lb_per_in3", "lb/in³"), ("_lbf_in", "lbf·in"), ("_lbf", "lbf"),
                ("_deg", "°"), ("_Nm", "N·m"), ("_MPa", "MPa"), ("_psi", "psi"),
                ("_mm3", "mm³"), ("_mm", "mm"), ("_N", "N"))
#: keys of the spec's geometry tables that are numbers without a unit
PLAIN_KEYS = ("tooth.teeth",)
LENGTH_TABLES = ("tooth", "hub", "sleeve", "inspection")


def key_label(key: str, units: str = "mm") -> str:
    """A study key in words with its unit: ``hub.crowning.radius`` -> "hub crowning radius
    (in)" in an inch study (lengths of the spec's tables are in its file's ``units``),
    ``misalignment_deg`` -> "misalignment (°)", ``q`` -> "q"."""
    words, unit = _words_unit(key, units)
    return f"{words} ({unit})" if unit else words


def _words_unit(key: str, units: str) -> tuple[str, str]:
    """``key`` in words (dots and underscores as spaces, the unit suffix dropped) and its
    unit ("" for a plain number or a word)."""
    last = key.rsplit(".", 1)[-1]
    end, unit = next(((e, u) for e, u in SUFFIX_UNITS if last.endswith(e)), ("", ""))
    if not unit and key == "tooth.diametral_pitch":
        unit = "1/in"
    elif not unit and key.split(".")[0] in LENGTH_TABLES and key not in PLAIN_KEYS \
            and last not in ("kind", "generation"):
        unit = units
    return key.removesuffix(end).replace(".", " ").replace("_", " ").strip(), unit


def _value(key: str, value: Any, units: str) -> str:
    """``key = value`` of a legend, the value with its unit."""
    words, unit = _words_unit(key, units)
    shown = f"{value:g}" if isinstance(value, float) else str(value)
    return f"{words} = {shown}{'' if unit in ('', '°') else ' '}{unit}"


def plot_study(rows: list[dict[str, Any]], x: str, y: str, group: list[str] | tuple = (), *,
               title: str | None = None, ax=None, units: str = "mm"):
    """Line plot of ``y`` against ``x`` from study rows, one line per value of ``group``,
    each with its own marker and dash (:data:`MARKERS`, :data:`DASHES`); axes labelled
    with their units (:func:`key_label`, lengths of the spec in ``units``). An angle of
    :data:`~gearcoupling.study.file.SPEC_OUTPUTS` that is empty (none up to 6°) is drawn
    at 6° as an open triangle; other rows with an error or an empty ``y`` are left out (a
    gap, not a zero) and the legend says how many. Returns the Figure."""
    if ax is None:
        fig, ax = new_figure(figsize=(7, 4.5))
    else:
        fig = ax.figure
    top = MISALIGNMENT_RANGE_DEG[1]
    capped = y in SPEC_OUTPUTS
    lines: dict[tuple, list[tuple[float, float]]] = {}
    above: dict[tuple, list[float]] = {}
    errors = empty = 0
    for r in rows:
        key = tuple(r[g] for g in group)
        if r.get("error") is not None:
            errors += 1
        elif r.get(y) is not None:
            lines.setdefault(key, []).append((r[x], r[y]))
        elif capped:
            above.setdefault(key, []).append(r[x])
        else:
            empty += 1
    for k, key in enumerate(sorted(set(lines) | set(above), key=str)):
        pts = sorted(lines.get(key, []))
        label = ", ".join(_value(g, v, units) for g, v in zip(group, key, strict=True))
        style = {"marker": MARKERS[k % len(MARKERS)], "ms": 3.5 + 1.2 * (k % len(MARKERS)),
                 "mfc": "none", "color": f"C{k % 10}"}
        ax.plot([p[0] for p in pts], [p[1] for p in pts], ls=DASHES[k % len(DASHES)],
                label=label or None, **style)
        if key in above:
            ax.plot(above[key], [top] * len(above[key]), ls="none", **{**style, "marker": "^"})
    if above:
        ax.plot([], [], "^", color="0.3", mfc="none",
                label=f"none up to {top:g}° ({sum(map(len, above.values()))}, drawn at "
                      f"{top:g}°)")
    left_out = [f"{n} row{'s' if n > 1 else ''} {what}"
                for n, what in ((errors, "with an error"), (empty, "without a value")) if n]
    if left_out:
        ax.plot([], [], " ", label=f"left out: {', '.join(left_out)}")
    ax.set_xlabel(key_label(x, units))
    ax.set_ylabel(key_label(y, units))
    if title:
        ax.set_title(title)
    if ax.get_legend_handles_labels()[1]:
        ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)
    return fig


def study_units(study) -> str:
    """The length unit of a study's spec keys: its base spec file's ``units``."""
    return build_spec(study.base_name, study.base_text, study.fixed).units


def study_plots(study, rows: list[dict[str, Any]], out: Path) -> list[Path]:
    """The plots a study file asks for (``[[plot]]``), as PNG files in ``out``; lengths
    of the spec in its file's units (:func:`study_units`)."""
    units = study_units(study)
    paths = []
    for k, p in enumerate(study.plots):
        fig = plot_study(rows, p["x"], p["y"], p.get("group", []), title=p.get("title"),
                         units=units)
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
