"""Design studies on dask.distributed: study files, sampled parameters, Parquet tables
(``gearcoupling study FILE``), tolerance Monte Carlo and crown optimisation.

dask and pyarrow are imported at the call that needs them (``pip install
'gearcoupling[study]'``).
"""

from .evaluate import evaluate
from .file import Parameter, Study, load_study, optimise_options, samples, spec_hash, study_names
from .optimise import (
    compare_curves,
    optimise_crown,
    plot_capacity_curves,
    write_rows,
)
from .plots import plot_k_histogram, study_plots
from .runner import MAX_WORKERS, StudyRun, chunks, read_table, run_study, scheduler_address
from .tolerance import summarise_rows

__all__ = [
    "MAX_WORKERS",
    "Parameter",
    "Study",
    "StudyRun",
    "chunks",
    "compare_curves",
    "evaluate",
    "load_study",
    "optimise_crown",
    "optimise_options",
    "plot_capacity_curves",
    "plot_k_histogram",
    "read_table",
    "run_study",
    "samples",
    "scheduler_address",
    "spec_hash",
    "study_names",
    "study_plots",
    "summarise_rows",
    "write_rows",
]
