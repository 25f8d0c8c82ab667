"""Pictures of the tooth geometry: transverse sections and the axial view of the crown."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ArgumentError, BackendError
from .geometry import hub_flank_model, hub_model, plane_rack, transverse_section
from .interrupts import reraise as reraise_interrupt
from .io import atomic_path, plot_text, writable_file

if TYPE_CHECKING:  # matplotlib is imported where a plot is drawn
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from .spec import CouplingSpec


_FIGURE_KEYS = ("figsize", "dpi", "layout", "facecolor")


def import_matplotlib():
    """``matplotlib``, or :class:`~gearcoupling.errors.BackendError` naming the extra."""
    try:
        import matplotlib
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("plots need matplotlib (a dependency of gearcoupling): "
                           "pip install matplotlib") from err
    return matplotlib


def new_figure(*args: Any, **kwargs: Any) -> tuple[Figure, Any]:
    """A new ``(figure, axes)`` like ``plt.subplots``, without pyplot.

    The figure is a plain :class:`matplotlib.figure.Figure`: no back-end is selected or
    switched (never ``matplotlib.use``) and nothing is registered with pyplot, so the
    caller's interactive session is untouched; ``figure.savefig`` writes files with any
    back-end. ``figsize``, ``dpi``, ``layout`` and ``facecolor`` go to the figure, the
    rest to :meth:`Figure.subplots`.
    """
    import_matplotlib()
    from matplotlib.figure import Figure

    fig = Figure(**{k: kwargs.pop(k) for k in _FIGURE_KEYS if k in kwargs})
    return fig, fig.subplots(*args, **kwargs)


def figure_axes(ax: Any, shape: tuple[int, int], **kwargs: Any) -> tuple[Figure, Any]:
    """``(figure, axes)`` for a plot of ``shape = (rows, cols)`` panels: the caller's Axes
    (one, or rows x cols of them in any nesting) shaped as :func:`new_figure` returns them,
    or a new figure (``kwargs`` as for :func:`new_figure`) when ``ax`` is None."""
    if ax is None:
        return new_figure(*shape, **kwargs)
    axes = np.asarray(ax, dtype=object)
    count = shape[0] * shape[1]
    if axes.size != count:
        raise ArgumentError("ax", f"{axes.size} Axes", f"must hold {count} Axes for this plot")
    axes = axes.reshape(shape).squeeze() if count > 1 else axes.ravel()[0]  # as subplots
    return np.ravel(axes)[0].figure, axes


def fixed_layout(fig: Figure, left: float, right: float, bottom: float, top: float, *,
                 wspace: float | None = None, hspace: float | None = None) -> Figure:
    """Place ``fig``'s subplot grid ``left``, ``right``, ``bottom``, ``top`` inches in from
    its edges (``wspace``, ``hspace`` as in :meth:`Figure.subplots_adjust`): the layout a
    layout engine finds for the figure's usual titles and tick labels, measured once. An
    engine measures every text again on each draw."""
    w, h = fig.get_size_inches()
    fig.set_layout_engine("none")
    fig.subplots_adjust(left=left / w, right=1.0 - right / w, bottom=bottom / h,
                        top=1.0 - top / h, wspace=wspace, hspace=hspace)
    return fig


def figure_png(fig: Figure, dpi: int) -> bytes:
    """``fig`` as PNG bytes: RGB, since the figures are opaque, and zlib level 3 (less
    work than matplotlib's RGBA at level 6, and smaller)."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    fig.set_dpi(dpi)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    rgba = np.asarray(canvas.buffer_rgba())
    buf = io.BytesIO()
    Image.frombuffer("RGBA", canvas.get_width_height(physical=True), rgba, "raw", "RGBA", 0,
                     1).convert("RGB").save(buf, format="png", compress_level=3)
    return buf.getvalue()


def save_figure(fig: Figure, path: str | Path, dpi: int = 130) -> Path:
    """Write ``fig`` as PNG (:func:`figure_png`) atomically (nothing is closed: the figure
    stays usable). A target that may not be written is refused before the figure is drawn."""
    writable_file(path)
    data = figure_png(fig, dpi)
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)
    return Path(path)


def section_planes(spec: CouplingSpec, count: int = 5) -> np.ndarray:
    """Axial positions (mm) from the midplane to the face end for the section plots."""
    return np.linspace(0.0, 0.5 * spec.hub.face_width, count)


def crown_profile(spec: CouplingSpec, z_mm: np.ndarray) -> dict[str, np.ndarray]:
    """Pitch-circle tooth thickness, transverse pressure angle and crown drop along ``z``.

    Returns arrays in mm and degrees for the spec's crowning generated both ways, and
    ``e``, the feed-path tangent angle (rad) at the enveloped pitch-line point.
    """
    out: dict[str, np.ndarray] = {}
    for gen in ("enveloped", "revolved"):
        m = hub_model(spec.replace(**{"hub.crowning.generation": gen}))
        pts, nrm, h = hub_flank_model(m, "cw", z_mm, m.R)
        out[f"thickness_{gen}_mm"] = 2.0 * m.R * np.abs(np.arctan2(pts[:, 1], pts[:, 0]))
        radial = pts[:, :2] / np.linalg.norm(pts[:, :2], axis=1)[:, None]
        tangential = np.stack([-radial[:, 1], radial[:, 0]], axis=-1)
        nr = np.einsum("ij,ij->i", nrm[:, :2], radial)
        nt = np.abs(np.einsum("ij,ij->i", nrm[:, :2], tangential))
        out[f"pressure_angle_{gen}_deg"] = np.degrees(np.arctan2(nr, nt))
        if gen == "enveloped":
            out["e"] = plane_rack(m, z_mm, h)[1]
    out["crown_drop_mm"] = hub_model(spec).path.drop(z_mm)
    return out


def sections_figure(spec: CouplingSpec, tolerance_mm: float | None = None, *,
                    ax: Sequence[Axes] | None = None) -> Figure:
    """Transverse sections of hub and sleeve at several planes, and the crown along the face.

    Top (``ax[0]``): three hub teeth and the sleeve spaces around them at planes from the
    midplane to the face end. Bottom: pitch-circle tooth thickness (``ax[1]``) and
    transverse pressure angle (``ax[2]``) along the face for the enveloped (hob-generated)
    and revolved constructions, with Renzo's eq. (1) ``tan phi' = tan phi cos e``.

    Parameters
    ----------
    tolerance_mm : float, optional
        Chordal tolerance of the plotted sections (default module / 1000).
    ax : sequence of 3 Axes, optional
        Where to draw; default a new 14 x 10 in figure. Returns the figure of ``ax[0]``.
    """
    import_matplotlib()
    from matplotlib import colormaps

    tol = 1e-3 * spec.tooth.module if tolerance_mm is None else tolerance_mm
    N = spec.tooth.teeth
    own = ax is None
    if ax is None:
        fig, grid = new_figure(2, 2, figsize=(14, 10), gridspec_kw={"height_ratios": [1.1, 1]})
        grid[0, 0].remove()
        grid[0, 1].remove()
        axes = [fig.add_subplot(2, 1, 1), grid[1, 0], grid[1, 1]]
    else:
        axes = list(ax)
        if len(axes) != 3:
            raise ArgumentError("ax", ax, "3 axes (sections, thickness, pressure angle)")
        fig = axes[0].figure
    ax0 = axes[0]
    planes = section_planes(spec)
    colours = colormaps["viridis"](np.linspace(0, 0.9, len(planes)))
    window = 1.25 * 2 * math.pi / N

    def clip(poly):
        # start the ring opposite tooth 0 so the kept window is one contiguous run
        poly = np.roll(poly, -int(np.argmin(np.abs(np.arctan2(-poly[:, 1], -poly[:, 0])))), axis=0)
        ang = np.arctan2(poly[:, 1], poly[:, 0])
        keep = np.abs(ang) < window
        # rotate so tooth 0 points up
        x, y = poly[keep, 0], poly[keep, 1]
        return -y, x

    sleeve = transverse_section(spec, "sleeve", 0.0, tol)
    ax0.plot(*clip(sleeve), color="k", lw=1.2, label="sleeve (all z)")
    for z, c in zip(planes, colours, strict=True):
        hub = transverse_section(spec, "hub", z, tol)
        ax0.plot(*clip(hub), color=c, lw=1.0, label=f"hub z = {z:.3g} mm")
    ax0.set_aspect("equal")
    ax0.set_title(f"{plot_text(spec.name)}: transverse sections (tooth 0 up)")
    ax0.set_xlabel("across the teeth, from tooth 0's centre line (mm)")
    ax0.set_ylabel("from the axis, along tooth 0's centre line (mm)")
    ax0.legend(fontsize=7, loc="lower left")

    z = np.linspace(-0.5 * spec.hub.face_width, 0.5 * spec.hub.face_width, 81)
    prof = crown_profile(spec, z)
    a1 = axes[1]
    a1.plot(z, prof["thickness_enveloped_mm"], label="enveloped (hob)")
    a1.plot(z, prof["thickness_revolved_mm"], "--", label="revolved")
    a1.set_xlabel("z (mm)")
    a1.set_ylabel("tooth thickness at pitch circle (mm)")
    a1.set_title("crown: tooth thickness along the face")
    a1.legend(fontsize=8, loc="best")
    ax2 = a1.twinx()
    ax2.plot(z, prof["crown_drop_mm"], color="grey", lw=0.8)
    ax2.set_ylabel("feed-path crown drop (mm)", color="grey")

    a2 = axes[2]
    a2.plot(z, prof["pressure_angle_enveloped_deg"], label="enveloped (hob)")
    a2.plot(z, prof["pressure_angle_revolved_deg"], "--", label="revolved")
    a2.plot(z, np.degrees(np.arctan(np.tan(spec.tooth.pressure_angle) * np.cos(prof["e"]))),
            ":", color="k", label="tan φ' = tan φ cos e (Renzo eq. 1)")
    a2.set_xlabel("z (mm)")
    a2.set_ylabel("transverse pressure angle at pitch circle (deg)")
    a2.set_title("transverse pressure angle (cf. Renzo Fig. 7)")
    a2.legend(fontsize=8, loc="best")
    if own:
        fixed_layout(fig, 0.76, 0.15, 0.59, 0.36, wspace=0.25, hspace=0.19)
    return fig


def plot_sections(spec: CouplingSpec, path: str | Path,
                  tolerance_mm: float | None = None, *, dpi: int = 130) -> Path:
    """:func:`sections_figure` written to ``path`` as PNG (atomically)."""
    return save_figure(sections_figure(spec, tolerance_mm), path, dpi)
