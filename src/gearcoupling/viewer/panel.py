"""The live viewer's GUI panel (viser, right-hand side): pose sliders with play/pause and
speed, the clearance-vs-θ plot, colour and contact controls with the legend and a status
line per flank, part display, level of detail, and the button that saves the static HTML.

:class:`Panel` only builds the controls, reports which kind of change each one makes, and
shows what :class:`~.server.ViewerApp` computed; it holds no state of the scene.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import ClassVar

import numpy as np

from ..errors import GearCouplingError
from ..io import markdown_text
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec
from .nodes import FRAMES, CouplingScene, ViewSettings
from .scene import COLOR_MODES, CUTAWAYS, LOD_DIVISORS, legend_markdown, plot_range

CHANGES = {"misalignment": "misalignment", "rotation": "pose", "frame": "pose",
           "band": "pose", "show_hub": "display", "hub_opacity": "display",
           "show_sleeve": "display", "sleeve_opacity": "display", "cutaway": "cutaway",
           "lod": "lod", "scale": "scale", "color_mode": "scale", "show_contacts": "display",
           "show_interference": "display"}
"""Control -> the kind of change it makes (what :meth:`~.server.ViewerApp.apply` redoes)."""


class Controls:
    """What a viewer's panel shares: the "Share" folder with the button that saves the
    static HTML, and the wiring of its controls to the kinds of change they make
    (``CHANGES``: control -> kind)."""

    CHANGES: ClassVar[dict[str, str]] = {}

    def add_colours(self, gui, mode: str, scale_mm: float, band_mm: float) -> None:
        """The colour mode, the colour scale and the contact band."""
        self.color_mode = gui.add_dropdown("colour by", COLOR_MODES, initial_value=mode)
        self.scale = gui.add_number("colour scale (mm)", round(scale_mm, 5), min=1e-5,
                                    max=10.0, step=1e-4)
        self.band = gui.add_number("contact band (mm)", band_mm, min=0.0, max=1.0, step=1e-4)

    def add_share(self, gui) -> None:
        with gui.add_folder("Share"):
            self.save = gui.add_button("Save static HTML")
            self.saved = gui.add_markdown("")

    def on_change(self, mark: Callable[[str], None]) -> None:
        """Call ``mark(kind)`` (``CHANGES``; ``"save"`` for the save button) when a control
        changes."""
        for name, kind in self.CHANGES.items():
            getattr(self, name).on_update(lambda _event, kind=kind: mark(kind))
        self.save.on_click(lambda _event: mark("save"))


class Panel(Controls):
    """The controls of one viewer, built in ``gui`` (a ``viser`` GUI API).

    Parameters
    ----------
    gui : viser.GuiApi
    spec : CouplingSpec
    settings : ViewSettings
        Start values.
    color_scale_mm : float
        Start colour scale (the settings' or the spec's default).
    lod : str or None
        Start level of detail, None for a custom tolerance.
    plot_data : tuple of arrays
        Start data of the clearance plot (:func:`~.scene.plot_series`).
    """

    CHANGES = CHANGES

    def __init__(self, gui, spec: CouplingSpec, settings: ViewSettings, color_scale_mm: float,
                 lod: str | None, plot_data: tuple):
        st = settings
        gui.add_markdown(f"**{markdown_text(spec.name)}** — {spec.tooth.teeth} teeth, module "
                         f"{spec.tooth.module:.4g} mm")
        with gui.add_folder("Pose"):
            self.misalignment = gui.add_slider("misalignment (°)", *MISALIGNMENT_RANGE_DEG, 0.05,
                                               round(st.misalignment_deg, 2))
            self.rotation = gui.add_slider("rotation ψ (°)", 0.0, 360.0, 0.5,
                                           float(np.mod(st.psi_deg, 360.0)))
            self.play = gui.add_button("Play", icon=None)
            self.speed = gui.add_slider("speed (°/s)", 1.0, 90.0, 1.0, 15.0)
            self.frame = gui.add_dropdown("still frame", FRAMES, initial_value=st.frame,
                                          hint="sleeve: the hub wobbles in the sleeve; "
                                               "ground: both turn about their axes")
        self.plot = gui.add_uplot(plot_data, _plot_series_styles(), aspect=1.3,
                                  title="clearance (mm) vs θ; dots: teeth now, ring: θ = ψ",
                                  scales=_scales(plot_data),
                                  axes=({"label": "θ (°)"}, {"label": "mm", "size": 60}))
        with gui.add_folder("Clearance"):
            self.add_colours(gui, st.color_mode, color_scale_mm, st.band_mm)
            self.show_contacts = gui.add_checkbox("mark contact points", st.show_contacts)
            self.show_interference = gui.add_checkbox("show interference (red)",
                                                      st.show_interference)
            self.legend = gui.add_markdown(legend_markdown(color_scale_mm, st.color_mode))
            self.status = gui.add_markdown("")
        with gui.add_folder("Parts"):
            self.show_hub = gui.add_checkbox("show hub", st.show_hub)
            self.hub_opacity = gui.add_slider("hub opacity", 0.1, 1.0, 0.05, st.hub_opacity)
            self.show_sleeve = gui.add_checkbox("show sleeve", st.show_sleeve)
            self.sleeve_opacity = gui.add_slider("sleeve opacity", 0.1, 1.0, 0.05,
                                                 st.sleeve_opacity)
            self.cutaway = gui.add_dropdown("sleeve cutaway", CUTAWAYS, initial_value=st.cutaway)
            options = (*LOD_DIVISORS,) if lod else (*LOD_DIVISORS, "custom")
            self.lod = gui.add_dropdown("level of detail", options,
                                        initial_value=lod or "custom")
            self.mesh_info = gui.add_markdown("")
        self.add_share(gui)

    def read_display(self, st: ViewSettings) -> None:
        """Copy the display controls (parts, contacts, interference, band, frame) into
        ``st``."""
        st.show_hub, st.show_sleeve = self.show_hub.value, self.show_sleeve.value
        st.hub_opacity, st.sleeve_opacity = self.hub_opacity.value, self.sleeve_opacity.value
        st.show_contacts = self.show_contacts.value
        st.show_interference = self.show_interference.value
        st.band_mm = float(self.band.value)
        st.frame = self.frame.value

    def show_plot(self, data: tuple) -> None:
        self.plot.scales = _scales(data)
        self.plot.data = data

    def show_scene(self, scene: CouplingScene) -> None:
        """The mesh line and the status lines (per flank, and the interference volume)."""
        self.mesh_info.content = (f"tolerance {scene.meshes.tolerance_mm:.4g} mm, "
                                  f"{scene.meshes.triangles} triangles")
        if scene.state is None:  # CouplingScene sets a pose when it is built
            raise GearCouplingError("the viewer scene has no pose")
        text = scene.state.summary().replace("\n", "<br/>")
        if scene.interference_volume_mm3 > 0:
            text += f"<br/>**interference volume {scene.interference_volume_mm3:.3f} mm³**"
        self.status.content = text


def _plot_series_styles() -> tuple:
    import viser.uplot as up

    return (up.Series(label="θ (°)"),
            up.Series(label="cw", stroke="rgb(30,110,200)", width=2),
            up.Series(label="ccw", stroke="rgb(230,120,20)", width=2),
            up.Series(label="cw now", stroke="rgb(30,110,200)", width=0,
                      points={"show": True, "size": 6, "fill": "rgb(30,110,200)"}),
            up.Series(label="ccw now", stroke="rgb(230,120,20)", width=0,
                      points={"show": True, "size": 6, "fill": "rgb(230,120,20)"}),
            up.Series(label="tooth 0 (θ = ψ)", stroke="black", width=0,
                      points={"show": True, "size": 12, "width": 2,
                              "stroke": "black", "fill": "rgba(0,0,0,0)"}))


def _scales(data) -> dict:
    lo, hi = plot_range(data)
    return {"x": {"time": False}, "y": {"auto": False, "range": [lo, hi]}}
