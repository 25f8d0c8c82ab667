"""The viewer in a real browser: Debian chromium driven by playwright, software WebGL.

``scripts/test.sh`` installs chromium (``apt-get install chromium``) and the ``browser``
extra (playwright; its own browser download is never used). Screenshots are kept in
``outputs/test-screenshots/`` for a person to look at. Software WebGL takes 10-40 s per
first frame on a busy 2-core machine, so the two tests share one browser.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from gearcoupling.browser import chromium, drawn_fraction, png_pixels
from gearcoupling.errors import BackendError
from gearcoupling.viewer import pixels as br

pytestmark = [pytest.mark.needs_browser, pytest.mark.slow]

SHOTS = Path(__file__).resolve().parents[1] / "outputs" / "test-screenshots"
VIEWPORT = {"width": 800, "height": 560}  # larger views cost seconds per frame


@pytest.fixture(scope="module")
def browser():
    SHOTS.mkdir(parents=True, exist_ok=True)
    try:
        with chromium() as b:
            yield b
    except BackendError as err:  # CI installs both: a missing browser is a failure
        pytest.fail(f"{err} (run `bash scripts/test.sh`)")


def settled_box(locator, timeout_s: float = 10.0) -> dict:
    """The locator's bounding box once two readings 0.2 s apart agree within half a pixel."""
    last, deadline = None, time.time() + timeout_s
    while time.time() < deadline:
        box = locator.bounding_box()
        if box and last and all(abs(box[k] - last[k]) < 0.5 for k in box):
            return box
        last = box
        time.sleep(0.2)
    assert last is not None, "the slider never appeared"
    return last


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
        before, _ = br.wait_rendered(page)
        print(f"\nlive viewer: first render {time.perf_counter() - t_start:.1f} s after start")
        page.screenshot(path=str(SHOTS / "live-initial.png"))
        assert drawn_fraction(before) > 0.05
        assert br.reddish_pixels(before) > 200  # interfering flanks at 3° are drawn red

        # the scene tree (viser's settings panel) lists hub and sleeve
        page.locator(".mantine-ActionIcon-root").first.click()
        for name in ("/hub", "/sleeve"):
            node = page.locator(f'[aria-label="Edit props for {name}"]')
            node.first.wait_for(state="visible", timeout=10_000)
        page.wait_for_timeout(1000)  # let the panel finish its transition for the picture
        page.screenshot(path=str(SHOTS / "live-scene-tree.png"))
        page.locator(".mantine-ActionIcon-root").first.click()  # back to the GUI
        page.wait_for_selector("text=rotation ψ (°)", state="visible", timeout=10_000)

        # move the rotation slider: click a quarter along its track (psi = 90°)
        slider_id = page.locator("label", has_text="rotation ψ (°)").get_attribute("for")
        track = page.locator(f'[id="{slider_id}"] .mantine-Slider-track')
        box = settled_box(track)  # the panel slides back in: click where it comes to rest
        updates = app.pose_updates
        page.mouse.click(box["x"] + 0.25 * box["width"], box["y"] + 0.5 * box["height"])
        deadline = time.time() + 20
        while app.pose_updates == updates and time.time() < deadline:
            time.sleep(0.2)
        assert app.pose_updates > updates, "the server never saw the slider move"
        psi = app.scene.settings.psi_deg
        assert 80.0 <= psi <= 100.0, f"the click set psi = {psi}"
        after, seconds = br.wait_rendered(page, previous=before)
        changed = np.mean(np.abs(after - before).max(axis=-1) > 40)
        print(f"live viewer: redrawn {seconds:.1f} s after the slider moved, "
              f"{changed:.1%} of the view changed")
        page.screenshot(path=str(SHOTS / "live-rotated-90.png"))
        assert changed > 0.01, f"only {changed:.2%} of the view changed"
    except Exception:
        page.screenshot(path=str(SHOTS / "live-failure.png"))  # for a person to look at
        raise
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
        t0 = time.perf_counter()
        page.goto(path.as_uri())
        assert "renzo-1967" in page.title() and "i = 3°" in page.title()
        assert "ψ = 20°" in page.locator("#gc-caption").inner_text()
        # the still picture goes once WebGL has drawn; what is seen then is the WebGL view
        page.locator("#gc-still").wait_for(state="detached", timeout=180_000)
        print(f"\nstill picture replaced after {time.perf_counter() - t0:.1f} s")
        view, seconds = br.wait_rendered(page)
        print(f"static HTML ({path.stat().st_size / 1e6:.2f} MB): rendered in {seconds:.1f} s")
        page.screenshot(path=str(SHOTS / "static-html.png"))
        assert drawn_fraction(view) > 0.05
        assert br.reddish_pixels(view) > 200
        # its scene tree lists hub, sleeve and the colour legend (labels are drawn in 3D)
        page.locator('[aria-label="Show scene tree"]').first.click()
        for name in ("/hub", "/sleeve", "/legend"):
            node = page.locator(f'[aria-label="Edit props for {name}"]')
            node.first.wait_for(state="visible", timeout=10_000)
        # self-contained: nothing but the file itself (and inline data) is fetched
        assert all(u.startswith(("file:", "data:", "blob:")) for u in requests), requests
    finally:
        page.close()


def test_static_html_shows_its_still_picture_until_webgl_draws(browser, renzo):
    """Without WebGL (here: none at all) the still picture of the pose stays, named by the
    page's title and caption."""
    from gearcoupling.viewer.html import write_html
    from gearcoupling.viewer.nodes import ViewSettings

    path = write_html(renzo, SHOTS / "renzo-1967-still.html",
                      settings=ViewSettings(misalignment_deg=3.0, psi_deg=20.0))
    page = browser.new_page(viewport=VIEWPORT)
    page.add_init_script("HTMLCanvasElement.prototype.getContext = function () { return null; };")
    try:
        page.goto(path.as_uri())
        assert "i = 3°, rotation ψ = 20°" in page.title()
        still = page.locator("#gc-still")
        still.wait_for(state="visible", timeout=10_000)
        time.sleep(2.0)  # past the first checks of the page's script: the still stays
        view = png_pixels(still.screenshot(path=str(SHOTS / "static-still.png")))
        assert drawn_fraction(view) > 0.05
        assert br.reddish_pixels(view) > 200  # the interfering flanks at 3°, as drawn later
        assert "ψ = 20°" in page.locator("#gc-caption").inner_text()
        still.click()  # a click gives the (here empty) interactive view
        still.wait_for(state="detached", timeout=5_000)
    finally:
        page.close()
