"""The load models by name (like the exporters' registry): each solver takes a
:class:`~.inputs.LoadProblem` and returns one typed :class:`ModelOutput`.

- ``linear``: Renzo's constant mesh stiffness ``C`` (:mod:`.linear`);
- ``compliance``: tooth-pair cantilever plus non-linear contact compliance (:mod:`.compliance`);
- ``surface``: contact pressure on the exact gap field (:mod:`.surface`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..inputs import LoadProblem, nominal_root_stress_MPa
from .compliance import solve_compliance
from .linear import solve_linear
from .surface import DEFAULT_GRID, solve_surface

#: per-tooth arrays ``(N, M)`` every model reports, with the value where a model has none
TOOTH_ARRAYS: dict[str, Any] = {
    "deflection_mm": 0.0, "tangential_force_N": 0.0, "normal_force_N": 0.0,
    "contact_z_mm": None, "contact_r_mm": None, "max_pressure_MPa": 0.0,
    "interior_pressure_MPa": None, "edge_load_share": 0.0, "patch_length_mm": 0.0,
    "patch_width_mm": 0.0, "edge_contact": False, "contact_regime": 0, "root_stress_MPa": 0.0,
}


@dataclass(frozen=True, eq=False)
class ModelOutput:
    """What a load model found for every tooth and rotation.

    Attributes
    ----------
    windup_rad : (M,) float
        Wind-up magnitude per rotation.
    mesh_stiffness_Nm_per_rad : (M,) float
        Torsional mesh stiffness ``dT/d(dpsi)`` at the load.
    arrays : dict of str -> (N, M) array
        The per-tooth quantities of :data:`TOOTH_ARRAYS`, all present.
    extra : dict
        What only this model reports (the surface model's edge intensity, patch extent, ...).
    """

    windup_rad: NDArray[np.float64]
    mesh_stiffness_Nm_per_rad: NDArray[np.float64]
    arrays: dict[str, NDArray[Any]]
    extra: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def from_solver(cls, problem: LoadProblem, out: dict[str, Any]) -> ModelOutput:
        """Collect a solver's dict: arrays broadcast to ``(N, M)``, missing ones defaulted
        (contact point: the sweep's first touch; interior pressure: the peak)."""
        shape = problem.gap_rad.shape
        fallback = {"contact_z_mm": problem.z_mm, "contact_r_mm": problem.r_mm,
                    "interior_pressure_MPa": out.get("max_pressure_MPa", 0.0)}
        arrays = {}
        for name, default in TOOTH_ARRAYS.items():
            value = out.get(name, fallback.get(name, default))
            arrays[name] = np.broadcast_to(np.asarray(value), shape).copy()
        arrays["edge_contact"] = arrays["edge_contact"].astype(bool)
        arrays["contact_regime"] = arrays["contact_regime"].astype(np.int8)
        extra = {k: v for k, v in out.items() if k not in TOOTH_ARRAYS
                 and k not in ("windup_rad", "mesh_stiffness_Nm_per_rad")}
        return cls(np.asarray(out["windup_rad"], dtype=float),
                   np.asarray(out["mesh_stiffness_Nm_per_rad"], dtype=float), arrays, extra)

    def non_finite(self) -> list[str]:
        """Names of float outputs holding NaN or infinity."""
        named = {"windup_rad": self.windup_rad,
                 "mesh_stiffness_Nm_per_rad": self.mesh_stiffness_Nm_per_rad, **self.arrays}
        return [k for k, v in named.items() if v.dtype.kind == "f" and not np.all(np.isfinite(v))]


#: ``progress(done, total)``: called as a model's work advances (the surface model: after
#: each distinct pose it solves), or None
Progress = Callable[[int, int], Any] | None


def _finished(progress: Progress) -> None:
    """Report a model that solves every rotation at once as done."""
    if progress is not None:
        progress(1, 1)


def _linear(problem: LoadProblem, progress: Progress = None) -> ModelOutput:
    out = solve_linear(problem.spec, problem.gap_rad, problem.z_mm, problem.r_mm,
                       problem.torque_Nmm)
    _finished(progress)
    return ModelOutput.from_solver(problem, out)


def _compliance(problem: LoadProblem, progress: Progress = None) -> ModelOutput:
    out = solve_compliance(problem.spec, problem.gap_rad, problem.z_mm, problem.r_mm,
                           problem.torque_Nmm, problem.compliance)
    _finished(progress)
    return ModelOutput.from_solver(problem, out)


def _surface(problem: LoadProblem, progress: Progress = None) -> ModelOutput:
    spec, c = problem.spec, problem.compliance
    out = solve_surface(spec, problem.sweep, torque_Nm=problem.torque_Nm, compliance=c,
                        grid=problem.pressure_grid or DEFAULT_GRID,
                        gap_offset_rad=problem.gap_offset_rad, progress=progress)
    Fn = np.asarray(out["normal_force_N"])
    z, r = out["contact_z_mm"], out["contact_r_mm"]
    out.setdefault("contact_regime", np.where(Fn > 0, 2, 0))
    out.setdefault("root_stress_MPa", nominal_root_stress_MPa(spec, Fn, z, r))
    k = spec.tooth.pitch_radius ** 2 / c.pair_compliance_mm_per_N(problem.z_mm, problem.r_mm)
    out.setdefault("mesh_stiffness_Nm_per_rad",
                   np.sum(np.where(Fn > 0, k, 0.0), axis=0) * 1e-3)
    return ModelOutput.from_solver(problem, out)


MODELS: dict[str, Callable[[LoadProblem, Progress], ModelOutput]] = {
    "linear": _linear, "compliance": _compliance, "surface": _surface}


def solve(problem: LoadProblem, model: str, progress: Progress = None) -> ModelOutput:
    """Solve ``problem`` with the model named ``model`` (a key of :data:`MODELS`);
    ``progress(done, total)`` as the model advances (models that take under a second
    may not call it)."""
    return MODELS[model](problem, progress)
