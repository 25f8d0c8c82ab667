"""The live viewer of the whole coupling (a double-engagement spec, docs/coupling.md): the
placed assembly with sliders for the shaft offset and angle (and their azimuths) and the
coupling's rotation, each mesh's flanks coloured at its own angle and rotation, a status
line per mesh, the sleeve rings' cutaway, and the button that saves the static HTML.

:class:`AssemblyPanel` only builds the controls; :class:`AssemblyApp` applies them on the
worker thread of :class:`~.server.LiveApp` (a slider drag skips stale poses).
"""

from __future__ import annotations

import math

import numpy as np

from ..coupling import spec_geometry
from ..io import markdown_text
from ..spec import MAX_SHAFT_ANGLE_DEG, MISALIGNMENT_RANGE_DEG, CouplingSpec
from .assembly import AssemblyScene, AssemblySettings
from .html import save_html
from .live import LiveApp
from .nodes import import_viser
from .panel import Controls
from .scene import CUTAWAYS, legend_markdown, lod_tolerance, view_tolerance

CHANGES = {"offset": "pose", "offset_azimuth": "pose", "angle": "pose",
           "angle_azimuth": "pose", "rotation": "pose", "band": "pose",
           "color_mode": "scale", "scale": "scale", "cutaway": "cutaway"}
"""Control -> the kind of change it makes (what :meth:`AssemblyApp.apply` redoes)."""


class AssemblyPanel(Controls):
    """The controls of the whole coupling's viewer, built in ``gui`` (a viser GUI API):
    the shaft alignment (start values: ``settings`` or the spec's ``[alignment]``, the
    offset slider up to the offset that puts a mesh at 6°), the rotation with play/pause,
    colours and the cutaway."""

    CHANGES = CHANGES

    def __init__(self, gui, spec: CouplingSpec, settings: AssemblySettings,
                 color_scale_mm: float, span_mm: float, start: dict[str, float]):
        st = settings
        gui.add_markdown(f"**{markdown_text(spec.name)}**: two engagements, span "
                         f"{span_mm:.4g} mm")
        top = span_mm * math.tan(math.radians(MISALIGNMENT_RANGE_DEG[1]))
        with gui.add_folder("Shaft alignment"):
            self.offset = gui.add_slider("offset (mm)", 0.0, round(top, 2),
                                         max(round(top / 500, 3), 1e-3),
                                         min(start["offset_mm"], top))
            self.offset_azimuth = gui.add_slider("offset azimuth (°)", -180.0, 180.0, 1.0,
                                                 _wrapped(start["offset_azimuth_deg"]))
            self.angle = gui.add_slider("shaft angle (°)", 0.0, MAX_SHAFT_ANGLE_DEG, 0.01,
                                        start["angle_deg"])
            self.angle_azimuth = gui.add_slider("angle azimuth (°)", -180.0, 180.0, 1.0,
                                                _wrapped(start["angle_azimuth_deg"]))
        with gui.add_folder("Rotation"):
            self.rotation = gui.add_slider("rotation ψ (°), shaft A", 0.0, 360.0, 0.5,
                                           float(np.mod(st.psi_deg, 360.0)))
            self.play = gui.add_button("Play", icon=None)
            self.speed = gui.add_slider("speed (°/s)", 1.0, 90.0, 1.0, 15.0)
        with gui.add_folder("Colours"):
            self.add_colours(gui, st.color_mode, color_scale_mm, st.band_mm)
            self.legend = gui.add_markdown(legend_markdown(color_scale_mm, st.color_mode))
            self.status = gui.add_markdown("")
        with gui.add_folder("Parts"):
            self.cutaway = gui.add_dropdown("sleeve rings' cutaway", CUTAWAYS,
                                            initial_value=st.cutaway)
        self.add_share(gui)

    def read(self, st: AssemblySettings) -> None:
        """Copy the alignment, rotation and band into ``st``."""
        st.offset_mm, st.offset_azimuth_deg = (float(self.offset.value),
                                               float(self.offset_azimuth.value))
        st.angle_deg, st.angle_azimuth_deg = (float(self.angle.value),
                                              float(self.angle_azimuth.value))
        st.psi_deg, st.band_mm = float(self.rotation.value), float(self.band.value)

    def show_scene(self, scene: AssemblyScene) -> None:
        """One status line per mesh: its angle, its smallest clearance per flank."""
        lines = []
        geom = scene.pose.geometry
        for m in geom.meshes:
            c = scene.pose.states[m].min_clearance_mm
            lines.append(f"mesh {m}: i = {geom.misalignment_deg(m):.4f}°, smallest clearance "
                         f"cw {c[0]:+.4f} / ccw {c[1]:+.4f} mm")
        self.status.content = "<br/>".join(lines)


def _wrapped(deg: float) -> float:
    """An azimuth in [-180, 180)."""
    return float((deg + 180.0) % 360.0 - 180.0)


class AssemblyApp(LiveApp):
    """A running viewer of a double-engagement spec's whole coupling; the arguments as
    :class:`~.server.ViewerApp` (``settings`` an :class:`AssemblySettings`)."""

    def __init__(self, spec: CouplingSpec, *, host: str = "127.0.0.1", port: int = 8080,
                 settings: AssemblySettings | None = None, lod: str = "coarse",
                 tolerance_mm: float | None = None, html_path=None):
        import_viser()
        settings = AssemblySettings() if settings is None else settings
        tol = view_tolerance(spec, lod_tolerance(spec, lod) if tolerance_mm is None
                             else tolerance_mm)
        geom = spec_geometry(spec, settings.changes())  # a bad alignment: no server
        super().__init__(spec, host, port, html_path)

        def build() -> None:
            self.scene = AssemblyScene(self.server, spec, settings, tol)
            self.panel = AssemblyPanel(self.server.gui, spec, settings,
                                       self.scene.color_scale_mm, geom.span_mm,
                                       geom.alignment.summary())

        self._build(build)

    def _apply(self, dirty: set[str]) -> None:
        """Any of pose, scale, cutaway, save."""
        sc, st, panel = self.scene, self.scene.settings, self.panel
        if "cutaway" in dirty:
            sc.set_cutaway(panel.cutaway.value)
        panel.read(st)
        self._new_scale(dirty)
        if dirty & {"pose", "scale"}:
            sc.set_pose()
            self.pose_updates += 1
        panel.show_scene(sc)
        if "save" in dirty:
            save_html(sc, self.html_path)
            panel.saved.content = f"saved {self.html_path}"
