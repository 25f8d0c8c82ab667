"""Geometry kernel figures: flank-grid evaluation time and the section tolerance table.

Run: ``python benchmarks/bench_geometry.py [TEMPLATE]`` (default renzo-1967). Prints
timings (median of repeats, this machine) and the measured largest distance between exact
flank/fillet points and the section polygon for each chordal tolerance.
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np

import gearcoupling as gc
from gearcoupling.geometry.hub import envelope, form_radius, hub_model, round_point, tip_radius


def median_time(fn, repeat: int = 7) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def flank_grid_times(spec, n: int = 100) -> list[tuple[str, float]]:
    rows = []
    for gen in ("enveloped", "revolved"):
        s = spec.replace(**{"hub.crowning.generation": gen})
        m = hub_model(s)
        z = np.linspace(-m.half_face, m.half_face, n)
        lo, hi = form_radius(m, z), tip_radius(m, z)
        r = lo[:, None] + (hi - lo)[:, None] * np.linspace(0, 1, n)[None, :]
        zz = np.broadcast_to(z[:, None], r.shape)
        rows.append((gen, median_time(lambda s=s, zz=zz, r=r: gc.hub_flank(s, "cw", zz, r))))
    return rows


def section_table(spec, tolerances=(1e-2, 1e-3, 1e-4, 1e-5)):
    import shapely

    m = hub_model(spec)
    z = 0.8 * m.half_face
    r = np.linspace(form_radius(m, z), tip_radius(m, z), 2000)
    exact_flank, _ = gc.hub_flank(spec, "cw", z, r)
    gamma = np.linspace(m.phi, math.pi / 2, 2000)
    exact_fillet, _ = envelope(m, z, *round_point(m, gamma), gamma)
    exact = shapely.points(np.concatenate([exact_flank, exact_fillet])[:, :2])
    rows = []
    for tol in tolerances:
        t = median_time(lambda tol=tol: gc.transverse_section(spec, "hub", z, tol), repeat=3)
        poly = gc.transverse_section(spec, "hub", z, tol)
        dev = float(np.max(shapely.distance(exact, shapely.LinearRing(poly))))
        ts = median_time(lambda tol=tol: gc.transverse_section(spec, "sleeve", z, tol), repeat=3)
        ns = len(gc.transverse_section(spec, "sleeve", z, tol))
        rows.append((tol, len(poly), t, dev, ns, ts))
    return rows


def main(name: str = "renzo-1967") -> None:
    spec = gc.load_spec(name)
    print(f"# {name}: hub_flank on a 100 x 100 (z, r) grid, one flank")
    for gen, t in flank_grid_times(spec):
        print(f"  {gen:10s} {1e3 * t:7.1f} ms  ({1e9 * t / 1e4:.0f} ns per point)")
    print(f"\n# {name}: transverse_section at z = 0.8 b/2, all {spec.tooth.teeth} teeth")
    print("| tolerance mm | hub vertices | hub time ms | measured max deviation mm "
          "| sleeve vertices | sleeve time ms |")
    print("|---|---|---|---|---|---|")
    for tol, n, t, dev, ns, ts in section_table(spec):
        print(f"| {tol:g} | {n} | {1e3 * t:.1f} | {dev:.2e} | {ns} | {1e3 * ts:.1f} |")


if __name__ == "__main__":
    main(*sys.argv[1:])
