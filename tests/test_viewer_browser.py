"""The viewer in a real browser: Debian chromium driven by playwright, software WebGL.

``scripts/test.sh`` installs chromium (``apt-get install chromium``) and the ``browser``
extra (playwright; its own browser download is never used). Screenshots are kept in
``outputs/test-screenshots/`` for a person to look at.
"""

from __future__ import annotations

import io
import os
import time
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
SHOTS = Path(__file__).resolve().parents[1] / "outputs" / "test-screenshots"
VIEWPORT = {"width": 1100, "height": 720}
RENDER_TIMEOUT_S = 120.0


@pytest.fixture(scope="module")
def browser():
    if not os.access(CHROMIUM, os.X_OK):
        pytest.fail(f"{CHROMIUM} is missing: run `bash scripts/test.sh`, which installs "
                    "Debian's chromium for these tests")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.fail("playwright is missing: pip install -e '.[test]' (or '.[browser]')")
    SHOTS.mkdir(parents=True, exist_ok=True)
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield b
        b.close()


def _pixels(page) -> np.ndarray:
    """The 3D view of a screenshot (RGB), without the GUI panel and notifications."""
    from PIL import Image

    img = np.asarray(Image.open(io.BytesIO(page.screenshot())).convert("RGB"), dtype=np.int16)
    h, w, _ = img.shape
    return img[int(0.2 * h):int(0.95 * h), int(0.05 * w):int(0.6 * w)]


def _drawn_fraction(view: np.ndarray) -> float:
    """Share of pixels that differ from the background colour (the view's corner pixel)."""
    background = view[-1, 0]
    return float(np.mean(np.abs(view - background).max(axis=-1) > 40))


def _close_notifications(page) -> None:
    close = page.locator(".mantine-Notification-closeButton")
    for i in range(close.count()):
        if close.nth(i).is_visible():
            close.nth(i).click()


def _wait_rendered(page, *, previous: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """Poll screenshots until the parts are drawn and two shots agree (and, if given,
    the picture differs from ``previous``); returns the view and the seconds waited."""
    t0 = time.perf_counter()
    last = None
    while time.perf_counter() - t0 < RENDER_TIMEOUT_S:
        _close_notifications(page)
        view = _pixels(page)
        drawn = _drawn_fraction(view) > 0.05
        changed = previous is None or np.mean(np.abs(view - previous)) > 0.5
        if drawn and changed and last is not None and np.mean(np.abs(view - last)) < 0.2:
            return view, time.perf_counter() - t0
        last = view
        time.sleep(1.0)
    pytest.fail(f"nothing rendered within {RENDER_TIMEOUT_S:.0f} s "
                f"(drawn fraction {_drawn_fraction(last):.3f})")


def _reddish(view: np.ndarray) -> int:
    """Pixels of the interference colour family (flanks with negative clearance)."""
    r, g, b = view[..., 0], view[..., 1], view[..., 2]
    return int(np.sum((r > 130) & (g < 70) & (b < 70)))


def test_live_viewer_renders_and_the_rotation_slider_moves_the_hub(browser, renzo):
    from gearcoupling.viewer.html import free_port
    from gearcoupling.viewer.nodes import ViewSettings
    from gearcoupling.viewer.server import ViewerApp

    t_start = time.perf_counter()
    app = ViewerApp(renzo, port=free_port(), settings=ViewSettings(misalignment_deg=3.0))
    page = browser.new_page(viewport=VIEWPORT)
    try:
        page.goto(app.url)
        page.wait_for_selector("text=rotation ψ (°)", timeout=60_000)
        before, _ = _wait_rendered(page)
        print(f"\nlive viewer: first render {time.perf_counter() - t_start:.1f} s after start")
        page.screenshot(path=str(SHOTS / "live-initial.png"))
        assert _drawn_fraction(before) > 0.05
        assert _reddish(before) > 200  # interfering flanks at 3° are drawn in red

        # the scene tree (viser's settings panel) lists hub and sleeve
        page.locator(".mantine-ActionIcon-root").first.click()
        for name in ("/hub", "/sleeve"):
            node = page.locator(f'[aria-label="Edit props for {name}"]')
            node.first.wait_for(state="visible", timeout=10_000)
        page.screenshot(path=str(SHOTS / "live-scene-tree.png"))
        page.locator(".mantine-ActionIcon-root").first.click()  # back to the GUI
        page.wait_for_selector("text=rotation ψ (°)", state="visible", timeout=10_000)

        # move the rotation slider: click a quarter along its track (psi = 90°)
        slider_id = page.locator("label", has_text="rotation ψ (°)").get_attribute("for")
        track = page.locator(f'[id="{slider_id}"] .mantine-Slider-track')
        box = track.bounding_box()
        updates = app.pose_updates
        page.mouse.click(box["x"] + 0.25 * box["width"], box["y"] + 0.5 * box["height"])
        deadline = time.time() + 20
        while app.pose_updates == updates and time.time() < deadline:
            time.sleep(0.2)
        assert app.pose_updates > updates, "the server never saw the slider move"
        assert 80.0 <= app.scene.settings.psi_deg <= 100.0
        after, seconds = _wait_rendered(page, previous=before)
        print(f"live viewer: redrawn {seconds:.1f} s after the slider moved")
        page.screenshot(path=str(SHOTS / "live-rotated-90.png"))
        changed = np.mean(np.abs(after - before).max(axis=-1) > 40)
        assert changed > 0.01, f"only {changed:.2%} of the view changed"
    finally:
        page.close()
        app.stop()


def test_static_html_opens_from_disk_and_renders(browser, renzo):
    from gearcoupling.viewer.html import write_html
    from gearcoupling.viewer.nodes import ViewSettings

    path = write_html(renzo, SHOTS / "renzo-1967-static.html",
                      settings=ViewSettings(misalignment_deg=3.0, psi_deg=20.0))
    page = browser.new_page(viewport=VIEWPORT)
    requests: list[str] = []
    page.on("request", lambda r: requests.append(r.url))
    try:
        page.goto(path.as_uri())
        view, seconds = _wait_rendered(page)
        print(f"\nstatic HTML ({path.stat().st_size / 1e6:.2f} MB): rendered in {seconds:.1f} s")
        page.screenshot(path=str(SHOTS / "static-html.png"))
        assert _drawn_fraction(view) > 0.05
        assert _reddish(view) > 200
        # its scene tree lists hub, sleeve and the colour legend (labels are drawn in 3D)
        page.locator('[aria-label="Show scene tree"]').first.click()
        for name in ("/hub", "/sleeve", "/legend"):
            node = page.locator(f'[aria-label="Edit props for {name}"]')
            node.first.wait_for(state="visible", timeout=10_000)
        # self-contained: nothing but the file itself (and inline data) is fetched
        assert all(u.startswith(("file:", "data:", "blob:")) for u in requests), requests
    finally:
        page.close()
