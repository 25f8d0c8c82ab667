"""Manufacturing: hob feed programs and measuring-machine charts (geometry level).

Pure numpy kernels over the feed path and the exact hub flank; writers and plots import
matplotlib lazily.
"""

from .charts import (
    MeasuringCharts,
    Trace,
    evaluation_ranges,
    measuring_charts,
    plot_measuring_charts,
    write_nominal_csv,
)
from .program import (
    FEED_RANGE_MM_PER_REV,
    MAX_HOB_DIAMETER_MM,
    HobProgram,
    Move,
    check_hob_diameter,
    hob_program,
)

__all__ = [
    "FEED_RANGE_MM_PER_REV",
    "MAX_HOB_DIAMETER_MM",
    "HobProgram",
    "MeasuringCharts",
    "Move",
    "Trace",
    "check_hob_diameter",
    "evaluation_ranges",
    "hob_program",
    "measuring_charts",
    "plot_measuring_charts",
    "write_nominal_csv",
]
