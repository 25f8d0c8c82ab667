"""Viewer figures: command to first render in chromium, pose update cost, static HTML size.

Run: ``python benchmarks/bench_viewer.py [TEMPLATE]`` (default renzo-1967). Needs the
``viewer`` and ``browser`` extras and ``/usr/bin/chromium``. Prints

- the time from ``gearcoupling view TEMPLATE`` (a new process) until the server prints
  its URL, and until chromium (already running, as a user's browser is) shows the parts;
- the cost of one pose change (exact sweep of every tooth + transform and colour
  messages) and of a level-of-detail change;
- size, triangles and write time of the static HTML per level of detail, and the time
  chromium takes to show the coarse one's still picture and to replace it by the WebGL
  drawing.

Software WebGL (SwiftShader) on a shared 2-core machine dominates the render times; a
desktop GPU draws the same scene in well under a second.
"""

from __future__ import annotations

import contextlib
import io
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import gearcoupling as gc
from gearcoupling.browser import chromium
from gearcoupling.viewer import pixels as br
from gearcoupling.viewer.html import free_port, write_html
from gearcoupling.viewer.nodes import CouplingScene, ViewSettings, import_viser
from gearcoupling.viewer.scene import LOD_DIVISORS, lod_tolerance

VIEWPORT = {"width": 800, "height": 560}  # larger views cost seconds per frame


def command_to_render(name: str, browser) -> tuple[float, float]:
    """Seconds from starting ``gearcoupling view`` to its URL line and to a drawn frame."""
    port = free_port()
    page = browser.new_page(viewport=VIEWPORT)
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "gearcoupling", "view", name, "--port",
                             str(port), "--serve-seconds", "600"], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True)
    try:
        url = None
        for line in proc.stdout:
            if line.startswith("gearcoupling viewer for"):
                url = line.split(": ", 1)[1].split()[0]
                break
        if url is None:
            raise RuntimeError("gearcoupling view exited without printing its URL")
        t_url = time.perf_counter() - t0
        page.goto(url)
        br.wait_rendered(page)
        t_render = time.perf_counter() - t0
    finally:
        page.close()
        proc.terminate()
        proc.wait(timeout=10)
    return t_url, t_render


def pose_costs(spec) -> dict[str, float]:
    viser = import_viser()
    with contextlib.redirect_stdout(io.StringIO()):
        server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
    try:
        t0 = time.perf_counter()
        scene = CouplingScene(server, spec, ViewSettings(misalignment_deg=1.0))
        first = time.perf_counter() - t0
        out = {"scene setup s": first}
        for mis in (1.0, 3.0):
            times = []
            for psi in np.linspace(0.0, 30.0, 15):
                t = time.perf_counter()
                scene.set_pose(mis, psi)
                times.append(time.perf_counter() - t)
            out[f"pose change at {mis:g}° ms"] = 1e3 * float(np.median(times))
        for lod in ("medium", "fine", "coarse"):
            t = time.perf_counter()
            scene.set_tolerance(lod_tolerance(spec, lod))
            out[f"LOD -> {lod} s"] = time.perf_counter() - t
    finally:
        with contextlib.redirect_stdout(io.StringIO()):
            server.stop()
    return out


def main(name: str = "renzo-1967") -> None:
    spec = gc.load_spec(name)
    print(f"# viewer figures for {name} ({spec.tooth.teeth} teeth, module "
          f"{spec.tooth.module:g} mm), {os.cpu_count()} cores, load "
          f"{os.getloadavg()[0]:.1f}")
    for key, value in pose_costs(spec).items():
        print(f"{key:28s} {value:8.3f}")
    print("\n| LOD | tolerance mm | triangles | HTML MB | write s |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        paths = {}
        for lod in LOD_DIVISORS:
            tol = lod_tolerance(spec, lod)
            t = time.perf_counter()
            path = write_html(spec, Path(tmp) / f"{lod}.html", tolerance_mm=tol)
            dt = time.perf_counter() - t
            tris = sum(len(gc.parts.build_part(spec, p, tolerance_mm=tol).faces)
                       for p in ("hub", "sleeve"))
            paths[lod] = path
            print(f"| {lod} | {tol:.4g} | {tris} | {path.stat().st_size / 1e6:.2f} | {dt:.2f} |")
        with chromium() as browser:
            page = browser.new_page(viewport=VIEWPORT)
            t = time.perf_counter()
            page.goto(paths["coarse"].as_uri())
            still = page.locator("#gc-still")
            still.wait_for(state="visible")
            t_still = time.perf_counter() - t
            still.wait_for(state="detached", timeout=300_000)
            print(f"\nstatic coarse HTML in chromium: still picture after {t_still:.1f} s, "
                  f"replaced by the WebGL view after {time.perf_counter() - t:.1f} s")
            page.close()
            t_url, t_render = command_to_render(name, browser)
            print(f"`gearcoupling view {name}`: URL after {t_url:.1f} s, first render "
                  f"in chromium after {t_render:.1f} s")


if __name__ == "__main__":
    main(*sys.argv[1:2])
