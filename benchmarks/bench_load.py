"""Speed and accuracy of the loaded-contact analysis; prints the docs/load.md tables.

Run: ``python benchmarks/bench_load.py [--quick]``. Times are medians of several runs of
CPU time of this process and wall time (the machine is shared; quote ratios).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

from gearcoupling.clearance import sweep
from gearcoupling.loading import capacity, capacity_curve, capacity_from_sweep, load_from_sweep
from gearcoupling.loading.contact import ContactModel
from gearcoupling.loading.kernels.cantilever import CantileverCompliance
from gearcoupling.loading.plots import renzo_q
from gearcoupling.spec import load_spec, template_names

LBF = 4.4482216152605
IN = 25.4


def timed(fn, repeats):
    cpu, wall = [], []
    out = None
    for _ in range(repeats):
        c, w = time.process_time(), time.perf_counter()
        out = fn()
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - w)
    return statistics.median(cpu), statistics.median(wall), out


def speed(quick):
    spec = load_spec("renzo-1967")
    psi = np.arange(360.0)
    t_sw = timed(lambda: sweep(spec, 1.0, psi), 1 if quick else 3)
    sw = t_sw[2]
    load_from_sweep(sw, model="compliance")  # warm caches (cantilever, curvatures)
    print("## Speed (renzo-1967, 1°, 360 rotations x 50 teeth, after the sweep)\n")
    print("| step | CPU median s | wall median s |\n|---|---|---|")
    print(f"| sweep (for reference) | {t_sw[0]:.3f} | {t_sw[1]:.3f} |")
    for model in ("linear", "compliance"):
        c, w, _ = timed(lambda m=model: load_from_sweep(sw, model=m), 5)
        print(f"| {model} model, full turn | {c:.3f} | {w:.3f} |")
    c, w, _ = timed(lambda: load_from_sweep(sw).summary(), 3)
    print(f"| compliance + summary (machine loads, wear) | {c:.3f} | {w:.3f} |")
    c, w, _ = timed(lambda: capacity_curve(spec, np.linspace(0, 1.0, 25), model="compliance"),
                    1)
    print(f"| capacity curve, 25 angles (compliance, sweeps included) | {c:.2f} | {w:.2f} |")
    print()


def knobs(quick):
    spec = load_spec("renzo-1967")
    ref = CantileverCompliance(spec, n_radii=512, n_quad=801)
    r = np.linspace(ref.r_table[0], ref.r_table[-1], 997)
    z = np.zeros_like(r)
    c_ref = ref.pair_compliance_mm_per_N(z, r)
    print("## Accuracy knobs\n")
    print("Cantilever table (`CantileverCompliance(n_radii, n_quad)`), against 512 x 801:\n")
    print("| n_radii | n_quad | build s | max rel. error of pair compliance |\n|---|---|---|---|")
    for n_r, n_q in ((8, 51), (16, 101), (32, 201), (64, 201), (128, 401)):
        c, _, cc = timed(lambda a=n_r, b=n_q: CantileverCompliance(spec, n_radii=a, n_quad=b), 3)
        err = np.max(np.abs(cc.pair_compliance_mm_per_N(z, r) / c_ref - 1))
        print(f"| {n_r} | {n_q} | {c:.4f} | {err:.1e} |")
    sw = sweep(spec, 1.0, np.arange(0.0, 7.2, 0.6))
    print("\nCurvature table (`ContactModel(n_z, n_r)`), against 65 x 49, at the template torque"
          " (max tooth load and max interior pressure over a pitch):\n")
    print("| n_z x n_r | build s | max tooth load rel. err | max pressure rel. err |")
    print("|---|---|---|---|")
    import gearcoupling.loading.contact as contact

    def run_with(nz, nr):
        cm = ContactModel(spec, n_z=nz, n_r=nr)
        old = contact.contact_model
        contact.contact_model = lambda s, cm=cm: cm
        import gearcoupling.loading.models.compliance as comp

        comp.contact_model = contact.contact_model
        try:
            res = load_from_sweep(sw, model="compliance")
        finally:
            contact.contact_model = old
            comp.contact_model = old
        return res

    base = run_with(65, 49)
    for nz, nr in ((5, 4), (9, 7), (17, 13), (33, 25)):
        c, _, _ = timed(lambda a=nz, b=nr: ContactModel(spec, n_z=a, n_r=b), 1)
        res = run_with(nz, nr)
        e1 = abs(res.tangential_force_N.max() / base.tangential_force_N.max() - 1)
        e2 = abs(res.interior_pressure_MPa.max() / base.interior_pressure_MPa.max() - 1)
        print(f"| {nz} x {nr} | {c:.3f} | {e1:.1e} | {e2:.1e} |")
    print("\nSweep tolerance (its accuracy knob) vs loads and capacity (compliance, 1°, a pitch "
          "of 13 rotations), against 1e-9 mm:\n")
    print("| tolerance_mm | sweep s | max tooth load rel. err | capacity rel. err |")
    print("|---|---|---|---|")
    psi = np.linspace(0, 7.2, 13, endpoint=False)
    ref_sw = sweep(spec, 1.0, psi, tolerance_mm=1e-9)
    ref_P = load_from_sweep(ref_sw).tangential_force_N.max()
    ref_C = capacity_from_sweep(ref_sw).capacity_Nm
    for tol in (1e-3, 1e-4, 1e-5, 1e-7):
        c, _, s = timed(lambda t=tol: sweep(spec, 1.0, psi, tolerance_mm=t), 1)
        e1 = abs(load_from_sweep(s).tangential_force_N.max() / ref_P - 1)
        e2 = abs(capacity_from_sweep(s).capacity_Nm / ref_C - 1)
        print(f"| {tol:g} | {c:.3f} | {e1:.1e} | {e2:.1e} |")
    print("\nRotations per tooth pitch searched by `capacity` (compliance, 1°), against 97:\n")
    print("| rotations | time s | capacity rel. err |\n|---|---|---|")
    ref = capacity(spec, 1.0, angles_deg=np.linspace(0, 7.2, 97, endpoint=False)).capacity_Nm
    for n in (3, 5, 9, 25, 49):
        a = np.linspace(0, 7.2, n, endpoint=False)
        c, _, out = timed(lambda a=a: capacity(spec, 1.0, angles_deg=a), 1)
        print(f"| {n} | {c:.2f} | {abs(out.capacity_Nm / ref - 1):.1e} |")
    print()


def discrete_q(N, ratio, n_rot=64):
    psi = np.linspace(0, 2 * np.pi / N, n_rot, endpoint=False)
    theta = psi[None, :] + 2 * np.pi * np.arange(N)[:, None] / N
    g = np.sin(theta) ** 2
    T = np.min(np.sum(np.maximum(np.min(g, axis=0) + ratio - g, 0), axis=0))
    return T / (N * ratio)


def q_graph():
    print("## Renzo's q (eq. 8) vs the linear model with N discrete teeth on z = z0 sin²θ\n")
    ratios = (0.0625, 0.25, 0.5, 1.0, 2.0)
    print("| N | " + " | ".join(f"zc/z0 = {r:g}" for r in ratios) + " |")
    print("|---|" + "---|" * len(ratios))
    print("| eq. 8 | " + " | ".join(f"{renzo_q(r):.4f}" for r in ratios) + " |")
    for N in (12, 24, 50, 100, 400):
        print(f"| {N} | " + " | ".join(f"{discrete_q(N, r):.4f}" for r in ratios) + " |")
    print()


def renzo_examples():
    spec = load_spec("renzo-1967")
    ld = spec.load
    N, K, P_i = spec.tooth.teeth, ld.accuracy_factor, ld.allowable_tooth_load_N / LBF
    zc = ld.allowable_tooth_load_N / ld.mesh_stiffness_N_per_mm / IN
    rc = spec.derived["crowning_radius_midplane_mm"] / IN
    print("## Renzo's Examples 1-3 (total tangential load K q N P_i, lb)\n")
    print("| i | Renzo | eq. 8, Renzo's z0 | eq. 4 z0 from the spec, 50 teeth | exact geometry, "
          "linear | exact geometry, compliance | the same, FE springs | sweep z0 (pitch line, "
          "normal) in | sweep peak-to-peak over the whole flank in |")
    print("|---|---|---|---|---|---|---|---|---|")
    fe_spec = load_spec("renzo-1967", **{"load.stiffness": "fe"})
    for i, z0r, lb in ((1.0, 0.001, 8720), (0.5, 0.00025, 20000), (2.0, 0.004, 4280)):
        z0 = 0.5 * rc * math.tan(math.radians(i)) ** 2 / math.tan(spec.tooth.pressure_angle)
        a = K * renzo_q(zc / z0r) * N * P_i
        b = K * discrete_q(N, zc / z0) * N * P_i
        R = spec.tooth.pitch_radius
        lin = capacity(spec, i, model="linear").criteria_Nm["tooth_load"] * 1e3 / R / LBF
        com = capacity(spec, i, model="compliance").criteria_Nm["tooth_load"] * 1e3 / R / LBF
        fe = capacity(fe_spec, i, model="compliance").criteria_Nm["tooth_load"] * 1e3 / R / LBF
        sw = sweep(spec, i, np.arange(0, 360.0, 2.0))
        summ = sw.summary()
        z0_sweep = summ["pitch_line_peak_to_peak_normal_mm"]["ccw"] / IN
        z0_flank = summ["flank_peak_to_peak_normal_mm"]["ccw"] / IN
        print(f"| {i}° | {lb} | {a:.0f} | {b:.0f} | {lin:.0f} | {com:.0f} | {fe:.0f} | "
              f"{z0_sweep:.5f} "
              f"(eq. 4: {z0:.5f}) | {z0_flank:.5f} |")
    print()


def crowns(stiffness: str):
    names = ("renzo-1967", "renzo-1967-vari-crown", "renzo-1967-end-round")
    angles = (0.5, 1.0, 2.0, 3.0)
    print(f"## Capacity vs misalignment (compliance model, {stiffness} springs, K applied, "
          "N·m): governing / tooth load / face-end torque\n")
    print("| spec | " + " | ".join(f"{a}°" for a in angles) + " |")
    print("|---|" + "---|" * len(angles))
    caps = {}
    for n in names:
        spec = load_spec(n, **{"load.stiffness": stiffness})
        cells = []
        for a in angles:
            c = capacity(spec, a, model="compliance")
            caps[(n, a)] = c
            fe = c.face_end_torque_Nm
            cells.append(f"{c.capacity_Nm:.0f} ({c.governing[:4]}) / "
                         f"{c.criteria_Nm['tooth_load']:.0f} / {fe:.0f}")
        print(f"| {n} | " + " | ".join(cells) + " |")
    for a in angles:
        r1 = caps[(names[1], a)].capacity_Nm / caps[(names[0], a)].capacity_Nm
        r2 = (caps[(names[1], a)].criteria_Nm["tooth_load"]
              / caps[(names[0], a)].criteria_Nm["tooth_load"])
        print(f"\nVari-Crown / uniform at {a}°: governing {r1:.2f}, tooth load {r2:.2f}", end="")
    print("\n")


def iso():
    print("## Mesh stiffness per face width vs ISO 6336-1 (pair at the pitch point, bending + "
          "foundation, no contact flattening)\n")
    print("| template | c' N/(mm·µm) | ISO c'_th (z2 -> inf) | ratio to c'_th | ratio to 14 |")
    print("|---|---|---|---|---|")
    for n in template_names():
        spec = load_spec(n)
        c = CantileverCompliance(spec)
        R = spec.tooth.pitch_radius
        unit = np.interp(R, c.r_table, c.hub_unit) + np.interp(R, c.r_table, c.sleeve_unit)
        cp = 1e-3 / unit
        cth = 1 / (0.04723 + 0.15551 / spec.tooth.teeth)
        print(f"| {n} | {cp:.2f} | {cth:.2f} | {cp / cth:.2f} | {cp / 14:.2f} |")
    print()


def regimes():
    spec = load_spec("renzo-1967")
    sw = sweep(spec, 1.0, np.arange(0.0, 7.2, 0.9))
    print("## Contact regime per loaded tooth (renzo-1967, 1°, compliance)\n")
    print("| torque N·m | hertz | line | edge contact | q | max p0 MPa |")
    print("|---|---|---|---|---|---|")
    for T in (1.0, 30.0, 300.0, 2260.0, 20000.0, 200000.0):
        r = load_from_sweep(sw, torque_Nm=T)
        print(f"| {T:g} | {int(np.sum(r.contact_regime == 1))} | "
              f"{int(np.sum(r.contact_regime == 2))} | {int(np.sum(r.edge_contact))} | "
              f"{r.q():.3f} | {r.interior_pressure_MPa.max():.0f} |")
    print()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    speed(args.quick)
    q_graph()
    renzo_examples()
    iso()
    regimes()
    for stiffness in ("cantilever", "fe"):
        crowns(stiffness)
    knobs(args.quick)


if __name__ == "__main__":
    main()
