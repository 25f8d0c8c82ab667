"""The stage ``inspection``: a measured hub against the nominal (``inspection.csv``,
``inspection.png``, ``deviation_map.png``); skipped without a scan."""

from __future__ import annotations

from pathlib import Path

from ..inspection import InspectionReport, compare_part, plot_deviation_map, plot_inspection
from ..io import write_csv_records
from ..plots import save_figure
from .stage import SkipStage, StageInputs


def inspect(inputs: StageInputs) -> InspectionReport:
    """The stage ``inspection``: the settings' scan, limits and class."""
    s = inputs.settings
    if s.scan is None:
        raise SkipStage("no scan given (--scan FILE)")
    return compare_part(inputs.spec, s.scan, units=s.scan_units, limits=s.limits,
                        grade=s.grade, fit_points=s.fit_points)


def files(rep: InspectionReport, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``inspection``'s data and pictures."""
    dpi = inputs.settings.dpi
    return [write_csv_records(folder / "inspection.csv", rep.rows(),
                              ["lengths in mm, + = material excess / toward increasing "
                               "polar angle"]),
            save_figure(plot_inspection(rep), folder / "inspection.png", dpi),
            save_figure(plot_deviation_map(rep), folder / "deviation_map.png", dpi)]
