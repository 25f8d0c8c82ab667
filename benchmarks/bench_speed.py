"""Before / after: the paths where users wait (issue 26's table), old and new in one run.

Run: ``python benchmarks/bench_speed.py [--against OLD_CHECKOUT [--old-numpy] | --at REV]
[--rounds 1] [--repeats 5] [--command-repeats 2] [--only ROW ...] [--fe]
[--ci-log NEW.log [OLD.log]] [--ci]``.

Every row runs in fresh subprocesses, one per checkout, with ``PYTHONPATH=<checkout>/src``:
the library of that checkout, the measuring code of this script for both, on the same
machine at the same moment (old and new alternate row by row, and with ``--rounds N`` the
whole set of rows N times, the figures of all rounds together). Printed per row: the
minimum and the median of the repeats, before and after, and the speed-up of the minima.
``--at REV`` compares with the commit ``REV`` of this repository, checked out into a
temporary ``git worktree`` (removed after; its numba cache is compiled by the first
call, before any timing). ``--old-numpy`` runs the old checkout with
``GEARCOUPLING_NUMBA=0``: its default install, where numba was an optional extra.

- ``map``, ``per-tooth``: :func:`gearcoupling.sweep` of renzo-1967 at 1°, 360 rotations,
  tolerance 1e-6 mm (``benchmarks/bench_sweep.py``'s map), periodic and ``periodic=False``;
  CPU time of the process, repeated in one process after a first call.
- ``sweep-map``, ``sweep-per-tooth``: the same maps as a user calls them,
  ``gc.sweep(spec, 1.0, range(360))`` (default tolerance) and with ``periodic=False``;
  wall time; ``sweep-map-cpu``, ``sweep-per-tooth-cpu``: their CPU time.
- ``first-map``: the first map in a new process (``import gearcoupling`` apart): what
  ``gearcoupling run`` pays once, with the compiled kernels in numba's cache;
  ``first-map-compile``: the same with an empty cache (a new install: numba compiles);
  wall time, one process per repeat (``first-map-compile`` once).
- ``run``, ``report``, ``datasheet``: ``gearcoupling run renzo-1967``, ``gearcoupling
  report renzo-1967`` and ``gearcoupling datasheet renzo-1967`` into a temporary folder;
  wall time of the command (exit status 1, the report's failed check, counts as done);
  ``run-cpu``, ``report-cpu``, ``datasheet-cpu``: the same, CPU time (user + system) of
  the command and the workers it forks, which a loaded machine changes less than wall time.
- ``capacity``: the default capacity, ``gc.capacity(spec, angle)`` at 1 and 3°,
  of the templates and the random specs of 170-260 teeth of ``tests/random_specs.py``
  (``springs_specs(55)``, the springs data set); CPU per call, the mean over the set, in
  one process after a first capacity (compiled kernels, flank tables).
- with ``--fe`` (minutes each, once): ``fe-table``, the FE tooth-spring table of renzo-1967
  (``stiffness = "fe"``, the cache bypassed: ``refresh``, a temporary cache folder);
  ``fea-contact``, ``gearcoupling fea-contact renzo-1967`` (aligned, default mesh);
  ``sector``, one misaligned sector pose, 5 teeth (``gearcoupling fea-contact renzo-1967
  --misalignment 1 --rotation 3.6 --sector 5 --size 0.85``, the first pose of
  ``benchmarks/bench_fea_sector.py``); wall time.
- ``ci``: the test suite's total, read from pytest logs (``--ci-log NEW.log [OLD.log]``,
  the summary line ``N passed ... in S s``), or timed with ``--ci`` (``bash
  scripts/test.sh`` in each checkout: half an hour each).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent
SPEC = "renzo-1967"
ENV: dict[Path, dict[str, str]] = {}  # per checkout: variables set for its processes

MAP = """
import json, time, numpy as np
from gearcoupling import load_spec, sweep
spec, angles = load_spec({spec!r}), np.arange(360.0)
sweep(spec, 1.0, angles[:2], tolerance_mm=1e-6, periodic={periodic})  # loads what it needs
out = []
for _ in range({repeats}):
    c = time.process_time()
    sweep(spec, 1.0, angles, tolerance_mm=1e-6, periodic={periodic})
    out.append(time.process_time() - c)
print(json.dumps(out))
"""
SWEEP = """
import json, time
import gearcoupling as gc
spec = gc.load_spec({spec!r})
gc.sweep(spec, 1.0, range(2), periodic={periodic})  # loads what it needs
out = []
for _ in range({repeats}):
    c, w = time.process_time(), time.perf_counter()
    gc.sweep(spec, 1.0, range(360), periodic={periodic})
    out.append((time.process_time() - c) if {cpu} else (time.perf_counter() - w))
print(json.dumps(out))
"""
FIRST_MAP = """
import json, time, numpy as np
from gearcoupling import load_spec, sweep
spec, angles = load_spec({spec!r}), np.arange(360.0)
t = time.perf_counter()
sweep(spec, 1.0, angles, tolerance_mm=1e-6)
print(json.dumps([time.perf_counter() - t]))
"""
CAPACITY = """
import json, sys, time
sys.path.insert(0, {tests!r})
import gearcoupling as gc
from random_specs import springs_specs
specs = [gc.load_spec(n) for n in gc.template_names()]
specs += [s for s in springs_specs(55) if 170 <= s.tooth.teeth <= 260]
gc.capacity(gc.load_spec("industrial-m2"), 1.0)  # loads what it needs
out = []
for _ in range({repeats}):
    c, n = time.process_time(), 0
    for spec in specs:
        for a in (1.0, 3.0):
            gc.capacity(spec, a)
            n += 1
    out.append((time.process_time() - c) / n)
print(json.dumps(out))
"""
FE_TABLE = """
import json, tempfile, time
from gearcoupling import load_spec
from gearcoupling.fea import tooth_compliance_table
spec = load_spec({spec!r})
with tempfile.TemporaryDirectory() as cache:
    t = time.perf_counter()
    tooth_compliance_table(spec, cache=cache, refresh=True)
    print(json.dumps([time.perf_counter() - t]))
"""


def _env(checkout: Path, **extra: str) -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(checkout / "src"), "OPENBLAS_NUM_THREADS": "1",
            **ENV.get(checkout, {}), **extra}


def python_row(code: str, processes: int = 1, **extra: str):
    """A row timed inside a Python process (its code prints a JSON list of seconds);
    ``processes`` new processes, their lists joined."""
    def measure(checkout: Path) -> list[float]:
        times: list[float] = []
        for _ in range(processes):
            with tempfile.TemporaryDirectory() as cache:
                env = _env(checkout, **extra)
                if "NUMBA_CACHE_DIR" in extra:  # an empty numba cache of its own
                    env["NUMBA_CACHE_DIR"] = cache
                out = subprocess.run([sys.executable, "-c", code], env=env,
                                     capture_output=True, text=True, check=False)
            if out.returncode:
                raise RuntimeError(out.stderr.strip().splitlines()[-1] if out.stderr else
                                   f"exit {out.returncode}")
            times += json.loads(out.stdout.strip().splitlines()[-1])
        return times
    return measure


def command_row(args: list[str], repeats: int, clock: str = "wall"):
    """``gearcoupling ARGS -o <temporary folder>``, ``repeats`` times: wall time, or with
    ``clock="CPU"`` the CPU time (user + system) of the command and every process it
    started. Exit status 1 (a finding, as the report's failed check) counts as done."""
    def measure(checkout: Path) -> list[float]:
        times = []
        for _ in range(repeats):
            with tempfile.TemporaryDirectory() as out:
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                t = time.perf_counter()
                res = subprocess.run([sys.executable, "-m", "gearcoupling.cli", *args, "-o", out],
                                     env=_env(checkout), capture_output=True, text=True,
                                     check=False)
                wall = time.perf_counter() - t
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            times.append(cpu if clock == "CPU" else wall)
            if res.returncode not in (0, 1):
                raise RuntimeError(res.stderr.strip().splitlines()[-1] if res.stderr else
                                   f"exit {res.returncode}")
        return times
    return measure


def ci_row(logs: list[Path] | None, run_suite: bool):
    """The suite's total seconds: from a pytest log (the new one first, the old one second)
    or, with ``run_suite``, by running ``bash scripts/test.sh`` in the checkout."""
    def measure(checkout: Path) -> list[float]:
        if run_suite:
            t = time.perf_counter()
            subprocess.run(["bash", "scripts/test.sh"], cwd=checkout, check=False,
                           capture_output=True)
            return [time.perf_counter() - t]
        log = (logs or [])[0 if checkout == HERE else 1] if logs else None
        return [] if log is None else [pytest_total(log)]
    return measure


def pytest_total(log: Path) -> float:
    """Seconds of a pytest run from its summary line (``... passed ... in 1234.5s``)."""
    found = re.findall(r"\d+ passed.*? in ([\d.]+)s", log.read_text(errors="replace"))
    if not found:
        raise RuntimeError(f"{log}: no pytest summary line ('N passed ... in S s')")
    return float(found[-1])


def rows(args) -> list[tuple[str, str, str, object]]:
    """``(key, path, clock, measure)`` of every row asked for."""
    r, rc = args.repeats, args.command_repeats
    out = [
        ("map", f"full clearance map, {SPEC}, 1°, 360 rotations", "CPU",
         python_row(MAP.format(spec=SPEC, periodic=True, repeats=r))),
        ("per-tooth", "exact per-tooth map (periodic=False)", "CPU",
         python_row(MAP.format(spec=SPEC, periodic=False, repeats=max(1, r // 2)))),
        *((f"sweep-{key}{'-cpu' if cpu else ''}", path, "CPU" if cpu else "wall",
           python_row(SWEEP.format(spec=SPEC, periodic=periodic, cpu=cpu,
                                   repeats=r if periodic else max(1, r // 2))))
          for cpu in (False, True)
          for key, periodic, path in (
              ("map", True, f"full clearance map, {SPEC}, 1°, 360 rotations (`gc.sweep`)"),
              ("per-tooth", False, "exact per-tooth map (`periodic=False`)"))),
        ("first-map", "first map in a new process (compiled code cached)", "wall",
         python_row(FIRST_MAP.format(spec=SPEC), processes=r)),
        ("first-map-compile", "first map after install (empty numba cache)", "wall",
         python_row(FIRST_MAP.format(spec=SPEC), NUMBA_CACHE_DIR="")),
        ("run", f"gearcoupling run {SPEC}", "wall", command_row(["run", SPEC], rc)),
        ("run-cpu", f"gearcoupling run {SPEC}", "CPU", command_row(["run", SPEC], rc, "CPU")),
        ("report", f"gearcoupling report {SPEC}", "wall", command_row(["report", SPEC], rc)),
        ("report-cpu", f"gearcoupling report {SPEC}", "CPU",
         command_row(["report", SPEC], rc, "CPU")),
        ("datasheet", f"gearcoupling datasheet {SPEC}", "wall",
         command_row(["datasheet", SPEC], rc)),
        ("datasheet-cpu", f"gearcoupling datasheet {SPEC}", "CPU",
         command_row(["datasheet", SPEC], rc, "CPU")),
        ("capacity", "default capacity per angle (templates, random specs of 170-260 teeth;"
         " 1° and 3°)", "CPU",
         python_row(CAPACITY.format(tests=str(HERE / "tests"), repeats=1))),
    ]
    if args.fe:
        out += [
            ("fe-table", f"FE tooth-spring table, {SPEC}, cache bypassed", "wall",
             python_row(FE_TABLE.format(spec=SPEC))),
            ("fea-contact", f"fea-contact {SPEC} aligned, default mesh", "wall",
             command_row(["fea-contact", SPEC], 1)),
            ("sector", "one misaligned sector pose, 5 teeth", "wall",
             command_row(["fea-contact", SPEC, "--misalignment", "1", "--rotation", "3.6",
                          "--sector", "5", "--size", "0.85"], 1)),
        ]
    if args.ci_log or args.ci:
        out.append(("ci", "CI: the whole suite (scripts/test.sh)", "wall",
                    ci_row(args.ci_log, args.ci)))
    return [row for row in out if args.only is None or row[0] in args.only]


def _fmt(seconds: list[float]) -> str:
    if not seconds:
        return "-"
    lo, med = min(seconds), statistics.median(seconds)
    if lo < 1.0:
        return f"{lo * 1e3:.1f} / {med * 1e3:.1f} ms"
    return f"{lo:.2f} / {med:.2f} s"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--against", type=Path, metavar="OLD_CHECKOUT",
                    help="the checkout to compare with (its src/ is imported)")
    ap.add_argument("--old-numpy", action="store_true",
                    help="the old checkout with GEARCOUPLING_NUMBA=0 (its default install)")
    ap.add_argument("--at", metavar="REV",
                    help="compare with commit REV of this repository (a temporary worktree)")
    ap.add_argument("--rounds", type=int, default=1,
                    help="the rows this many times, old and new alternating")
    ap.add_argument("--repeats", type=int, default=5, help="repeats of the map rows")
    ap.add_argument("--command-repeats", type=int, default=2, help="repeats of run, report")
    ap.add_argument("--only", nargs="*", default=None, metavar="ROW",
                    help="rows: map per-tooth sweep-map sweep-per-tooth sweep-map-cpu "
                         "sweep-per-tooth-cpu first-map first-map-compile run run-cpu report "
                         "report-cpu datasheet datasheet-cpu capacity fe-table fea-contact "
                         "sector ci")
    ap.add_argument("--fe", action="store_true", help="also the FE rows (minutes each)")
    ap.add_argument("--ci-log", type=Path, nargs="+", metavar="LOG",
                    help="pytest logs of the whole suite: the new one, then the old one")
    ap.add_argument("--ci", action="store_true", help="time scripts/test.sh in each checkout")
    args = ap.parse_args(argv)
    if args.repeats < 1 or args.command_repeats < 1 or args.rounds < 1:
        ap.error("--repeats, --command-repeats and --rounds must be at least 1")
    if args.at is not None and args.against is not None:
        ap.error("--at and --against exclude each other")
    if args.at is None:
        return compare(args)
    with tempfile.TemporaryDirectory() as tmp:
        old = Path(tmp) / "old"
        subprocess.run(["git", "-C", str(HERE), "worktree", "add", "--detach", str(old),
                        args.at], check=True, capture_output=True)
        try:
            args.against = old
            return compare(args, label=f"{args.at} (a worktree of it)")
        finally:
            subprocess.run(["git", "-C", str(HERE), "worktree", "remove", "--force", str(old)],
                           check=False, capture_output=True)


def compare(args, label: str | None = None) -> int:
    """The rows of ``args``, printed as a table (old and new where ``args.against``)."""
    checkouts = [HERE] if args.against is None else [args.against.resolve(), HERE]
    if args.old_numpy and args.against is not None:
        ENV[checkouts[0]] = {"GEARCOUPLING_NUMBA": "0"}
    for c in checkouts:
        if not (c / "src" / "gearcoupling").is_dir():
            raise SystemExit(f"{c}: no src/gearcoupling in it")
    head = ["path", "clock"] + (["before (min / median)"] if args.against else []) + \
        ["after (min / median)"] + (["speed-up", "after / before"] if args.against else [])
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load average "
          f"{os.getloadavg()[0]:.1f}, {os.cpu_count()} cores; after = {HERE}" +
          (f", before = {label or args.against}" if args.against else "") +
          (" with GEARCOUPLING_NUMBA=0" if args.old_numpy and args.against else "") +
          (f"; {args.rounds} rounds" if args.rounds > 1 else ""))
    table = rows(args)
    found: list[list[list[float] | Exception]] = [[[] for _ in checkouts] for _ in table]
    for done in range(args.rounds):
        for row, (_, _, _, measure) in zip(found, table, strict=True):
            for j, c in enumerate(checkouts):
                if isinstance(row[j], Exception):
                    continue
                try:
                    row[j] += measure(c)
                except (RuntimeError, OSError) as err:
                    row[j] = err
        print(f"round {done + 1} of {args.rounds} done", file=sys.stderr, flush=True)
    print("\n| " + " | ".join(head) + " |\n|" + "---|" * len(head))
    for (_, path, clock, _), cells in zip(table, found, strict=True):
        text = [_fmt(x) if isinstance(x, list) else f"failed: {x}" for x in cells]
        if args.against:
            old, new = cells
            ok = isinstance(old, list) and isinstance(new, list) and old and new
            text += [f"{min(old) / min(new):.1f}x", f"{min(new) / min(old):.2f}x"] if ok else \
                ["-", "-"]
        print(f"| {path} | {clock} | " + " | ".join(text) + " |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
