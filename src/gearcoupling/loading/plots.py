"""Load plots after the papers' figures; each returns a Figure and accepts ``ax=``.

Tooth load vs turning angle (Renzo Fig. 11, Wei Fig. 11), q vs z_c/z0 with eq. 8 (Renzo
Fig. 12), maximum tooth load vs misalignment for several torques (Wei Fig. 12), additional
moment vs misalignment (Wei Fig. 13), capacity vs misalignment per criterion.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..plots import new_figure
from .contact import contact_model


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
    ax.set_title(f"{res.spec.name}: {res.model}, T = {res.torque_Nm:.4g} N·m, "
                 f"i = {res.misalignment_deg:.3g}°, q = {res.q():.3f}")
    ax.set_xlim(0, 360)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def plot_q_graph(points: dict[str, Sequence[tuple[float, float]]] | None = None, ax=None):
    """q vs ``z_c / z0``: Renzo's eq. 8 and measured points ``{label: [(ratio, q), ...]}``."""
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
    ax.legend(fontsize=8)
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
    ax.legend(fontsize=8)
    return fig


def plot_capacity(curves: dict[str, list], ax=None):
    """Capacity vs misalignment per criterion (dashed) and governing (solid), per spec."""
    fig, ax = _axes(ax, figsize=(8, 4.8))
    for k, (name, rows) in enumerate(curves.items()):
        colour = f"C{k}"
        mis = [r.misalignment_deg for r in rows]
        gov = [r.capacity_Nm if r.capacity_Nm is not None else np.nan for r in rows]
        ax.plot(mis, gov, "-", color=colour, lw=2, label=f"{name} (governing)")
        styles = {"tooth_load": "--", "contact_stress": ":", "bending_stress": "-."}
        for crit, style in styles.items():
            ys = [r.criteria_Nm.get(crit) for r in rows]
            if any(y is not None for y in ys):
                ax.plot(mis, [np.nan if y is None else y for y in ys], style, color=colour,
                        lw=1, label=f"{name}: {crit}")
    ax.set_yscale("log")
    ax.set_xlabel("misalignment i (deg)")
    ax.set_ylabel("capacity K·T (N·m)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2, loc="lower left")
    return fig


def plot_patches(res, rotation: int = 0, ax=None):
    """Contact patches on the developed loaded flanks of all teeth at one rotation: tooth k
    side by side (axial position z across, involute roll length up), each patch an ellipse
    (Hertz) or a band (line contact) of its length along the face and width across the
    depth, coloured by the interior pressure; face ends drawn, edge contacts outlined red."""
    import matplotlib.patches as mpatches
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize


    fig, ax = _axes(ax, figsize=(12, 3.6))
    spec = res.spec
    half = 0.5 * spec.hub.face_width
    r_b = spec.tooth.base_radius
    pitch = 2.6 * half
    p = res.interior_pressure_MPa[:, rotation]
    norm = Normalize(0.0, max(float(np.max(p)), 1e-9))
    cmap = colormaps["viridis"]
    cm = contact_model(spec)
    for k in range(res.teeth):
        x0 = k * pitch
        ax.plot([x0 - half, x0 - half], [0, 1], color="0.7", lw=0.5,
                transform=ax.get_xaxis_transform())
        ax.plot([x0 + half, x0 + half], [0, 1], color="0.7", lw=0.5,
                transform=ax.get_xaxis_transform())
        if res.tangential_force_N[k, rotation] <= 0:
            continue
        s = math.sqrt(max(res.contact_r_mm[k, rotation] ** 2 - r_b**2, 0.0))
        w, h = res.patch_length_mm[k, rotation], res.patch_width_mm[k, rotation]
        xy = (x0 + res.contact_z_mm[k, rotation], s)
        edge = "red" if res.edge_contact[k, rotation] else "none"
        patch: mpatches.Patch
        if res.contact_regime[k, rotation] == 1:
            patch = mpatches.Ellipse(xy, w, h, facecolor=cmap(norm(p[k])), edgecolor=edge)
        else:  # line contact: a band over the whole active profile at that z
            _, lo, hi = cm._lookup(cm.A_f, res.contact_z_mm[k, rotation], 0.0)
            s0, s1 = (math.sqrt(max(float(v) ** 2 - r_b**2, 0.0)) for v in (lo, hi))
            patch = mpatches.Rectangle((xy[0] - w / 2, s0), w, s1 - s0,
                                       facecolor=cmap(norm(p[k])), edgecolor=edge)
        ax.add_patch(patch)
    ax.set_xlim(-pitch / 2, res.teeth * pitch - pitch / 2)
    s_lo, s_hi = (np.sqrt(np.maximum(v**2 - r_b**2, 0.0)) for v in (cm.r_lo, cm.r_hi))
    margin = 0.05 * (np.max(s_hi) - np.min(s_lo))
    ax.set_ylim(np.min(s_lo) - margin, np.max(s_hi) + margin)
    ax.set_xlabel(f"teeth 0..{res.teeth - 1} side by side (axial z within each, face "
                  f"{spec.hub.face_width:.3g} mm)")
    ax.set_ylabel("involute roll length (mm)")
    ax.set_title(f"{spec.name}: contact patches at psi = {res.angles_deg[rotation]:.3g}°, "
                 f"T = {res.torque_Nm:.4g} N·m ({res.model})")
    fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax, label="interior pressure (MPa)")
    fig.tight_layout()
    return fig
