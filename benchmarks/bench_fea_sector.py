"""The misaligned contact reference: a CalculiX tooth sector against the load models.

Run: ``python benchmarks/bench_fea_sector.py [--runs FILE] [--stored] [--sectors K ...]
[--poses I ...]``; ``--against OLD_CHECKOUT [--poses I ...] [--rounds R]`` instead times
the five-tooth sector pose before and after (:func:`against`).
For each pose (spec, misalignment, turning angle, torque, element size, and the model and
tooth springs that pick the wind-up), :func:`gearcoupling.sector_check` solves the model
(wind-up + bodies, the most loaded tooth); the FE sector of ``K`` teeth on that tooth is
turned by that wind-up. Printed
per pose and sector: nodes, solve time, memory and the FE tooth loads; then the sector's
growth (the compared tooth's load from ``K`` to the next ``K``: the cut conditions' effect)
and every model and spring at the same wind-up (:func:`loads_at_windup`): the torque it
needs for it and its loads on the compared teeth against the FE's. ``--runs`` keeps the FE
runs in a JSON file and reuses those already there; ``--stored`` solves nothing new.
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
from bench_fea_contact import golden_file, reference_spec

import gearcoupling as gc
from gearcoupling.loading.sector_check import loads_at_windup

ROOT = Path(__file__).resolve().parent.parent
# (spec, misalignment °, turning angle ° (half a pitch; three quarters on industrial-m2), torque
# N m, element size mm (at 0° 1.7 % stiffer than converged at 0.85 mm on renzo-1967, 9 % at
# 1 mm on industrial-m2), the model and springs that pick the wind-up)
POSES = [("renzo-1967", 1.0, 3.6, 2259.7, 0.85, "surface", "fe-fit"),
         ("renzo-1967", 1.0, 3.6, 1129.85, 0.85, "surface", "fe-fit"),
         ("renzo-1967", 2.0, 3.6, 2259.7, 0.85, "surface", "fe-fit"),
         ("renzo-1967", 2.0, 3.6, 1129.85, 0.85, "surface", "fe-fit"),
         ("industrial-m2", 1.0, 7.1, 400.0, 1.0, "surface", "fe-fit"),
         ("industrial-m2", 1.0, 7.1, 200.0, 1.0, "surface", "fe-fit"),
         ("industrial-m2", 2.0, 7.1, 400.0, 1.0, "surface", "fe-fit"),
         ("industrial-m2", 2.0, 7.1, 200.0, 1.0, "surface", "fe-fit"),
         # a random spec of the aligned references (bench_fea_contact.py) where the default
         # and the FE table's springs differ most at a misalignment among the small ones
         ("springs-24-circular", 2.0, 5.8, 114.0, 0.6, "surface", "fe-fit")]
SPRINGS = ("fe-fit", "fe", "cantilever")
MODELS = ("surface", "compliance", "linear")


def pose_spec(name: str) -> gc.CouplingSpec:
    """A template, or a random spec of the aligned references (``bench_fea_contact.py``)."""
    return reference_spec(name, golden_file()["specs"])


def key(pose, sector: int) -> str:
    return "|".join(f"{v:g}" if isinstance(v, float) else v for v in pose) + f"|{sector}"


def with_springs(spec: gc.CouplingSpec, springs: str) -> gc.CouplingSpec:
    return replace(spec, load=replace(spec.load, stiffness=springs))


def fe_runs(poses, sectors, store: Path, solve: bool = True) -> dict:
    """``{key: SectorCheck dict}``, from ``store`` where there, else solved (and kept)."""
    runs = json.loads(store.read_text()) if store.exists() else {}
    for pose in poses if solve else ():
        name, mis, rot, T, size, model, springs = pose
        for k in sectors:
            if key(pose, k) in runs:
                continue
            spec = with_springs(pose_spec(name), springs)
            work = store.parent / f"fe_sector-{key(pose, k)}".replace("|", "_")
            chk = gc.sector_check(spec, mis, rotation_deg=rot, torque_Nm=T, model=model,
                                  sector=k, size_mm=size, workdir=work)
            runs[key(pose, k)] = chk.to_dict()
            store.parent.mkdir(parents=True, exist_ok=True)
            store.write_text(json.dumps(runs, indent=1))
    return runs


def fe_table(pose, runs: dict, sectors) -> None:
    print("\n| sector | nodes | solve s | memory MB | teeth | FE tangential load N |")
    print("|---|---|---|---|---|---|")
    for k in sectors:
        if (run := runs.get(key(pose, k))) is None:
            continue
        fe = run["fe"]
        print(f"| {k} | {fe['nodes']} | {fe['solve_seconds']:.0f} | {fe['max_rss_MB']:.0f} | "
              f"{fe['teeth'][0]}-{fe['teeth'][-1]} | "
              f"{' · '.join(f'{w:.0f}' for w in fe['tangential_force_N'])} |")


def growth(pose, runs: dict, sectors) -> None:
    """The most loaded tooth's FE load as the sector grows."""
    got = [(k, runs[key(pose, k)]) for k in sectors if key(pose, k) in runs]
    for (k0, a), (k1, b) in itertools.pairwise(got):
        t = a["fe"]["teeth"][k0 // 2]
        w0 = a["fe"]["tangential_force_N"][k0 // 2]
        w1 = b["fe"]["tangential_force_N"][b["fe"]["teeth"].index(t)]
        print(f"\nsector {k0} -> {k1}: tooth {t} {w0:.0f} -> {w1:.0f} N "
              f"({100 * (w1 / w0 - 1):+.1f} %)")


def models_at_windup(pose, run: dict) -> None:
    """Every model and spring at the FE run's wind-up, on its compared teeth."""
    name, mis, rot = pose[:3]
    fe = run["fe"]
    teeth = [fe["teeth"][k] for k in run["compared"]]
    W_fe = np.array([fe["tangential_force_N"][k] for k in run["compared"]])
    print(f"\nAt the wind-up {fe['windup_rad'] * 1e6:.1f} µrad (teeth {teeth}; FE "
          f"{' · '.join(f'{w:.0f}' for w in W_fe)} N; the sector's first touch "
          f"{min(fe['gap_angle_rad']) * 1e6:.1f} µrad):\n")
    print("| model | springs | torque for this wind-up N·m | compared loads N | FE / model |")
    print("|---|---|---|---|---|")
    spec = pose_spec(name)
    for model in MODELS:
        for springs in SPRINGS if model != "linear" else ("template C",):
            s = with_springs(spec, "cantilever" if model == "linear" else springs)
            Tm, W = loads_at_windup(s, mis, rot, fe["windup_rad"], model=model)
            Wm = W[teeth]
            print(f"| {model} | {springs} | {Tm:.0f} | {' · '.join(f'{w:.0f}' for w in Wm)} | "
                  f"{' · '.join(f'{r:.3f}' for r in W_fe / Wm)} |")


SOLVE = """
import json, resource, sys, tempfile
from pathlib import Path
sys.path.insert(0, {bench!r})
import bench_fea_sector as b
name, mis, rot, T, size, model, springs = b.POSES[{pose}]
spec = b.with_springs(b.pose_spec(name), springs)
with tempfile.TemporaryDirectory() as work:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    chk = b.gc.sector_check(spec, mis, rotation_deg=rot, torque_Nm=T, model=model, sector=5,
                            size_mm=size, workdir=work)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cvg = (Path(work) / "fe_sector.cvg").read_text().splitlines()
rows = [ln.split() for ln in cvg if ln.split()[:1] == ["1"]]
k = chk.compared[0]
print(json.dumps({{"cpu": after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime,
                  "wall": chk.fe.solve_seconds, "nodes": chk.fe.nodes,
                  "increments": len({{r[1] for r in rows}}), "iterations": len(rows),
                  "contact_elements": [int(r[4]) for r in rows],
                  "tooth": chk.fe.teeth[k], "load_N": chk.fe.tangential_force_N[k]}}))
"""


def solve_in(checkout: Path, pose: int) -> dict:
    """One five-tooth pose solved by ``checkout``'s library in a new process: the CPU time
    of its child processes (the ccx run; gmsh meshes in the process itself), ccx's wall
    time, increments and equilibrium iterations (its ``.cvg``) and the compared tooth's
    load."""
    env = {**os.environ, "PYTHONPATH": str(checkout / "src"), "OPENBLAS_NUM_THREADS": "1"}
    code = SOLVE.format(bench=str(Path(__file__).resolve().parent), pose=pose)
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=False)
    if out.returncode:
        raise SystemExit(f"{checkout}, pose {pose}: {out.stderr.strip()[-2000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def against(old: Path, poses: list[int], rounds: int) -> None:
    """Each pose's five-tooth sector solved by ``old`` and by this checkout, alternating,
    ``rounds`` times: the solver's CPU and wall time, its iterations, and the compared
    tooth's load, new / old."""
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load average "
          f"{os.getloadavg()[0]:.1f}, {os.cpu_count()} cores; after = {ROOT}, before = {old}")
    print("\n| pose | nodes | solver CPU s before / after | new / old | ccx wall s before / "
          "after | increments · iterations before / after | compared tooth | load N before "
          "/ after | change |")
    print("|---|---|---|---|---|---|---|---|---|")
    for i in poses:
        got: dict[str, list[dict]] = {"old": [], "new": []}
        for _ in range(rounds):
            got["old"].append(solve_in(old, i))
            got["new"].append(solve_in(ROOT, i))
        o = min(got["old"], key=lambda r: r["cpu"])
        n = min(got["new"], key=lambda r: r["cpu"])
        name, mis, rot = POSES[i][:3]
        print(f"| {name} {mis:g}°, {rot:g}° | {n['nodes']} | {o['cpu']:.0f} / {n['cpu']:.0f} | "
              f"{n['cpu'] / o['cpu']:.2f}x | {o['wall']:.0f} / {n['wall']:.0f} | "
              f"{o['increments']} · {o['iterations']} / {n['increments']} · "
              f"{n['iterations']} | {n['tooth']} | {o['load_N']:.1f} / {n['load_N']:.1f} | "
              f"{100 * (n['load_N'] / o['load_N'] - 1):+.2f} % |", flush=True)
        for label in ("old", "new"):
            print(f"<!-- {name} {mis:g}° {label}: contact elements per iteration "
                  f"{[r['contact_elements'] for r in got[label]]} -->", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=Path, default=ROOT / "outputs" / "bench_fea_sector.json")
    ap.add_argument("--sectors", nargs="*", type=int, default=[5, 7])
    ap.add_argument("--stored", action="store_true", help="only the runs in --runs")
    ap.add_argument("--poses", nargs="*", type=int, default=None,
                    help="indices into POSES (default: all)")
    ap.add_argument("--against", type=Path, metavar="OLD_CHECKOUT",
                    help="time the five-tooth pose: OLD_CHECKOUT's src/ against this one's")
    ap.add_argument("--rounds", type=int, default=1, help="with --against: old, new this "
                    "many times (the least CPU of each is printed)")
    a = ap.parse_args()
    if a.against is not None:
        against(a.against.resolve(), a.poses if a.poses is not None else [0, 6], a.rounds)
        return
    poses = POSES if a.poses is None else [POSES[i] for i in a.poses]
    runs = fe_runs(poses, a.sectors, a.runs, solve=not a.stored)
    print("## The misaligned sector reference (cyclic cuts, turned by the wind-up)")
    for pose in poses:
        have = [k for k in a.sectors if key(pose, k) in runs]
        if not have:
            continue
        print(f"\n### {pose[0]}, {pose[1]:g}°, turning angle {pose[2]:g}°, {pose[3]:g} N·m, "
              f"element size {pose[4]:g} mm, wind-up of {pose[5]} ({pose[6]})")
        fe_table(pose, runs, a.sectors)
        growth(pose, runs, a.sectors)
        models_at_windup(pose, runs[key(pose, max(have))])


if __name__ == "__main__":
    main()
