"""The entry points: :func:`load` (sweep, then load sharing) and :func:`load_from_sweep`."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..arguments import GAP_TOLERANCE_MM, SWEEP_GRID
from ..clearance import SweepResult, sweep
from ..errors import ArgumentError
from ..spec import CouplingSpec, as_spec
from .inputs import LoadProblem, load_problem, resolve_torque_Nm
from .models.registry import ModelOutput, Progress, resolve_model, solve
from .result import LoadResult


def load(spec: CouplingSpec, misalignment_deg: float, angles_deg: ArrayLike, *,
         torque_Nm: float | None = None, model: str | None = None,
         gap_offset_rad: ArrayLike | None = None, progress: Progress = None,
         pressure_grid: tuple[int, int] | None = None,
         tolerance_mm: float = GAP_TOLERANCE_MM, grid: int = SWEEP_GRID,
         periodic: bool = True) -> LoadResult:
    """Load sharing of every tooth over rotations ``angles_deg`` at a misalignment.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
        0-6 degrees.
    angles_deg : (M,) float
        Coupling rotations ``psi`` (degrees).
    torque_Nm : float, optional
        Signed torque (positive loads the ccw flanks); default ``spec.load.torque_Nm``.
    model : str, optional
        A load model's name (:data:`~gearcoupling.loading.MODELS`: ``linear``,
        ``compliance``, ``surface``); default ``spec.load.model``.
    gap_offset_rad : (N,) or (2, N) float, optional
        Per-tooth additions to the gap angles (index errors, docs/conventions.md).
    progress : callable, optional
        ``progress(done, total)`` as the load model advances (the ``surface`` model: after
        each distinct pose; for a progress bar).
    pressure_grid : (int, int), optional
        The surface model's cells along the face and across the depth of each loaded
        tooth (default 48 x 32; ``benchmarks/bench_surface.py`` gives what a grid costs
        and buys).
    tolerance_mm, grid, periodic
        The sweep's accuracy (:func:`gearcoupling.sweep`).

    Examples
    --------
    The teeth carry the torque at every rotation (tangential forces at the pitch radius),
    and Renzo's load proportion ``q`` is at most 1:

    >>> import gearcoupling as gc
    >>> spec = gc.load_spec("renzo-1967")
    >>> res = gc.load(spec, 1.0, range(0, 360, 30), torque_Nm=2000.0)
    >>> res.tangential_force_N.shape  # (teeth, rotations)
    (50, 12)
    >>> R = spec.tooth.pitch_radius  # mm
    >>> [round(float(t)) for t in res.tangential_force_N.sum(axis=0) * R / 1e3][:3]  # N·m
    [2000, 2000, 2000]
    >>> 0 < res.q() <= 1
    True
    """
    spec = as_spec(spec)
    torque = resolve_torque_Nm(spec, torque_Nm)  # once, before the sweep
    resolve_model(spec, model)
    sw = sweep(spec, misalignment_deg, angles_deg, tolerance_mm=tolerance_mm, grid=grid,
               periodic=periodic)
    return load_from_sweep(sw, torque_Nm=torque, model=model, gap_offset_rad=gap_offset_rad,
                           progress=progress, pressure_grid=pressure_grid)


def load_from_sweep(sweep_result: SweepResult, *, torque_Nm: float | None = None,
                    model: str | None = None, gap_offset_rad: ArrayLike | None = None,
                    progress: Progress = None,
                    pressure_grid: tuple[int, int] | None = None) -> LoadResult:
    """Load sharing on an existing sweep (its spec gives the teeth, materials and defaults);
    arguments as :func:`load`."""
    problem = load_problem(sweep_result, torque_Nm, gap_offset_rad, pressure_grid)
    m = resolve_model(problem.spec, model)
    return _result(problem, m, solve(problem, m, progress))


def _result(problem: LoadProblem, model: str, out: ModelOutput) -> LoadResult:
    bad = out.non_finite()
    if bad:
        raise ArgumentError("torque_Nm", problem.torque_Nm, f"the {model} model gave non-finite "
                        f"{bad}; the load is outside what the model covers")
    sw = problem.sweep
    sign = 1.0 if problem.torque_Nm >= 0 else -1.0
    return LoadResult(
        spec=problem.spec, misalignment_deg=float(sw.misalignment_deg),
        torque_Nm=problem.torque_Nm, model=model, loaded_flank=problem.loaded_flank,
        angles_deg=np.asarray(sw.angles_deg), theta_deg=np.asarray(sw.theta_deg),
        windup_rad=sign * out.windup_rad, gap_angle_rad=problem.gap_rad,
        mesh_stiffness_Nm_per_rad=out.mesh_stiffness_Nm_per_rad, **out.arrays,
        pressure_fields=_fields(out.extra.get("fields")))


def _fields(fields) -> tuple[dict[str, Any], ...] | None:
    """What :func:`~.patchmap.patch_maps` draws of each rotation's solved pressure grid
    (references, not copies: rotations rolled from one solved pose share it); None when
    the model solves no grid or carried no load."""
    if not fields or not all(fields):
        return None
    return tuple({"teeth": f["teeth"], "z_mm": f["field"].z_mm, "s_mm": f["field"].s_mm,
                  "mask": f["field"].mask, "pressure_MPa": f["pressure_MPa"]} for f in fields)
