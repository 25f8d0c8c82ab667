"""Compute stages: each once per scope, in an order their needs allow, over two forked
workers where the machine has two cores.

A single engagement has one scope, the root: every stage runs once and its result is
keyed by its name. A double-engagement coupling (docs/coupling.md) has a scope per mesh
(``mesh-a``, ``mesh-b``: :class:`~.settings.Scope`): each mesh-level stage
(:attr:`Stage.level`) runs once in each, on the mesh's spec at its angle, torque and
rotation phase, its files in the scope's folder and its result keyed ``mesh-a/sweep``; the
whole coupling's stages run at the root and read both meshes' results. The parent hands a
worker a job whose needs are done (the costliest first), with the results of those needs
that the worker does not hold yet; the worker computes it, writes its files and sends the
result back. A parallel stage (:attr:`Stage.parallel`) is cut into parts in the parent
once its needs are done (its :class:`~.stage.Plan`); the parts go to the workers like
stages, and a last task combines their values. Nothing is kept between calls: the results
of one call are its return value.
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
from .settings import ROOT, Scope, StageSettings
from .stage import Plan, Results, SkipStage, Stage, StageInputs, key_of

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


@dataclass(frozen=True)
class Job:
    """A stage in a scope: its result's ``key`` (``sweep``, ``mesh-a/sweep``), the keys of
    the results it needs and of the jobs that write first, and why it does not apply
    (None: it does)."""

    key: str
    scope: str
    stage: Stage
    needs: tuple[str, ...]
    after: tuple[str, ...]
    refused: str | None = None


#: why a stage of a level does not apply to one engagement or to two
NOT_FOR = {("whole", 1): "a single engagement has no floating member ([coupling] "
                         "engagements = 2)",
           ("single", 2): "a double-engagement coupling: its data sheet is the stage "
                          "whole_datasheet"}


def jobs(names: Sequence[str], meshes: Sequence[str] = ()) -> list[Job]:
    """The jobs of the stages ``names`` and those they need (:func:`plan`): each stage
    once at the root, but a mesh-level stage once in each of ``meshes`` (the scopes of a
    double-engagement coupling; none: a single engagement)."""
    out = []
    engagements = 2 if meshes else 1
    for stage in plan(names):
        for scope in meshes if meshes and stage.level == "mesh" else (ROOT,):
            out.append(Job(key_of(scope, stage.name), scope, stage,
                           _keys(stage.needs, scope, meshes), _keys(stage.after, scope, meshes),
                           NOT_FOR.get((stage.level, engagements))))
    return out


def _keys(names: Sequence[str], scope: str, meshes: Sequence[str]) -> tuple[str, ...]:
    """The keys of the stages ``names`` a job in ``scope`` reads: a mesh-level stage in
    its own scope, or in every mesh from the root."""
    out: list[str] = []
    for name in names:
        mesh = meshes and registry.STAGES[name].level == "mesh"
        out += [key_of(s, name) for s in ((scope,) if scope else meshes)] if mesh else [name]
    return tuple(out)


@dataclass
class _Task:
    """A job to run; for a parallel stage one of its plan's tasks (``index``, ``work``)
    or the combination of their values (``plan``, ``parts``)."""

    job: Job
    cost: float
    index: int | None = None
    work: Callable[[], Any] | None = None
    plan: Plan | None = None
    parts: list[Any] | None = None


@dataclass
class _State:
    """The parent's book of a computation (keyed by the jobs' keys)."""

    spec: CouplingSpec
    settings: StageSettings
    folder: Path | None
    scopes: dict[str, Scope]
    stages: list[Job]
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

    def inputs(self, job: Job, results: Results | None = None) -> StageInputs:
        return _inputs(self.scopes, self.settings, job, results or self.results())

    @property
    def planned(self) -> set[str]:
        return {j.key for j in self.stages}

    def finished(self, key: str) -> bool:
        return key in self.values or key in self.skipped

    def ready(self) -> list[Job]:
        """Jobs not started whose needs are finished; a job whose need was skipped, or
        that does not apply, is skipped (said so) instead."""
        out = []
        for j in self.stages:
            if j.key in self.started or not all(
                    self.finished(n) for n in j.needs + j.after
                    if n in self.planned or n in j.needs):
                continue
            missing = [n for n in j.needs if n in self.skipped]
            if j.refused is not None:
                self.started.add(j.key)
                self.skipped[j.key] = j.refused
            elif missing:
                self.started.add(j.key)
                self.skipped[j.key] = f"needs {missing[0]}: {self.skipped[missing[0]]}"
            else:
                out.append(j)
        return out


def _inputs(scopes: dict[str, Scope], settings: StageSettings, job: Job,
            results: Results) -> StageInputs:
    """What ``job`` receives: its scope's spec and operating point, the results seen from
    its scope."""
    scope = scopes[job.scope]
    return StageInputs(scope.spec, settings, scope.point, results.scope(job.scope))


def _folder(folder: Path | None, job: Job) -> Path | None:
    """Where ``job`` writes: the scope's folder in ``folder``."""
    return folder / job.scope if folder is not None and job.scope else folder


def _run_task(task: _Task, inputs: StageInputs, folder: Path | None
              ) -> tuple[str, Any, tuple[Path, ...], float]:
    """Run ``task``: ``(kind, value, files, seconds)`` with kind ``"part"``, ``"done"`` or
    ``"skipped"`` (value the reason)."""
    t0 = time.perf_counter()
    if task.work is not None:
        return "part", task.work(), (), time.perf_counter() - t0
    stage = task.job.stage
    try:
        value = stage.run(inputs) if task.plan is None else task.plan.combine(task.parts or [])
        files = () if folder is None else tuple(stage.write(value, inputs, folder))
    except (BackendError, SkipStage) as err:  # an extra missing, or it does not apply
        return "skipped", str(err), (), time.perf_counter() - t0
    return "done", value, files, time.perf_counter() - t0


def _tasks_of(state: _State, job: Job) -> list[_Task]:
    """The tasks of a ready job: itself, or its plan's tasks (none: combined at once).
    A plan that is refused skips the job."""
    state.started.add(job.key)
    stage = job.stage
    if not stage.parallel:
        return [_Task(job, stage.cost)]
    try:
        plan = stage.run(state.inputs(job))
    except (BackendError, SkipStage) as err:
        state.skipped[job.key] = str(err)
        return []
    work = list(plan.tasks)
    if not work:
        return [_Task(job, 0.0, plan=plan, parts=[])]
    state.plans[job.key] = plan
    state.parts[job.key] = [None] * len(work)
    state.waiting[job.key] = len(work)
    return [_Task(job, stage.cost / len(work), i, w) for i, w in enumerate(work)]


def _record(state: _State, task: _Task, kind: str, value: Any, files: tuple[Path, ...],
            seconds: float) -> list[_Task]:
    """Book a finished task; returns the combining task of a job whose parts are all
    done."""
    name = task.job.key
    state.done_units += task.cost
    state.seconds[name] = state.seconds.get(name, 0.0) + seconds
    if kind == "part":
        assert task.index is not None
        state.parts[name][task.index] = value
        state.waiting[name] -= 1
        if state.waiting[name] == 0:
            return [_Task(task.job, 0.0, plan=state.plans.pop(name),
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
    written into ``folder`` (None: none written); for a double-engagement ``spec`` the
    mesh-level stages once per mesh (:func:`jobs`), their files in the folder's ``mesh-a``
    and ``mesh-b`` (made here).

    ``workers`` 2 runs the stages in two forked processes where forking is safe
    (:func:`~gearcoupling.forked.can_fork`), this one handing them out and waiting; any
    exception here (a stage's error, ``KeyboardInterrupt``, the CLI's signal) kills and
    reaps them before it propagates, so no file is written after it. ``progress(done,
    total)`` in tenths of the stages' expected CPU seconds. ``written``: a list that each
    file is added to as it is written (what an interrupted computation left)."""
    scopes = settings.scopes(spec)
    meshes = tuple(k for k in scopes if k != ROOT)
    out = None if folder is None else Path(folder)
    state = _State(spec, settings, out, scopes, jobs(names, meshes))
    if written is not None:
        state.written = written
    if out is not None:
        for mesh in meshes:
            (out / mesh).mkdir(exist_ok=True)
    total = max(1, round(10 * sum(j.stage.cost for j in state.stages)))

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
        queue += _record(state, task, *_run_task(task, state.inputs(task.job),
                                                 _folder(state.folder, task.job)))
        tick()


# ---------------------------------------------------------------- forked workers


def _worker(state: _State, conn) -> None:
    """A forked worker: run each task it is sent (a job by key, with the results it
    needs, or a plan's task), and send back what it found (or the error that stopped it)."""
    worker_signals()
    held: dict[str, Any] = {}
    by_key = {j.key: j for j in state.stages}
    try:
        while True:
            message = conn.recv()
            if message is None:
                return
            key, index, work, plan, parts, values = message
            held.update(values)
            job = by_key[key]
            inputs = _inputs(state.scopes, state.settings, job, Results(dict(held)))
            task = _Task(job, 0.0, index, work, plan, parts)
            conn.send(("ok", _run_task(task, inputs, _folder(state.folder, job))))
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
            proc = ctx.Process(target=_worker, args=(state, theirs), daemon=True)
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
                needs = [n for n in task.job.needs if n in state.values and n not in held[w]]
                send = {n: state.values[n] for n in needs} if task.work is None else {}
                held[w].update(send)
                conns[w].send((task.job.key, task.index, task.work, task.plan, task.parts,
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
    counts = Counter(u for j in state.stages for u in j.stage.uses)
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
