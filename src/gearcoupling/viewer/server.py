"""The live viewer: a viser server with the coupling scene and its controls.

GUI (right-hand panel): misalignment and rotation sliders with play/pause and speed;
per part show/hide and opacity, the sleeve cutaway and the level of detail; the colour
scale and contact band, the legend, a status line per flank, the clearance-vs-θ plot
with every tooth's current θ marked, and a button that saves the static HTML.

Controls stay responsive: GUI callbacks only record that something changed; one worker
thread applies the newest settings (a pose costs one exact sweep call plus colour and
transform messages), so a fast slider drag skips stale poses instead of queueing them.
Meshes are rebuilt only for a new level of detail.
"""

from __future__ import annotations

import ipaddress
import math
import socket

from ..arguments import choice, count
from ..errors import ArgumentError, GearCouplingError
from ..spec import CouplingSpec, as_spec
from .assembly import AssemblySettings
from .assembly_app import AssemblyApp
from .html import save_html
from .live import PORT_TRIES, LiveApp, free_port
from .nodes import CouplingScene, ViewSettings, import_viser
from .panel import Panel
from .scene import (
    LOD_DIVISORS,
    ClearanceCurve,
    clearance_curve,
    lod_tolerance,
    plot_series,
    view_tolerance,
)

__all__ = ["PORT_TRIES", "ViewerApp", "exposure_warning", "free_port", "serve"]


def exposure_warning(host: str) -> str | None:
    """A warning if ``host`` serves beyond this machine, else ``None``.

    Anyone who can reach the address sees the coupling and can use every control,
    including "Save static HTML", which writes a file on this machine.
    """
    try:
        loopback = all(ipaddress.ip_address(info[4][0]).is_loopback
                       for info in socket.getaddrinfo(host, None))
    except (OSError, UnicodeError):
        return None  # not resolvable: serving fails with its own error
    if loopback:
        return None
    return (f"--host {host} serves the viewer to the network: anyone who reaches it sees "
            "the coupling and can use every control, including 'Save static HTML', which "
            "writes a file on this machine. Use 127.0.0.1 (the default) unless you mean it.")


class ViewerApp(LiveApp):
    """A running viewer for one spec.

    Parameters
    ----------
    spec : CouplingSpec
    host, port : str, int
        Where to serve: the first free port of ``port`` and the next
        :data:`PORT_TRIES` - 1; an unresolvable host or all ports taken raise
        :class:`~gearcoupling.errors.SpecError`. A host other than loopback exposes the
        viewer, including its save button (:func:`exposure_warning`).
    settings : ViewSettings, optional
        Start values (default: design misalignment, rotation 0).
    lod : str
        Start level of detail (:data:`~gearcoupling.viewer.scene.LOD_DIVISORS`), unless
        ``tolerance_mm`` is given.
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (mm), overrides ``lod``.
    html_path : path-like, optional
        Where the "save static HTML" button writes.
    """

    def __init__(self, spec: CouplingSpec, *, host: str = "127.0.0.1", port: int = 8080,
                 settings: ViewSettings | None = None, lod: str = "coarse",
                 tolerance_mm: float | None = None, html_path=None):
        import_viser()
        if settings is None:
            settings = ViewSettings(misalignment_deg=math.degrees(spec.design_misalignment))
        tol = view_tolerance(spec, lod_tolerance(spec, lod) if tolerance_mm is None
                             else tolerance_mm)
        super().__init__(spec, host, port, html_path)
        self._curve: ClearanceCurve | None = None

        def build() -> None:
            self.scene = CouplingScene(self.server, spec, settings, tol)
            self.panel = Panel(self.server.gui, spec, settings, self.scene.color_scale_mm,
                               lod if tolerance_mm is None else None, self._plot_data())

        self._build(build)

    def _plot_data(self) -> tuple:
        """The clearance plot's data at the scene's pose (the curve is kept per
        misalignment)."""
        state = self.scene.state
        if state is None:  # CouplingScene sets a pose when it is built
            raise GearCouplingError("the viewer scene has no pose")
        if self._curve is None or self._curve.misalignment_deg != state.misalignment_deg:
            self._curve = clearance_curve(self.spec, state.misalignment_deg)
        return plot_series(self._curve, state)

    def _apply(self, dirty: set[str]) -> None:
        """Any of pose, misalignment, display, cutaway, lod, scale, save."""
        sc, st, panel = self.scene, self.scene.settings, self.panel
        if "lod" in dirty and panel.lod.value in LOD_DIVISORS:
            sc.set_tolerance(lod_tolerance(self.spec, panel.lod.value))
        if "cutaway" in dirty:
            sc.set_cutaway(panel.cutaway.value)
        panel.read_display(st)
        if self._new_scale(dirty):
            sc.recolor()
        if dirty & {"pose", "misalignment", "lod"}:
            sc.set_pose(panel.misalignment.value, panel.rotation.value)
            self.pose_updates += 1
        if dirty & {"display", "cutaway", "lod", "pose", "misalignment"}:
            sc.set_display()
        if dirty & {"pose", "misalignment", "lod", "scale"}:
            panel.show_plot(self._plot_data())
        panel.show_scene(sc)
        if "save" in dirty:
            save_html(sc, self.html_path)
            panel.saved.content = f"saved {self.html_path}"


def serve(spec: CouplingSpec, *, host: str = "127.0.0.1", port: int = 8080,
          settings: ViewSettings | AssemblySettings | None = None, lod: str = "coarse",
          tolerance_mm: float | None = None, html_path=None) -> ViewerApp | AssemblyApp:
    """Start a :class:`ViewerApp`, or for a double-engagement spec an
    :class:`~.assembly_app.AssemblyApp` (the whole coupling with sliders for the shaft
    offset and angle); returns at once, the server runs in threads. The arguments as
    :class:`ViewerApp` (``port`` 1-65535; ``settings`` an
    :class:`~.assembly.AssemblySettings` for two engagements)."""
    spec = as_spec(spec)
    count(port, "port", 1, 65535)
    choice(lod, "lod", tuple(LOD_DIVISORS))
    if spec.coupling.engagements == 2:
        if settings is not None and not isinstance(settings, AssemblySettings):
            raise ArgumentError("settings", str(settings)[:60], "an AssemblySettings (a "
                                "double-engagement spec)")
        return AssemblyApp(spec, host=host, port=port, settings=settings, lod=lod,
                           tolerance_mm=tolerance_mm, html_path=html_path)
    if settings is not None and not isinstance(settings, ViewSettings):
        raise ArgumentError("settings", str(settings)[:60], "a ViewSettings")
    return ViewerApp(spec, host=host, port=port, settings=settings, lod=lod,
                     tolerance_mm=tolerance_mm, html_path=html_path)
