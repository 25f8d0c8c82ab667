"""What a live viewer runs on (:class:`LiveApp`): a viser server on a free port and one
worker thread that applies the newest GUI changes (a fast slider drag skips stale poses
instead of queueing them)."""

from __future__ import annotations

import errno
import socket
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..errors import ArgumentError
from ..io import default_output_dir, markdown_text
from ..spec import CouplingSpec
from .nodes import import_viser
from .scene import legend_markdown

PLAY_INTERVAL_S = 0.1
PORT_TRIES = 10  # ports tried from the one asked for before giving up


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


class LiveApp:
    """What a live viewer runs on: a viser server on the first free port of ``port`` (the
    next :data:`PORT_TRIES` - 1 tried), and one worker thread that applies the newest GUI
    changes (:meth:`apply`, given by the subclass's ``_apply``), turning the rotation while
    playing. The subclass builds its scene and its panel (with ``rotation``, ``speed``,
    ``play`` and ``status`` controls) in :meth:`_build`."""

    panel: Any  # the subclass's GUI panel and scene
    scene: Any

    def __init__(self, spec: CouplingSpec, host: str, port: int, html_path=None):
        viser = import_viser()
        self.spec = spec
        self.html_path = Path(html_path) if html_path else \
            default_output_dir(spec.name) / "viewer.html"
        port = free_port(host, port)  # viser itself would retry without end
        self.server = viser.ViserServer(host=host, port=port, verbose=False)
        self.server.gui.configure_theme(control_width="large", show_share_button=False)
        self._lock = threading.Lock()
        self._apply_lock = threading.Lock()
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._dirty: set[str] = set()
        self.playing = False
        self.pose_updates = 0
        self.ticks = 0
        """Worker iterations completed (each applies the changes pending at its start)."""
        self._ticked = threading.Condition()
        self._worker = threading.Thread(target=self._run, name="gearcoupling-viewer",
                                        daemon=True)

    def _build(self, build: Callable[[], None]) -> None:
        """``build()`` the scene and the panel, wire the panel's controls, show the scene,
        then start the worker; on any error the server stops first (bad input leaves no
        server behind)."""
        try:
            build()
            self.panel.on_change(self._mark)
            self.panel.play.on_click(lambda _: self._toggle_play())
            self.panel.show_scene(self.scene)
        except BaseException:
            self.server.stop()
            raise
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
        """Apply the GUI's current values for the kinds of change in ``dirty``."""
        with self._apply_lock:
            self._apply(dirty)

    def _apply(self, dirty: set[str]) -> None:
        raise NotImplementedError

    def _new_scale(self, dirty: set[str]) -> bool:
        """Take the colour scale and mode from the panel where they changed (a scale of 0
        is left as it was), with the legend; whether they did."""
        if "scale" not in dirty or not self.panel.scale.value > 0:
            return False
        st = self.scene.settings
        st.color_scale_mm = float(self.panel.scale.value)
        st.color_mode = self.panel.color_mode.value
        self.panel.legend.content = legend_markdown(self.scene.color_scale_mm, st.color_mode)
        return True

    def stop(self) -> None:
        """Stop the worker and the server."""
        self._stop.set()
        self._wake.set()
        if self._worker.is_alive():
            self._worker.join(timeout=5)
        self.server.stop()
