"""Geometry kernel figures: flank-grid evaluation time and the section tolerance table.

Run: ``python benchmarks/bench_geometry.py [TEMPLATE]`` (default renzo-1967). Prints
timings (median of repeats, this machine) and the measured largest distance between exact
flank/fillet points and the section polygon for each chordal tolerance.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

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


def theory_errors() -> dict[str, float]:
    """Worst errors against theory over every template (the checks of test_hub_geometry)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from gearcoupling.geometry.hub import hub_flank_model
    from test_hub_geometry import brute_force_polar, polar

    from conftest import flank_grid

    worst = dict.fromkeys(("spur_mm", "base_pitch_mm", "eq1_rad", "brute_force_mm"), 0.0)
    for name in gc.template_names():
        t = gc.load_spec(name)
        spur = t.replace(**{"hub.crowning.kind": "none", "hub.crowning.radius": math.inf})
        m = hub_model(spur)
        z, r = flank_grid(m)
        p, _ = gc.hub_flank(spur, "cw", z, r)
        ang = -(m.thickness / (2 * m.R) + gc.inv(m.phi)
                - gc.inv(np.arccos(m.R * math.cos(m.phi) / r)))
        err = np.hypot(p[..., 0] - r * np.cos(ang), p[..., 1] - r * np.sin(ang))
        worst["spur_mm"] = max(worst["spur_mm"], float(err.max()))
        m = hub_model(t)
        z, r = flank_grid(m, 11, 9, 0.05)
        p, n = gc.hub_flank(t, "cw", z, r)
        a = 2 * math.pi / m.teeth
        rot = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
        q = (p + t.tooth.base_pitch * n) @ rot.T
        rq = np.hypot(q[..., 0], q[..., 1])
        ok = ((np.abs(q[..., 2]) < m.half_face) & (rq < tip_radius(m, q[..., 2]))
              & (rq > form_radius(m, q[..., 2])))
        back, _, _ = hub_flank_model(m, "cw", q[..., 2][ok], rq[ok])
        worst["base_pitch_mm"] = max(worst["base_pitch_mm"],
                                     float(np.linalg.norm(back - q[ok], axis=-1).max()))
    for rc in (1.2, 2.5, 6.0):
        s = gc.load_spec("renzo-1967", **{"hub.crowning.radius": rc})
        m = hub_model(s)
        z = np.linspace(-m.half_face, m.half_face, 41)
        p, n = gc.hub_flank(s, "cw", z, m.R)
        rad = p[:, :2] / np.linalg.norm(p[:, :2], axis=1)[:, None]
        nr = np.einsum("ij,ij->i", n[:, :2], rad)
        nt = np.abs(n[:, 0] * rad[:, 1] - n[:, 1] * rad[:, 0])
        e = np.arctan(z / (rc * 25.4))
        err = np.abs(np.arctan2(nr, nt) - np.arctan(math.tan(m.phi) * np.cos(e)))
        worst["eq1_rad"] = max(worst["eq1_rad"], float(err.max()))
    s = gc.load_spec("renzo-1967")
    for z, r in [(0.0, 61.6), (2.0, 63.5), (-4.5, 65.0), (6.2, 62.3), (5.0, 64.0)]:
        p, _ = gc.hub_flank(s, "cw", z, r)
        worst["brute_force_mm"] = max(worst["brute_force_mm"],
                                      r * abs(float(polar(p)) - brute_force_polar(s, z, r)))
    return worst


def main(name: str = "renzo-1967") -> None:
    print("# worst errors against theory over every template (Renzo eq. 1 on R_c = 1.2, 2.5,"
          " 6 in; brute-force envelope on renzo-1967)")
    for key, value in theory_errors().items():
        print(f"  {key:16s} {value:.2e}")
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
