"""Wear over life: Archard wear of the hub and sleeve flanks under the surface model's
pressure, the loads solved again on the worn flanks, the life to the wear limit
(docs/wear.md)."""

from .api import wear
from .coefficients import DEFAULT_REGIME, REGIMES, Regime
from .files import (
    write_depth_csv,
    write_wear,
    write_wear_csv,
    write_wear_plots,
    write_wear_summary,
)
from .plots import plot_wear_history, plot_wear_maps
from .result import CSV_COLUMNS, DEPTH_COLUMNS, WearResult
from .settings import (
    DEFAULT_PHASES,
    DEFAULT_STEP_FRACTION,
    MAX_PHASES,
    Accuracy,
    DutyPoint,
    WearSettings,
)

__all__ = [
    "CSV_COLUMNS",
    "DEFAULT_PHASES",
    "DEFAULT_REGIME",
    "DEFAULT_STEP_FRACTION",
    "DEPTH_COLUMNS",
    "MAX_PHASES",
    "REGIMES",
    "Accuracy",
    "DutyPoint",
    "Regime",
    "WearResult",
    "WearSettings",
    "plot_wear_history",
    "plot_wear_maps",
    "wear",
    "write_depth_csv",
    "write_wear",
    "write_wear_csv",
    "write_wear_plots",
    "write_wear_summary",
]
