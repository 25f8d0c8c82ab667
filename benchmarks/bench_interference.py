"""Interference check figures: what each tolerance and model costs and buys.

Run::

    python benchmarks/bench_interference.py [TEMPLATE] [--misalignment DEG] [--angles N]
        [--tolerances MM,MM,...] [--repeat N] [--engines]

(default renzo-1967 at its design angle, 24 angles over a turn). For each chordal
tolerance it prints the triangles of the full parts and of one tooth-pair sector, the wall
time per pose of the boolean check on the full parts and on the sweep-chosen sector
submodels (and the distance method on the sectors), the speed-up, and the largest error of
the mesh minimum gap against the exact smallest normal clearance of the semi-analytic
sweep at the same angles; the last row is the sweep itself. ``--engines`` prints the
distance-engine comparison behind :mod:`gearcoupling.interference.distance`.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

import gearcoupling as gc
from gearcoupling.clearance import sweep
from gearcoupling.interference import build_model, check_interference


def _gap_error(res, exact) -> float:
    """Largest |mesh gap - exact| over the angles whose closest pair is flank to flank."""
    flanks = np.array([h.startswith("flank") and s.startswith("flank")
                       for h, s in zip(res.gap_hub_surface, res.gap_sleeve_surface, strict=True)])
    flanks |= res.overlap_depth_mm > 0
    if not np.any(flanks):
        return float("nan")
    return float(np.max(np.abs(res.min_gap_mm - exact)[flanks]))


def best_of(repeat: int, fn):
    """The run with the smallest time per pose among ``repeat`` (shared, noisy machine)."""
    return min((fn() for _ in range(repeat)), key=lambda r: r.seconds_per_pose)


def table(spec, mis: float, angles, tolerances, repeat: int = 2) -> list[str]:
    sw = sweep(spec, mis, angles)  # warm-up: builds the cached flank table
    t_sweep = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        sweep(spec, mis, angles)
        t_sweep = min(t_sweep, (time.perf_counter() - t0) / len(angles))
    exact = sw.normal_clearance_mm.min(axis=(0, 1))
    lines = [
        f"{spec.name}, misalignment {mis:g}°, {len(angles)} angles over a turn; exact "
        f"smallest normal clearance {exact.min():+.5f} .. {exact.max():+.5f} mm",
        "",
        "| tolerance mm | triangles full | triangles pair | full boolean ms/pose | "
        "sector boolean ms/pose | sector distance ms/pose | speed-up | pairs/pose | "
        "gap error mm | overlap mm³ (max) |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for tol in tolerances:
        full = build_model(spec, tol, None)
        pair = build_model(spec, tol, 0)
        rf = best_of(repeat, lambda tol=tol, full=full: check_interference(
            spec, mis, angles, tolerance_mm=tol, teeth="all", model=full))
        rs = best_of(repeat, lambda tol=tol, pair=pair: check_interference(
            spec, mis, angles, tolerance_mm=tol, model=pair))
        rd = best_of(repeat, lambda tol=tol, pair=pair: check_interference(
            spec, mis, angles, tolerance_mm=tol, model=pair, method="distance"))
        err = max(_gap_error(rf, exact), _gap_error(rs, exact))
        lines.append(
            f"| {tol:g} | {sum(full.triangles)} | {sum(pair.triangles)} | "
            f"{1e3 * rf.seconds_per_pose:.1f} | {1e3 * rs.seconds_per_pose:.1f} | "
            f"{1e3 * rd.seconds_per_pose:.1f} | "
            f"{rf.seconds_per_pose / rs.seconds_per_pose:.1f}x | {rs.windows.mean():.1f} | "
            f"{err:.5f} | {rs.overlap_volume_mm3.max():.4g} |")
    lines.append(f"| sweep (exact, 1e-7 mm) | – | – | {1e3 * t_sweep:.1f} (every tooth and "
                 f"flank) | – | – | – | {spec.tooth.teeth} | 0 (reference) | – |")
    return lines


def engines(spec, tol: float) -> list[str]:
    """Distance engines on the pose of the smallest clearance at the design angle."""
    import fcl
    import igl

    from gearcoupling.interference.posed import window_pose

    mis = spec.design_misalignment
    N = spec.tooth.teeth
    sw = sweep(spec, math.degrees(mis), [0.0])
    k = int(np.argmin(sw.normal_clearance_mm[:, :, 0].min(axis=0)))
    A = window_pose(mis, 0.0, k, N)
    lines = ["| model | triangles | fcl distance ms | fcl setup ms | libigl both ways ms | "
             "manifold3d min_gap ms | fcl collide ms | distances mm |",
             "|---|---:|---:|---:|---:|---:|---:|---|"]
    for label, half in (("tooth pair", 0), ("±1 sector", 1), ("full parts", None)):
        model = build_model(spec, tol, half)
        h, s = model.hub, model.sleeve
        hv = h.vertices @ A.T

        def clock(fn, repeat=3):
            t = time.perf_counter()
            for _ in range(repeat):
                out = fn()
            return 1e3 * (time.perf_counter() - t) / repeat, out

        t_setup, _ = clock(lambda h=h, s=s: (h.__dict__.pop("shell_bvh", None),
                                             s.__dict__.pop("shell_bvh", None),
                                             h.shell_bvh, s.shell_bvh), 1)
        oh, os_ = h.fcl_object(A), s.fcl_object()
        req = fcl.DistanceRequest(enable_nearest_points=True)
        t_fcl, d_fcl = clock(lambda oh=oh, os_=os_, req=req:
                             fcl.distance(oh, os_, req, fcl.DistanceResult()))

        def igl_both(h=h, s=s, hv=hv):
            d1, _, _ = igl.point_mesh_squared_distance(hv, s.vertices, s.faces)
            d2, _, _ = igl.point_mesh_squared_distance(s.vertices, hv, h.faces)
            return math.sqrt(min(d1.min(), d2.min()))

        t_igl, d_igl = clock(igl_both)
        ph, ps = h.posed_manifold(A), s.manifold
        t_m3d, d_m3d = clock(lambda ph=ph, ps=ps: ph.min_gap(ps, 1.0), 1)
        t_col, _ = clock(lambda oh=oh, os_=os_:
                         fcl.collide(oh, os_, fcl.CollisionRequest(), fcl.CollisionResult()))
        lines.append(f"| {label} | {sum(model.triangles)} | {t_fcl:.1f} | {t_setup:.1f} | "
                     f"{t_igl:.1f} | {t_m3d:.1f} | {t_col:.1f} | "
                     f"{d_fcl:.6f} / {d_igl:.6f} / {d_m3d:.6f} |")
    return lines


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("template", nargs="?", default="renzo-1967")
    p.add_argument("--misalignment", type=float, default=None, metavar="DEG")
    p.add_argument("--angles", type=int, default=24)
    p.add_argument("--tolerances", default=None, metavar="MM,MM",
                   help="chordal tolerances (default module/50, /200, /1000, /2500)")
    p.add_argument("--repeat", type=int, default=2,
                   help="runs per measurement; the fastest counts (default 2)")
    p.add_argument("--engines", action="store_true")
    args = p.parse_args(argv)
    spec = gc.load_spec(args.template)
    m = spec.tooth.module
    tols = ([float(t) for t in args.tolerances.split(",")] if args.tolerances
            else [m / 50, m / 200, m / 1000, m / 2500])
    if args.engines:
        print("\n".join(engines(spec, m / 200)))
        return
    mis = math.degrees(spec.design_misalignment) if args.misalignment is None \
        else args.misalignment
    angles = 360.0 * np.arange(args.angles) / args.angles
    print("\n".join(table(spec, mis, angles, tols, max(1, args.repeat))))


if __name__ == "__main__":
    main()
