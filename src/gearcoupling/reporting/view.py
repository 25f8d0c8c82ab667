"""What a report section is and what its renderer reads."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from ..outputs import OperatingPoint, Results
from ..spec import CouplingSpec
from .document import Block, Figure
from .settings import ReportSettings
from .verdict import Verdict

R = TypeVar("R")


@dataclass(frozen=True)
class View:
    """What a renderer reads: the spec, the settings, the operating point, the stages'
    results and the folder their files are in (the report's own). A mesh's view of a
    double-engagement coupling (``scope`` ``mesh-a``, ``mesh-b``) reads the mesh's spec,
    point, results and folder; its figures link their data in that folder."""

    spec: CouplingSpec
    settings: ReportSettings
    point: OperatingPoint
    results: Results
    folder: Path
    scope: str = ""

    def get(self, name: str, kind: type[R]) -> R | None:
        """The result of stage ``name`` (None where it was skipped)."""
        return self.results.get(name, kind) if self.results.has(name) else None

    def why(self, name: str) -> str:
        """Why stage ``name`` has no result."""
        return self.results.skipped.get(name, "not computed")

    def figure(self, key: str, title: str, png: str, settings: str, data_file: str | None,
               note: str = "") -> Figure:
        """A figure from a stage's picture ``png`` in the folder; ``data_file`` the name of
        its data beside it (linked from the report's folder)."""
        if self.scope:
            key = f"{key}-{self.scope}"
            data_file = None if data_file is None else f"{self.scope}/{data_file}"
        return Figure(key, title, (self.folder / png).read_bytes(), settings, data_file, note)


@dataclass(frozen=True)
class ReportSection:
    """One section of the report.

    Attributes
    ----------
    key, title : str
    stages : tuple of str
        The stages whose results it shows (computed for the report).
    render : callable
        ``render(view) -> list of blocks``.
    verdicts : callable, optional
        ``verdicts(view) -> list of Verdict``: the checks it judges.
    shown : callable
        ``shown(settings) -> bool``: whether the report has it.
    level : str
        Like its stages' (:attr:`gearcoupling.outputs.Stage.level`): ``mesh`` (the
        default: rendered once per mesh of a double-engagement coupling, its title and
        its verdicts saying which), ``spec`` (once), ``single`` (a single engagement's
        only) or ``whole`` (a double-engagement coupling's only).
    asked : callable, optional
        ``asked(settings, spec) -> bool``: whether the spec asks for it (the wear history,
        where ``[wear]`` gives a speed and hours); None: every spec.
    """

    key: str
    title: str
    stages: tuple[str, ...]
    render: Callable[[View], list[Block]]
    verdicts: Callable[[View], list[Verdict]] | None = None
    shown: Callable[[ReportSettings], bool] = lambda s: True
    level: str = "mesh"
    asked: Callable[[ReportSettings, CouplingSpec], bool] | None = None

    def applies(self, settings: ReportSettings, engagements: int,
                spec: CouplingSpec | None = None) -> bool:
        """Whether a report with these settings on a spec of ``engagements`` has it (on
        ``spec`` where given: None counts every section the spec could ask for)."""
        wrong = {1: "whole", 2: "single"}[engagements]
        return self.level != wrong and self.shown(settings) and (
            self.asked is None or spec is None or self.asked(settings, spec))
