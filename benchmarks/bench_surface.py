"""Speed and accuracy of the ``surface`` load model: the grid trade.

For renzo-1967 at a misalignment and torque, one pose (rotation 0) is solved on a ladder of
fine grids (cells along the face x across the depth); each row prints the CPU and wall
time of the pose, the largest tooth load, the wind-up, the largest peak pressure (grid
dependent where a flank end cuts the patch: it grows like 1/sqrt(cell)), the interior
pressure and the edge intensity p sqrt(cell) (both grid independent), the patch length,
and their differences from the finest grid.

``--figures DIR`` writes pressure maps of the most loaded tooth on the developed flank
(renzo-1967: aligned, 1°, and past the critical misalignment) as PNG files.
``--speed [--against DIR]`` times what users wait for (one pose cold, a pose warm-started
from its neighbouring rotation, a turn of 360 rotations, the surface capacity at one
misalignment), each in a subprocess of this checkout and (``--against``) of another
checkout (``DIR/src``) in the same run: medians of CPU seconds, and their ratio.
``--theory`` prints the validation tables instead: Hertz's elliptic contact (curvature
ratios 1-20) and a quadratic gap cut by a straight edge, against grid refinement, and the
crowned renzo-1967 patch against the line contact of the exact lead curvature.

Run: ``python benchmarks/bench_surface.py [--misalignment 1] [--torque 2000] [--quick]``.
The machine is shared: times are the best of ``--repeats`` runs.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

from gearcoupling.clearance import sweep
from gearcoupling.loading.inputs import tooth_compliance
from gearcoupling.loading.models.surface import DEFAULT_GRID, solve_surface
from gearcoupling.spec import load_spec

LADDER = ((16, 12), (24, 16), (32, 24), (48, 32), (64, 48), (96, 64), (128, 96))


def timed(fn, repeats):
    best = (np.inf, np.inf, None)
    for _ in range(repeats):
        c, w = time.process_time(), time.perf_counter()
        out = fn()
        cpu, wall = time.process_time() - c, time.perf_counter() - w
        if cpu < best[0]:
            best = (cpu, wall, out)
    return best


def measures(res):
    W = res["normal_force_N"][:, 0]
    k = int(np.argmax(W))
    return {
        "W_max": float(W[k]),
        "windup_urad": float(res["windup_rad"][0]) * 1e6,
        "p_max": float(np.max(res["max_pressure_MPa"][:, 0])),
        "p_int": float(np.max(res["interior_pressure_MPa"][:, 0])),
        "edge_I": float(np.max(res["edge_intensity_MPa_sqrt_mm"][:, 0])),
        "length": float(res["patch_length_mm"][k, 0]),
        "loaded": int(np.count_nonzero(W)),
    }


def theory():
    import math

    from gearcoupling.geometry.hub import hub_flank
    from gearcoupling.geometry.sleeve import sleeve_model
    from gearcoupling.loading.kernels.halfspace import (
        composite_modulus,
        half_space,
        hertz_ellipse,
        solve_contact,
    )
    from gearcoupling.loading.models.surface import contact_modulus

    E = composite_modulus(206000.0, 0.3, 206000.0, 0.3)
    print("Hertz ellipse, W = 200 N, ry = 15 mm, grid over 2.5 semi-axes; errors of p0, a, b "
          "(a, b from a least-squares fit of p^2 against x^2 along the axes)")
    print("| rx/ry | cells | p0 error | a error | b error | iterations | s |")
    print("|---|---|---|---|---|---|---|")
    for ratio in (1, 2, 5, 10, 20):
        for n in (17, 33, 65, 129):
            h = hertz_ellipse(200.0, 15.0 * ratio, 15.0, E)
            dx, dy = 2.5 * h["a_mm"] / n, 2.5 * h["b_mm"] / n
            x = (np.arange(n) - (n - 1) / 2) * dx
            y = (np.arange(n) - (n - 1) / 2) * dy
            gap = x[:, None] ** 2 / (30.0 * ratio) + y[None, :] ** 2 / 30.0
            t = time.perf_counter()
            sol = solve_contact(half_space((n, n), dx, dy, E), gap, load_N=200.0,
                                tolerance=1e-10)
            dt = time.perf_counter() - t
            p = sol.pressure_MPa
            c = n // 2
            errs = [p.max() / h["p0_MPa"] - 1]
            for prof, coord, ref in ((p[:, c], x, h["a_mm"]), (p[c, :], y, h["b_mm"])):
                keep = prof > 0.3 * prof.max()
                sl, ic = np.polyfit(coord[keep] ** 2, prof[keep] ** 2, 1)
                errs.append(math.sqrt(-ic / sl) / ref - 1)
            print(f"| {ratio} | {n} x {n} | {errs[0]:+.3%} | {errs[1]:+.3%} | {errs[2]:+.3%} | "
                  f"{sol.iterations} | {dt:.2f} |")
    print("\nQuadratic gap (R = 20 mm, W = 100 N) cut by a straight edge at x = 0.4 a")
    print("| cells | cell mm | edge peak MPa | growth per halving | p sqrt(h) MPa sqrt(mm) |")
    print("|---|---|---|---|---|")
    a = hertz_ellipse(100.0, 20.0, 20.0, E)["a_mm"]
    last = None
    for n in (16, 32, 64, 128, 256):
        dx = 2.6 * a / n
        x = -1.3 * a + (np.arange(n) + 0.5) * dx
        gap = (x[:, None] ** 2 + x[None, :] ** 2) / 40.0
        mask = np.broadcast_to((x <= 0.4 * a)[:, None], gap.shape)
        p = solve_contact(half_space((n, n), dx, dx, E), gap, load_N=100.0, mask=mask,
                          tolerance=1e-9).pressure_MPa.max()
        grow = "" if last is None else f"{p / last:.3f}"
        print(f"| {n} x {n} | {dx:.4f} | {p:.1f} | {grow} | {p * math.sqrt(dx):.1f} |")
        last = p
    spec = load_spec("renzo-1967")
    sm = sleeve_model(spec)
    R = spec.tooth.pitch_radius
    z = np.linspace(-1.0, 1.0, 21)
    pts, _ = hub_flank(spec, "cw", z, np.full_like(z, R))
    gap = sm.r_base * (np.arctan2(pts[:, 1], pts[:, 0]) + sm.half_angle(R))
    kappa = 2.0 * np.polyfit(z, gap, 4)[2]
    Es = contact_modulus(spec)
    sw = sweep(spec, 0.0, [0.0])
    print(f"\nrenzo-1967 aligned: exact lead curvature at the pitch line {kappa:.6g} 1/mm "
          f"(sin(phi)/R_c = {math.sin(spec.tooth.pressure_angle) / R:.6g})")
    print("| torque N·m | grid | tooth load N | q = W/w N/mm | line-contact 2a mm | patch length "
          "mm | extent mm | line-contact p0 MPa | interior p MPa | edge share |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for T in (500.0, 2000.0, 8000.0):
        for grid in ((48, 32), (96, 64)):
            res = solve_surface(spec, sw, torque_Nm=T, grid=grid)
            W, w = res["normal_force_N"][0, 0], res["patch_width_mm"][0, 0]
            q = W / w
            a2 = 2 * math.sqrt(4 * q / (math.pi * Es * kappa))
            p0 = math.sqrt(q * Es * kappa / math.pi)
            print(f"| {T:g} | {grid[0]} x {grid[1]} | {W:.1f} | {q:.1f} | {a2:.3f} | "
                  f"{res['patch_length_mm'][0, 0]:.3f} | {res['patch_extent_mm'][0, 0]:.3f} | "
                  f"{p0:.1f} | {res['interior_pressure_MPa'][0, 0]:.1f} | "
                  f"{res['edge_load_share'][0, 0]:.3f} |")


def figures(out_dir):
    from pathlib import Path

    from gearcoupling.clearance.design import critical_misalignment_deg
    from gearcoupling.plots import new_figure, save_figure

    spec = load_spec("renzo-1967")
    comp = tooth_compliance(spec)
    crit = critical_misalignment_deg(spec)
    cases = (("aligned", 0.0), ("1deg", 1.0), ("past_critical", crit + 0.3))
    fig, axes = new_figure(1, len(cases), figsize=(5.6 * len(cases), 4.4), layout="constrained")
    for ax, (name, mis) in zip(axes, cases, strict=True):
        res = solve_surface(spec, sweep(spec, mis, [0.0]), torque_Nm=2000.0, compliance=comp,
                            keep_fields=True)
        f = res["fields"][0]
        W = res["normal_force_N"][:, 0]
        k = int(np.argmax(W))
        i = int(np.flatnonzero(f["teeth"] == k)[0])
        gf, p = f["field"], f["pressure_MPa"][i]
        shown = np.where(gf.mask[i], p, np.nan)
        im = ax.pcolormesh(gf.z_mm[i], gf.s_mm, shown.T, shading="nearest", cmap="inferno")
        ax.contour(gf.z_mm[i], gf.s_mm, gf.mask[i].T.astype(float), levels=[0.5],
                   colors="c", linewidths=0.8)
        ax.set_title(f"{name} ({mis:.2f}°), tooth {k}: W = {W[k]:.0f} N\n"
                     f"p_max {res['max_pressure_MPa'][k, 0]:.0f}, interior "
                     f"{res['interior_pressure_MPa'][k, 0]:.0f} MPa, edge "
                     f"{bool(res['edge_contact'][k, 0])}", fontsize=8)
        ax.set_xlabel("z (mm, sleeve frame)")
        ax.set_ylabel("s (mm, involute arc from the base circle)")
        fig.colorbar(im, ax=ax, label="pressure (MPa)")
    path = save_figure(fig, Path(out_dir) / "surface_pressure_renzo.png")
    print(f"wrote {path}")


_SPEED = """
import dataclasses, json, statistics, sys, time
import numpy as np
from gearcoupling.clearance import sweep
from gearcoupling.loading import capacity, load_from_sweep
from gearcoupling.loading.inputs import tooth_compliance
from gearcoupling.loading.models.surface import solve_surface
from gearcoupling.spec import load_spec
spec = load_spec("renzo-1967")
comp = tooth_compliance(spec)
which, repeats = sys.argv[1], int(sys.argv[2])
def cpu(fn):
    c = time.process_time(); fn(); return time.process_time() - c
def fresh(sw):  # a copy: no start kept from an earlier load of the same sweep object
    return dataclasses.replace(sw)
solve_surface(spec, sweep(spec, 1.0, [0.0]), torque_Nm=2000.0, compliance=comp)  # caches
out = {}
if which == "pose":
    sws = [sweep(spec, 1.0, [a]) for a in (0.0, 2.0, 4.0)]
    out["cold"] = statistics.median(
        cpu(lambda s=s: solve_surface(spec, fresh(s), torque_Nm=2000.0, compliance=comp))
        for s in sws for _ in range(repeats))
    one, turn = sweep(spec, 1.0, [0.0]), sweep(spec, 1.0, np.arange(11.0))
    t1 = statistics.median(cpu(lambda: solve_surface(spec, fresh(one), torque_Nm=2000.0,
                                                     compliance=comp)) for _ in range(repeats))
    t11 = statistics.median(cpu(lambda: solve_surface(spec, fresh(turn), torque_Nm=2000.0,
                                                      compliance=comp)) for _ in range(repeats))
    out["warm"] = (t11 - t1) / 10.0
elif which == "turn":
    sw = sweep(spec, 1.0, np.arange(360.0))
    out["turn"] = statistics.median(cpu(lambda: load_from_sweep(
        fresh(sw), torque_Nm=3000.0, model="surface")) for _ in range(repeats))
elif which == "capacity":
    res = {}
    def run():
        res["c"] = capacity(spec, 1.0, model="surface")
    out["capacity"] = statistics.median(cpu(run) for _ in range(repeats))
    out["capacity_Nm"] = res["c"].capacity_Nm
    out["solves"] = res["c"].solves
print(json.dumps(out))
"""


def speed_in(path: str, which: str, repeats: int) -> dict:
    """Medians (CPU s) of the speed measurement ``which`` with the checkout ``path``."""
    import json
    import subprocess
    import sys

    env = dict(os.environ, PYTHONPATH=os.path.join(path, "src"), OPENBLAS_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", _SPEED, which, str(repeats)], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.splitlines()[-1])


def speed(against: str | None, repeats: int, with_capacity: bool):
    """The speed table: this checkout against ``against`` (the same measurements)."""
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rows = [("one pose, cold (1°, 2000 N·m)", "pose", "cold", repeats),
            ("one pose, warm from the neighbouring rotation (1° apart)", "pose", "warm",
             repeats),
            ("turn of 360 rotations (3000 N·m, load_from_sweep)", "turn", "turn",
             max(1, repeats // 3))]
    if with_capacity:
        rows.append(("capacity at 1° (25 rotations, 4 criteria)", "capacity", "capacity", 1))
    cache: dict = {}
    print("renzo-1967, surface model, CPU seconds (median; the same run, subprocesses)\n")
    print("| measurement | before | after | before / after |\n|---|---|---|---|")
    for label, which, key, reps in rows:
        new = cache.setdefault((here, which), speed_in(here, which, reps))
        old = cache.setdefault((against, which), speed_in(against, which, reps)) \
            if against else None
        if old is None:
            print(f"| {label} | | {new[key]:.3f} | |")
        else:
            print(f"| {label} | {old[key]:.3f} | {new[key]:.3f} | "
                  f"{old[key] / new[key]:.1f} |")
    if with_capacity:
        new = cache[(here, "capacity")]
        line = f"\ncapacity: {new['capacity_Nm']:.1f} N·m from {new['solves']} solves"
        if against:
            old = cache[(against, "capacity")]
            line += (f" (before: {old['capacity_Nm']:.1f} N·m from {old['solves']} "
                     "full-turn solves)")
        print(line)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spec", default="renzo-1967")
    ap.add_argument("--misalignment", type=float, default=1.0)
    ap.add_argument("--torque", type=float, default=2000.0, help="N·m")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="stop at the 96 x 64 grid")
    ap.add_argument("--rigid", action="store_true", help="rigid teeth (no bending compliance)")
    ap.add_argument("--theory", action="store_true", help="print the validation tables")
    ap.add_argument("--figures", metavar="DIR", help="write pressure maps into DIR")
    ap.add_argument("--speed", action="store_true", help="print the speed table")
    ap.add_argument("--against", metavar="DIR", help="--speed: also time this checkout")
    ap.add_argument("--capacity", action="store_true", help="--speed: also the capacity")
    args = ap.parse_args(argv)
    if args.speed:
        speed(args.against, args.repeats, args.capacity)
        return
    if args.figures:
        figures(args.figures)
        return
    if args.theory:
        theory()
        return
    spec = load_spec(args.spec)
    sw = sweep(spec, args.misalignment, [0.0])
    ladder = LADDER[:-1] if args.quick else LADDER
    comp = None if args.rigid else tooth_compliance(spec)
    rows = []
    for grid in ladder:
        reps = 1 if grid[0] * grid[1] > 64 * 48 else args.repeats
        # a copy of the sweep per call: each pose solved cold (no start kept from the last)
        cpu, wall, res = timed(lambda g=grid: solve_surface(
            spec, dataclasses.replace(sw), torque_Nm=args.torque, grid=g, compliance=comp),
            reps)
        rows.append((grid, cpu, wall, measures(res)))
    ref = rows[-1][3]
    print(f"{args.spec}, misalignment {args.misalignment}°, torque {args.torque} N·m, "
          f"rotation 0, {'rigid teeth' if args.rigid else 'cantilever tooth compliance'}; "
          f"default grid {DEFAULT_GRID}")
    print("| grid (face x depth) | CPU s | wall s | teeth loaded | max tooth load N | "
          "wind-up µrad | p_max MPa | interior p MPa | edge p·√h MPa·√mm | "
          "patch length mm |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for grid, cpu, wall, m in rows:
        def rel(key, m=m):
            return f"{m[key]:.4g} ({(m[key] / ref[key] - 1) * 100:+.2f} %)"
        print(f"| {grid[0]} x {grid[1]} | {cpu:.2f} | {wall:.2f} | {m['loaded']} | "
              f"{rel('W_max')} | {rel('windup_urad')} | {rel('p_max')} | {rel('p_int')} | "
              f"{rel('edge_I')} | {rel('length')} |")


if __name__ == "__main__":
    main()
