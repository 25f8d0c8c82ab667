"""Design studies on dask.distributed: study files, sampled parameters, Parquet tables
(``gearcoupling study FILE``), tolerance Monte Carlo and crown optimisation.

dask and pyarrow are imported at the call that needs them (``pip install
'gearcoupling[study]'``).
"""

from .evaluate import evaluate, spec_hash
from .file import Parameter, Study, load_study, samples, study_names
from .runner import StudyRun, read_table, run_study

__all__ = ["Parameter", "Study", "StudyRun", "evaluate", "load_study", "read_table",
           "run_study", "samples", "spec_hash", "study_names"]
