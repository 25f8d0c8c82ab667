"""The manufacturing stages: ``hob`` (the hob centre path and its G-code:
``hob_program.nc``, ``hob_path.csv``, ``hob.json``, ``hob_path.png``) and ``charts``
(nominal measuring charts: ``charts.png``, ``nominal_traces.csv``, ``charts.json``)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..hob import (
    HobProgram,
    MeasuringCharts,
    hob_program,
    measuring_charts,
    plot_measuring_charts,
    write_nominal_csv,
)
from ..io import plot_text, write_csv_records, write_json, write_text
from ..plots import fixed_layout, new_figure, save_figure
from ..spec import CouplingSpec
from .stage import StageInputs


@dataclass(frozen=True)
class Hob:
    """The hob program; ``illustrative`` where no hob diameter was given (then
    ``max(50, 20 module)`` mm)."""

    program: HobProgram
    illustrative: bool


def illustrative_diameter_mm(spec: CouplingSpec) -> float:
    """The hob outside diameter used where none is given: ``max(50, 20 module)`` mm."""
    return float(round(max(50.0, 20.0 * spec.tooth.module)))


def hob(inputs: StageInputs) -> Hob:
    """The stage ``hob``."""
    D = inputs.settings.hob_diameter_mm
    return Hob(hob_program(inputs.spec, D or illustrative_diameter_mm(inputs.spec)), D is None)


def hob_files(result: Hob, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``hob``'s files (:func:`program_files`) and the path's picture."""
    return [*program_files(result.program, folder),
            save_figure(plot_hob_path(result.program), folder / "hob_path.png",
                        inputs.settings.dpi)]


def program_files(prog: HobProgram, folder: Path, feed_mm_per_rev: float = 1.0
                  ) -> list[Path]:
    """``hob_path.csv``, ``hob_program.nc`` and ``hob.json`` (the summary with the files)."""
    files = [write_csv_records(folder / "hob_path.csv", prog.rows(),
                               [f"hob centre path for {prog.spec_name}; mm and degrees; x = "
                                "centre distance from the hub axis, z = axial, infeed = x(0) "
                                "- x"]),
             write_text(folder / "hob_program.nc", prog.gcode(feed_mm_per_rev))]
    return [*files, write_json(folder / "hob.json", {**prog.summary(),
                                                     "files": [str(f) for f in files]})]


def plot_hob_path(prog: HobProgram):
    """The hob centre's infeed from the midplane against its axial position."""
    fig, ax = new_figure(figsize=(9, 3.6))
    fixed_layout(fig, 0.7, 0.05, 0.48, 0.24)
    ax.plot(prog.table["z_mm"], prog.table["infeed_mm"] * 1e3, "-")
    ax.set_xlabel("hob centre Z (mm)")
    ax.set_ylabel("infeed from the midplane (µm)")
    ax.invert_yaxis()
    ax.grid(alpha=0.3)
    ax.set_title(f"{plot_text(prog.spec_name)}: hob centre path, {prog.crown_kind} crown, hob Ø "
                 f"{prog.hob_diameter_mm:g} mm", fontsize=10)
    return fig


def charts(inputs: StageInputs) -> MeasuringCharts:
    """The stage ``charts``: 101 points a trace, tip exclusion 8 %."""
    return measuring_charts(inputs.spec)


def charts_files(result: MeasuringCharts, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``charts``'s files (:func:`chart_files`)."""
    return chart_files(result, folder, inputs.settings.dpi)


def chart_files(result: MeasuringCharts, folder: Path, dpi: int = 130) -> list[Path]:
    """``charts.png``, ``nominal_traces.csv`` and ``charts.json`` (the summary with the
    files)."""
    files = [save_figure(plot_measuring_charts(result), folder / "charts.png", dpi),
             write_nominal_csv(result, folder / "nominal_traces.csv")]
    return [*files, write_json(folder / "charts.json", {**result.summary(),
                                                        "files": [str(f) for f in files]})]
