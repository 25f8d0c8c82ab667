"""The record of one pipeline stage, what a stage receives, and the results of a run.

A :class:`Stage` says what it computes, from which stages, which files it writes and what
it costs; :data:`~gearcoupling.outputs.registry.STAGES` holds them all, as
:data:`~gearcoupling.export.WRITERS` holds the file formats. Its functions are named
``"module:function"`` in :mod:`gearcoupling.outputs` and imported only when the stage
runs, so a process loads the libraries of the stages it runs and no others.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol, TypeVar

from ..errors import GearCouplingError
from ..spec import CouplingSpec
from .settings import OperatingPoint, StageSettings

R = TypeVar("R")

#: where a stage runs (:attr:`Stage.level`): in each engagement's scope, once for the whole
#: spec, only for a single engagement, only for the whole of a double-engagement coupling
LEVELS = ("mesh", "spec", "single", "whole")


def key_of(scope: str, name: str) -> str:
    """The key of stage ``name``'s result in ``scope``: its name at the root (``""``),
    ``scope/name`` in a mesh's scope."""
    return f"{scope}/{name}" if scope else name


class SkipStage(GearCouplingError):
    """A stage that does not apply to this spec or these settings (no torque for the loads,
    no scan to inspect); the stages that do not need it still run."""


@dataclass(frozen=True)
class Stage:
    """One stage of the pipeline.

    Attributes
    ----------
    name : str
        Its key (``gearcoupling run --only``, ``run_summary.json``).
    what : str
        What it computes, in a few words.
    needs : tuple of str
        The stages whose results it takes.
    compute : str or callable
        ``"module:function"`` (of :mod:`gearcoupling.outputs`, imported when it runs) or
        the function itself: ``function(inputs) -> result`` (a frozen dataclass); for a
        ``parallel`` stage ``function(inputs) -> Plan``, its parts and how they combine.
    files : str, callable or None
        ``"module:function"`` or the function itself: ``function(result, inputs,
        folder) -> list[Path]``, the files it writes (None: it writes none).
    cost : float
        CPU seconds on renzo-1967 with the default settings: what the workers balance
        and what the progress bar counts.
    parallel : bool
        Whether ``compute`` only plans (:class:`Plan`, made in the parent once the needs
        are done: it must be cheap): its tasks run in parallel, then combine.
    uses : tuple of str
        Libraries it loads (``"figures"``, ``"meshes"``, ``"kernels"``, ``"loads"``): those
        that more than one stage of a run uses are loaded before the workers start.
    after : tuple of str
        Stages that must have written their files first where both run (their results are
        not passed).
    writes : tuple of str
        The names of the files it may write (:mod:`~gearcoupling.outputs.files`): checked
        before any stage runs.
    level : str
        One of :data:`LEVELS`. ``mesh``: the analysis of one engagement at its operating
        point, run once per mesh of a double-engagement coupling (``mesh-a/``,
        ``mesh-b/``); ``spec``: once, of the spec (hub A and the sleeve); ``single``: a
        single engagement's only; ``whole``: the whole of a double-engagement coupling's
        only, reading both meshes' results (:mod:`~gearcoupling.outputs.executor`).
    """

    name: str
    what: str
    needs: tuple[str, ...]
    compute: str | Callable[[StageInputs], Any]
    files: str | Callable[[Any, StageInputs, Path], list[Path]] | None
    cost: float
    parallel: bool = False
    uses: tuple[str, ...] = ()
    after: tuple[str, ...] = ()
    writes: tuple[str, ...] = ()
    level: str = "mesh"

    def run(self, inputs: StageInputs) -> Any:
        """The stage's result, or its :class:`Plan` where it is :attr:`parallel`."""
        return function(self.compute)(inputs)

    def write(self, result: Any, inputs: StageInputs, folder: Path) -> list[Path]:
        """The stage's files for ``result`` in ``folder``."""
        return [] if self.files is None else list(function(self.files)(result, inputs, folder))


class Plan(Protocol):
    """The work of a :attr:`Stage.parallel` stage: :attr:`tasks` (picklable callables of
    no arguments, run in any process and order) and how their values, in the order of the
    tasks, make the result."""

    @property
    def tasks(self) -> Sequence[Callable[[], Any]]: ...

    def combine(self, values: Sequence[Any]) -> Any: ...


def function(ref: str | Callable[..., Any]) -> Callable[..., Any]:
    """The function ``"module:name"`` of :mod:`gearcoupling.outputs`, imported now (a
    callable as it is)."""
    if callable(ref):
        return ref
    module, _, name = ref.partition(":")
    return getattr(importlib.import_module(f"{__package__}.{module}"), name)


@dataclass(frozen=True)
class Results:
    """The results of the stages computed so far, by stage name; each read with the type
    it must have (:meth:`get`)."""

    values: Mapping[str, Any] = field(default_factory=dict)
    files: Mapping[str, tuple[Path, ...]] = field(default_factory=dict)
    seconds: Mapping[str, float] = field(default_factory=dict)
    skipped: Mapping[str, str] = field(default_factory=dict)

    def get(self, name: str, kind: type[R]) -> R:
        """The result of stage ``name``, checked to be a ``kind``."""
        value = self.values[name]
        if not isinstance(value, kind):
            raise TypeError(f"stage {name!r} gave a {type(value).__name__}, not a "
                            f"{kind.__name__}")
        return value

    def has(self, name: str) -> bool:
        """Whether stage ``name`` was computed (not skipped)."""
        return name in self.values

    def all_files(self, order: Sequence[str]) -> list[Path]:
        """The files of the stages ``order``, in that order."""
        return [p for name in order for p in self.files.get(name, ())]

    def scope(self, scope: str) -> Results:
        """The results as a job in ``scope`` sees them: the scope's own (``mesh-a/sweep``
        read as ``sweep``) and the root's; all of them at the root (``""``)."""
        if not scope:
            return self
        prefix = f"{scope}/"

        def own(data: Mapping[str, Any]) -> dict[str, Any]:
            return {**{k: v for k, v in data.items() if "/" not in k},
                    **{k[len(prefix):]: v for k, v in data.items() if k.startswith(prefix)}}

        return Results(own(self.values), own(self.files), own(self.seconds),
                       own(self.skipped))


@dataclass(frozen=True)
class StageInputs:
    """What a stage receives: the spec, the settings resolved against it, and the results
    of the stages it needs."""

    spec: CouplingSpec
    settings: StageSettings
    point: OperatingPoint
    results: Results

    def get(self, name: str, kind: type[R]) -> R:
        """The result of the needed stage ``name`` (:meth:`Results.get`)."""
        return self.results.get(name, kind)
