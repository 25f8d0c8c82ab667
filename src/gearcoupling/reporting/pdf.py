"""Print the report to PDF through headless chromium (playwright, Debian's chromium).

The page is opened from disk with WebGL off: the embedded 3D view's still picture (drawn
once when the report was written, :mod:`gearcoupling.viewer.still`) replaces the
interactive view for print, so nothing waits for software WebGL. Chromium prints A4
pages with the section headings as the PDF outline. Never downloads a browser.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, cast

from ..browser import chromium
from ..io import atomic_path

VIEWPORT = {"width": 1240, "height": 900}
NO_WEBGL = """(() => {
    const getContext = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (type, attrs) {
        return /webgl/.test(type) ? null : getContext.call(this, type, attrs);
    };
})();"""
"""Page script that leaves the page without WebGL (in every frame)."""


def still_picture(page) -> str | None:
    """The ``data:`` URL of the embedded 3D view's still picture, or None without a view."""
    if page.locator(".viewer iframe").count() == 0:
        return None
    still = page.frame_locator(".viewer iframe").first.locator("#gc-still")
    still.wait_for(state="attached")
    return still.get_attribute("src")


def print_pdf(html_path: Path, pdf_path: Path) -> Path:
    """Print ``html_path`` (a report) to ``pdf_path`` atomically; returns the path."""
    with chromium() as browser:
        page = cast(Any, browser).new_page(viewport=VIEWPORT)
        try:
            page.add_init_script(NO_WEBGL)
            page.goto(Path(html_path).resolve().as_uri(), wait_until="load")
            src = still_picture(page)
            if src is not None:
                page.evaluate("""src => {
                    for (const p of document.querySelectorAll('.viewer .print-only')) {
                        p.textContent = 'The 3D view of the HTML report:';
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
