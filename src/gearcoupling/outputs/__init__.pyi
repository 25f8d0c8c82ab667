# The names of gearcoupling.outputs, read by type checkers and, at run time, by
# lazy_loader.attach_stub: each module is imported on first use, so a process loads only
# what the stages it runs need (gearcoupling.run).
from .capacity import CapacityAgainstMisalignment as CapacityAgainstMisalignment
from .capacity import CapacityComparison as CapacityComparison
from .capacity import compare_capacity as compare_capacity
from .capacity import comparison_range as comparison_range
from .executor import compute as compute
from .interference import Check as Check
from .interference import write_interference as write_interference
from .load import LoadStudy as LoadStudy
from .load import QGraph as QGraph
from .load import QPoint as QPoint
from .load import load_studies as load_studies
from .load import load_study as load_study
from .load import q_graph as q_graph
from .load import study_misalignments as study_misalignments
from .load import write_load as write_load
from .parts import PART_NAMES as PART_NAMES
from .parts import write_parts as write_parts
from .parts import write_step_files as write_step_files
from .pipeline import STEPS as STEPS
from .pipeline import RunResult as RunResult
from .pipeline import run as run
from .registry import RUN as RUN
from .registry import STAGES as STAGES
from .settings import StageSettings as StageSettings
from .spec import resolved_spec as resolved_spec
from .spec import write_spec as write_spec
from .stage import Results as Results
from .stage import SkipStage as SkipStage
from .stage import Stage as Stage
from .stage import StageInputs as StageInputs
from .sweep import BacklashCurve as BacklashCurve
from .sweep import DesignPoint as DesignPoint
from .sweep import write_sweep as write_sweep
