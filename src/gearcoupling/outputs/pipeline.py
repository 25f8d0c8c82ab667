"""``gc.run``: every file the project can make for a spec, into one folder.

The steps fall in two chains of near equal cost (:func:`chains`) that share nothing but the
folder; with two workers each chain runs in a forked process, so a two-core machine does
both at once. The stages the steps compute (:mod:`~gearcoupling.outputs.stages`) are kept
in this process, the workers' included, for a report made after the run (``gc.report``)
to reuse.
"""

from __future__ import annotations

import itertools
import os
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import outputs
from ..clearance import sweep
from ..errors import ArgumentError, BackendError, GearCouplingError
from ..forked import can_fork, messages, start_workers, stop_workers, worker_signals
from ..io import output_folder, remove_stale_temporaries, writable_targets, write_json
from ..plots import import_matplotlib, plot_sections
from ..spec import CouplingSpec, as_spec
from . import files as file_names
from .spec import write_spec
from .stages import remember, take_new

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
#: the files each step may write (:mod:`~gearcoupling.outputs.files`)
FILES: dict[str, tuple[str, ...]] = {
    "spec": file_names.SPEC, "sections": file_names.SECTIONS,
    "parts": tuple(file_names.part_files()),
    "step": file_names.STEP, "sweep": file_names.SWEEP, "load": file_names.LOAD,
    "check": file_names.INTERFERENCE, "viewer": file_names.VIEWER}
#: CPU seconds of each step on renzo-1967 (this pipeline, the modules of :data:`NEEDS`
#: loaded before the fork, a step's own modules in it: OpenCASCADE 0.7 s in ``step``, the
#: load models in ``load``, its study on the compiled contact solver; a loaded machine:
#: their ratios count): what the two workers balance (:func:`chains`)
COST = {"spec": 0.0, "sections": 0.4, "parts": 0.45, "step": 1.65, "sweep": 1.3,
        "load": 4.5, "check": 1.75, "viewer": 0.55}
#: steps that run in one process, in this order (``step`` adds its files to ``parts.json``)
TOGETHER = (("parts", "step"),)
#: what a step loads that another step may load too: with two workers, what both need is
#: loaded once before the fork, not once in each (matplotlib 0.3 s, trimesh and the parts
#: 0.3 s, the compiled sweep kernels 0.4 s, the load models 0.2 s of CPU); what one
#: chain alone needs its worker loads
NEEDS = {"spec": (), "sections": ("figures",), "parts": ("meshes",), "step": (),
         "sweep": ("figures", "kernels"), "load": ("figures", "kernels", "loads"),
         "check": ("figures", "meshes", "kernels"),
         "viewer": ("figures", "meshes", "kernels", "loads")}
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
    """Run step ``key``. Its writer comes from the package, whose names load on first use:
    each step's stage is imported in the worker that runs it (the parent loads only what
    every chain needs, :func:`_preload`)."""
    mis = spec.design_misalignment_deg
    if key == "spec":
        return write_spec(spec, out)
    if key == "sections":
        return [plot_sections(spec, out / "sections.png")]
    if key == "parts":
        return outputs.write_parts(spec, out)[0]
    if key == "step":
        return outputs.write_step_files(spec, out)
    if key == "sweep":
        return outputs.write_sweep(spec, out, mis, RUN_ANGLES)[1]
    if key == "load":
        if spec.load.torque_Nm is None:
            raise SkipStep("no [load] torque_Nm in the spec")
        return outputs.write_load(spec, out, mis)[1]  # a turn of PHASES poses per pitch
    if key == "check":
        angles = [360.0 * j / CHECK_ANGLES for j in range(CHECK_ANGLES)]
        return outputs.write_check(spec, out, mis, angles)
    return outputs.write_viewer(spec, out)


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


def run_files(only: Iterable[str] | None = None, skip: Iterable[str] = ()) -> list[str]:
    """The files :func:`run` may write with these ``only`` and ``skip`` (the steps' and
    ``run_summary.json``), each once, in the order of the steps."""
    keys = _chosen(only, skip)
    return list(dict.fromkeys([n for k in keys for n in FILES[k]] + [file_names.RUN_SUMMARY]))


def chains(keys: Sequence[str]) -> list[list[str]]:
    """The steps ``keys`` split in two chains of near equal :data:`COST` (of the splits
    that keep :data:`TOGETHER` steps in one chain, the one with the cheapest longer chain,
    two chains where that ties), each chain in the order of :data:`STEPS`."""
    groups = [[k for k in g if k in keys] for g in TOGETHER]
    groups = [g for g in groups if g] + [[k] for k in keys
                                         if not any(k in g for g in TOGETHER)]
    if not groups:
        return []
    scored = []
    for sides in itertools.product((0, 1), repeat=len(groups) - 1):
        halves: list[list[str]] = [[], []]
        for side, group in zip((0, *sides), groups, strict=True):
            halves[side] += group
        scored.append(((max(sum(COST[k] for k in h) for h in halves),
                        sum(not h for h in halves)), halves))
    best = min(scored, key=lambda item: item[0])[1]
    return [[k for k in STEPS if k in h] for h in best if h]


def _preload(spec: CouplingSpec, split: list[list[str]]) -> None:
    """Load here, before the fork, what steps of every chain need (:data:`NEEDS`): once,
    not once in each worker."""
    both = set.intersection(*({n for k in chain for n in NEEDS[k]} for chain in split))
    if "figures" in both:
        import_matplotlib()
        import matplotlib.backends.backend_agg
        import matplotlib.figure  # noqa: F401
    if "meshes" in both:  # trimesh, and the parts through their writer's module
        import trimesh  # noqa: F401

        _ = outputs.write_parts
    if "loads" in both:  # the load models through their writer's module
        _ = outputs.write_load
    if "kernels" in both:  # the compiled sweep kernels and the spec's flank table
        try:
            sweep(spec, spec.design_misalignment_deg, [0.0])
        except GearCouplingError:  # the steps report it
            pass


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


def _run_forked(split: list[list[str]], spec: CouplingSpec, out: Path,
                finished: Callable[[tuple[str, list[Path], float, str | None]], None]) -> None:
    """Run each chain in its own forked process, this one only waiting (so it answers a
    signal at once). On any exception here (an error of a step, ``KeyboardInterrupt``,
    the CLI's signal) the workers are killed and reaped and their temporaries removed
    before it propagates: no file is written after it."""
    _preload(spec, split)
    workers: list = []
    try:
        start_workers(_chain_worker, [(chain, spec, out) for chain in split], workers)
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
        :func:`~gearcoupling.io.output_folder`, or anything but a regular file where a
        step writes one, :func:`run_files`: before any step runs).
    only, skip : iterable of str
        Steps of :data:`STEPS` to run, or to leave out (default: all).
    workers : int, optional
        1 runs every step in this process; 2 (the default where the machine has two cores
        and this process runs no other thread) runs each of the two :func:`chains` of the
        steps in a forked process while this one waits. Interrupted
        (``KeyboardInterrupt`` or any other exception), the workers are killed first: no
        file is written after it.
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
    writable_targets(out, run_files(only, skip), field="out")
    if workers is None:
        workers = 2 if (os.cpu_count() or 1) >= 2 else 1
    if workers not in (1, 2) or isinstance(workers, bool):
        raise ArgumentError("workers", workers, "1 or 2")
    folder = output_folder(out, "out")
    split = chains(keys)
    parallel = workers == 2 and len(split) == 2 and can_fork()
    done: dict[str, tuple[str, list[Path], float, str | None]] = {}

    def finished(item: tuple[str, list[Path], float, str | None]) -> None:
        done[item[0]] = item
        if progress is not None:
            progress(len(done), len(keys))

    t0 = time.perf_counter()
    if parallel:
        _run_forked(split, spec, folder, finished)
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
