"""Load plots after the papers' figures; each returns a Figure and accepts ``ax=``.

Tooth load vs turning angle (Renzo Fig. 11, Wei Fig. 11), q vs z_c/z0 with eq. 8 (Renzo
Fig. 12), maximum tooth load vs misalignment for several torques (Wei Fig. 12), additional
moment vs misalignment (Wei Fig. 13), capacity vs misalignment per criterion.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import ArgumentError
from ..io import plot_text
from ..plots import fixed_layout, import_matplotlib, new_figure
from .models.registry import load_model
from .patchmap import patch_extent, patch_maps
from .summary import rotation_table


def torque_text(torque_Nm: float) -> str:
    """A torque for a title: 4 significant digits, whole N·m from 10 000 up (not 4e+04)."""
    return f"{torque_Nm:.4g}" if abs(torque_Nm) < 1e4 else f"{torque_Nm:.0f}"


def _axes(ax, **kw):
    if ax is None:
        return new_figure(figsize=kw.get("figsize", (7, 4.2)))
    return ax.figure, ax


def renzo_q(ratio: float) -> float:
    """Renzo's eq. 8: load proportion ``q`` at ``z_c / z0``; above 1, ``1 - z0 / (2 z_c)``."""
    if ratio >= 1:
        return 1 - 1 / (2 * ratio)
    if ratio <= 0:
        return 0.0
    th = math.asin(math.sqrt(ratio))
    return math.cos(2 * th) * (math.tan(2 * th) - 2 * th) / (math.pi * (1 - math.cos(2 * th)))


def plot_tooth_load(res, ax=None, rotation: int = 0):
    """Tangential load of every tooth vs its turning angle at one rotation, and of tooth 0
    over all rotations given (Renzo Fig. 11, Wei Fig. 11)."""
    fig, ax = _axes(ax)
    th = res.theta_deg[:, rotation]
    order = np.argsort(th)
    ax.plot(th[order], res.tangential_force_N[order, rotation], "o-", ms=3,
            label=f"all teeth at psi = {res.angles_deg[rotation]:.3g}°")
    t0 = np.argsort(res.theta_deg[0])
    ax.plot(res.theta_deg[0, t0], res.tangential_force_N[0, t0], "-", lw=1,
            label="tooth 0 over the rotations")
    ax.set_xlabel("turning angle theta (deg, from the tilt axis)")
    ax.set_ylabel("tangential tooth load P (N)")
    ax.set_title(f"{plot_text(res.spec.name)}: {res.model}, T = {torque_text(res.torque_Nm)} N·m, "
                 f"i = {res.misalignment_deg:.3g}°, q = {res.q():.3f}")
    ax.set_xlim(0, 360)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    return fig


def plot_loads_over_turn(res, ax=None):
    """Over the rotations of ``res``: teeth in contact; the largest interior pressure and
    root stress against their allowables; the tilting moment, axial thrust and radial force
    the coupling puts on the machine (3 panels, ``ax``: 3 Axes)."""
    t = rotation_table(res)
    if ax is None:
        fig, axes = new_figure(3, 1, figsize=(9, 8.4), sharex=True)
        fixed_layout(fig, 0.7, 2.25, 0.48, 0.24, hspace=0.069)
    else:
        axes = list(np.ravel(np.asarray(ax, dtype=object)))
        if len(axes) != 3:
            raise ArgumentError("ax", f"{len(axes)} Axes", "3 Axes")
        fig = axes[0].figure
    order = np.argsort(t["psi_deg"])
    psi = t["psi_deg"][order]
    mat = res.spec.material
    a0, a1, a2 = axes
    a0.step(psi, t["teeth_in_contact"][order], where="mid", color="C0")
    a0.set_ylabel("teeth in contact")
    a0.set_ylim(0, res.teeth * 1.05)
    a0.set_title(f"{plot_text(res.spec.name)}: loads over the rotations, {res.model} model, "
                 f"T = {torque_text(res.torque_Nm)} N·m, i = {res.misalignment_deg:.3g}°",
                 fontsize=10)
    a1.plot(psi, t["max_interior_pressure_MPa"][order], color="C1",
            label="largest contact pressure (interior)")
    a1.plot(psi, t["max_root_stress_MPa"][order], color="C2", label="largest root stress")
    a1.axhline(min(mat.hub.allowable_contact_stress_MPa, mat.sleeve.allowable_contact_stress_MPa),
               color="C1", ls="--", lw=1, label="allowable contact stress")
    a1.axhline(min(mat.hub.allowable_bending_stress_MPa, mat.sleeve.allowable_bending_stress_MPa),
               color="C2", ls="--", lw=1, label="allowable bending stress")
    a1.set_ylabel("stress (MPa)")
    a1.set_ylim(bottom=0)
    a1.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    a2.plot(psi, t["tilting_moment_Nm"][order], color="C3", label="tilting moment (N·m)")
    a2.plot(psi, np.abs(t["axial_force_N"][order]), color="C4", label="|axial thrust| (N)")
    a2.plot(psi, t["radial_force_N"][order], color="C5", label="radial force (N)")
    a2.set_ylabel("machine loads")
    a2.set_xlabel("rotation ψ (deg)")
    a2.set_ylim(bottom=0)
    a2.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    for a in axes:
        a.grid(alpha=0.3)
    return fig


def plot_q_graph(points: dict[str, Sequence[tuple[float, float]]] | None = None, ax=None, *,
                 title: str = "load proportion q against z_c / z0 (Renzo Fig. 12)"):
    """q vs ``z_c / z0``: Renzo's eq. 8 and measured points ``{label: [(ratio, q), ...]}``;
    ``title`` names the spec and the model of the points."""
    fig, ax = _axes(ax)
    x = np.logspace(-2, 1, 300)
    ax.semilogx(x, [renzo_q(v) for v in x], "k-", label="Renzo eq. 8")
    for label, pts in (points or {}).items():
        if pts:
            a = np.asarray(pts, dtype=float)
            ax.semilogx(a[:, 0], a[:, 1], "o", ms=4, label=label)
    ax.set_xlabel("z_c / z0")
    ax.set_ylabel("load proportion q")
    ax.set_ylim(0, 1)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title, fontsize=10)
    return fig


def plot_vs_misalignment(misalignments_deg, series: dict[str, Sequence[float]], ylabel: str,
                         title: str = "", ax=None):
    """Any quantity vs misalignment, one line per series (Wei Figs. 12 and 13)."""
    fig, ax = _axes(ax)
    for label, ys in series.items():
        ax.plot(misalignments_deg, ys, "o-", ms=3, label=label)
    ax.set_xlabel("misalignment i (deg)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    return fig


CRITERION_STYLES = {"tooth_load": "--", "contact_stress": ":", "bending_stress": "-."}
SPEC_MARKERS = ("o", "s", "^", "D", "v", "P", "X")


def plot_capacity(curves: Mapping[str, Sequence], ax=None, *,
                  critical_deg: dict[str, float | None] | None = None):
    """Capacity against misalignment per criterion (thin: dashed, dotted, dash-dot) and the
    governing one (thick), per spec; each spec's design point (design angle, ``[load]``
    torque) starred and its critical misalignment (``critical_deg``) marked.

    Curves that coincide stay apart: each spec has its colour and marker (markers placed
    at different misalignments), and lines and stars are drawn wide to narrow in the given
    order, so a later spec's line runs inside an earlier one's. The legends sit outside
    the axes (on the figure's right when the figure is made here).
    """
    from matplotlib.lines import Line2D

    own = ax is None
    fig, ax = new_figure(figsize=(11, 5.4), layout="constrained") if own else (ax.figure, ax)
    count = len(curves)
    spec_handles = []
    for k, (name, rows) in enumerate(curves.items()):
        colour, marker = f"C{k}", SPEC_MARKERS[k % len(SPEC_MARKERS)]
        nest = (count - 1 - k) / max(count - 1, 1)  # 1 for the first spec, 0 for the last
        mis = np.array([r.misalignment_deg for r in rows])
        gov = np.array([np.nan if r.capacity_Nm is None else r.capacity_Nm for r in rows])
        every = max(1, mis.size // 6)
        ax.plot(mis, gov, "-", color=colour, lw=1.4 + 2.0 * nest, marker=marker, ms=5,
                markevery=(min(k * every // max(count, 1), max(mis.size - 1, 0)), every),
                zorder=3 + k, alpha=0.9)
        for crit, style in CRITERION_STYLES.items():
            ys = [r.criteria_Nm.get(crit) for r in rows]
            if any(y is not None for y in ys):
                ax.plot(mis, [np.nan if y is None else y for y in ys], style, color=colour,
                        lw=0.8 + 1.0 * nest, alpha=0.85, zorder=2 + k)
        spec = rows[0].spec if rows else None
        if spec is not None and spec.load.torque_Nm is not None:
            ax.plot([spec.design_misalignment_deg], [abs(spec.load.torque_Nm)], "*",
                    color=colour, ms=9 + 7 * nest, mec="k", mew=0.6, zorder=20 + k)
        label = plot_text(name)
        i_crit = (critical_deg or {}).get(name)
        if i_crit is not None:
            ax.axvline(i_crit, color=colour, lw=1.0, alpha=0.6, zorder=1)
            ax.annotate(f"{i_crit:.2f}°", (i_crit, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(2, -2 - 10 * k), textcoords="offset points", va="top",
                        fontsize=7, color=colour)
            label += f" (critical {i_crit:.2f}°)"
        spec_handles.append(Line2D([], [], color=colour, lw=2, marker=marker, label=label))
    kinds = [Line2D([], [], color="k", lw=2.2, label="governing (smallest)")]
    kinds += [Line2D([], [], color="k", lw=1, ls=style, label=crit.replace("_", " "))
              for crit, style in CRITERION_STYLES.items()]
    kinds.append(Line2D([], [], color="0.4", marker="*", ms=11, ls="none", mec="k",
                        label="design point (design angle, torque)"))
    if critical_deg:
        kinds.append(Line2D([], [], color="0.4", lw=1.0, alpha=0.6,
                            label="critical misalignment"))
    ax.set_yscale("log")
    ax.set_xlabel("misalignment i (deg)")
    ax.set_ylabel("capacity K·T (N·m)")
    ax.grid(alpha=0.3, which="both")
    if own:
        fig.legend(handles=spec_handles, title="spec", loc="outside right upper", fontsize=8,
                   title_fontsize=8)
        fig.legend(handles=kinds, title="line", loc="outside right lower", fontsize=8,
                   title_fontsize=8)
    else:
        ax.add_artist(ax.legend(handles=spec_handles, title="spec", loc="upper left",
                                bbox_to_anchor=(1.01, 1.0), fontsize=8, title_fontsize=8))
        ax.legend(handles=kinds, title="line", loc="lower left", bbox_to_anchor=(1.01, 0.0),
                  fontsize=8, title_fontsize=8)
    rows0 = [r for rows in curves.values() for r in rows]
    models = sorted({r.model for r in rows0})
    factors = sorted({r.accuracy_factor for r in rows0})
    ax.set_title(f"torque capacity against misalignment: {', '.join(map(plot_text, curves))}\n"
                 f"{'/'.join(models)} model, capacity = K × torque at the first limit reached "
                 f"(K = {', '.join(f'{f:g}' for f in factors)})", fontsize=10)
    return fig


REGIME_NAMES = {"hertz": "Hertz ellipse", "line": "line contact", "grid": "pressure grid",
                "none": "no load"}


def plot_patches(res, rotation: int = 0, ax=None, *, count: int = 6):
    """Contact pressure on the developed loaded flanks at one rotation: maps of the
    ``count`` most loaded teeth (axial position z across, involute arc length up; the
    active flank grey, face ends dashed) and an overview of every tooth (where along the
    face its patch lies against its turning angle, coloured by its peak pressure).

    The linear and compliance models draw their contact laws' patch (a Hertz ellipse, or a
    strip over the active profile in the line regime), the surface model its pressure grid
    (:func:`~gearcoupling.loading.patchmap.patch_maps`). ``ax``: ``count + 1`` Axes (maps,
    then the overview), or None for a new figure.
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    maps = patch_maps(res, rotation, count=count)
    cols = min(3, len(maps))
    rows = -(-len(maps) // cols)
    cax, title_y = None, 0.98  # suptitle's default
    if ax is None:
        import_matplotlib()
        from matplotlib.figure import Figure

        W, H = 4.6 * cols + 1.2, 2.7 * rows + 3.4
        fig = Figure(figsize=(W, H))
        # a fixed layout, in inches from the edges; the colour bar in the right margin
        grid = fig.add_gridspec(rows + 1, cols, height_ratios=[1.0] * rows + [1.15],
                                left=0.6 / W, right=1.0 - 1.71 / W, bottom=0.48 / H,
                                top=1.0 - 0.81 / H, wspace=0.066, hspace=0.31)
        panels = [fig.add_subplot(grid[i // cols, i % cols]) for i in range(len(maps))]
        overview = fig.add_subplot(grid[rows, :])
        cax = fig.add_axes((1.0 - 0.935 / W, 1.22 / H, 0.3 / W, 1.0 - 2.79 / H))
        title_y = 1.0 - 0.05 / H
    else:
        axes = list(np.ravel(np.asarray(ax, dtype=object)))
        if len(axes) != len(maps) + 1:
            raise ArgumentError("ax", f"{len(axes)} Axes", f"{len(maps) + 1} Axes (one per "
                                "map, then the overview)")
        panels, overview = axes[:-1], axes[-1]
        fig = overview.figure
    j = rotation
    # the colour scale covers the interior pressure with room; profile-end and face-end
    # peaks of a pressure grid (singular at the edges) saturate and are named in the titles
    interior = float(np.max(res.interior_pressure_MPa[:, j]))
    peak = max(m.peak_MPa for m in maps)
    top = peak if peak <= 1.5 * interior else 1.5 * interior
    norm = Normalize(0.0, max(top, 1e-9))
    cmap = colormaps["viridis"]
    hf = maps[0].half_face_mm
    for m, a in zip(maps, panels, strict=True):
        a.fill_between(m.face_z_mm, m.s_lo_mm, m.s_hi_mm, color="0.9", lw=0)
        for z in (-hf, hf):
            a.axvline(z, color="k", ls="--", lw=0.8)
        p = np.ma.masked_less_equal(m.pressure_MPa.T, 0.0)
        if p.count():
            a.pcolormesh(m.z_mm, m.s_mm, p, cmap=cmap, norm=norm, shading="nearest")
        a.set_xlim(-1.04 * hf, 1.04 * hf)
        a.set_ylim(min(m.s_mm[0], float(np.min(m.s_lo_mm))),
                   max(m.s_mm[-1], float(np.max(m.s_hi_mm))))
        edge = ", edge contact" if m.edge_contact else ""
        peak_text = f", peak {m.peak_MPa:.0f}" if m.peak_MPa > 1.01 * m.interior_pressure_MPa \
            else ""
        a.set_title(f"tooth {m.tooth} at θ = {m.theta_deg:.0f}°: W = {m.normal_force_N:.0f} N\n"
                    f"p {m.interior_pressure_MPa:.0f} MPa{peak_text} "
                    f"({REGIME_NAMES[m.regime]}{edge})", fontsize=9)
        a.tick_params(labelsize=8)
    for a in panels[-cols:]:
        a.set_xlabel("axial position z (mm)", fontsize=8)
    for a in panels[::cols]:
        a.set_ylabel("arc length s (mm)", fontsize=8)
    _overview(res, j, overview, cmap, norm, [m.tooth for m in maps])
    fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), label="contact pressure (MPa)",
                 extend="max" if peak > top else "neither",
                 **({"ax": [*panels, overview], "shrink": 0.8} if cax is None else {"cax": cax}))
    how = ("its pressure grid; p: interior pressure, peak: at a profile or face end"
           if load_model(res.model).pressure_grid else
           "its contact laws' patch: Hertz ellipse, or strip over the active profile")
    fig.suptitle(f"{plot_text(res.spec.name)}: "
                 f"contact pressure on the loaded {res.loaded_flank} flanks at "
                 f"ψ = {res.angles_deg[j]:.3g}°, i = {res.misalignment_deg:.3g}°, "
                 f"T = {torque_text(res.torque_Nm)} N·m\n{res.model} model ({how}); "
                 "grey: active "
                 "flank, dashed: face ends", fontsize=10, y=title_y)
    return fig


def _overview(res, j: int, ax, cmap, norm, marked) -> None:
    """Every tooth's patch along the face (bar) at its turning angle, coloured by its peak
    pressure; the teeth with maps numbered."""
    hf = 0.5 * res.spec.hub.face_width
    lo, hi = patch_extent(res, j)
    theta = res.theta_deg[:, j]
    loaded = res.normal_force_N[:, j] > 0
    width = 0.8 * 360.0 / res.teeth
    ax.bar(theta[loaded], (hi - lo)[loaded], bottom=lo[loaded], width=width,
           color=cmap(norm(res.interior_pressure_MPa[loaded, j])), edgecolor="none")
    ax.plot(theta[~loaded], res.contact_z_mm[~loaded, j], "_", color="0.6", ms=4,
            label="no load (first-touch point)")
    for k in marked:
        ax.annotate(str(k), (theta[k], hi[k]), xytext=(0, 3), textcoords="offset points",
                    ha="center", fontsize=7)
    for z in (-hf, hf):
        ax.axhline(z, color="k", ls="--", lw=0.8)
    ax.set_xlim(0, 360)
    ax.set_ylim(-1.15 * hf, 1.15 * hf)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel("turning angle θ of the tooth (deg, from the tilt axis)")
    ax.set_ylabel("patch along the face z (mm)")
    ax.set_title(f"every tooth ({int(np.sum(res.normal_force_N[:, j] > 0))} of {res.teeth} "
                 "loaded): patch extent along the face, coloured by its interior pressure; "
                 "numbers: the maps above", fontsize=9)
    if np.any(~loaded):
        ax.legend(fontsize=7, loc="upper right")
