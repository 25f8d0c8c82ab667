"""The bodies tooth by tooth: the whole hub and sleeve rings in CalculiX under the load
model's own tooth loads, against the load models' uniform body torsion and the influence
model (docs/load.md, "The bodies").

Run: ``python benchmarks/bench_bodies.py [--specs NAME ...] [--size MM] [--runs FILE]
[--stored] [--table-only] [--sector-runs FILE]``. For each spec (the poses of
``bench_fea_sector.py``: its turning angle, the template's torque, 0°, 1° and 2°) the FE
(kept in ``--runs``, reused from there; ``--stored`` solves nothing new; ``--table-only``
only the influence table, the first item):

- the body influence table (:func:`gearcoupling.fea.compute_body_influence`): the ring's
  kernel at three ``|z|``, the tooth table's 3-tooth sector on the same mesh, the body
  shell's twist under equal loads;
- per part, the whole ring under the ``surface`` model's tooth loads (``fe`` springs), each
  tooth loaded at its own contact point, and the 3-tooth sector under each loaded tooth's
  own load alone: the body deflection the FE shows is ring - sector, tooth by tooth;
- per part, a sector of 5 teeth with cyclic cuts under a unit load on its middle tooth (the
  K-periodic kernel).

Printed: the set-up; the 0° check (the shell's twist against the closed-form annulus,
exact for the z-mean of a full-length body, and the uniform body per tooth against the
models' closed form); the kernel and its harmonics; per pose the body deflection of the
most loaded teeth (FE, the models' uniform torsion, the influence model, the torsion per
tooth); the most loaded tooth's load with each (a fixed point of the ``surface`` model
with the body deflection as gap offsets); the 5-tooth periodic kernel against the FE;
and the stored misaligned sector references (``--sector-runs``, ``bench_fea_sector.py``'s
runs) against the model at the sector's wind-up, with the bodies counted as the models
do (the uniform closed form) and as the sector has them (its cuts are cyclic: its loads
repeat every K teeth round the whole ring, so its bodies carry N / K times its own teeth's
torque; the K-periodic kernel).
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
from bench_fea_sector import pose_spec
from scipy.optimize import brentq

import gearcoupling as gc
from gearcoupling.fea import BodyInfluenceTable, compute_body_influence, ring_deflections
from gearcoupling.fea import sector_self as fe_sector_self
from gearcoupling.fea.bodies import default_patch, pitch_mesh
from gearcoupling.loading import load_from_sweep
from gearcoupling.loading.body import (
    body_deflection_mm,
    body_influence_matrix,
    kernel_harmonics,
    periodic_kernel,
)
from gearcoupling.loading.sector_check import loads_at_windup

ROOT = Path(__file__).resolve().parent.parent
SPECS = {"renzo-1967": 3.6, "industrial-m2": 7.1,  # turning angle (°) of bench_fea_sector
         "springs-24-circular": 5.8}
ANGLES = (0.0, 1.0, 2.0)
PARTS = ("hub", "sleeve")
PERIOD = 5


def fe_spec(name: str) -> gc.CouplingSpec:
    spec = pose_spec(name)
    return replace(spec, load=replace(spec.load, stiffness="fe"))


def poses(spec: gc.CouplingSpec, rotation: float) -> dict:
    """The ``surface`` model's loads and load points at each misalignment."""
    out = {}
    for mis in ANGLES:
        res = gc.load(spec, mis, [rotation], model="surface")
        r = res.contact_r_mm[:, 0]
        out[f"{mis:g}"] = {"W": res.tangential_force_N[:, 0].tolist(),
                           "z": res.contact_z_mm[:, 0].tolist(),
                           "r": np.where(r > 0, r, spec.tooth.pitch_radius).tolist(),
                           "windup_rad": float(res.windup_rad[0])}
    return out


def solve(name: str, size: float, work: Path, run: dict, table_only: bool) -> dict:
    """Every FE run of one spec not yet in ``run`` (module docstring)."""
    spec = fe_spec(name)
    R = spec.tooth.pitch_radius
    if "table" not in run:
        t0 = time.perf_counter()
        table = compute_body_influence(spec, size_mm=size, workdir=work / "table")
        run["table"] = table.to_dict()
        run["table_seconds"] = time.perf_counter() - t0
    if table_only or "poses" in run:
        return run
    run["poses"] = poses(spec, SPECS[name])
    patch = default_patch(spec, size)
    P = run["poses"]
    for part in PARTS:
        pitch = pitch_mesh(spec, part, size)
        W = np.array([P[k]["W"] for k in P])
        z = np.array([P[k]["z"] for k in P])
        r = np.array([P[k]["r"] for k in P])
        sol = ring_deflections(pitch, spec, W, z, r, patch_mm=patch, workdir=work / part,
                               job="poses")
        loaded = sorted({(round(a, 9), round(b, 9)) for a, b, w in
                         zip(z.ravel(), r.ravel(), W.ravel(), strict=True) if w > 0})
        own, secs = fe_sector_self(pitch, spec, [p[0] for p in loaded], [p[1] for p in loaded],
                                   patch_mm=patch, workdir=work / part, job="own")
        unit = np.zeros((1, PERIOD))
        unit[0, PERIOD // 2] = 1.0
        cyc = ring_deflections(pitch, spec, unit, 0.0, R, patch_mm=patch, period=PERIOD,
                               workdir=work / part, job="cyclic")
        run[part] = {"ring_mm": sol.deflection_mm.tolist(), "ring_seconds": sol.solve_seconds,
                     "max_rss_MB": sol.max_rss_MB, "points": loaded, "own_mm_per_N": own.tolist(),
                     "own_seconds": secs, "cyclic_mm_per_N": cyc.deflection_mm[0].tolist()}
    return run


def fe_body(run: dict, part: str, key: str) -> np.ndarray:
    """FE body deflection of every tooth at one pose (mm): ring less the sector's own."""
    p = run["poses"][key]
    c = list(run["poses"]).index(key)
    own = dict(zip(map(tuple, run[part]["points"]), run[part]["own_mm_per_N"], strict=True))
    W = np.array(p["W"])
    s = np.array([own.get((round(z, 9), round(r, 9)), 0.0) if w > 0 else 0.0
                  for z, r, w in zip(p["z"], p["r"], W, strict=True)])
    return np.array(run[part]["ring_mm"][c]) - s * W


def setup_table(runs: dict) -> None:
    print("\n| spec | part | element mm | pitch nodes | harmonics | table: ring s | sector s | "
          "poses: ring s | own sector s | solver memory MB |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, run in runs.items():
        info = run["table"]["info"]
        for part in PARTS:
            t = info["parts"][part]
            p = run.get(part, {"ring_seconds": np.nan, "own_seconds": np.nan, "max_rss_MB": 0})
            print(f"| {name} | {part} | {info['size_mm']:g} | {t['pitch_nodes']} | "
                  f"{t['harmonics']} | {t['ring_seconds']:.0f} | {t['sector_seconds']:.0f} | "
                  f"{p['ring_seconds']:.0f} | {p['own_seconds']:.0f} | "
                  f"{max(t['max_rss_MB'], p['max_rss_MB']):.0f} |")


def closed_shell_twist(spec: gc.CouplingSpec, shell, part: str) -> float:
    """The closed-form annulus twist per N·mm, volume mean over the shell (exact for the
    z-mean of a full-length body)."""
    a, r1, r2, L = shell
    G = getattr(spec.material, part).shear_modulus_MPa
    r = np.linspace(r1, r2, 4001)
    theta = np.abs(1 / a**2 - 1 / r**2) / (4 * np.pi * G * L)
    return float(np.trapezoid(theta * r, r) / np.trapezoid(r, r))


def uniform_check(runs: dict) -> None:
    print("\n### 0°: the FE set-up against the closed form\n")
    print("| spec | part | shell radii mm (fixed at) | FE shell twist µrad/(kN·m) | closed form "
          "| FE / closed | FE body per tooth beyond the table nm/N (λ0) | models' closed form "
          "N R² θ/T | FE / closed |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, run in runs.items():
        spec, tab = fe_spec(name), BodyInfluenceTable.from_dict(run["table"])
        N, R = spec.tooth.teeth, spec.tooth.pitch_radius
        cf = gc.body_windup_rad(spec, 1e-3)  # rad per N·mm
        for i, part in enumerate(PARTS):
            shell = tab.info["parts"][part]["shell_mm"]
            fe = abs(tab.shell_twist_rad_per_Nmm[i]) * 1e12
            closed = closed_shell_twist(spec, shell, part) * 1e12
            b = tab.ring_mm_per_N[i, 0].copy()
            b[0] -= tab.sector_mm_per_N[i, 0]
            lam0, model = b.sum() * 1e6, N * R**2 * cf[f"{part}_rad"] * 1e6
            print(f"| {name} | {part} | {shell[1]:.2f}-{shell[2]:.2f} ({shell[0]:.2f}) | "
                  f"{fe:.3f} | {closed:.3f} | {fe / closed:.4f} | {lam0:.3f} | {model:.3f} | "
                  f"{lam0 / model:.2f} |")


def kernel_table(runs: dict) -> None:
    print("\n### The kernel (hub + sleeve, unit load at mid-face, pitch radius; nm/N)\n")
    print("| spec | part | ring b(0) | table sector | b(0) = ring - sector | b(1) | b(2) | b(3) | "
          "b(5) | λ0 | λ1 | λ2 | λ4 | λ6 | λ(N/2) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, run in runs.items():
        tab = BodyInfluenceTable.from_dict(run["table"])
        rows = [(p, tab.ring_mm_per_N[i, 0], tab.sector_mm_per_N[i, 0])
                for i, p in enumerate(PARTS)]
        rows.append(("both", tab.ring_mm_per_N[:, 0].sum(0), tab.sector_mm_per_N[:, 0].sum()))
        for part, ring, sec in rows:
            b = ring.copy()
            b[0] -= sec
            lam = kernel_harmonics(b)
            f = [ring[0], sec, b[0], b[1], b[2], b[3], b[5], lam[0], lam[1], lam[2], lam[4],
                 lam[6], lam[-1]]
            print(f"| {name} | {part} | " + " | ".join(f"{1e6 * v:.3f}" for v in f) + " |")


def fixed_point(sw, spec, T: float, body, tol: float = 1e-4):
    """The ``surface`` model with the body deflection ``body(W, z) (N,)`` (mm) as gap
    offsets, iterated (half steps) to ``tol`` of the largest load."""
    R = spec.tooth.pitch_radius
    res = load_from_sweep(sw, torque_Nm=T, model="surface")
    W = res.tangential_force_N[:, 0]
    for it in range(1, 100):
        off = body(W, res.contact_z_mm[:, 0]) / R
        res = load_from_sweep(sw, torque_Nm=T, model="surface", gap_offset_rad=off)
        new = res.tangential_force_N[:, 0]
        done = np.max(np.abs(new - W)) <= tol * new.max()
        W = 0.5 * (W + new)
        if done:
            return new, res, it
    raise RuntimeError("the body fixed point did not converge")


def pose_tables(runs: dict, top: int = 4) -> None:
    for name, run in runs.items():
        if "poses" not in run:
            continue
        spec, tab = fe_spec(name), BodyInfluenceTable.from_dict(run["table"])
        N, R, T = spec.tooth.teeth, spec.tooth.pitch_radius, spec.load.torque_Nm
        kb = gc.body_windup_rad(spec, 1e-3)["body_rad"]
        print(f"\n### {name}, turning angle {SPECS[name]:g}°, {T:g} N·m: body deflection at "
              "the pitch radius, µm\n")
        print("| misalignment | tooth | load N | z mm | FE (ring - table sector) | uniform "
              "(models today) | influence model | torsion per tooth |")
        print("|---|---|---|---|---|---|---|---|")
        summary = []
        for key, p in run["poses"].items():
            W, z = np.array(p["W"]), np.array(p["z"])
            fe = sum(fe_body(run, part, key) for part in PARTS)
            uniform = np.full(N, R * kb * T * 1e3)
            model = body_deflection_mm(spec, W, z, table=tab)
            per = N * R**2 * kb * W
            for k in np.argsort(W)[::-1][:top]:
                print(f"| {key}° | {k} | {W[k]:.0f} | {z[k]:+.2f} | {1e3 * fe[k]:.3f} | "
                      f"{1e3 * uniform[k]:.3f} | {1e3 * model[k]:.3f} | {1e3 * per[k]:.3f} |")
            on = W > 0
            summary.append((key, on.sum(), *(1e3 * np.sqrt(np.mean((x - fe)[on] ** 2))
                                              for x in (uniform, model, per)),
                            np.max(np.abs(model - fe)[on] / fe[on])))
        print("\n| misalignment | loaded teeth | rms error µm: uniform | influence model | "
              "per tooth | influence model, largest error / FE |")
        print("|---|---|---|---|---|---|")
        for key, n, u, m, t, worst in summary:
            print(f"| {key}° | {n} | {u:.3f} | {m:.3f} | {t:.3f} | {100 * worst:.1f} % |")


def load_effect(runs: dict) -> None:
    print("\n### The most loaded tooth's load (`surface`, `fe` springs, the template torque)\n")
    print("| spec | misalignment | uniform body (today) N | influence model N | change | "
          "torsion per tooth N | change | fixed-point iterations |")
    print("|---|---|---|---|---|---|---|---|")
    for name, run in runs.items():
        spec, tab = fe_spec(name), BodyInfluenceTable.from_dict(run["table"])
        N, R, T = spec.tooth.teeth, spec.tooth.pitch_radius, spec.load.torque_Nm
        kb = gc.body_windup_rad(spec, 1e-3)["body_rad"]
        for mis in ANGLES[1:]:
            sw = gc.sweep(spec, mis, [SPECS[name]])
            W0 = load_from_sweep(sw, torque_Nm=T, model="surface").tangential_force_N[:, 0]
            Wm, _, it = fixed_point(sw, spec, T, lambda W, z, s=spec, t=tab:
                                    body_deflection_mm(s, W, z, table=t))
            Wt, _, _ = fixed_point(sw, spec, T, lambda W, z, c=N * R**2 * kb: c * W)
            print(f"| {name} | {mis:g}° | {W0.max():.0f} | {Wm.max():.0f} | "
                  f"{100 * (Wm.max() / W0.max() - 1):+.1f} % | {Wt.max():.0f} | "
                  f"{100 * (Wt.max() / W0.max() - 1):+.1f} % | {it} |")


def periodic_check(runs: dict) -> None:
    print(f"\n### A sector of {PERIOD} teeth with cyclic cuts, unit load on the middle tooth "
          "(nm/N; FE cyclic sector less the table sector on the loaded tooth)\n")
    print("| spec | part | FE | periodic_kernel of the ring kernel | largest difference |")
    print("|---|---|---|---|---|")
    for name, run in runs.items():
        if "poses" not in run:
            continue
        tab = BodyInfluenceTable.from_dict(run["table"])
        for i, part in enumerate(PARTS):
            fe = np.roll(np.array(run[part]["cyclic_mm_per_N"]), -(PERIOD // 2))
            fe[0] -= tab.sector_mm_per_N[i, 0]
            b = tab.ring_mm_per_N[i, 0].copy()
            b[0] -= tab.sector_mm_per_N[i, 0]
            model = periodic_kernel(b, PERIOD)
            print(f"| {name} | {part} | {' · '.join(f'{1e6 * v:.3f}' for v in fe)} | "
                  f"{' · '.join(f'{1e6 * v:.3f}' for v in model)} | "
                  f"{1e6 * np.max(np.abs(model - fe)):.4f} |")


def sector_loads(spec: gc.CouplingSpec, mis: float, rot: float, fe: dict, tab, model: str,
                 tol: float = 1e-4) -> np.ndarray:
    """The ``model``'s loads on the sector's teeth ``fe["teeth"]`` at the sector's
    wind-up with the bodies as the sector has them: each tooth's gap grows by the
    K-periodic kernel's deflection under the sector's loads (:func:`body_influence_matrix`
    with ``period = K``; at a fixed wind-up the model's teeth are independent), iterated
    (half steps) to ``tol`` of the largest load."""
    teeth, R = fe["teeth"], spec.tooth.pitch_radius
    sw = gc.sweep(spec, mis, [rot])
    _, W0 = loads_at_windup(spec, mis, rot, fe["windup_rad"], model=model)
    z = load_from_sweep(sw, torque_Nm=spec.load.torque_Nm, model=model).contact_z_mm[teeth, 0]
    B = body_influence_matrix(spec, z, period=len(teeth), table=tab)
    W = W0[teeth]
    for _ in range(100):
        off = np.zeros(spec.tooth.teeth)
        off[teeth] = B @ W / R

        def excess(T: float, off=off) -> float:
            res = load_from_sweep(sw, torque_Nm=T, model=model, gap_offset_rad=off)
            return float(res.windup_rad[0]) - fe["windup_rad"]

        T = brentq(excess, 1e-3 * spec.load.torque_Nm, 1e2 * spec.load.torque_Nm, rtol=1e-6)
        new = load_from_sweep(sw, torque_Nm=T, model=model,
                              gap_offset_rad=off).tangential_force_N[teeth, 0]
        if np.max(np.abs(new - W)) <= tol * new.max():
            return new
        W = 0.5 * (W + new)
    raise RuntimeError("the sector's body fixed point did not converge")


def sector_reference(runs: dict, sector_runs: Path) -> None:
    """The stored sector references against the model, bodies counted two ways."""
    stored = json.loads(sector_runs.read_text()) if sector_runs.exists() else {}
    rows = [(k, r) for k, r in stored.items() if k.split("|")[0] in runs]
    if not rows:
        return
    print("\n### The misaligned sector reference and its bodies (compared tooth; FE / model "
          "at the sector's wind-up)\n")
    print("| pose | sector | model | springs | FE load N | model, uniform body (as compared "
          "so far) N | FE / model | model, the sector's K-periodic bodies N | FE / model |")
    print("|---|---|---|---|---|---|---|---|---|")
    for (k, run), model in itertools.product(sorted(rows), ("surface", "compliance")):
        name, mis, rot, T = k.split("|")[:4]
        fe, c = run["fe"], run["compared"][0]
        tab = BodyInfluenceTable.from_dict(runs[name]["table"])
        t = fe["teeth"][c]
        for springs in ("fe-fit", "fe"):
            spec = pose_spec(name)
            spec = replace(spec, load=replace(spec.load, stiffness=springs, torque_Nm=float(T)))
            _, W0 = loads_at_windup(spec, float(mis), float(rot), fe["windup_rad"],
                                    model=model)
            Wk = sector_loads(spec, float(mis), float(rot), fe, tab, model)[c]
            w = fe["tangential_force_N"][c]
            print(f"| {name} {mis}°, {T} N·m | {len(fe['teeth'])} | {model} | {springs} | "
                  f"{w:.0f} | {W0[t]:.0f} | {w / W0[t]:.3f} | {Wk:.0f} | {w / Wk:.3f} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--specs", nargs="*", default=list(SPECS), choices=list(SPECS))
    ap.add_argument("--size", type=float, default=1.0, help="element size on the teeth, mm")
    ap.add_argument("--runs", type=Path, default=ROOT / "outputs" / "bench_bodies.json")
    ap.add_argument("--stored", action="store_true", help="only the runs in --runs")
    ap.add_argument("--table-only", action="store_true",
                    help="solve only the influence table of specs without one")
    ap.add_argument("--sector-runs", type=Path,
                    default=ROOT / "outputs" / "bench_fea_sector.json",
                    help="bench_fea_sector.py's stored runs")
    a = ap.parse_args()
    runs = json.loads(a.runs.read_text()) if a.runs.exists() else {}
    for name in a.specs:
        key = f"{name}|{a.size:g}"
        if not a.stored and "poses" not in runs.get(key, {}) and not (
                a.table_only and key in runs):
            runs[key] = solve(name, a.size, a.runs.parent / f"bench_bodies-{name}",
                              runs.get(key, {}), a.table_only)
            a.runs.parent.mkdir(parents=True, exist_ok=True)
            a.runs.write_text(json.dumps(runs))
    have = {k.split("|")[0]: v for k, v in runs.items()
            if k.split("|")[0] in a.specs and k.endswith(f"|{a.size:g}")}
    if not have:
        print("no runs: run without --stored first")
        return
    print(f"## The bodies tooth by tooth (element size {a.size:g} mm)")
    setup_table(have)
    uniform_check(have)
    kernel_table(have)
    pose_tables(have)
    periodic_check(have)
    load_effect(have)
    sector_reference(have, a.sector_runs)


if __name__ == "__main__":
    main()
