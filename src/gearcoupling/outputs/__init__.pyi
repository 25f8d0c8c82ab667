# The names of gearcoupling.outputs, read by type checkers and, at run time, by
# lazy_loader.attach_stub: each writer's module is imported on first use, so the
# pipeline's parent process loads only what every step needs (gearcoupling.run).
from .interference import write_check as write_check
from .interference import write_interference as write_interference
from .load import load_studies as load_studies
from .load import write_load as write_load
from .load_stages import LoadStudy as LoadStudy
from .load_stages import QPoint as QPoint
from .load_stages import load_study as load_study
from .load_stages import q_points as q_points
from .parts import PART_NAMES as PART_NAMES
from .parts import write_parts as write_parts
from .parts import write_step_files as write_step_files
from .pipeline import STEPS as STEPS
from .pipeline import RunResult as RunResult
from .pipeline import SkipStep as SkipStep
from .pipeline import run as run
from .spec import resolved_spec as resolved_spec
from .spec import write_spec as write_spec
from .stages import backlash_grid as backlash_grid
from .stages import backlash_range_deg as backlash_range_deg
from .stages import design_point as design_point
from .stages import study_misalignments as study_misalignments
from .stages import turn_sweep as turn_sweep
from .sweep import write_sweep as write_sweep
from .viewer import write_viewer as write_viewer
