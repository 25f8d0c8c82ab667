"""Contact pressure over the developed loaded flank of chosen teeth, for every load model.

The developed flank has the axial position ``z`` across and the involute arc length from
the base circle ``s = (r² - r_b²) / (2 r_b)`` up (the surface model's grid). The
``linear`` and ``compliance`` models report a patch per tooth, drawn here with their
contact laws' pressure distribution: a Hertz ellipse ``p0 sqrt(1 - (dz/b)² - (ds/a)²)``
(semi-axes ``b`` along the face, ``a`` across the depth) in the elliptic regime, a strip
``p0 sqrt(1 - (dz/b)²)`` over the whole active profile in the line regime, cut at the face
ends. The ``surface`` model's own pressure grid is the one it solved at that rotation
(kept in :attr:`LoadResult.pressure_fields`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError
from ..geometry import developed_arc
from .contact import REGIMES, contact_model
from .models.registry import load_model


@dataclass(frozen=True)
class PatchMap:
    """Contact pressure of one tooth over its developed loaded flank.

    Attributes
    ----------
    regime : str
        ``hertz``, ``line`` or ``none`` (the contact laws' patch), ``grid`` (the pressure
        grid of a model that solves one).
    z_mm : (nz,) float
        Axial cell centres across the face.
    s_mm : (ns,) float
        Involute arc length from the base circle of the cell centres.
    pressure_MPa : (nz, ns) float
        Contact pressure (0 outside the patch and off the flank).
    face_z_mm, s_lo_mm, s_hi_mm : (nf,) float
        The active profile (where hub and sleeve flanks both exist) over the whole face.
    interior_pressure_MPa : float
        The model's grid-independent pressure of the tooth (``LoadResult``'s).
    """

    tooth: int
    theta_deg: float
    normal_force_N: float
    regime: str
    edge_contact: bool
    half_face_mm: float
    z_mm: NDArray[np.float64]
    s_mm: NDArray[np.float64]
    pressure_MPa: NDArray[np.float64]
    face_z_mm: NDArray[np.float64]
    s_lo_mm: NDArray[np.float64]
    s_hi_mm: NDArray[np.float64]
    interior_pressure_MPa: float

    @property
    def peak_MPa(self) -> float:
        return float(np.max(self.pressure_MPa, initial=0.0))


def most_loaded(res, rotation: int, count: int) -> NDArray[np.intp]:
    """The ``count`` most loaded teeth at ``rotation`` (largest normal load first)."""
    W = res.normal_force_N[:, rotation]
    order = np.argsort(-W, kind="stable")
    return order[:max(1, min(count, int(np.sum(W > 0)) or 1))]


def patch_maps(res, rotation: int = 0, teeth=None, *, count: int = 6,
               grid: tuple[int, int] = (481, 61)) -> list[PatchMap]:
    """Pressure maps of ``teeth`` (default: the ``count`` most loaded) at one rotation.

    Parameters
    ----------
    res : LoadResult
    rotation : int
        Index into ``res.angles_deg``.
    teeth : sequence of int, optional
    count : int
        Teeth drawn when ``teeth`` is not given.
    grid : (int, int)
        Cells across the face and the depth of the analytical maps (the surface model keeps
        its own grid).

    Returns
    -------
    list of PatchMap
    """
    M = res.angles_deg.size
    if not (isinstance(rotation, int | np.integer) and 0 <= rotation < M):
        raise ArgumentError("rotation", rotation, f"an index of the {M} rotations")
    chosen = most_loaded(res, rotation, count) if teeth is None else np.asarray(teeth, int)
    if chosen.size == 0 or np.any((chosen < 0) | (chosen >= res.teeth)):
        raise ArgumentError("teeth", teeth, f"tooth numbers 0-{res.teeth - 1}")
    if load_model(res.model).pressure_grid and abs(res.torque_Nm) > 0:
        return _surface_maps(res, rotation, chosen)
    return _analytic_maps(res, rotation, chosen, grid)


def _profile(cm, r_b: float, z: NDArray) -> tuple[NDArray, NDArray]:
    """Active profile ``(s_lo, s_hi)`` at axial positions ``z``."""
    lo, hi = cm.depth_limits(z)
    return developed_arc(lo, r_b), developed_arc(hi, r_b)


def _analytic_maps(res, j: int, teeth: NDArray, grid: tuple[int, int]) -> list[PatchMap]:
    spec = res.spec
    cm = contact_model(spec)
    r_b, hf = spec.tooth.base_radius, cm.half_face
    nz, ns = grid
    z = np.linspace(-hf, hf, nz)
    s_lo, s_hi = _profile(cm, r_b, z)
    s = np.linspace(float(np.min(s_lo)), float(np.max(s_hi)), ns)
    on_flank = (s[None, :] >= s_lo[:, None]) & (s[None, :] <= s_hi[:, None])
    out = []
    for k in teeth:
        W = float(res.normal_force_N[k, j])
        zc, rc = float(res.contact_z_mm[k, j]), float(res.contact_r_mm[k, j])
        p = np.zeros((nz, ns))
        if W > 0:
            g = cm.geometry(np.array([zc]), np.array([rc]))
            p0 = float(res.interior_pressure_MPa[k, j])
            if res.contact_regime[k, j] == REGIMES.index("hertz"):
                a, b, _ = (float(v[0]) for v in cm._hertz(np.array([W]), g))
                sc = float(developed_arc(rc, r_b))
                u = ((z[:, None] - zc) / b) ** 2 + ((s[None, :] - sc) / a) ** 2
            else:
                b = float(cm._line(np.array([W]), g)[0][0])
                u = np.broadcast_to(((z[:, None] - zc) / b) ** 2, (nz, ns))
            p = np.where(on_flank, p0 * np.sqrt(np.clip(1.0 - u, 0.0, None)), 0.0)
        out.append(PatchMap(int(k), float(res.theta_deg[k, j]), W,
                            REGIMES[int(res.contact_regime[k, j])],
                            bool(res.edge_contact[k, j]), hf, z, s, p, z, s_lo, s_hi,
                            float(res.interior_pressure_MPa[k, j])))
    return out


def _surface_maps(res, j: int, teeth: NDArray) -> list[PatchMap]:
    spec = res.spec
    if res.pressure_fields is None:
        raise ArgumentError("res", "a LoadResult without pressure_fields", "the result of "
                            "a load with the surface model (it keeps its pressure grids)")
    f = res.pressure_fields[j]
    pressure, solved = f["pressure_MPa"], list(f["teeth"])
    cm = contact_model(spec)
    r_b, hf = spec.tooth.base_radius, cm.half_face
    face = np.linspace(-hf, hf, 101)
    s_lo, s_hi = _profile(cm, r_b, face)
    maps = []
    for k in teeth:
        if int(k) in solved:
            i = solved.index(int(k))
            z, p = f["z_mm"][i], np.where(f["mask"][i], pressure[i], 0.0)
        elif len(solved):  # an unloaded tooth: an empty map over a solved tooth's grid
            z, p = f["z_mm"][0], np.zeros_like(pressure[0])
        else:
            z, p = np.linspace(-hf, hf, 2), np.zeros((2, f["s_mm"].size))
        maps.append(PatchMap(int(k), float(res.theta_deg[k, j]),
                             float(res.normal_force_N[k, j]), "grid",
                             bool(res.edge_contact[k, j]), hf, np.asarray(z, float),
                             np.asarray(f["s_mm"], float), p, face, s_lo, s_hi,
                             float(res.interior_pressure_MPa[k, j])))
    return maps


def patch_extent(res, rotation: int = 0) -> tuple[NDArray, NDArray]:
    """Axial extent ``(z_lo, z_hi)`` ``(N,)`` of every tooth's patch at one rotation, cut at
    the face ends (equal where a tooth carries no load): the patch length along the face
    about its contact point."""
    j = rotation
    hf = 0.5 * res.spec.hub.face_width
    zc = res.contact_z_mm[:, j]
    half = 0.5 * res.patch_length_mm[:, j]
    loaded = res.normal_force_N[:, j] > 0
    lo = np.where(loaded, np.clip(zc - half, -hf, hf), zc)
    hi = np.where(loaded, np.clip(zc + half, -hf, hf), zc)
    if not np.all(np.isfinite(lo) & np.isfinite(hi)):  # pragma: no cover - LoadResult is finite
        raise ArgumentError("patch extent", "not finite", "a finite patch")
    return lo, hi

