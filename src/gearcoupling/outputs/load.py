"""``load.csv``, ``load_summary.json`` and the load plots, with the misalignment studies
(Wei Figs. 12-13, Renzo's q-graph)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, sweep
from ..io import plot_text, write_json
from ..loading import (
    LoadResult,
    load_from_sweep,
    plot_patches,
    plot_q_graph,
    plot_tooth_load,
    plot_vs_misalignment,
    resolve_torque_Nm,
    turn_phases,
)
from ..plots import save_figure
from ..spec import CouplingSpec
from .load_stages import load_study, q_points
from .sweep import turn_angles


def load_studies(spec: CouplingSpec, torque_Nm: float, model: str | None, out: Path, *,
                 progress: Callable[[int, int], None] | None = None) -> list[Path]:
    """Wei Figs. 12-13 and Renzo's q-graph (Fig. 12) for the spec, over one tooth pitch
    (the stages :func:`load_study` and :func:`q_points`); ``progress(done, total)`` after
    each misalignment."""
    study = load_study(spec, torque_Nm, model, progress=progress)
    mis = study.misalignments_deg
    label = model or spec.load.model
    paths = [
        save_figure(plot_vs_misalignment(mis, dict(study.peak_N), "max tooth load P (N)",
                                         f"{plot_text(spec.name)}: {label}, max tooth load"),
                    out / "load_max_vs_misalignment.png"),
        save_figure(plot_vs_misalignment(mis, dict(study.moment_Nm),
                                         "additional (tilting) moment (N·m)",
                                         f"{plot_text(spec.name)}: {label}, mean over the turn"),
                    out / "load_moment_vs_misalignment.png"),
    ]
    pts = q_points(spec)
    if pts:
        title = (f"{plot_text(spec.name)}: load proportion q against z_c / z0 (Renzo Fig. 12)\n"
                 "points: the linear model's tooth-load capacity on the exact geometry, "
                 f"{mis[0]:.2g}-{mis[-1]:.2g}°")
        paths.append(save_figure(plot_q_graph({"linear model, exact geometry":
                                               [(p.zc_over_z0, p.q_linear) for p in pts]},
                                              title=title), out / "load_q_graph.png"))
    return paths


def write_load(spec: CouplingSpec, out: Path, misalignment_deg: float,
               angles: int | None = None, *,
               torque_Nm: float | None = None, model: str | None = None,
               tolerance_mm: float = GAP_TOLERANCE_MM, plots: bool = True,
               with_studies: bool = True,
               swept: SweepResult | None = None,
               progress: Callable[[int, int], None] | None = None
               ) -> tuple[LoadResult, list[Path]]:
    """The loaded analysis over ``angles`` rotations of a turn (default
    :data:`~gearcoupling.loading.PHASES` per tooth pitch, a turn of as many distinct poses):
    ``load.csv``, ``load_summary.json`` and plots. ``swept``: a sweep of this spec at these
    rotations and misalignment to reuse (else one is made); ``progress(done, total)`` as
    the surface model and the studies go. Returns the loads and the paths."""
    torque = resolve_torque_Nm(spec, torque_Nm)  # once, before any work
    if swept is None:
        a = turn_phases(spec) if angles is None else turn_angles(angles)
        swept = sweep(spec, misalignment_deg, a, tolerance_mm=tolerance_mm)
    res = load_from_sweep(swept, torque_Nm=torque, model=model, progress=progress)
    summary = res.summary()
    paths = [res.write_csv(out / "load.csv"), write_json(out / "load_summary.json", summary)]
    if plots:
        paths.append(save_figure(plot_tooth_load(res), out / "load_tooth_load.png"))
        paths.append(save_figure(plot_patches(res), out / "load_patches.png"))
        if with_studies:
            paths += load_studies(spec, torque, model, out,
                                  progress=progress)
    return res, paths
