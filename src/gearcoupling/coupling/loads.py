"""Both meshes loaded at one torque, the loads each puts on its machine over a turn, and the
floating member's equilibrium (docs/coupling.md, Loads).

Each mesh is the single-engagement load analysis at its own angle and rotation phase
(:mod:`.geometry`); the same torque passes both: hub A takes ``T`` (its ccw flanks for
``T > 0``), hub B ``-T`` in its frame (both frames' ``z`` point from A toward B; the
sleeve drives hub B, so its cw flanks carry the load). The teeth's forces on each hub
(normal loads and Coulomb friction, :func:`gearcoupling.rotordynamics.hub_wrench`) are
taken into the coupling frame. Their reactions load the floating member, which is held
by what the hubs give it at the mesh centres:

- across its axis, the two shear forces that balance its forces and bending moments (a
  beam on two supports: statically determinate);
- along its axis, its net thrust, shared equally by the two meshes (the teeth hold it by
  friction; zero for an even tooth count);
- about its axis, the difference of the torques the two meshes pass to it at one torque
  (friction and the tilt: a fraction of a percent), carried by hub B: shaft B's torque is
  shaft A's less it.

The machine loads are each hub's whole wrench: its teeth's and these reactions.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import angle_list
from ..errors import ArgumentError
from ..io import write_csv_rows
from ..loading import PHASES, LoadResult, load, resolve_model, resolve_torque_Nm
from ..rotordynamics import hub_wrench
from ..spec import CouplingSpec
from .geometry import CouplingGeometry, coupling_geometry
from .layout import CouplingLayout, ShaftAlignment

#: per rotation and mesh, what each mesh puts on its shaft (``WholeLoads.rows``)
LOAD_COLUMNS = ("psi_deg", "mesh", "misalignment_deg", "mesh_psi_deg", "bending_moment_Nm",
                "radial_force_N", "axial_force_N", "torque_Nm", "max_tooth_load_N",
                "windup_rad")
#: the machine loads by name (per rotation, per mesh)
MACHINE_LOADS = ("bending_moment_Nm", "radial_force_N", "axial_force_N", "torque_Nm")


def mesh_torque_Nm(mesh: str, torque_Nm: float) -> float:
    """The torque a mesh's load analysis takes: ``T`` at A, ``-T`` at B (module docstring)."""
    return torque_Nm if mesh == "A" else -torque_Nm


def default_turn(geometry: CouplingGeometry) -> NDArray[np.float64]:
    """Coupling rotations over a turn (degrees): :data:`~gearcoupling.loading.PHASES` per
    tooth pitch of the finer engagement (equal teeth: as many distinct poses a mesh)."""
    n = PHASES * max(geometry.spec(m).tooth.teeth for m in geometry.meshes)
    return np.arange(n) * 360.0 / n


@dataclass(frozen=True, eq=False)
class WholeLoads:
    """Both meshes at one torque over a turn (module docstring). Vectors ``(M, 3)`` are in
    the coupling frame (docs/coupling.md), forces in N, moments in N·m about the mesh
    centre they name.

    Attributes
    ----------
    geometry : CouplingGeometry
    torque_Nm : float
        Shaft A's torque as given (signed).
    angles_deg : (M,) float
        The coupling's rotations ``psi`` (shaft A's turn).
    results : dict of str -> LoadResult
        Each mesh's load analysis (``"A"``, ``"B"``), at its own angle and rotations.
    tooth_force_N, tooth_moment_Nm : dict of str -> (M, 3) float
        The teeth's force on each hub and its moment about the mesh centre.
    shear_N : dict of str -> (M, 3) float
        The force the floating member takes from each hub at its mesh centre, across its
        axis (empty for one engagement).
    thrust_share_N : (M,) float
        The force the floating member takes from each hub along its axis (each half its
        net thrust).
    torque_share_Nm : (M,) float
        The moment the floating member takes from hub B about its axis: its torque
        imbalance at one torque.
    """

    geometry: CouplingGeometry = field(repr=False)
    torque_Nm: float
    angles_deg: NDArray[np.float64]
    results: dict[str, LoadResult] = field(repr=False)
    tooth_force_N: dict[str, NDArray[np.float64]] = field(repr=False)
    tooth_moment_Nm: dict[str, NDArray[np.float64]] = field(repr=False)
    shear_N: dict[str, NDArray[np.float64]] = field(repr=False)
    thrust_share_N: NDArray[np.float64] = field(repr=False)
    torque_share_Nm: NDArray[np.float64] = field(repr=False)

    @property
    def meshes(self) -> tuple[str, ...]:
        return self.geometry.meshes

    def hub_force_N(self, mesh: str) -> NDArray[np.float64]:
        """Everything the coupling puts on hub ``mesh`` ``(M, 3)``: its teeth's force less
        what the floating member takes from it (shear and thrust share)."""
        f = self.tooth_force_N[mesh].copy()
        if mesh in self.shear_N:
            f -= self.thrust_share_N[:, None] * self.geometry.sleeve_axis + self.shear_N[mesh]
        return f

    def hub_moment_Nm(self, mesh: str) -> NDArray[np.float64]:
        """The moment on hub ``mesh`` about its mesh centre ``(M, 3)`` (hub B's with the
        torque imbalance it carries)."""
        m = self.tooth_moment_Nm[mesh].copy()
        if mesh == "B":
            m -= self.torque_share_Nm[:, None] * self.geometry.sleeve_axis
        return m

    def machine_loads(self, mesh: str) -> dict[str, NDArray[np.float64]]:
        """Per rotation ``(M,)``: the bending moment on the shaft at the mesh centre and
        the radial force (magnitudes across the shaft's axis), the axial force (along it,
        positive pulling the shaft toward the coupling's centre) and the torque it
        carries (positive for positive torque)."""
        h = self.geometry.hub_axis(mesh)
        F, M = self.hub_force_N(mesh), self.hub_moment_Nm(mesh)
        f_ax, m_ax = F @ h, M @ h
        inward = 1.0 if mesh == "A" else -1.0
        return {"bending_moment_Nm": np.linalg.norm(M - m_ax[:, None] * h, axis=1),
                "radial_force_N": np.linalg.norm(F - f_ax[:, None] * h, axis=1),
                "axial_force_N": inward * f_ax, "torque_Nm": -inward * m_ax}

    def floating_residual(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """What is left of the floating member's force ``(M, 3)`` and moment about ``O_A``
        ``(M, 3)`` once all its loads are summed: rounding (two engagements)."""
        if len(self.meshes) < 2:
            raise ArgumentError("engagements", 1, "2: a single engagement has no floating "
                                "member")
        F = -(self.hub_force_N("A") + self.hub_force_N("B"))
        arm = 1e-3 * self.geometry.centre_b_mm
        M = -(self.hub_moment_Nm("A") + self.hub_moment_Nm("B")
              + np.cross(arm, self.hub_force_N("B")))
        return F, M

    def windup_rad(self) -> NDArray[np.float64]:
        """Shaft A's turn against shaft B at the teeth ``(M,)``: the meshes' wind-ups in
        series (signed like the torque)."""
        out = np.asarray(self.results["A"].windup_rad, float).copy()
        if "B" in self.results:
            out -= self.results["B"].windup_rad
        return out

    def rows(self) -> Iterator[tuple]:
        """Per rotation and mesh, :data:`LOAD_COLUMNS`."""
        loads = {m: self.machine_loads(m) for m in self.meshes}
        for j, psi in enumerate(self.angles_deg.tolist()):
            for m in self.meshes:
                res = self.results[m]
                yield (psi, m, res.misalignment_deg, float(res.angles_deg[j]),
                       *(float(loads[m][k][j]) for k in MACHINE_LOADS),
                       float(np.max(res.tangential_force_N[:, j])),
                       float(res.windup_rad[j]))

    def write_csv(self, path: str | Path) -> Path:
        """:meth:`rows` under :data:`LOAD_COLUMNS`, atomically."""
        return write_csv_rows(path, LOAD_COLUMNS, self.rows(), comments=[
            "loads each gear mesh puts on its shaft over a turn: moments about the mesh "
            "centre, forces in N (docs/coupling.md)"])

    def summary(self) -> dict[str, Any]:
        """Plain data (units in the keys): the operating point, each mesh's angle, phase,
        tooth loads and machine loads over the turn, the torques, the wind-up and the
        floating member's equilibrium."""
        out: dict[str, Any] = {"torque_Nm": self.torque_Nm, "angles": int(self.angles_deg.size),
                               "model": self.results["A"].model,
                               **self.geometry.summary()}
        torques = {}
        for m in self.meshes:
            res, loads = self.results[m], self.machine_loads(m)
            torques[m] = float(np.mean(loads["torque_Nm"]))
            out[f"mesh_{m}"].update(
                loaded_flank=res.loaded_flank, q=res.q(),
                max_tooth_load_N=float(np.max(res.tangential_force_N)),
                max_normal_force_N=float(np.max(res.normal_force_N)),
                **{k: _extremes(v) for k, v in loads.items()})
        windup = self.windup_rad()
        out["windup_rad"] = _extremes(windup)
        if len(self.meshes) == 2:
            out["torque_loss_Nm"] = torques["A"] - torques["B"]
            out["equilibrium"] = self.equilibrium()
        return out

    def equilibrium(self) -> dict[str, float]:
        """The floating member's largest residual force and moment over the turn, each
        relative to the largest tooth normal force and to the largest mesh moment (the
        teeth's, about the mesh centre)."""
        F, M = self.floating_residual()
        scale_f = max(float(np.max(r.normal_force_N)) for r in self.results.values())
        scale_m = max(float(np.max(np.linalg.norm(v, axis=1)))
                      for v in self.tooth_moment_Nm.values())
        return {"residual_force_N": float(np.max(np.linalg.norm(F, axis=1))),
                "residual_moment_Nm": float(np.max(np.linalg.norm(M, axis=1))),
                "relative_force": _ratio(np.max(np.linalg.norm(F, axis=1)), scale_f),
                "relative_moment": _ratio(np.max(np.linalg.norm(M, axis=1)), scale_m),
                "shear_max_N": float(max(np.max(np.linalg.norm(v, axis=1))
                                         for v in self.shear_N.values())),
                "thrust_share_max_N": float(np.max(np.abs(self.thrust_share_N))),
                "torque_share_mean_Nm": float(np.mean(self.torque_share_Nm))}


def _ratio(a: float, b: float) -> float:
    return float(a / b) if b > 0 else 0.0


def _extremes(a: NDArray) -> dict[str, float]:
    return {"min": float(np.min(a)), "mean": float(np.mean(a)), "max": float(np.max(a))}


def floating_balance(centre_b_mm: NDArray, axis: NDArray, force_N: dict[str, NDArray],
                     moment_Nm: dict[str, NDArray]
                     ) -> tuple[dict[str, NDArray], NDArray, NDArray]:
    """What holds the floating member (module docstring): the shear it takes from each hub
    ``{"A", "B"}`` (each ``(M, 3)``, across ``axis``), the thrust it takes from each
    ``(M,)`` and the moment about ``axis`` it takes from hub B ``(M,)``, from the teeth's
    forces ``(M, 3)`` on the hubs and their moments about the mesh centres ``O_A`` (the
    origin) and ``O_B`` (``centre_b_mm``)."""
    s = np.asarray(axis, float)
    arm = 1e-3 * np.asarray(centre_b_mm, float)
    F = -(force_N["A"] + force_N["B"])
    M = -(moment_Nm["A"] + moment_Nm["B"]) - np.cross(arm, force_N["B"])
    thrust, torque = F @ s, M @ s
    m_across = M - torque[:, None] * s
    f_across = F - thrust[:, None] * s
    shear_b = np.cross(s, m_across) / float(np.linalg.norm(arm))
    return {"A": -f_across - shear_b, "B": shear_b}, -0.5 * thrust, -torque


def whole_loads(spec: CouplingSpec, layout: CouplingLayout, alignment: ShaftAlignment,
                torque_Nm: float | None = None, *, angles_deg: ArrayLike | None = None,
                model: str | None = None) -> WholeLoads:
    """Both meshes of the coupling at one torque over a turn (module docstring).

    Parameters
    ----------
    spec : CouplingSpec
        Hub A (and hub B unless the layout gives its own).
    layout : CouplingLayout
    alignment : ShaftAlignment
    torque_Nm : float, optional
        Shaft A's torque, signed; default the spec's ``[load]`` torque.
    angles_deg : (M,) float, optional
        Coupling rotations (shaft A's turn); default :func:`default_turn`.
    model : str, optional
        Load model of both meshes; default the spec's.
    """
    geom = coupling_geometry(spec, layout, alignment)
    T = resolve_torque_Nm(geom.spec_a, torque_Nm)
    model = resolve_model(geom.spec_a, model)
    psi = default_turn(geom) if angles_deg is None else angle_list(angles_deg, "angles_deg")
    results = {m: load(geom.spec(m), geom.misalignment_deg(m), geom.mesh_rotations_deg(m, psi),
                       torque_Nm=mesh_torque_Nm(m, T), model=model) for m in geom.meshes}
    return loads_from_results(geom, T, psi, results)


def loads_from_results(geom: CouplingGeometry, torque_Nm: float, psi_deg: NDArray,
                       results: dict[str, LoadResult]) -> WholeLoads:
    """:class:`WholeLoads` of the meshes' load results (each at its rotations of
    ``psi_deg`` and its torque, :func:`mesh_torque_Nm`)."""
    force, moment = {}, {}
    for m, res in results.items():
        F, M = hub_wrench(res)
        H = geom.hub_frame(m)
        force[m], moment[m] = F @ H.T, M @ H.T
    n = len(psi_deg)
    if len(results) == 2:
        shear, thrust, torque = floating_balance(geom.centre_b_mm, geom.sleeve_axis, force,
                                                 moment)
    else:
        shear, thrust, torque = {}, np.zeros(n), np.zeros(n)
    return WholeLoads(geom, float(torque_Nm), np.asarray(psi_deg, float), results, force,
                      moment, shear, thrust, torque)


__all__ = ["LOAD_COLUMNS", "MACHINE_LOADS", "WholeLoads", "default_turn", "floating_balance",
           "loads_from_results", "mesh_torque_Nm", "whole_loads"]
