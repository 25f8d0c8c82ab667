"""The files gearcoupling writes: one writer per stage and :func:`run`, the pipeline of
``gearcoupling run`` (every file the project can make for a spec, into one folder).

Each writer validates before it writes (no NaN, no half-written file) and returns the
paths it wrote; the commands only parse their options, call these and print.
"""

from .interference import write_interference
from .load import load_studies, write_load
from .parts import PART_NAMES, write_parts, write_step_files
from .pipeline import STEPS, RunResult, SkipStep, run
from .spec import resolved_spec, write_spec
from .stages import (
    LoadStudy,
    QPoint,
    backlash_grid,
    backlash_range_deg,
    design_point,
    load_study,
    q_points,
    study_misalignments,
    turn_sweep,
)
from .sweep import write_sweep

__all__ = [
    "PART_NAMES",
    "STEPS",
    "LoadStudy",
    "QPoint",
    "RunResult",
    "SkipStep",
    "backlash_grid",
    "backlash_range_deg",
    "design_point",
    "load_studies",
    "load_study",
    "q_points",
    "resolved_spec",
    "run",
    "study_misalignments",
    "turn_sweep",
    "write_interference",
    "write_load",
    "write_parts",
    "write_spec",
    "write_step_files",
    "write_sweep",
]
