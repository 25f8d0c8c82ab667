"""The files of a wear history, one writer per file, each taking the result and a folder
(``wear.csv``, ``wear_depth.csv``, ``wear_summary.json``, ``wear_maps.png``,
``wear_history.png``); every file is written atomically."""

from __future__ import annotations

from pathlib import Path

from ..io import write_csv_columns, write_csv_rows, write_json
from ..plots import save_figure
from .plots import plot_wear_history, plot_wear_maps
from .result import CSV_COLUMNS, DEPTH_COLUMNS, WearResult

_UNITS = "lengths in mm, pressures in MPa, forces in N, torque in N·m, hours at the coefficient"


def write_wear_csv(result: WearResult, folder: str | Path) -> Path:
    """``wear.csv``: a row per state of the history and operating point."""
    return write_csv_rows(Path(folder) / "wear.csv", CSV_COLUMNS, result.rows(),
                          comments=[_UNITS, "depths along the flank normal; thickness loss "
                                    "and backlash as arcs at the pitch circle"], finite=True)


def write_depth_csv(result: WearResult, folder: str | Path) -> Path:
    """``wear_depth.csv``: the final depth of every worn flank on its grid."""
    return write_csv_columns(Path(folder) / "wear_depth.csv", DEPTH_COLUMNS,
                             result.depth_columns(),
                             comments=["depth_mm along the flank normal at the cell centre "
                                       "(z_mm axial, s_mm involute arc from the base circle, "
                                       "r_mm its radius); hub cells in the hub frame, sleeve "
                                       "cells in the sleeve frame; tooth 'all': every tooth"],
                             finite=True)


def write_wear_summary(result: WearResult, folder: str | Path) -> Path:
    """``wear_summary.json``: :meth:`WearResult.summary`."""
    return write_json(Path(folder) / "wear_summary.json", result.summary())


def write_wear_plots(result: WearResult, folder: str | Path, dpi: int = 130) -> list[Path]:
    """``wear_maps.png`` (depth maps and tooth bearing pictures over time) and
    ``wear_history.png`` (backlash, q and pressures against hours), at ``dpi``."""
    folder = Path(folder)
    return [save_figure(plot_wear_maps(result), folder / "wear_maps.png", dpi),
            save_figure(plot_wear_history(result), folder / "wear_history.png", dpi)]


def write_wear(result: WearResult, folder: str | Path, *, plots: bool = True,
               dpi: int = 130) -> list[Path]:
    """Every file of a wear history into ``folder`` (which must exist); their paths."""
    paths = [write_wear_csv(result, folder), write_depth_csv(result, folder),
             write_wear_summary(result, folder)]
    if plots:
        paths += write_wear_plots(result, folder, dpi)
    return paths


__all__ = ["write_depth_csv", "write_wear", "write_wear_csv", "write_wear_plots",
           "write_wear_summary"]
