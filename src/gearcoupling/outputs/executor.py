"""Compute stages: each once, in an order their needs allow, over two forked workers
where the machine has two cores.

The parent hands a worker a stage whose needs are done (the costliest first), with the
results of those needs that the worker does not hold yet; the worker computes it, writes
its files and sends the result back. A parallel stage (:attr:`Stage.parallel`) is cut into
parts in the parent once its needs are done (its :class:`~.stage.Plan`); the parts go to
the workers like stages, and a last task combines their values. Nothing is kept between
calls: the results of one call are its return value.
"""

from __future__ import annotations

import importlib
import multiprocessing
import multiprocessing.connection
import os
import time
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..clearance import sweep
from ..errors import ArgumentError, BackendError, GearCouplingError
from ..forked import can_fork, held_signals, stop_workers, worker_signals
from ..interrupts import check
from ..io import remove_stale_temporaries
from ..spec import CouplingSpec
from . import registry
from .settings import StageSettings
from .stage import Plan, Results, SkipStage, Stage, StageInputs

Progress = Callable[[int, int], None]


def plan(names: Sequence[str]) -> list[Stage]:
    """The stages ``names`` with every stage they need, in the order of
    :data:`~.registry.STAGES` (where each stage follows its needs)."""
    stages = registry.STAGES
    unknown = sorted(set(names) - set(stages))
    if unknown:
        raise ArgumentError("stages", ", ".join(unknown), f"unknown: the stages are "
                            f"{', '.join(stages)}")
    wanted: set[str] = set()
    todo = list(names)
    while todo:
        name = todo.pop()
        if name not in wanted:
            wanted.add(name)
            todo += stages[name].needs
    return [s for s in stages.values() if s.name in wanted]


@dataclass
class _Task:
    """A stage to run; for a parallel stage one of its plan's tasks (``index``, ``work``)
    or the combination of their values (``plan``, ``parts``)."""

    stage: Stage
    cost: float
    index: int | None = None
    work: Callable[[], Any] | None = None
    plan: Plan | None = None
    parts: list[Any] | None = None


@dataclass
class _State:
    """The parent's book of a computation."""

    spec: CouplingSpec
    settings: StageSettings
    folder: Path | None
    stages: list[Stage]
    values: dict[str, Any] = field(default_factory=dict)
    files: dict[str, tuple[Path, ...]] = field(default_factory=dict)
    seconds: dict[str, float] = field(default_factory=dict)
    skipped: dict[str, str] = field(default_factory=dict)
    plans: dict[str, Plan] = field(default_factory=dict)  # parallel stages' plans
    parts: dict[str, list[Any]] = field(default_factory=dict)  # and their tasks' values
    waiting: dict[str, int] = field(default_factory=dict)  # parts still running
    started: set[str] = field(default_factory=set)
    done_units: float = 0.0
    written: list[Path] = field(default_factory=list)  # every file so far, in order

    def results(self) -> Results:
        return Results(dict(self.values), dict(self.files), dict(self.seconds),
                       dict(self.skipped))

    def inputs(self, results: Results | None = None) -> StageInputs:
        return StageInputs(self.spec, self.settings, self.settings.resolve(self.spec),
                           results or self.results())

    @property
    def planned(self) -> set[str]:
        return {s.name for s in self.stages}

    def finished(self, name: str) -> bool:
        return name in self.values or name in self.skipped

    def ready(self) -> list[Stage]:
        """Stages not started whose needs are finished; a stage whose need was skipped is
        skipped (said so) instead."""
        out = []
        for s in self.stages:
            if s.name in self.started or not all(
                    self.finished(n) for n in s.needs + s.after
                    if n in self.planned or n in s.needs):
                continue
            missing = [n for n in s.needs if n in self.skipped]
            if missing:
                self.started.add(s.name)
                self.skipped[s.name] = f"needs {missing[0]}: {self.skipped[missing[0]]}"
            else:
                out.append(s)
        return out


def _run_task(task: _Task, inputs: StageInputs, folder: Path | None
              ) -> tuple[str, Any, tuple[Path, ...], float]:
    """Run ``task``: ``(kind, value, files, seconds)`` with kind ``"part"``, ``"done"`` or
    ``"skipped"`` (value the reason)."""
    t0 = time.perf_counter()
    if task.work is not None:
        return "part", task.work(), (), time.perf_counter() - t0
    try:
        value = task.stage.run(inputs) if task.plan is None else \
            task.plan.combine(task.parts or [])
        files = () if folder is None else tuple(task.stage.write(value, inputs, folder))
    except (BackendError, SkipStage) as err:  # an extra missing, or it does not apply
        return "skipped", str(err), (), time.perf_counter() - t0
    return "done", value, files, time.perf_counter() - t0


def _tasks_of(state: _State, stage: Stage) -> list[_Task]:
    """The tasks of a ready stage: itself, or its plan's tasks (none: combined at once).
    A plan that is refused skips the stage."""
    state.started.add(stage.name)
    if not stage.parallel:
        return [_Task(stage, stage.cost)]
    try:
        plan = stage.run(state.inputs())
    except (BackendError, SkipStage) as err:
        state.skipped[stage.name] = str(err)
        return []
    work = list(plan.tasks)
    if not work:
        return [_Task(stage, 0.0, plan=plan, parts=[])]
    state.plans[stage.name] = plan
    state.parts[stage.name] = [None] * len(work)
    state.waiting[stage.name] = len(work)
    return [_Task(stage, stage.cost / len(work), i, w) for i, w in enumerate(work)]


def _record(state: _State, task: _Task, kind: str, value: Any, files: tuple[Path, ...],
            seconds: float) -> list[_Task]:
    """Book a finished task; returns the combining task of a stage whose parts are all
    done."""
    name = task.stage.name
    state.done_units += task.cost
    state.seconds[name] = state.seconds.get(name, 0.0) + seconds
    if kind == "part":
        assert task.index is not None
        state.parts[name][task.index] = value
        state.waiting[name] -= 1
        if state.waiting[name] == 0:
            return [_Task(task.stage, 0.0, plan=state.plans.pop(name),
                          parts=state.parts.pop(name))]
        return []
    if kind == "skipped":
        state.skipped[name] = value
    else:
        state.values[name], state.files[name] = value, files
        state.written += files
    return []


def compute(spec: CouplingSpec, settings: StageSettings, names: Sequence[str], *,
            folder: str | os.PathLike | None = None, workers: int = 1,
            progress: Progress | None = None, written: list[Path] | None = None) -> Results:
    """The results of the stages ``names`` and those they need (:func:`plan`), their files
    written into ``folder`` (None: none written).

    ``workers`` 2 runs the stages in two forked processes where forking is safe
    (:func:`~gearcoupling.forked.can_fork`), this one handing them out and waiting; any
    exception here (a stage's error, ``KeyboardInterrupt``, the CLI's signal) kills and
    reaps them before it propagates, so no file is written after it. ``progress(done,
    total)`` in tenths of the stages' expected CPU seconds. ``written``: a list that each
    file is added to as it is written (what an interrupted computation left)."""
    state = _State(spec, settings, None if folder is None else Path(folder), plan(names))
    if written is not None:
        state.written = written
    total = max(1, round(10 * sum(s.cost for s in state.stages)))

    def tick() -> None:
        if progress is not None:
            progress(min(total, round(10 * state.done_units)), total)

    if workers >= 2 and len(state.stages) >= 2 and can_fork():
        _forked(state, tick)
    else:
        _inline(state, tick)
    return state.results()


def _inline(state: _State, tick: Callable[[], None]) -> None:
    queue: list[_Task] = []
    while True:
        for stage in state.ready():
            queue += _tasks_of(state, stage)
        if not queue:
            return
        check()  # an interruption a library dropped: no next stage
        task = queue.pop(0)
        queue += _record(state, task, *_run_task(task, state.inputs(), state.folder))
        tick()


# ---------------------------------------------------------------- forked workers


def _worker(spec: CouplingSpec, settings: StageSettings, folder: Path | None, conn) -> None:
    """A forked worker: run each task it is sent (a stage by name, with the results it
    needs, or a plan's task), and send back what it found (or the error that stopped it)."""
    worker_signals()
    held: dict[str, Any] = {}
    try:
        while True:
            message = conn.recv()
            if message is None:
                return
            name, index, work, plan, parts, values = message
            held.update(values)
            inputs = StageInputs(spec, settings, settings.resolve(spec), Results(dict(held)))
            task = _Task(registry.STAGES[name], 0.0, index, work, plan, parts)
            conn.send(("ok", _run_task(task, inputs, folder)))
    except EOFError:  # the parent is gone
        return
    except Exception as err:  # re-raised by the parent
        try:
            conn.send(("error", err))
        except Exception:  # an error that does not pickle: its text
            conn.send(("error", BackendError(f"{type(err).__name__}: {err}")))
    finally:
        conn.close()


def _start(state: _State, count: int, procs: list) -> None:
    """Fork ``count`` workers with a duplex pipe each, SIGINT and SIGTERM held meanwhile
    (:func:`~gearcoupling.forked.held_signals`)."""
    ctx = multiprocessing.get_context("fork")
    with held_signals():
        for _ in range(count):
            mine, theirs = ctx.Pipe(duplex=True)
            proc = ctx.Process(target=_worker, args=(state.spec, state.settings,
                                                      state.folder, theirs), daemon=True)
            proc.start()
            theirs.close()
            del theirs
            procs.append((proc, mine))


def _forked(state: _State, tick: Callable[[], None]) -> None:
    _preload(state)
    procs: list = []
    try:
        _start(state, 2, procs)
        _dispatch(state, procs, tick)
        for _, conn in procs:
            conn.send(None)
    finally:
        stop_workers(procs)
        if state.folder is not None:
            remove_stale_temporaries(state.folder)


def _dispatch(state: _State, procs: list, tick: Callable[[], None]) -> None:
    """Hand out tasks to idle workers, costliest first, until every stage is finished."""
    queue: list[_Task] = []
    held: list[set[str]] = [set() for _ in procs]
    busy: dict[int, _Task] = {}
    conns = [conn for _, conn in procs]
    while True:
        for stage in state.ready():
            queue += _tasks_of(state, stage)
        queue.sort(key=lambda t: -t.cost)
        for w in range(len(procs)):
            if w not in busy and queue:
                task = queue.pop(0)
                needs = [n for n in task.stage.needs if n in state.values and n not in held[w]]
                send = {n: state.values[n] for n in needs} if task.work is None else {}
                held[w].update(send)
                conns[w].send((task.stage.name, task.index, task.work, task.plan, task.parts,
                               send))
                busy[w] = task
        if not busy:
            return
        check()  # an interruption a library dropped stops the dispatch here
        for ready in multiprocessing.connection.wait([conns[w] for w in busy]):
            w = conns.index(ready)
            try:
                kind, payload = conns[w].recv()
            except EOFError:
                raise BackendError(f"a worker process ended with exit code "
                                   f"{procs[w][0].exitcode}") from None
            if kind == "error":
                raise payload
            queue += _record(state, busy.pop(w), *payload)
            tick()


def _preload(state: _State) -> None:
    """Load before the fork what more than one stage uses (:attr:`Stage.uses`): once, not
    once in each worker."""
    counts = Counter(u for s in state.stages for u in s.uses)
    for group in (g for g, n in counts.items() if n >= 2):
        for module in PRELOAD[group]:
            importlib.import_module(module)
        if group == "kernels":  # the compiled sweep kernels and the spec's flank table
            try:
                sweep(state.spec, state.spec.design_misalignment_deg, [0.0])
            except GearCouplingError:  # the stages report it
                pass


#: the modules each library group of :attr:`Stage.uses` loads
PRELOAD: dict[str, tuple[str, ...]] = {
    "figures": ("matplotlib.backends.backend_agg", "matplotlib.figure"),
    "meshes": ("trimesh", "gearcoupling.parts"),
    "loads": ("gearcoupling.loading",),
    "kernels": ("gearcoupling.clearance",)}
