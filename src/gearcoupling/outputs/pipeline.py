"""``gc.run``: the stages a spec alone gives, their files into one folder
(:data:`~.registry.RUN` by default, any stage of :data:`~.registry.STAGES` on request),
computed once each by :func:`~.executor.compute`."""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, TypeVar

from ..arguments import keywords
from ..errors import ArgumentError
from ..forked import can_fork
from ..io import output_folder, writable_targets, write_json
from ..spec import CouplingSpec, as_spec
from .executor import compute, jobs
from .files import RUN_SUMMARY
from .registry import RUN, STAGES, run_stages
from .settings import MESH_SCOPES, StageSettings
from .stage import Results

#: the stages ``gearcoupling run --only`` takes, each with what it computes
STEPS: dict[str, str] = {name: stage.what for name, stage in STAGES.items()}


@dataclass(frozen=True)
class RunResult:
    """What :func:`run` wrote and computed: the files, each stage's seconds, the skipped
    stages with their reasons (``run_summary.json`` holds the same) and the stages'
    results (:class:`~.stage.Results`)."""

    spec_name: str
    out: Path
    files: tuple[Path, ...]
    seconds: dict[str, float]
    skipped: dict[str, str]
    wall_seconds: float
    workers: int
    results: Results = field(default_factory=Results, repr=False, compare=False)

    def summary(self) -> dict[str, Any]:
        """``run_summary.json``: stages with their seconds and files (relative to the
        folder: a mesh's in ``mesh-a/``, ``mesh-b/``), skipped stages, wall time and
        workers."""
        return {"spec": self.spec_name, "workers": self.workers,
                "wall_seconds": self.wall_seconds, "step_seconds": self.seconds,
                "skipped": self.skipped,
                "files": [p.relative_to(self.out).as_posix() for p in self.files]}


def chosen(only: Iterable[str] | None, skip: Iterable[str], default: Iterable[str] = RUN
           ) -> list[str]:
    """The stages of ``only`` (default ``default``) less those of ``skip``, in the order
    of :data:`STAGES`; unknown names refused."""
    only_set = set(default) if only is None else _names(only, "only")
    skip_set = _names(skip, "skip")
    unknown = (only_set | skip_set) - set(STAGES)
    if unknown:
        raise ArgumentError("steps", ", ".join(sorted(unknown)), "unknown: the stages are "
                            f"{', '.join(STAGES)}")
    return [k for k in STAGES if k in only_set - skip_set]


def _names(value: Any, name: str) -> set[str]:
    """Stage names given as a list (not one string: ``"spec"`` would be four letters)."""
    try:
        names = None if isinstance(value, str | bytes) else list(value)
    except TypeError:
        names = None
    if names is None or not all(isinstance(k, str) for k in names):
        raise ArgumentError(name, value, f"a list of stage names from {', '.join(STAGES)}")
    return set(names)


S = TypeVar("S", bound=StageSettings)


def run_files(only: Iterable[str] | None = None, skip: Iterable[str] = (),
              engagements: int = 1, wear: bool = False) -> list[str]:
    """The files :func:`run` may write with these ``only`` and ``skip`` for a spec of one
    or two ``engagements`` (those of the stages it computes, :attr:`~.stage.Stage.writes`,
    and ``run_summary.json``), each once, in the order of the stages; ``wear``: the spec
    asks for wear (:meth:`~.settings.StageSettings.wear_asked`)."""
    return [*stage_files(chosen(only, skip, run_stages(engagements, wear)), engagements),
            RUN_SUMMARY]


def stage_files(names: Iterable[str], engagements: int = 1) -> list[str]:
    """The files the stages ``names`` and those they need may write, each once: for two
    ``engagements`` a mesh's in its folder (``mesh-a/sweep.csv``, :func:`run_folders`)."""
    meshes = MESH_SCOPES if engagements == 2 else ()
    return list(dict.fromkeys(f"{j.scope}/{f}" if j.scope else f
                              for j in jobs(list(names), meshes) if j.refused is None
                              for f in j.stage.writes))


def run_folders(engagements: int = 1) -> tuple[str, ...]:
    """The folders of their own that :func:`run` and :func:`~gearcoupling.report` make: a
    double-engagement coupling's meshes' (``mesh-a``, ``mesh-b``)."""
    return MESH_SCOPES if engagements == 2 else ()


def settings_from(settings: S | None, options: dict[str, Any], kind: type[S],
                  caller: str) -> S:
    """``settings``, or one made of the keyword ``options`` (names checked)."""
    if settings is not None:
        if not isinstance(settings, kind):
            raise ArgumentError("settings", settings, f"a {kind.__name__}")
        keywords(options, [], caller)
        return settings
    keywords(options, [f.name for f in fields(kind)], caller)
    return kind(**options)


def default_workers(workers: int | None) -> int:
    """``workers`` checked (1 or 2); None: 2 where the machine has two cores."""
    if workers is None:
        return 2 if (os.cpu_count() or 1) >= 2 else 1
    if workers not in (1, 2) or isinstance(workers, bool):
        raise ArgumentError("workers", workers, "1 or 2")
    return workers


def run(spec: CouplingSpec, out: str | os.PathLike, *, only: Iterable[str] | None = None,
        skip: Iterable[str] = (), workers: int | None = None,
        progress: Callable[[int, int], None] | None = None,
        settings: StageSettings | None = None, **options: Any) -> RunResult:
    """Write everything the project can make for ``spec`` into the folder ``out``.

    Parameters
    ----------
    spec : CouplingSpec
    out : path-like
        Output folder (created; refused if it holds a device, pipe or socket, see
        :func:`~gearcoupling.io.output_folder`, or anything but a regular file where a
        stage writes one, :func:`run_files`: before any stage runs).
    only, skip : iterable of str
        Stages of :data:`STEPS` to run (default :data:`~.registry.RUN`, for a
        double-engagement spec also :data:`~.registry.RUN_WHOLE`, and the stage ``wear``
        where the spec's ``[wear]`` or the settings give a speed and hours), or to leave
        out; the stages they need are computed too. A double-engagement spec's mesh-level
        stages run for each mesh, their files in ``mesh-a/`` and ``mesh-b/``
        (docs/coupling.md).
    workers : int, optional
        1 runs every stage in this process; 2 (the default where the machine has two
        cores and this process runs no other thread) runs them in two forked processes
        while this one hands them out. Interrupted (``KeyboardInterrupt`` or any other
        exception), the workers are killed first: no file is written after it.
    progress : callable, optional
        ``progress(done, total)`` as stages finish (tenths of their expected seconds).
    settings : StageSettings, optional
        The operating point and accuracy knobs; or give them as keyword arguments
        (``misalignment_deg``, ``torque_Nm``, ``angles``, ...; for a double-engagement
        spec ``offset_mm``, ``shaft_angle_deg`` and their azimuths).

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
    engagements = spec.coupling.engagements
    s = settings_from(settings, options, StageSettings, "run")
    wear = s.wear_asked(spec)
    keys = chosen(only, skip, run_stages(engagements, wear))
    writable_targets(out, run_files(only, skip, engagements, wear), run_folders(engagements),
                     field="out")
    s.resolve(spec)
    n = default_workers(workers)
    folder = output_folder(out, "out")
    planned = jobs(keys, run_folders(engagements))
    t0 = time.perf_counter()
    results = compute(spec, s, keys, folder=folder, workers=n, progress=progress)
    used = 2 if n == 2 and len(planned) >= 2 and can_fork() else 1
    files = results.all_files([j.key for j in planned])
    result = RunResult(spec.name, folder, tuple(files), dict(results.seconds),
                       dict(results.skipped), time.perf_counter() - t0, used, results)
    summary = write_json(folder / RUN_SUMMARY, result.summary())
    return RunResult(result.spec_name, folder, (*files, summary), result.seconds,
                     result.skipped, result.wall_seconds, result.workers, results)
