"""The default model's capacity over the whole supported range: the five templates and
seeded random specs at 0, 0.5, ..., 6°, each point a capacity and loads at three torques.

Run: ``python benchmarks/bench_capacity_range.py [--count 100] [--seed 38] [--jobs N]
[--angles 0 0.5 ... 6]``; ``--summarise DETAILS_JSON`` prints an earlier run's summary.

Each point is ``gc.capacity(spec, angle)`` and the load (``gc.load_from_sweep``) at the
spec's torque (else the capacity there), a tenth and ten times it, on one pose
(``tests/capacity_range.py``): *ok* (every number finite, the governing criterion named,
the loads carrying their torque), *finding* (a returned value fails those checks),
*refused* (a ``GearCouplingError``: a typed refusal, its text kept) or *crash* (any other
exception). Printed: the counts, the governing criteria, the capacities of 0 (over a
limit at no torque), the largest change of the capacity between neighbouring angles under
one governing criterion (with and without the patch starting to reach a face end at the
capacity) and the jumps over ``capacity_range.JUMP`` in one regime, the CPU per point and
the elapsed time; the details go to ``outputs/bench_capacity_range.json`` (rewritten after
each spec). ``--jobs N`` runs N specs at a time in forked worker processes (the CPU is
each worker's own; they die with this process).
"""

from __future__ import annotations

import argparse
import collections
import json
import multiprocessing
import os
import sys
import time
import traceback
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import gearcoupling as gc
from capacity_range import (
    ANGLES,
    JUMP,
    SEED,
    changes,
    curve_point,
    jumps,
    point,
    problems,
    range_specs,
)
from gearcoupling.forked import worker_signals
from gearcoupling.io import write_json


def run_spec(work: tuple) -> dict:
    """One spec's points: a row per angle."""
    spec, angles = work
    rows = []
    for angle in angles:
        row: dict = {"angle": angle}
        t0 = time.process_time()
        try:
            c, loads = point(spec, angle)
            found = problems(c, loads)
            row.update(outcome="finding" if found else "ok", problems=found,
                       capacity_Nm=c.capacity_Nm, governing=c.governing, solves=c.solves,
                       face_end_torque_Nm=c.face_end_torque_Nm, edge=curve_point(c)[3])
        except gc.GearCouplingError as err:
            row.update(outcome="refused", error=f"{type(err).__name__}: {err}"[:400])
        except Exception as err:  # a crash is what this benchmark counts
            frame = traceback.extract_tb(err.__traceback__)[-1]
            row.update(outcome="crash", error=f"{type(err).__name__}: {err} ({frame.name}, "
                       f"{Path(frame.filename).name}:{frame.lineno})"[:400])
        row["cpu_s"] = time.process_time() - t0
        rows.append(row)
    return {"spec": spec.name, "teeth": spec.tooth.teeth, "rows": rows}


def results(work: list[tuple], jobs: int):
    """:func:`run_spec` of each item of ``work`` in order, ``jobs`` at a time."""
    if jobs <= 1:
        yield from map(run_spec, work)
        return
    with multiprocessing.get_context("fork").Pool(jobs, initializer=worker_signals) as pool:
        yield from pool.imap(run_spec, work)


def curve(res: dict) -> list[tuple]:
    """A spec's points ``(angle, capacity_Nm, governing, edge)`` where its capacity was
    found (``capacity_range.curve_point``)."""
    return [(r["angle"], r["capacity_Nm"], r["governing"], r["edge"]) for r in res["rows"]
            if "governing" in r]


def summarise(done: list[dict], elapsed: float, jobs: int) -> None:
    """Print the counts, criteria, jumps and times of the specs' rows."""
    rows = [r for res in done for r in res["rows"]]
    outcomes = collections.Counter(r["outcome"] for r in rows)
    governing = collections.Counter(r["governing"] for r in rows if "governing" in r)
    cpu = sorted(r["cpu_s"] for r in rows)
    print(f"\n{len(done)} specs x {len(done[0]['rows'])} angles = {len(rows)} points; "
          f"{elapsed:.0f} s elapsed, {jobs} job(s)\n")
    print("| outcome | points |\n|---|---|")
    for k in ("ok", "finding", "refused", "crash"):
        print(f"| {k} | {outcomes[k]} |")
    print("\n| governing | points |\n|---|---|")
    for k, n in governing.most_common():
        print(f"| {k} | {n} |")
    zero = [(res["spec"], r["angle"]) for res in done for r in res["rows"]
            if r.get("capacity_Nm") == 0.0]
    print(f"\ncapacity 0 (a limit reached at no torque): {len(zero)} points {zero[:10]}")
    print(f"face-end torque 0 (edge contact at any torque): "
          f"{sum(r.get('face_end_torque_Nm') == 0.0 for r in rows)} points")
    print(f"CPU per point (capacity and three loads): median {cpu[len(cpu) // 2]:.2f} s, "
          f"largest {cpu[-1]:.1f} s, total {sum(cpu):.0f} s")
    print("\nneighbouring angles under one governing criterion: the largest change of the "
          f"capacity, and how many of the pairs change by more than x{JUMP:g}")
    print("| angles | face end reached at the capacity | pairs | largest | over |\n"
          "|---|---|---|---|---|")
    for name, first in (("0° -> 0.5°", True), ("from 0.5° on", False)):
        for regime, moved in (("at both or neither", False), ("at one of them", True)):
            found = [(f, res["spec"], a, b) for res in done
                     for a, b, f, m in changes(curve(res)) if (a == 0.0) == first and m == moved]
            if found:
                f, spec, a, b = max(found)
                print(f"| {name} | {regime} | {len(found)} | x{f:.3g} ({spec}, {a:g}° -> "
                      f"{b:g}°) | {sum(x[0] > JUMP for x in found)} |")
    print("jumps (from 0.5° on, in one regime):")
    for res in done:
        for j in jumps([p for p in curve(res) if p[0] > 0.0]):
            print(f"  {res['spec']}: {j}")
    for res in done:
        for r in res["rows"]:
            if r["outcome"] != "ok":
                print(f"  {res['spec']} {r['angle']:g}°: {r['outcome']}: "
                      f"{r.get('error') or '; '.join(r['problems'])}")


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=100, help="random specs (default 100)")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--angles", nargs="*", type=float, default=list(ANGLES))
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--out", default="outputs/bench_capacity_range.json")
    ap.add_argument("--summarise", type=Path, metavar="DETAILS_JSON",
                    help="print the summary of an earlier run's details and stop")
    a = ap.parse_args(argv)
    if a.summarise:
        data = json.loads(a.summarise.read_text())
        summarise(data["specs"], data["seconds"], data["args"]["jobs"])
        return
    specs = [gc.load_spec(n) for n in gc.template_names()] + range_specs(a.count, a.seed)
    print(f"the {len(gc.template_names())} templates and {a.count} random specs (seed "
          f"{a.seed}) at {', '.join(f'{x:g}' for x in a.angles)}°")
    t0 = time.perf_counter()
    done = []
    for k, res in enumerate(results([(s, a.angles) for s in specs], a.jobs)):
        done.append(res)
        write_json(Path(a.out), {"args": vars(a), "seconds": time.perf_counter() - t0,
                                 "specs": done})  # so far: a stopped run keeps its points
        bad = [r for r in res["rows"] if r["outcome"] != "ok"]
        print(f"  {k + 1}/{len(specs)} {res['spec']} ({res['teeth']} teeth): "
              f"{len(res['rows']) - len(bad)}/{len(res['rows'])} ok, "
              f"{sum(r['cpu_s'] for r in res['rows']):.0f} s CPU"
              + "".join(f"; {r['angle']:g}° {r['outcome']}" for r in bad), file=sys.stderr,
              flush=True)
    summarise(done, time.perf_counter() - t0, a.jobs)
    print(f"\ndetails: {a.out}")


if __name__ == "__main__":
    main()
