"""The stages of the loads that :func:`~gearcoupling.outputs.run` and the design report
share (kept per spec like every :func:`~.stages.stage`): Renzo's q points and the
misalignment studies of the tooth loads."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..clearance import sweep
from ..geometry import renzo_z0_mm
from ..loading import (
    capacity_from_sweep,
    default_angles,
    load_from_sweep,
    load_model,
    renzo_q,
    resolve_model,
)
from ..spec import CouplingSpec
from .stages import stage, study_misalignments


@dataclass(frozen=True)
class QPoint:
    """One point of Renzo's q graph: the linear model's tooth-load capacity over the
    aligned capacity at a misalignment, against ``z_c / z0``, with Renzo's eq. 8."""

    misalignment_deg: float
    zc_over_z0: float
    q_linear: float
    q_renzo: float


@stage
def q_points(spec: CouplingSpec, top_deg: float | None = None) -> tuple[QPoint, ...]:
    """Renzo's q graph at :func:`study_misalignments` (needs ``load.allowable_tooth_load``
    and ``load.mesh_stiffness``; empty without them): the linear model on the exact
    geometry, 25 rotations over a tooth pitch at each misalignment."""
    ld = spec.load
    if ld.allowable_tooth_load_N is None or ld.mesh_stiffness_N_per_mm is None:
        return ()
    zc = ld.allowable_tooth_load_N / ld.mesh_stiffness_N_per_mm
    rc = spec.derived["crowning_radius_midplane_mm"]
    pts = []
    for i in study_misalignments(spec, top_deg):
        c = capacity_from_sweep(sweep(spec, float(i), default_angles(spec, None)),
                                model="linear")
        z0 = renzo_z0_mm(rc, math.radians(i), spec.tooth.pressure_angle)
        T_tooth = c.criteria_Nm.get("tooth_load")
        if 0 < z0 < math.inf and T_tooth and c.aligned_capacity_Nm:
            pts.append(QPoint(float(i), zc / z0, T_tooth / c.aligned_capacity_Nm,
                              renzo_q(zc / z0)))
    return tuple(pts)


@dataclass(frozen=True)
class LoadStudy:
    """The largest tooth load (N) and the mean tilting moment (N·m) over a tooth pitch at
    each misalignment, per torque (Wei Figs. 12-13); keys ``T/2 = ... N·m`` and so on."""

    misalignments_deg: np.ndarray
    peak_N: dict[str, list[float]]
    moment_Nm: dict[str, list[float]]


@stage
def load_study(spec: CouplingSpec, torque_Nm: float, model: str | None,
               top_deg: float | None = None, *,
               progress: Callable[[int, int], None] | None = None) -> LoadStudy:
    """The loads at T/2, T and 2T over one tooth pitch at each of
    :func:`study_misalignments` (at the model's :attr:`~gearcoupling.loading.LoadModel.study`
    rotations and grid); ``progress(done, total)`` after each
    misalignment."""
    mis = study_misalignments(spec, top_deg)
    torques = [0.5 * torque_Nm, torque_Nm, 2.0 * torque_Nm]
    # one curve per factor, also where the torques coincide (0 N·m: three flat curves)
    labels = [f"{f} = {t:.4g} N·m" for f, t in zip(("T/2", "T", "2T"), torques, strict=True)]
    peak: dict[str, list[float]] = {k: [] for k in labels}
    moment: dict[str, list[float]] = {k: [] for k in labels}
    m = load_model(resolve_model(spec, model))
    rotations, grid = m.study or (m.rotations, None)
    for n, i in enumerate(mis):
        sw = sweep(spec, float(i), default_angles(spec, None, rotations))
        for t, key in zip(torques, labels, strict=True):
            res = load_from_sweep(sw, torque_Nm=t, model=model, pressure_grid=grid)
            peak[key].append(float(np.max(res.tangential_force_N)))
            moment[key].append(res.summary()["tilting_moment_Nm"]["mean"])
        if progress:
            progress(n + 1, mis.size)
    return LoadStudy(mis, peak, moment)
