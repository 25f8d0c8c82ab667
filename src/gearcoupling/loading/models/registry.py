"""The load models by name: each one :class:`LoadModel` in :data:`MODELS`, the one place
that knows them (what a model solves, what it costs, what it reports, how capacity
searches with it). Every solver takes a :class:`~..inputs.LoadProblem` and returns one
typed :class:`ModelOutput`.

- ``linear``: Renzo's constant mesh stiffness ``C`` (:mod:`.linear`);
- ``compliance``: tooth-pair cantilever plus non-linear contact compliance (:mod:`.compliance`);
- ``surface``: contact pressure on the exact gap field (:mod:`.surface`).

Adding a model is adding one entry to :data:`MODELS` (docs/api.md, "Adding a load model");
the spec's ``[load] model`` accepts the names of :data:`gearcoupling.spec.load.LOAD_MODELS`
(a test holds them equal to the built-in entries here).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from ...arguments import choice
from ...spec import CouplingSpec
from ..inputs import LoadProblem, nominal_root_stress_MPa
from .compliance import first_limit_torque_Nmm, solve_compliance
from .linear import linear_capacity_Nmm, solve_linear
from .surface import DEFAULT_GRID, solve_surface
from .surface_capacity import surface_torques

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
                        gap_offset_rad=problem.gap_offset_rad, keep_fields=True,
                        progress=progress)
    Fn = np.asarray(out["normal_force_N"])
    z, r = out["contact_z_mm"], out["contact_r_mm"]
    out.setdefault("contact_regime", np.where(Fn > 0, 2, 0))
    out.setdefault("root_stress_MPa", nominal_root_stress_MPa(spec, Fn, z, r))
    k = spec.tooth.pitch_radius ** 2 / c.pair_compliance_mm_per_N(problem.z_mm, problem.r_mm)
    out.setdefault("mesh_stiffness_Nm_per_rad",
                   np.sum(np.where(Fn > 0, k, 0.0), axis=0) * 1e-3)
    return ModelOutput.from_solver(problem, out)


class PoseSearch(Protocol):
    """A capacity search that solved single poses (the surface model's): the solves it
    made and the largest tooth load at a torque from them."""

    @property
    def solves(self) -> int: ...

    def peak_load_N(self, T_Nmm: float) -> float: ...


#: ``capacity(problem, limits)`` -> (each criterion's torque in N·m, the pose searches that
#: found them: empty where q then comes from a load solve of every rotation); ``limits``
#: are the per-tooth limit loads of :func:`~..limits.limit_loads`
CapacitySearch = Callable[[LoadProblem, dict[str, NDArray]],
                          tuple[dict[str, float], Sequence[PoseSearch]]]

COSTS = ("fast", "slow")  # the cost classes of :attr:`LoadModel.cost`
# the surface model's load studies: 3 rotations per tooth pitch on 12 x 8 cells, a fraction
# of the cost of 8 rotations on the load criteria's 24 x 16 cells (LOAD_GRID) for the same
# largest tooth load and mean tilting moment within half a percent at the 7 misalignments
# of the studies and T/2, T, 2T (``python benchmarks/bench_load_study.py`` measures each
# setting; benchmarks/RESULTS.md holds its figures)
SURFACE_STUDY = (3, (12, 8))


@dataclass(frozen=True)
class LoadModel:
    """One load model.

    Attributes
    ----------
    name : str
        The ``model=`` / ``--model`` / ``[load] model`` value.
    solve : callable
        ``solve(problem, progress)`` -> :class:`ModelOutput` (every rotation of the problem).
    capacity : callable
        ``capacity(problem, limits)``: how capacity searches with the model
        (:data:`CapacitySearch`).
    cost : {"fast", "slow"}
        ``fast``: every rotation in one solve (studies sample it freely); ``slow``: a solve
        per distinct pose (callers solve one tooth pitch, few rotations, on a coarser grid
        where they can).
    rotations : int
        Rotations per tooth pitch a capacity search takes by default (the largest tooth
        load varies by about 2 % over a pitch: ``benchmarks/bench_surface.py``).
    pressure_grid : bool
        The model solves the contact pressure on a grid over each loaded flank (its patch
        maps draw the grid it solved; its capacity and studies take
        ``pressure_grid``), else its patch maps draw the contact laws' patch.
    takes_mesh_stiffness : bool
        The model takes ``[load] mesh_stiffness_N_per_mm`` where the spec sets it
        (Renzo's ``C``, "template C" on the accuracy ladder) instead of the tooth springs.
    what : str
        One line for help texts and settings tables.
    study : (int, (int, int) or None) or None
        Rotations per tooth pitch and pressure grid (None: the model's own) of the load
        studies over the misalignments (``gc.run``'s Wei and Renzo graphs); None: the
        model's :attr:`rotations` and grid.
    """

    name: str
    solve: Callable[[LoadProblem, Progress], ModelOutput]
    capacity: CapacitySearch
    cost: str
    rotations: int
    pressure_grid: bool
    takes_mesh_stiffness: bool
    what: str
    study: tuple[int, tuple[int, int] | None] | None = None

    def __post_init__(self):
        choice(self.cost, "cost", COSTS)


def _per_criterion(torque_Nmm: Callable[[LoadProblem, NDArray], float]) -> CapacitySearch:
    """A capacity search that finds each criterion's torque by ``torque_Nmm(problem,
    W_lim)`` (closed form or one root per criterion)."""
    def search(problem: LoadProblem, limits: dict[str, NDArray]
               ) -> tuple[dict[str, float], Sequence[PoseSearch]]:
        return {name: torque_Nmm(problem, W) * 1e-3 for name, W in limits.items()}, ()
    return search


MODELS: dict[str, LoadModel] = {m.name: m for m in (
    LoadModel("linear", _linear, _per_criterion(
        lambda p, W: linear_capacity_Nmm(p.spec, p.gap_rad, W)),
        cost="fast", rotations=25, pressure_grid=False, takes_mesh_stiffness=True,
        what="Renzo's constant mesh stiffness C per tooth pair, exact in closed form"),
    LoadModel("compliance", _compliance, _per_criterion(
        lambda p, W: first_limit_torque_Nmm(p.spec, p.gap_rad, p.z_mm, p.r_mm, W,
                                            p.compliance)),
        cost="fast", rotations=25, pressure_grid=False, takes_mesh_stiffness=False,
        what="tooth-pair springs plus non-linear contact compliance, a fast estimate"),
    LoadModel("surface", _surface, surface_torques,
              cost="slow", rotations=8, pressure_grid=True, takes_mesh_stiffness=False,
              what="contact pressure on the exact gap field, the validated one",
              study=SURFACE_STUDY),
)}
"""Model name -> :class:`LoadModel`: the one table of load models."""


def model_names() -> tuple[str, ...]:
    """The names of :data:`MODELS` (the CLI's ``--model`` choices)."""
    return tuple(MODELS)


def models_help() -> str:
    """Each model's name and line, for help texts."""
    return "; ".join(f"{m.name}: {m.what}" for m in MODELS.values())


def load_model(name: str) -> LoadModel:
    """The :class:`LoadModel` named ``name``; :class:`ArgumentError` naming the others."""
    return MODELS[choice(name, "model", model_names())]


def resolve_model(spec: CouplingSpec, model: str | None) -> str:
    """The model name: the argument, else ``[load] model``; a key of :data:`MODELS`."""
    return spec.load.model if model is None else load_model(model).name


def solve(problem: LoadProblem, model: str, progress: Progress = None) -> ModelOutput:
    """Solve ``problem`` with the model named ``model`` (a key of :data:`MODELS`);
    ``progress(done, total)`` as the model advances (models that take under a second
    may not call it)."""
    return load_model(model).solve(problem, progress)
