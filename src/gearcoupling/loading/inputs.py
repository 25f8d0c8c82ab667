"""What every load model starts from: one spec's sweep, the torque and the loaded flank.

The leaf of :mod:`gearcoupling.loading`: the models, capacity and the entry points import
it; it imports none of them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import resolve_torque_Nm
from ..clearance import SweepResult
from ..errors import ArgumentError
from ..geometry import FLANKS
from ..spec import CouplingSpec
from .springs import cantilever, tooth_compliance


def loaded_gaps(sweep_result: SweepResult, flank: int,
                gap_offset_rad: ArrayLike | None) -> NDArray[np.float64]:
    """Gap angles ``(N, M)`` of the loaded flank plus the per-tooth offsets."""
    g = sweep_result.gap_angle_rad[flank]
    if gap_offset_rad is None:
        return g
    off = np.asarray(gap_offset_rad, dtype=float)
    N = g.shape[0]
    if off.shape == (2, N):
        off = off[flank]
    if off.shape != (N,) or not np.all(np.isfinite(off)):
        raise ArgumentError("gap_offset_rad", f"shape {off.shape}", f"finite, shaped ({N},) "
                            f"or (2, {N})")
    return g + off[:, None]


def contact_points(spec: CouplingSpec, sweep_result: SweepResult,
                   flank: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """First-touch ``(z, r)`` of the loaded flank, ``(N, M)``; where nothing faces the sleeve
    (no finite point) the midplane pitch point stands in (those teeth carry no load)."""
    z = sweep_result.contact_z_mm[flank]
    r = sweep_result.contact_r_mm[flank]
    ok = np.isfinite(z) & np.isfinite(r)
    return np.where(ok, z, 0.0), np.where(ok, r, spec.tooth.pitch_radius)


def nominal_root_stress_MPa(spec: CouplingSpec, normal_force_N, z_mm, r_mm) -> NDArray:
    """The root bending stress the allowable bending stress is compared with: the tapered
    cantilever's nominal stress, whichever tooth springs ``[load] stiffness`` chooses (the
    FE table's fillet stresses hold the fillet's stress concentration; they are reported in
    ``stiffness.csv``, not judged)."""
    return cantilever(spec).root_stress_MPa(normal_force_N, z_mm, r_mm)


@dataclass(frozen=True, eq=False)
class LoadProblem:
    """One load problem: a sweep, the signed torque and what follows from them.

    Attributes
    ----------
    sweep : SweepResult
        The sweep (its spec is the spec of the case).
    torque_Nm : float
        Signed torque; positive loads the ccw flanks.
    gap_rad, z_mm, r_mm : (N, M) float
        Gap angles (with offsets) and first-touch points of the loaded flank.
    gap_offset_rad : (N,) or (2, N) float or None
        Per-tooth additions to the gap angles (index errors).
    compliance : object with ``pair_compliance_mm_per_N(z_mm, r_mm)``
        The tooth springs of ``[load] stiffness``.
    pressure_grid : (int, int) or None
        Cells of the surface model's pressure grid (along the face, across the depth);
        None: its default.
    """

    sweep: SweepResult
    torque_Nm: float
    gap_rad: NDArray[np.float64]
    z_mm: NDArray[np.float64]
    r_mm: NDArray[np.float64]
    gap_offset_rad: NDArray[np.float64] | None = None
    compliance: Any = field(default=None, repr=False)
    pressure_grid: tuple[int, int] | None = None

    @property
    def spec(self):
        return self.sweep.spec

    @property
    def flank(self) -> int:
        """Index of the loaded flank in ``(cw, ccw)``."""
        return 1 if self.torque_Nm >= 0 else 0

    @property
    def loaded_flank(self) -> str:
        return FLANKS[self.flank]

    @property
    def torque_Nmm(self) -> float:
        """Torque magnitude in N·mm."""
        return abs(self.torque_Nm) * 1e3


def load_problem(sweep_result: SweepResult, torque_Nm: float | None = None,
                 gap_offset_rad: ArrayLike | None = None,
                 pressure_grid: tuple[int, int] | None = None) -> LoadProblem:
    """The :class:`LoadProblem` of a sweep at a torque (default the spec's ``[load]`` torque)."""
    if not isinstance(sweep_result, SweepResult):
        raise ArgumentError("sweep_result", type(sweep_result).__name__, "the SweepResult "
                            "of gearcoupling.sweep")
    spec = sweep_result.spec
    T = resolve_torque_Nm(spec, torque_Nm)
    flank = 1 if T >= 0 else 0
    g = loaded_gaps(sweep_result, flank, gap_offset_rad)
    z, r = contact_points(spec, sweep_result, flank)
    off = None if gap_offset_rad is None else np.asarray(gap_offset_rad, dtype=float)
    return LoadProblem(sweep_result, T, g, z, r, off, tooth_compliance(spec), pressure_grid)
