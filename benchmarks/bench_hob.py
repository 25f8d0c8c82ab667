"""Hob feed program: what the chordal tolerance costs (moves, time) and buys (deviation).

Run: ``python benchmarks/bench_hob.py``. For every template (plus a crown-drop table
variant of renzo-1967) and tolerances module/100 ... module/10000, with a hob of 40
modules outside diameter: arc and line moves, the largest chordal deviation measured on
65 exact-path samples per chord, and the build time (median of 3). Markdown on stdout.
"""

from __future__ import annotations

import math
import time

import numpy as np

import gearcoupling as gc
from gearcoupling.hob import hob_program

TABLE = {"hub.crowning.kind": "table", "hub.crowning.radius": math.inf,
         "hub.crowning.z": [0.0, 3.0, 6.0, 9.0, 12.0],
         "hub.crowning.drop": [0.0, 0.02, 0.09, 0.21, 0.40]}


def main():
    specs = [(n, gc.load_spec(n)) for n in gc.template_names()]
    specs.append(("renzo-1967 + drop table", gc.load_spec("renzo-1967").replace(**TABLE)))
    print("| spec | crowning | tolerance (mm) | arcs | lines | max deviation (mm) | time (ms) |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for name, spec in specs:
        m = spec.tooth.module
        for per in (100, 1000, 10000):
            tol = m / per
            times = []
            for _ in range(3):
                t0 = time.perf_counter()
                prog = hob_program(spec, 40 * m, tolerance_mm=tol)
                times.append(time.perf_counter() - t0)
            s = prog.summary()
            print(f"| {name} | {s['crowning']} | {tol:.2e} | {s['arc_moves']} | "
                  f"{s['line_moves']} | {s['max_deviation_mm']:.2e} | "
                  f"{1e3 * float(np.median(times)):.1f} |")


if __name__ == "__main__":
    main()
