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

import errno
import ipaddress
import math
import socket
import threading
import time
from pathlib import Path

from ..arguments import choice, count
from ..errors import ArgumentError, GearCouplingError
from ..io import default_output_dir, markdown_text
from ..spec import CouplingSpec, as_spec
from .html import save_html
from .nodes import CouplingScene, ViewSettings, import_viser
from .panel import Panel
from .scene import (
    LOD_DIVISORS,
    ClearanceCurve,
    clearance_curve,
    legend_markdown,
    lod_tolerance,
    plot_series,
    view_tolerance,
)

PLAY_INTERVAL_S = 0.1
PORT_TRIES = 10  # ports tried from the one asked for before giving up


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


def free_port(host: str, port: int, tries: int = PORT_TRIES) -> int:
    """The first port from ``port`` (at most ``tries`` of them, up to 65535) that ``host``
    can bind, or :class:`~gearcoupling.errors.SpecError` naming the host or the ports."""
    if not 1 <= port <= 65535:
        raise ArgumentError("port", port, "must be from 1 to 65535")
    try:
        infos = socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
    except (OSError, UnicodeError) as err:
        raise ArgumentError("host", host, f"cannot be resolved ({err}): give an address of this "
                        "machine, e.g. 127.0.0.1") from None
    family = infos[0][0]
    last = min(port + tries - 1, 65535)
    for candidate in range(port, last + 1):
        with socket.socket(family, socket.SOCK_STREAM) as probe:
            try:
                probe.bind((infos[0][4][0], candidate))
            except OSError as err:
                if err.errno == errno.EADDRNOTAVAIL:  # not an address of this machine
                    raise ArgumentError("host", host, "is not an address of this machine") \
                        from None
                continue
        return candidate
    raise ArgumentError("port", port, f"ports {port}-{last} are all taken on {host}: choose "
                    "another with --port")


class ViewerApp:
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
        viser = import_viser()
        self.spec = spec
        if settings is None:
            settings = ViewSettings(misalignment_deg=math.degrees(spec.design_misalignment))
        tol = view_tolerance(spec, lod_tolerance(spec, lod) if tolerance_mm is None
                             else tolerance_mm)
        port = free_port(host, port)  # viser itself would retry without end
        self.server = viser.ViserServer(host=host, port=port, verbose=False)
        self.server.gui.configure_theme(control_width="large", show_share_button=False)
        self.html_path = Path(html_path) if html_path else \
            default_output_dir(spec.name) / "viewer.html"
        self._lock = threading.Lock()
        self._apply_lock = threading.Lock()
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._dirty: set[str] = set()
        self._curve: ClearanceCurve | None = None
        self.playing = False
        try:
            self.scene = CouplingScene(self.server, spec, settings, tol)
            self.panel = Panel(self.server.gui, spec, settings, self.scene.color_scale_mm,
                               lod if tolerance_mm is None else None, self._plot_data())
            self.panel.on_change(self._mark)
            self.panel.play.on_click(lambda _: self._toggle_play())
            self.panel.show_scene(self.scene)
        except BaseException:
            self.server.stop()  # bad input: leave no server behind
            raise
        self.pose_updates = 0
        self.ticks = 0
        """Worker iterations completed (each applies the changes pending at its start)."""
        self._ticked = threading.Condition()
        self._worker = threading.Thread(target=self._run, name="gearcoupling-viewer",
                                        daemon=True)
        self._worker.start()

    @property
    def url(self) -> str:
        return f"http://{self.server.get_host()}:{self.server.get_port()}"

    # ------------------------------------------------------------------ GUI

    def _mark(self, what: str) -> None:
        with self._lock:
            self._dirty.add(what)
        self._wake.set()

    def _toggle_play(self) -> None:
        self.playing = not self.playing
        self.panel.play.label = "Pause" if self.playing else "Play"
        self._wake.set()

    def _plot_data(self) -> tuple:
        """The clearance plot's data at the scene's pose (the curve is kept per
        misalignment)."""
        state = self.scene.state
        if state is None:  # CouplingScene sets a pose when it is built
            raise GearCouplingError("the viewer scene has no pose")
        if self._curve is None or self._curve.misalignment_deg != state.misalignment_deg:
            self._curve = clearance_curve(self.spec, state.misalignment_deg)
        return plot_series(self._curve, state)

    # ------------------------------------------------------------------ worker

    def _run(self) -> None:
        last = time.monotonic()
        while not self._stop.is_set():
            self._wake.wait(PLAY_INTERVAL_S if self.playing else 0.5)
            self._wake.clear()
            now = time.monotonic()
            if self.playing:
                rotation = self.panel.rotation
                rotation.value = (rotation.value + self.panel.speed.value * (now - last)) % 360.0
                with self._lock:
                    self._dirty.add("pose")
            last = now
            with self._lock:
                dirty, self._dirty = self._dirty, set()
            if dirty:
                try:
                    self.apply(dirty)
                except Exception as err:  # keep serving; show what went wrong
                    self.panel.status.content = f"**error:** {markdown_text(err)}"
            with self._ticked:
                self.ticks += 1
                self._ticked.notify_all()

    def wait_ticks(self, count: int = 1, timeout_s: float = 60.0) -> bool:
        """Wake the worker and wait until it has completed ``count`` more iterations (the
        first may have started before the call); ``False`` on timeout."""
        with self._ticked:
            target = self.ticks + count
            self._wake.set()
            return self._ticked.wait_for(lambda: self.ticks >= target, timeout_s)

    def apply(self, dirty: set[str]) -> None:
        """Apply the GUI's current values for the kinds of change in ``dirty`` (any of
        pose, misalignment, display, cutaway, lod, scale, save)."""
        with self._apply_lock:
            self._apply(dirty)

    def _apply(self, dirty: set[str]) -> None:
        sc, st, panel = self.scene, self.scene.settings, self.panel
        if "lod" in dirty and panel.lod.value in LOD_DIVISORS:
            sc.set_tolerance(lod_tolerance(self.spec, panel.lod.value))
        if "cutaway" in dirty:
            sc.set_cutaway(panel.cutaway.value)
        panel.read_display(st)
        if "scale" in dirty and panel.scale.value > 0:
            st.color_scale_mm = float(panel.scale.value)
            st.color_mode = panel.color_mode.value
            panel.legend.content = legend_markdown(sc.color_scale_mm, st.color_mode)
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

    def stop(self) -> None:
        """Stop the worker and the server."""
        self._stop.set()
        self._wake.set()
        self._worker.join(timeout=5)
        self.server.stop()


def serve(spec: CouplingSpec, *, host: str = "127.0.0.1", port: int = 8080,
          settings: ViewSettings | None = None, lod: str = "coarse",
          tolerance_mm: float | None = None, html_path=None) -> ViewerApp:
    """Start a :class:`ViewerApp` (returns at once; the server runs in threads); the
    arguments as :class:`ViewerApp` (``port`` 1-65535)."""
    spec = as_spec(spec)
    count(port, "port", 1, 65535)
    choice(lod, "lod", tuple(LOD_DIVISORS))
    return ViewerApp(spec, host=host, port=port, settings=settings, lod=lod,
                     tolerance_mm=tolerance_mm, html_path=html_path)
