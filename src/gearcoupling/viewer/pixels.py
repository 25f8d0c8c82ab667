"""The viewer's page in a real browser (:func:`gearcoupling.browser.chromium`): its 3D
view's pixels, viser's notifications, waiting until it has drawn. Used by the browser
tests and ``benchmarks/bench_viewer.py``.
"""

from __future__ import annotations

import contextlib
import time

import numpy as np

from ..browser import drawn_fraction, png_pixels


def view_pixels(page) -> np.ndarray:
    """RGB pixels ``(h, w, 3) int16`` of the 3D view in a screenshot of the page: the
    region left of viser's GUI panel and below its notifications."""
    img = png_pixels(page.screenshot())
    h, w, _ = img.shape
    return img[int(0.2 * h):int(0.95 * h), int(0.03 * w):int(0.5 * w)]


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
