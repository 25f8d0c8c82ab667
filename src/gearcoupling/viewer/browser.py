"""Drive the viewer in a real browser (Debian chromium through playwright, software WebGL):
used by the browser tests and ``benchmarks/bench_viewer.py``.

Never runs ``playwright install``: the browser is the system's ``/usr/bin/chromium``
(``apt-get install chromium``; ``scripts/test.sh`` does it).
"""

from __future__ import annotations

import contextlib
import importlib
import io
import os
import time
from collections.abc import Iterator

import numpy as np

from ..errors import BackendError

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_FLAGS = ("--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update",
                  "--disable-sync", "--use-angle=swiftshader", "--enable-unsafe-swiftshader")
"""Flags that give WebGL in software (``--use-gl=swiftshader`` alone gives none)."""


def browser_backend(executable: str = CHROMIUM):
    """playwright's ``sync_api`` module when it and the chromium ``executable`` are there;
    else a :class:`BackendError` saying what to install (checked before any work)."""
    if not os.access(executable, os.X_OK):
        raise BackendError(f"{executable} is missing: apt-get install chromium (scripts/test.sh "
                           "installs it)")
    try:
        return importlib.import_module("playwright.sync_api")
    except ImportError as err:
        raise BackendError("driving a browser needs playwright: pip install "
                           "'gearcoupling[browser]'") from err


@contextlib.contextmanager
def chromium(executable: str = CHROMIUM) -> Iterator[object]:
    """A headless chromium ``playwright`` Browser; closed on exit."""
    sync_api = browser_backend(executable)
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=executable, args=list(CHROMIUM_FLAGS))
        try:
            yield browser
        finally:
            browser.close()


def view_pixels(page) -> np.ndarray:
    """RGB pixels ``(h, w, 3) int16`` of the 3D view in a screenshot of the page: the
    region left of viser's GUI panel and below its notifications."""
    from PIL import Image

    img = np.asarray(Image.open(io.BytesIO(page.screenshot())).convert("RGB"), dtype=np.int16)
    h, w, _ = img.shape
    return img[int(0.2 * h):int(0.95 * h), int(0.03 * w):int(0.5 * w)]


def drawn_fraction(view: np.ndarray, threshold: int = 40) -> float:
    """Share of pixels differing from the background (the view's bottom-left pixel) by
    more than ``threshold`` in some channel."""
    background = view[-1, 0]
    return float(np.mean(np.abs(view - background).max(axis=-1) > threshold))


def close_notifications(page) -> None:
    """Dismiss viser's notifications (e.g. "software WebGL rendering detected")."""
    close = page.locator(".mantine-Notification-closeButton")
    for i in range(close.count()):
        with contextlib.suppress(Exception):
            if close.nth(i).is_visible():
                close.nth(i).click(timeout=2000)


def wait_rendered(page, *, previous: np.ndarray | None = None, min_drawn: float = 0.05,
                  timeout_s: float = 120.0, interval_s: float = 0.5) -> tuple[np.ndarray, float]:
    """Poll screenshots until the parts are drawn and two shots in a row agree.

    Parameters
    ----------
    previous : (h, w, 3) array, optional
        Also wait until the view differs from this one (a redraw after a change).
    min_drawn : float
        Share of the view that must differ from the background.

    Returns
    -------
    view : (h, w, 3) int16
    seconds : float
        Time waited.

    Raises
    ------
    TimeoutError
        With the last drawn fraction, if nothing settles within ``timeout_s``.
    """
    t0 = time.perf_counter()
    last = None
    while True:
        close_notifications(page)
        view = view_pixels(page)
        drawn = drawn_fraction(view) >= min_drawn
        changed = previous is None or float(np.mean(np.abs(view - previous))) > 0.5
        if drawn and changed and last is not None and float(np.mean(np.abs(view - last))) < 0.2:
            return view, time.perf_counter() - t0
        if time.perf_counter() - t0 > timeout_s:
            raise TimeoutError(f"nothing settled within {timeout_s:.0f} s (drawn fraction "
                               f"{drawn_fraction(view):.3f}, changed {changed})")
        last = view
        time.sleep(interval_s)


def reddish_pixels(view: np.ndarray) -> int:
    """Pixels of the interference colour family (red, lit or shaded)."""
    r, g, b = view[..., 0], view[..., 1], view[..., 2]
    return int(np.sum((r > 130) & (g < 70) & (b < 70)))
