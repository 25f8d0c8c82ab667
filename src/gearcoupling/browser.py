"""Headless chromium through playwright (Debian's ``/usr/bin/chromium``, software WebGL):
the report prints its PDF with it, and the viewer's browser tests and benchmarks drive it.

Never runs ``playwright install``: the browser is the system's ``/usr/bin/chromium``
(``apt-get install chromium``; ``scripts/test.sh`` does it).
"""

from __future__ import annotations

import contextlib
import importlib
import io
import os
from collections.abc import Iterator

import numpy as np

from .errors import BackendError
from .interrupts import reraise as reraise_interrupt

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
        reraise_interrupt(err)  # a signal during the import
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


def png_pixels(png: bytes) -> np.ndarray:
    """RGB pixels ``(h, w, 3) int16`` of a PNG (a screenshot)."""
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def drawn_fraction(pixels: np.ndarray, threshold: int = 40) -> float:
    """Share of the pixels ``(h, w, 3)`` differing from the background (the bottom-left
    pixel) by more than ``threshold`` in some channel."""
    background = pixels[-1, 0]
    return float(np.mean(np.abs(pixels - background).max(axis=-1) > threshold))


__all__ = ["CHROMIUM", "CHROMIUM_FLAGS", "chromium", "drawn_fraction", "png_pixels"]
