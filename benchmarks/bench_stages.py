"""The pipeline's stages: what each costs, against the cost its record states.

Run: ``python benchmarks/bench_stages.py [TEMPLATE ...]`` (default renzo-1967). Computes
every stage of :data:`gearcoupling.outputs.STAGES` in one process (``workers=1``, files
written to a temporary folder) and prints, per stage, the seconds it took (its
compute and its files) beside the ``cost`` of its record, which the two workers balance
and the progress bar counts; a stage that skips says why. The costs in
``gearcoupling/outputs/registry.py`` are these figures for renzo-1967, rounded.
"""

from __future__ import annotations

import sys
import tempfile
import time

import gearcoupling as gc
from gearcoupling.outputs import STAGES, StageSettings, compute


def table(name: str) -> None:
    spec = gc.load_spec(name)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.process_time()
        res = compute(spec, StageSettings(), list(STAGES), folder=tmp, workers=1)
        total = time.process_time() - t0
    print(f"\n{name}: every stage in one process, {total:.1f} s of CPU in all")
    print("| stage | seconds | record's cost |\n|---|---|---|")
    for key, stage in STAGES.items():
        took = res.seconds.get(key)
        shown = f"skipped: {res.skipped[key]}" if key in res.skipped else f"{took:.2f}"
        print(f"| {key} | {shown} | {stage.cost:g} |")


if __name__ == "__main__":
    for name in sys.argv[1:] or ["renzo-1967"]:
        table(name)
