"""Throughput of studies on dask.distributed and of the tolerance Monte Carlo.

Prints
1. the serial time of one study row (``evaluate``) of a small study;
2. the same study on a LocalCluster with 1 and 2 worker processes (rows/s, wall time,
   cluster start-up separately), the apparent per-task overhead
   ``(wall * workers - rows * t_row) / tasks`` (it includes each worker's cold first row:
   imports, flank table) and the round trip of a no-op task;
3. the time of the per-tooth gap maps of the tolerance Monte Carlo for renzo-1967 at 1°
   (fast, crown-interpolated, exact per-tooth kernel) and the fast and interpolated paths'
   error against the exact map for one sample of grade-4 errors;
4. the projection for a 1 000 000-sample study on 64 workers.

Run: ``python benchmarks/bench_study.py [--rows 24]``. The machine is shared and noisy:
medians, and ratios are the robust figures.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

from gearcoupling.spec import load_spec
from gearcoupling.study import evaluate, load_study, run_study, samples
from gearcoupling.study.runner import connect
from gearcoupling.study.tolerance import (
    CrownMaps,
    Tolerances,
    draw_errors,
    exact_map,
    gap_offsets_rad,
    rotations,
)

STUDY = """\
[study]
base = "renzo-1967"
chunk = {chunk}
outputs = ["min_backlash_mm", "contact_z_max_mm"]
[accuracy]
steps = 4
[[vary]]
key = "misalignment_deg"
range = [0.1, 2.0]
steps = {rows}
"""


def study_file(folder: Path, rows: int, chunk: int) -> Path:
    path = folder / f"bench-{rows}-{chunk}.toml"
    path.write_text(STUDY.format(rows=rows, chunk=chunk))
    return path


def row_time(study, repeats: int = 3) -> float:
    items = samples(study)
    evaluate(study.payload(), items[0])  # flank table cached, as on a warm worker
    times = []
    for inputs in items[:repeats]:
        t = time.perf_counter()
        evaluate(study.payload(), inputs)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def _noop(x):
    return x


def on_cluster(study, workers: int, out: Path) -> tuple[float, float, float]:
    """Cluster start-up, the study's wall time, and the round trip of a no-op task
    (``as_completed`` over 200 tasks: the dask cost of one task, without the work)."""
    from distributed import as_completed

    t = time.perf_counter()
    client = connect(None, workers)
    client.wait_for_workers(workers, timeout=120)
    startup = time.perf_counter() - t
    try:
        client.run(lambda: __import__("gearcoupling.study.evaluate"))  # warm the imports
        t = time.perf_counter()
        run_study(study, out, fresh=True, client=client)
        wall = time.perf_counter() - t
        t = time.perf_counter()
        for fut in as_completed(client.map(_noop, range(200), pure=False)):
            fut.result()
        noop = (time.perf_counter() - t) / 200
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()
    return startup, wall, noop


def tolerance_maps() -> None:
    spec = load_spec("renzo-1967")
    i = math.radians(1.0)
    psi = rotations(spec, 4)
    tol = Tolerances.from_limits(pitch_mm=0.0035, thickness_mm=0.006, crown_mm=0.005,
                                 hub_runout_mm=0.009, sleeve_runout_mm=0.009)
    t = time.perf_counter()
    maps = CrownMaps(spec, i, psi, tol.crown_sd_mm, 1e-7)
    setup = time.perf_counter() - t
    err = draw_errors(tol, spec.tooth.teeth, np.random.default_rng(1))
    fast = maps.nominal + gap_offsets_rad(spec, err)[:, :, None]
    reps = []
    for _ in range(20):
        t = time.perf_counter()
        interp = maps.gap(err) + gap_offsets_rad(spec, err)[:, :, None]
        reps.append(time.perf_counter() - t)
    t = time.perf_counter()
    exact = exact_map(spec, i, psi, err, 1e-7)
    t_exact = time.perf_counter() - t
    scale = np.max(np.abs(exact - maps.nominal))
    print(f"\ntolerance maps, renzo-1967 at 1°, {spec.tooth.teeth} teeth x {psi.size} rotations "
          "x 2 flanks, grade-4 errors:")
    print(f"  crown-node maps (once per worker): {setup:.2f} s")
    print(f"  interpolated per-tooth map:        {1e3 * statistics.median(reps):.2f} ms")
    print(f"  exact per-tooth map (kernel):      {t_exact:.1f} s")
    print(f"  error vs exact (rad; errors move the gaps by up to {scale:.3g}):")
    print(f"    fast path         {np.max(np.abs(fast - exact)):.3g}")
    print(f"    interpolated path {np.max(np.abs(interp - exact)):.3g}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=24)
    ap.add_argument("--no-maps", action="store_true", help="skip the tolerance map timings")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        study = load_study(study_file(folder, args.rows, 1))
        t_row = row_time(study)
        print(f"serial row (min backlash + contact range, renzo-1967): {1e3 * t_row:.0f} ms")
        print(f"{'workers':>7} {'chunk':>5} {'rows':>5} {'start s':>8} {'wall s':>7} "
              f"{'rows/s':>7} {'overhead ms/task':>16} {'no-op task ms':>13}")
        noops = []
        for workers in (1, 2):
            for chunk in (1, 4):
                s = load_study(study_file(folder, args.rows, chunk))
                startup, wall, noop = on_cluster(s, workers, folder / f"out-{workers}-{chunk}")
                noops.append(noop)
                tasks = math.ceil(args.rows / chunk)
                over = (wall * workers - args.rows * t_row) / tasks
                print(f"{workers:>7} {chunk:>5} {args.rows:>5} {startup:>8.1f} {wall:>7.2f} "
                      f"{args.rows / wall:>7.2f} {1e3 * over:>16.0f} {1e3 * noop:>13.1f}")
        task = statistics.median(noops)
        n, w, chunk = 1_000_000, 64, 100
        hours = (n * t_row / w) / 3600
        sched = n / chunk * task / 3600
        print(f"\nprojection: {n} rows of {1e3 * t_row:.0f} ms on {w} workers: "
              f"{hours:.2f} h of work at perfect scaling; {n // chunk} tasks of {chunk} rows at "
              f"{1e3 * task:.1f} ms each through one scheduler: {sched:.2f} h if fully serial "
              "(an upper bound; it overlaps the work), plus one flank table per spec and worker")
    if not args.no_maps:
        tolerance_maps()


if __name__ == "__main__":
    main()
