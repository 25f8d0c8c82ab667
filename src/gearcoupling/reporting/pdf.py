"""Print the report to PDF through headless chromium (playwright, Debian's chromium).

The page is opened from disk; once the embedded 3D view shows a settled picture (its
still picture, or the WebGL drawing that replaces it after seconds to tens of seconds in
software WebGL), that picture replaces the interactive view for print, then chromium
prints A4 pages with the section headings as the PDF outline. Never downloads a browser.
"""

from __future__ import annotations

import base64
import contextlib
import time
from pathlib import Path
from typing import Any, cast

from ..browser import chromium, drawn_fraction, png_pixels
from ..io import atomic_path

VIEWPORT = {"width": 1240, "height": 900}
RENDER_TIMEOUT_S = 90.0


def viewer_picture(page, timeout_s: float = RENDER_TIMEOUT_S) -> bytes | None:
    """A screenshot of the embedded 3D view once it has drawn and settled (two shots in a
    row alike), or None when there is no view or it does not draw within ``timeout_s``."""
    frame = page.locator(".viewer iframe")
    if frame.count() == 0:
        return None
    frame.first.scroll_into_view_if_needed()
    notes = page.frame_locator(".viewer iframe").locator(".mantine-Notification-closeButton")
    t0, last = time.perf_counter(), None
    while time.perf_counter() - t0 < timeout_s:
        for i in range(notes.count()):  # viser's "software WebGL" notice covers the view
            with contextlib.suppress(Exception):
                notes.nth(i).click(timeout=1000)
        shot = frame.first.screenshot()
        if drawn_fraction(png_pixels(shot)) > 0.05 and last is not None and shot == last:
            return shot
        last = shot
        time.sleep(1.0)
    return None


def print_pdf(html_path: Path, pdf_path: Path, *, timeout_s: float = RENDER_TIMEOUT_S) -> Path:
    """Print ``html_path`` (a report) to ``pdf_path`` atomically; returns the path."""
    with chromium() as browser:
        page = cast(Any, browser).new_page(viewport=VIEWPORT)
        try:
            page.goto(Path(html_path).resolve().as_uri(), wait_until="load")
            shot = viewer_picture(page, timeout_s)
            if shot is not None:
                src = "data:image/png;base64," + base64.b64encode(shot).decode("ascii")
                page.evaluate("""src => {
                    for (const p of document.querySelectorAll('.viewer .print-only')) {
                        p.textContent = 'The 3D view as drawn in the HTML report:';
                        const img = document.createElement('img');
                        img.src = src; img.style.maxWidth = '100%';
                        p.after(img); img.className = 'print-only';
                    }}""", src)
            with atomic_path(pdf_path) as tmp:
                page.pdf(path=str(tmp), format="A4", print_background=True, outline=True,
                         tagged=True, prefer_css_page_size=True)
        finally:
            page.close()
    return Path(pdf_path)
