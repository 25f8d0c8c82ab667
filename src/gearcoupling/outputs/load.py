"""The load stages: the loads over a turn at the operating point (``load.csv``,
``load_summary.json`` and plots), the tooth load and tilting moment against misalignment
(Wei Figs. 12-13) and Renzo's q graph."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import SweepResult, sweep
from ..geometry import renzo_z0_mm
from ..io import plot_text, write_csv_rows, write_json
from ..loading import (
    LoadResult,
    capacity_from_sweep,
    default_angles,
    load_from_sweep,
    load_model,
    most_loaded,
    plot_loads_over_turn,
    plot_patches,
    plot_q_graph,
    plot_tooth_load,
    plot_vs_misalignment,
    renzo_q,
    resolve_model,
    resolve_torque_Nm,
    rotation_table,
    turn_phases,
)
from ..plots import save_figure
from ..spec import CouplingSpec
from .stage import SkipStage, StageInputs
from .sweep import turn_angles

STUDY_POINTS = 7  # misalignments of the studies and the q graph
NO_TORQUE = "no [load] torque_Nm in the spec and no torque given"


@dataclass(frozen=True)
class QPoint:
    """One point of Renzo's q graph: the linear model's tooth-load capacity over the
    aligned capacity at a misalignment, against ``z_c / z0``, with Renzo's eq. 8."""

    misalignment_deg: float
    zc_over_z0: float
    q_linear: float
    q_renzo: float


@dataclass(frozen=True)
class QGraph:
    """Renzo's q graph at :func:`study_misalignments` up to ``top_deg``."""

    top_deg: float
    points: tuple[QPoint, ...]


@dataclass(frozen=True)
class LoadStudy:
    """The largest tooth load (N) and the mean tilting moment (N·m) over a tooth pitch at
    each misalignment, per torque (Wei Figs. 12-13); keys ``T/2 = ... N·m`` and so on."""

    misalignments_deg: np.ndarray
    peak_N: dict[str, list[float]]
    moment_Nm: dict[str, list[float]]
    model: str


def study_misalignments(spec: CouplingSpec, top_deg: float | None = None,
                        count: int = STUDY_POINTS) -> np.ndarray:
    """Misalignments of the studies and the q graph: ``count`` from ``top / count`` to
    ``top`` (0 left out); ``top`` the design angle by default, at least 0.5°."""
    top = max(spec.design_misalignment_deg if top_deg is None else top_deg, 0.5)
    return np.linspace(top / count, top, count)


# ------------------------------------------------------------------- the turn


def turn_loads(inputs: StageInputs) -> LoadResult:
    """The stage ``load``: the loads over a turn, ``phases`` rotations per tooth pitch (less
    a mesh's phase)."""
    p = inputs.point
    if p.torque_Nm is None:
        raise SkipStage(NO_TORQUE)
    s = inputs.settings
    sw = sweep(inputs.spec, p.misalignment_deg, p.rotations(turn_phases(inputs.spec, s.phases)),
               tolerance_mm=s.tolerance_mm)
    return load_from_sweep(sw, torque_Nm=p.torque_Nm, model=p.model)


def files(res: LoadResult, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``load``'s files (:func:`load_files`)."""
    s = inputs.settings
    return load_files(res, folder, patch_teeth=s.patch_teeth, dpi=s.dpi)


def largest_rotation(res: LoadResult) -> int:
    """The rotation of the largest tooth load."""
    return int(np.argmax(np.max(res.tangential_force_N, axis=0)))


def load_files(res: LoadResult, folder: Path, *, plots: bool = True, patch_teeth: int = 6,
               dpi: int = 110) -> list[Path]:
    """``load.csv``, ``load_summary.json``, the loads per rotation (``loads_over_turn.csv``)
    and the patches at the rotation of the largest tooth load (``contact_patches.csv``);
    with ``plots`` their pictures."""
    table = rotation_table(res)
    j = largest_rotation(res)
    mapped = set(most_loaded(res, j, patch_teeth).tolist())  # the teeth plot_patches maps
    paths = [res.write_csv(folder / "load.csv"),
             write_json(folder / "load_summary.json", res.summary()),
             write_csv_rows(folder / "loads_over_turn.csv", tuple(table),
                            zip(*table.values(), strict=True)),
             write_csv_rows(folder / "contact_patches.csv", PATCH_COLUMNS,
                            ((k, res.theta_deg[k, j], res.normal_force_N[k, j],
                              res.contact_z_mm[k, j], res.contact_r_mm[k, j],
                              res.patch_length_mm[k, j], res.patch_width_mm[k, j],
                              res.interior_pressure_MPa[k, j], res.max_pressure_MPa[k, j],
                              bool(res.edge_contact[k, j]), k in mapped)
                             for k in range(res.teeth)))]
    if plots:
        paths += [save_figure(plot_tooth_load(res), folder / "load_tooth_load.png", dpi),
                  save_figure(plot_loads_over_turn(res), folder / "load_over_turn.png", dpi),
                  save_figure(plot_patches(res, j, count=patch_teeth),
                              folder / "load_patches.png", dpi)]
    return paths


PATCH_COLUMNS = ("tooth", "theta_deg", "normal_force_N", "contact_z_mm", "contact_r_mm",
                 "patch_length_mm", "patch_width_mm", "interior_pressure_MPa",
                 "max_pressure_MPa", "edge_contact", "mapped")


def write_load(spec: CouplingSpec, out: Path, misalignment_deg: float,
               angles: int | None = None, *, torque_Nm: float | None = None,
               model: str | None = None, tolerance_mm: float = GAP_TOLERANCE_MM,
               plots: bool = True, with_studies: bool = True,
               swept: SweepResult | None = None,
               progress: Callable[[int, int], None] | None = None
               ) -> tuple[LoadResult, list[Path]]:
    """``gearcoupling load``: the loads over ``angles`` rotations of a turn (default
    :data:`~gearcoupling.loading.PHASES` per tooth pitch) and their files
    (:func:`load_files`; ``with_studies``: also :func:`load_studies`). ``swept``: a sweep
    of this spec at these rotations and misalignment to reuse; ``progress(done, total)``
    as the model and the studies go. Returns the loads and the paths."""
    torque = resolve_torque_Nm(spec, torque_Nm)  # once, before any work
    if swept is None:
        a = turn_phases(spec) if angles is None else turn_angles(angles)
        swept = sweep(spec, misalignment_deg, a, tolerance_mm=tolerance_mm)
    res = load_from_sweep(swept, torque_Nm=torque, model=model, progress=progress)
    paths = load_files(res, out, plots=plots)
    if plots and with_studies:
        paths += load_studies(spec, torque, model, out, progress=progress)
    return res, paths


# ------------------------------------------------------------------- the studies


def study(inputs: StageInputs) -> LoadStudy:
    """The stage ``load_study`` (:func:`load_study`)."""
    p = inputs.point
    if p.torque_Nm is None:
        raise SkipStage(NO_TORQUE)
    return load_study(inputs.spec, p.torque_Nm, p.model, p.misalignment_deg)


def study_files(result: LoadStudy, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``load_study``'s pictures."""
    return study_plots(inputs.spec, result, folder, inputs.settings.dpi)


def load_study(spec: CouplingSpec, torque_Nm: float, model: str | None,
               top_deg: float | None = None, *,
               progress: Callable[[int, int], None] | None = None) -> LoadStudy:
    """The loads at T/2, T and 2T over one tooth pitch at each of
    :func:`study_misalignments` (at the model's :attr:`~gearcoupling.loading.LoadModel.study`
    rotations and grid); ``progress(done, total)`` after each misalignment."""
    mis = study_misalignments(spec, top_deg)
    torques = [0.5 * torque_Nm, torque_Nm, 2.0 * torque_Nm]
    # one curve per factor, also where the torques coincide (0 N·m: three flat curves)
    labels = [f"{f} = {t:.4g} N·m" for f, t in zip(("T/2", "T", "2T"), torques, strict=True)]
    peak: dict[str, list[float]] = {k: [] for k in labels}
    moment: dict[str, list[float]] = {k: [] for k in labels}
    name = resolve_model(spec, model)
    m = load_model(name)
    rotations, grid = m.study or (m.rotations, None)
    for n, i in enumerate(mis):
        sw = sweep(spec, float(i), default_angles(spec, None, rotations))
        for t, key in zip(torques, labels, strict=True):
            res = load_from_sweep(sw, torque_Nm=t, model=name, pressure_grid=grid)
            peak[key].append(float(np.max(res.tangential_force_N)))
            moment[key].append(res.summary()["tilting_moment_Nm"]["mean"])
        if progress:
            progress(n + 1, mis.size)
    return LoadStudy(mis, peak, moment, name)


def study_plots(spec: CouplingSpec, study: LoadStudy, folder: Path, dpi: int = 110
                ) -> list[Path]:
    """Wei Figs. 12-13: the largest tooth load and the mean tilting moment against
    misalignment."""
    mis = study.misalignments_deg
    head = f"{plot_text(spec.name)}: {study.model}"
    return [
        save_figure(plot_vs_misalignment(mis, dict(study.peak_N), "max tooth load P (N)",
                                         f"{head}, max tooth load"),
                    folder / "load_max_vs_misalignment.png", dpi),
        save_figure(plot_vs_misalignment(mis, dict(study.moment_Nm),
                                         "additional (tilting) moment (N·m)",
                                         f"{head}, mean over the turn"),
                    folder / "load_moment_vs_misalignment.png", dpi)]


def load_studies(spec: CouplingSpec, torque_Nm: float, model: str | None, out: Path, *,
                 progress: Callable[[int, int], None] | None = None) -> list[Path]:
    """Wei Figs. 12-13 and Renzo's q graph (Fig. 12) for the spec at its design angle
    (:func:`load_study`, :func:`q_graph`); ``progress(done, total)`` after each
    misalignment."""
    paths = study_plots(spec, load_study(spec, torque_Nm, model, progress=progress), out)
    graph = q_graph(spec)
    if graph.points:
        paths += q_files(graph, spec, out)
    return paths


# ------------------------------------------------------------------- Renzo's q graph


def q_stage(inputs: StageInputs) -> QGraph:
    """The stage ``q_graph`` (:func:`q_graph`); skipped without its limits."""
    graph = q_graph(inputs.spec, inputs.point.misalignment_deg)
    if not graph.points:
        raise SkipStage("Renzo's q graph needs [load] allowable_tooth_load and "
                        "mesh_stiffness (Renzo's C)")
    return graph


def q_stage_files(graph: QGraph, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``q_graph``'s data and picture."""
    return q_files(graph, inputs.spec, folder, inputs.settings.dpi)


def q_graph(spec: CouplingSpec, top_deg: float | None = None) -> QGraph:
    """Renzo's q graph at :func:`study_misalignments` (needs ``load.allowable_tooth_load``
    and ``load.mesh_stiffness``; no points without them): the linear model on the exact
    geometry, 25 rotations over a tooth pitch at each misalignment."""
    ld = spec.load
    top = max(spec.design_misalignment_deg if top_deg is None else top_deg, 0.5)
    if ld.allowable_tooth_load_N is None or ld.mesh_stiffness_N_per_mm is None:
        return QGraph(top, ())
    zc = ld.allowable_tooth_load_N / ld.mesh_stiffness_N_per_mm
    rc = spec.derived["crowning_radius_midplane_mm"]
    pts = []
    for i in study_misalignments(spec, top):
        c = capacity_from_sweep(sweep(spec, float(i), default_angles(spec, None)),
                                model="linear")
        z0 = renzo_z0_mm(rc, math.radians(i), spec.tooth.pressure_angle)
        T_tooth = c.criteria_Nm.get("tooth_load")
        if 0 < z0 < math.inf and T_tooth and c.aligned_capacity_Nm:
            pts.append(QPoint(float(i), zc / z0, T_tooth / c.aligned_capacity_Nm,
                              renzo_q(zc / z0)))
    return QGraph(top, tuple(pts))


def q_files(graph: QGraph, spec: CouplingSpec, folder: Path, dpi: int = 110) -> list[Path]:
    """``q_graph.csv`` and ``load_q_graph.png``."""
    pts = graph.points
    title = (f"{plot_text(spec.name)}: load proportion q against z_c / z0 (Renzo Fig. 12)\n"
             "points: the linear model's tooth-load capacity on the exact geometry, "
             f"{pts[0].misalignment_deg:.2g}-{pts[-1].misalignment_deg:.2g}°")
    fig = plot_q_graph({"linear model, exact geometry": [(p.zc_over_z0, p.q_linear)
                                                         for p in pts]}, title=title)
    return [write_csv_rows(folder / "q_graph.csv", ("misalignment_deg", "zc_over_z0",
                                                    "q_linear_model", "q_renzo_eq8"),
                           [(p.misalignment_deg, p.zc_over_z0, p.q_linear, p.q_renzo)
                            for p in pts]),
            save_figure(fig, folder / "load_q_graph.png", dpi)]
