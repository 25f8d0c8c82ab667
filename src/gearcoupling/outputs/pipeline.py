"""``gc.run``: every file the project can make for a spec, into one folder.

The steps fall in two chains that share nothing but the folder; with two workers each chain
runs in a forked process, so a two-core machine does both at once. The stages the steps
compute (:mod:`~gearcoupling.outputs.stages`) are kept in this process, the workers'
included, for a report made after the run (``gc.report``) to reuse.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ArgumentError, BackendError
from ..interference import check_interference
from ..io import output_folder, remove_stale_temporaries, write_json
from ..plots import plot_sections
from ..spec import CouplingSpec, as_spec
from ..viewer import write_html
from .forked import can_fork, messages, start_workers, stop_workers, worker_signals
from .interference import write_interference
from .load import write_load
from .parts import write_parts, write_step_files
from .spec import write_spec
from .stages import remember, take_new
from .sweep import write_sweep

#: the steps in the order they are listed, each with what it writes
STEPS: dict[str, str] = {
    "spec": "resolved spec (spec.json)",
    "sections": "section plots",
    "parts": "hub and sleeve STL",
    "step": "hub and sleeve STEP",
    "sweep": "sweep at the design angle",
    "load": "loaded contact at the design angle",
    "check": "interference check at the design angle",
    "viewer": "static viewer HTML",
}
# halves of the work as near equal as whole steps allow (renzo-1967, CPU seconds on a
# loaded machine: load 9.5 (its studies 5.1), viewer 0.7; spec 0, sections 0.7, sweep 2.7,
# parts 0.6, step 1.8, check 2.0)
CHAINS = (("load", "viewer"), ("spec", "sections", "sweep", "parts", "step", "check"))
CHECK_ANGLES = 72
RUN_ANGLES = 360


class SkipStep(Exception):
    """A step that does not apply to this spec; the others still run."""


@dataclass(frozen=True)
class RunResult:
    """What :func:`run` wrote: the files, each step's seconds and the skipped steps with
    their reasons (``run_summary.json`` holds the same)."""

    spec_name: str
    out: Path
    files: tuple[Path, ...]
    seconds: dict[str, float]
    skipped: dict[str, str]
    wall_seconds: float
    workers: int

    def summary(self) -> dict[str, Any]:
        """``run_summary.json``: steps with their seconds and files, skipped steps, wall
        time and workers."""
        return {"spec": self.spec_name, "workers": self.workers,
                "wall_seconds": self.wall_seconds, "step_seconds": self.seconds,
                "skipped": self.skipped, "files": [p.name for p in self.files]}


def _step(key: str, spec: CouplingSpec, out: Path) -> list[Path]:
    mis = spec.design_misalignment_deg
    if key == "spec":
        return write_spec(spec, out)
    if key == "sections":
        return [plot_sections(spec, out / "sections.png")]
    if key == "parts":
        return write_parts(spec, out)[0]
    if key == "step":
        return write_step_files(spec, out)
    if key == "sweep":
        return write_sweep(spec, out, mis, RUN_ANGLES)[1]
    if key == "load":
        if spec.load.torque_Nm is None:
            raise SkipStep("no [load] torque_Nm in the spec")
        return write_load(spec, out, mis)[1]  # a turn of PHASES poses per pitch
    if key == "check":
        angles = [360.0 * j / CHECK_ANGLES for j in range(CHECK_ANGLES)]
        return write_interference(spec, check_interference(spec, mis, angles), out)
    return [write_html(spec, out / "viewer.html")]


def _timed(key: str, spec: CouplingSpec, out: Path) -> tuple[str, list[Path], float, str | None]:
    """Run one step: ``(key, files, seconds, reason skipped or None)``."""
    t0 = time.perf_counter()
    try:
        files = _step(key, spec, out)
        reason = None
    except (BackendError, SkipStep) as err:  # an extra missing: the others stand
        files, reason = [], str(err)
    return key, files, time.perf_counter() - t0, reason


def _chosen(only: Iterable[str] | None, skip: Iterable[str]) -> list[str]:
    only_set = set(STEPS) if only is None else _names(only, "only")
    skip_set = _names(skip, "skip")
    unknown = (only_set | skip_set) - set(STEPS)
    if unknown:
        raise ArgumentError("steps", ", ".join(sorted(unknown)), "unknown: the steps are "
                            f"{', '.join(STEPS)}")
    return [k for k in STEPS if k in only_set - skip_set]


def _names(value: Any, name: str) -> set[str]:
    """Step names given as a list (not one string: ``"spec"`` would be four letters)."""
    try:
        names = None if isinstance(value, str | bytes) else list(value)
    except TypeError:
        names = None
    if names is None or not all(isinstance(k, str) for k in names):
        raise ArgumentError(name, value, f"a list of step names from {', '.join(STEPS)}")
    return set(names)


def _chain_worker(keys: list[str], spec: CouplingSpec, out: Path, conn) -> None:
    """A forked worker: run the steps ``keys`` in order, sending each ``_timed`` result (or
    the error that stopped the chain) to the parent. It dies with its parent and leaves
    signals to it: the parent stops the workers and cleans up (:func:`_run_forked`)."""
    worker_signals()
    try:
        for k in keys:  # each step's results, and the stages it computed for the parent
            conn.send(("done", _timed(k, spec, out), take_new()))
    except Exception as err:  # re-raised by the parent
        try:
            conn.send(("error", err))
        except Exception:  # an error that does not pickle: its text
            conn.send(("error", BackendError(f"{type(err).__name__}: {err}")))
    finally:
        conn.close()


def _run_forked(chains: list[list[str]], spec: CouplingSpec, out: Path,
                finished: Callable[[tuple[str, list[Path], float, str | None]], None]) -> None:
    """Run each chain in its own forked process, this one only waiting (so it answers a
    signal at once). On any exception here (an error of a step, ``KeyboardInterrupt``,
    the CLI's signal) the workers are killed and reaped and their temporaries removed
    before it propagates: no file is written after it."""
    workers: list = []
    try:
        start_workers(_chain_worker, [(chain, spec, out) for chain in chains], workers)
        for _, item, stages in messages(workers):
            remember(stages)
            finished(item)
    finally:
        stop_workers(workers)
        remove_stale_temporaries(out)


def run(spec: CouplingSpec, out: str | os.PathLike, *, only: Iterable[str] | None = None,
        skip: Iterable[str] = (), workers: int | None = None,
        progress: Callable[[int, int], None] | None = None) -> RunResult:
    """Write everything the project can make for ``spec`` into the folder ``out``.

    Parameters
    ----------
    spec : CouplingSpec
    out : path-like
        Output folder (created; refused if it holds a device, pipe or socket, see
        :func:`~gearcoupling.io.output_folder`).
    only, skip : iterable of str
        Steps of :data:`STEPS` to run, or to leave out (default: all).
    workers : int, optional
        1 runs every step in this process; 2 (the default where the machine has two cores
        and this process runs no other thread) runs each of :data:`CHAINS` in a forked
        process while this one waits. Interrupted (``KeyboardInterrupt`` or any other
        exception), the workers are killed first: no file is written after it.
    progress : callable, optional
        ``progress(done, total)`` after each step.

    Returns
    -------
    RunResult
        Also written as ``run_summary.json``.

    Examples
    --------
    >>> import gearcoupling as gc
    >>> res = gc.run(gc.load_spec("renzo-1967"), "outputs/renzo-1967", only=["spec"])
    >>> [p.name for p in res.files]
    ['spec.json', 'run_summary.json']
    """
    spec = as_spec(spec)
    output_folder(out, "out", create=False)
    keys = _chosen(only, skip)
    if workers is None:
        workers = 2 if (os.cpu_count() or 1) >= 2 else 1
    if workers not in (1, 2) or isinstance(workers, bool):
        raise ArgumentError("workers", workers, "1 or 2")
    folder = output_folder(out, "out")
    chains = [[k for k in chain if k in keys] for chain in CHAINS]
    parallel = workers == 2 and all(chains) and can_fork()
    done: dict[str, tuple[str, list[Path], float, str | None]] = {}

    def finished(item: tuple[str, list[Path], float, str | None]) -> None:
        done[item[0]] = item
        if progress is not None:
            progress(len(done), len(keys))

    t0 = time.perf_counter()
    if parallel:
        _run_forked(chains, spec, folder, finished)
    else:
        for k in keys:
            finished(_timed(k, spec, folder))
    files = [p for k in keys for p in done[k][1]]
    result = RunResult(spec.name, folder, tuple(files), {k: done[k][2] for k in keys},
                       {k: r for k in keys if (r := done[k][3]) is not None},
                       time.perf_counter() - t0, 2 if parallel else 1)
    summary = write_json(folder / "run_summary.json", result.summary())
    return RunResult(result.spec_name, folder, (*files, summary), result.seconds,
                     result.skipped, result.wall_seconds, result.workers)
