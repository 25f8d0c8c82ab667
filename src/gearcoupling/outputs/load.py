"""``load.csv``, ``load_summary.json`` and the load plots, with the misalignment studies
(Wei Figs. 12-13, Renzo's q-graph)."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, sweep
from ..geometry import renzo_z0_mm
from ..io import write_json
from ..loading import (
    LOAD_GRID,
    capacity_from_sweep,
    default_angles,
    load_from_sweep,
    load_model,
    plot_patches,
    plot_q_graph,
    plot_tooth_load,
    plot_vs_misalignment,
    resolve_model,
    resolve_torque_Nm,
    turn_phases,
)
from ..plots import save_figure
from ..spec import CouplingSpec
from .sweep import turn_angles


def study_misalignments(spec: CouplingSpec, count: int = 7) -> np.ndarray:
    """Misalignments of the studies: 0 to the design angle (at least 0.5°), 0 left out."""
    top = max(math.degrees(spec.design_misalignment), 0.5)
    return np.linspace(top / count, top, count)


def load_studies(spec: CouplingSpec, torque_Nm: float, model: str | None, out: Path, *,
                 progress: Callable[[int, int], None] | None = None) -> list[Path]:
    """Wei Figs. 12-13 and Renzo's q-graph (Fig. 12) for the spec, over one tooth pitch;
    ``progress(done, total)`` after each misalignment."""
    mis = study_misalignments(spec)
    torques = [0.5 * torque_Nm, torque_Nm, 2.0 * torque_Nm]
    # one curve per factor, also where the torques coincide (0 N·m: three flat curves)
    labels = [f"{f} = {t:.4g} N·m" for f, t in zip(("T/2", "T", "2T"), torques, strict=True)]
    peak: dict[str, list[float]] = {k: [] for k in labels}
    moment: dict[str, list[float]] = {k: [] for k in labels}
    q_pts: list[tuple[float, float]] = []
    ld = spec.load
    m = load_model(resolve_model(spec, model))
    grid = LOAD_GRID if m.pressure_grid else None  # the load criteria's grid of capacity
    for n, i in enumerate(mis):
        sw = sweep(spec, float(i), default_angles(spec, None, m.rotations))
        for t, key in zip(torques, peak, strict=True):
            res = load_from_sweep(sw, torque_Nm=t, model=model, pressure_grid=grid)
            peak[key].append(float(np.max(res.tangential_force_N)))
            moment[key].append(res.summary()["tilting_moment_Nm"]["mean"])
        if ld.allowable_tooth_load_N is not None and ld.mesh_stiffness_N_per_mm is not None:
            c = capacity_from_sweep(sw, model="linear")
            rc = spec.derived["crowning_radius_midplane_mm"]
            z0 = renzo_z0_mm(rc, math.radians(i), spec.tooth.pressure_angle)
            zc = ld.allowable_tooth_load_N / ld.mesh_stiffness_N_per_mm
            if z0 > 0 and c.criteria_Nm["tooth_load"] and c.aligned_capacity_Nm:
                q_pts.append((zc / z0, c.criteria_Nm["tooth_load"] / c.aligned_capacity_Nm))
        if progress:
            progress(n + 1, mis.size)
    label = model or spec.load.model
    paths = [
        save_figure(plot_vs_misalignment(mis, dict(peak), "max tooth load P (N)",
                                         f"{spec.name}: {label}, max tooth load"),
                    out / "load_max_vs_misalignment.png"),
        save_figure(plot_vs_misalignment(mis, dict(moment), "additional (tilting) moment (N·m)",
                                         f"{spec.name}: {label}, mean over the turn"),
                    out / "load_moment_vs_misalignment.png"),
    ]
    if q_pts:
        title = (f"{spec.name}: load proportion q against z_c / z0 (Renzo Fig. 12)\n"
                 "points: the linear model's tooth-load capacity on the exact geometry, "
                 f"{mis[0]:.2g}-{mis[-1]:.2g}°")
        paths.append(save_figure(plot_q_graph({"linear model, exact geometry": q_pts},
                                              title=title), out / "load_q_graph.png"))
    return paths


def write_load(spec: CouplingSpec, out: Path, misalignment_deg: float,
               angles: int | None = None, *,
               torque_Nm: float | None = None, model: str | None = None,
               tolerance_mm: float = GAP_TOLERANCE_MM, plots: bool = True,
               with_studies: bool = True,
               swept: SweepResult | None = None,
               progress: Callable[[int, int], None] | None = None) -> list[Path]:
    """The loaded analysis over ``angles`` rotations of a turn (default
    :data:`~gearcoupling.loading.PHASES` per tooth pitch, a turn of as many distinct poses):
    ``load.csv``, ``load_summary.json`` and plots. ``swept``: a sweep of this spec at these
    rotations and misalignment to reuse (else one is made); ``progress(done, total)`` as
    the surface model and the studies go."""
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
    return paths
