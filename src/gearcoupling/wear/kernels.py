"""Pure numpy kernels of the wear model (docs/wear.md): depth maps on a developed flank, the
sliding speed at the cells of a pressure grid, the step rule, the wear limit's crossing and
the partial-slip test.

A depth map is ``(T, nz, ns)``: one map per tooth (``T = 1`` where every tooth wears
alike), constant over each cell of a developed flank (:class:`FlankGrid`: axial position
``z`` across, involute arc length from the base circle ``s`` up). :func:`sample` reads a
map on the cells of a pressure grid (each a rectangle on the flank: the map's mean over
it, or where the cells are finer than the map's, its linear interpolation), and
:func:`deposit` spreads a cell's value over the map cells its area overlaps, in
proportion, so what is deposited is kept to rounding and a pressure grid on a fixed
lattice leaves no stripes between its cells.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray


@dataclass(frozen=True)
class FlankGrid:
    """Cells over a developed flank: centres ``z0 + (i + 1/2) dz`` (``i < nz``) and ``s0 +
    (j + 1/2) ds`` (``j < ns``), mm."""

    z0: float
    dz: float
    nz: int
    s0: float
    ds: float
    ns: int

    @property
    def z_mm(self) -> NDArray[np.float64]:
        return np.asarray(self.z0 + (np.arange(self.nz) + 0.5) * self.dz, dtype=np.float64)

    @property
    def s_mm(self) -> NDArray[np.float64]:
        return np.asarray(self.s0 + (np.arange(self.ns) + 0.5) * self.ds, dtype=np.float64)

    @property
    def area_mm2(self) -> float:
        return self.dz * self.ds


def _overlaps(x: NDArray, width: float, lo: float, d: float, n: int
              ) -> tuple[NDArray[np.intp], NDArray]:
    """The map cells ``(K, ...)`` an interval ``[x - width/2, x + width/2]`` of each point
    overlaps along one axis of ``n`` cells ``[lo + i d, lo + (i + 1) d]``, and the share of
    the interval in each ``(K, ...)`` (summing to 1: the end cells reach to infinity, so
    what lies beyond the grid falls on them)."""
    a = (x - 0.5 * width - lo) / d
    b = (x + 0.5 * width - lo) / d
    K = math.ceil(width / d) + 1
    first = np.floor(a).astype(np.intp)
    idx = first[None] + np.arange(K).reshape((K,) + (1,) * x.ndim)
    left = np.where(idx <= 0, -np.inf, idx)
    right = np.where(idx >= n - 1, np.inf, idx + 1.0)
    share = np.maximum(np.minimum(b, right) - np.maximum(a, left), 0.0) / (b - a)
    share = np.where((idx >= 0) & (idx < n), share, 0.0)  # beyond: held by the end cells
    return np.clip(idx, 0, n - 1), share


def _linear(x: NDArray, lo: float, d: float, n: int) -> tuple[NDArray[np.intp], NDArray]:
    """The two cells ``(2, ...)`` whose centres bracket each point along one axis of ``n``
    cells, and the linear weights (beyond the end centres: the end cell's value)."""
    t = np.clip((x - lo) / d - 0.5, 0.0, n - 1.0)
    i = np.minimum(np.floor(t).astype(np.intp), max(n - 2, 0))
    w = t - i
    return np.stack([i, np.minimum(i + 1, n - 1)]), np.stack([1.0 - w, w])


def _weights(grid: FlankGrid, tooth: ArrayLike, z: NDArray, s: NDArray, dz: float,
             ds: float, smooth: bool = False):
    """Flat indices ``(K, ...)`` into ``(T, nz, ns)`` maps and the area shares ``(K, ...)``
    of cells ``dz`` by ``ds`` centred on ``(z, s)`` of teeth ``tooth`` (one per point of
    the first axis). ``smooth``: along an axis where the cells are narrower than the
    map's, the linear interpolation between the map's cell centres instead (so a map
    coarser than a grid reads as a smooth surface, not a staircase)."""
    z, s = np.broadcast_arrays(np.asarray(z, float), np.asarray(s, float))
    t = np.asarray(tooth, dtype=np.intp).reshape((-1,) + (1,) * (z.ndim - 1))
    iz, wz = (_linear(z, grid.z0, grid.dz, grid.nz) if smooth and dz < grid.dz else
              _overlaps(z, dz, grid.z0, grid.dz, grid.nz))
    js, ws = (_linear(s, grid.s0, grid.ds, grid.ns) if smooth and ds < grid.ds else
              _overlaps(s, ds, grid.s0, grid.ds, grid.ns))
    idx = ((t * grid.nz + iz)[:, None] * grid.ns + js[None, :])
    w = wz[:, None] * ws[None, :]
    return idx.reshape((-1, *z.shape)), w.reshape((-1, *z.shape))


def sample(maps: NDArray[np.float64], grid: FlankGrid, tooth: ArrayLike, z: ArrayLike,
           s: ArrayLike, dz: float, ds: float) -> NDArray[np.float64]:
    """``maps (T, nz, ns)`` read on cells ``dz`` by ``ds`` centred on ``z, s (n, ...)`` of
    teeth ``tooth (n,)`` (indices into the maps' first axis), shaped like the points: the
    map's mean over each cell (a map cell's value held over its area), or along an axis
    where the cells are narrower than the map's, its linear interpolation between cell
    centres."""
    idx, w = _weights(grid, tooth, np.asarray(z, float), np.asarray(s, float), dz, ds,
                      smooth=True)
    return np.sum(maps.reshape(-1)[idx] * w, axis=0)


def deposit(values: ArrayLike, grid: FlankGrid, tooth: ArrayLike, z: ArrayLike,
            s: ArrayLike, dz: float, ds: float, teeth: int) -> NDArray[np.float64]:
    """The transpose of :func:`sample` where the cells are no narrower than the map's:
    ``values (n, ...)`` of cells ``dz`` by ``ds`` centred on ``z, s`` of teeth ``tooth
    (n,)``, each spread over the map cells its area overlaps in proportion, as ``(teeth,
    nz, ns)`` sums; the total is kept."""
    return deposit_many([values], grid, tooth, z, s, dz, ds, teeth)[0]


def deposit_many(values: list[ArrayLike], grid: FlankGrid, tooth: ArrayLike, z: ArrayLike,
                 s: ArrayLike, dz: float, ds: float, teeth: int) -> list[NDArray[np.float64]]:
    """:func:`deposit` of several value arrays on the same cells (the overlaps found
    once)."""
    vs = [np.asarray(v, float) for v in values]
    shape = vs[0].shape
    idx, w = _weights(grid, tooth, np.broadcast_to(np.asarray(z, float), shape),
                      np.broadcast_to(np.asarray(s, float), shape), dz, ds)
    flat = idx.ravel()
    size = teeth * grid.nz * grid.ns
    return [np.bincount(flat, weights=(w * v).ravel(), minlength=size).astype(
        np.float64).reshape(teeth, grid.nz, grid.ns) for v in vs]


def sleeve_rows(r_mm: ArrayLike, half_angle: ArrayLike, r_b: float
                ) -> tuple[NDArray, NDArray, NDArray]:
    """Per depth row of the cw sleeve flank (polar angle ``-half_angle(r)`` at radius ``r``,
    ``(nd,)``): the polar angle, the unit tangent along the involute ``(nd, 2)`` (the
    developed ``s`` direction, in the transverse plane) and the unit normal ``(nd, 2)``."""
    r = np.asarray(r_mm, float)
    a = -np.asarray(half_angle, float)
    da = np.sqrt(np.maximum(r * r - r_b * r_b, 0.0)) / (r_b * r)  # d(-half)/dr
    t = np.stack([np.cos(a) - r * np.sin(a) * da, np.sin(a) + r * np.cos(a) * da], axis=-1)
    t /= np.linalg.norm(t, axis=-1, keepdims=True)
    return a, t, np.stack([-t[:, 1], t[:, 0]], axis=-1)


def slip_velocity(axis: NDArray, z_mm: NDArray, r_mm: NDArray, polar: NDArray,
                  tangent: NDArray, axial: ArrayLike = 0.0) -> tuple[NDArray, NDArray]:
    """Sliding velocity of the hub on the sleeve per unit rotation speed (mm/rad) at the
    sleeve flank points ``(r cos a, r sin a, z)`` of each tooth's frame, in the flank plane:
    its axial and profile (``s``) components, each ``(n, nf, nd)``.

    Both members turn at the same speed about their own axes through the pivot, the hub's
    axis ``axis (n, 3)`` in the tooth's frame, the sleeve's ``e_z``: ``v = (k - e_z) x q``,
    plus ``axial`` (mm/rad, ``(n,)`` or a number) along ``e_z`` (an axial float). ``z_mm (n,
    nf)``; ``r_mm, polar (nd,)`` and ``tangent (nd, 2)`` from :func:`sleeve_rows`. The
    component along the flank normal (a gap opening or closing, not sliding) is left out.
    """
    k = np.asarray(axis, float)
    kx, ky, kz = (k[:, i][:, None, None] for i in range(3))
    x = (np.asarray(r_mm) * np.cos(polar))[None, None, :]
    y = (np.asarray(r_mm) * np.sin(polar))[None, None, :]
    z = np.asarray(z_mm, float)[:, :, None]
    wx, wy, wz = kx, ky, kz - 1.0
    vx = wy * z - wz * y
    vy = wz * x - wx * z
    vz = wx * y - wy * x + np.reshape(np.asarray(axial, float), (-1, 1, 1))
    v_s = vx * tangent[:, 0] + vy * tangent[:, 1]
    return np.broadcast_to(vz, v_s.shape), v_s


def exposure_step(approach_mm: float, rate_max: float, fraction: float, floor: float,
                  remaining: float) -> float:
    """The next step of wear exposure (coefficient times hours): one that removes at most
    ``fraction`` of the elastic ``approach_mm`` at the point wearing fastest
    (``rate_max``, mm per unit exposure), at least ``floor``; all of ``remaining`` where
    nothing wears. The caller cuts it at the end of the history."""
    if not (rate_max > 0 and approach_mm > 0):
        return remaining
    return max(fraction * approach_mm / rate_max, floor)


def limit_crossing(loss0: ArrayLike, loss1: ArrayLike, limit: float) -> float | None:
    """Where along a step ``loss0 -> loss1`` (each ``(m,)``, linear in between) the largest
    loss first reaches ``limit``, as a share of the step in ``[0, 1]``; None if it does
    not."""
    a, b = np.asarray(loss0, float), np.asarray(loss1, float)
    if np.max(a) >= limit:
        return 0.0
    if np.max(b) < limit:
        return None
    rise = b - a
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = np.where(rise > 0, (limit - a) / np.where(rise > 0, rise, 1.0), np.inf)
    return float(np.clip(np.min(lam), 0.0, 1.0))


def slip_runs(loaded: NDArray[np.bool_], slip_z: NDArray, slip_s: NDArray,
              half_width_mm: NDArray, work: NDArray, dpsi: float, float_mm: float = 0.0
              ) -> tuple[float, float]:
    """The partial-slip test over a turn sampled every ``dpsi`` (rad): arrays ``(T, M)``
    per tooth and rotation in turning order. A run of consecutive loaded samples is one
    pass of a tooth through its loaded arc (a tooth loaded all round: the whole turn); its
    slip amplitude is half the largest excursion of the load centre's relative
    displacement (the signed sliding velocity ``slip_z``, ``slip_s`` mm/rad along the face
    and the profile, integrated), or an axial float's amplitude ``float_mm`` where larger,
    against the largest contact half-width along the sliding direction in the run.
    Returns the share of ``work`` (normal force times sliding) done in passes whose
    amplitude is below their half-width (partial slip, fretting: part of the contact is
    never uncovered), and the smallest ratio of amplitude to half-width (inf where nothing
    is loaded)."""
    partial = 0.0
    worst = math.inf
    total = float(np.sum(work))
    for row, vz, vs, hw, wk in zip(loaded, slip_z, slip_s, half_width_mm, work, strict=True):
        if not np.any(row):
            continue
        start = int(np.argmin(row)) if not np.all(row) else 0  # begin at an unloaded one
        order = np.roll(np.arange(row.size), -start)
        on = row[order]
        edges = np.flatnonzero(np.diff(np.concatenate([[0], on.astype(int), [0]])))
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            run = order[a:b]
            excursion = max(float(np.ptp(np.cumsum(v[run]))) for v in (vz, vs)) * dpsi
            amplitude = max(0.5 * excursion, float_mm)
            width = float(np.max(hw[run]))
            if width > 0:
                worst = min(worst, amplitude / width)
                if amplitude < width:
                    partial += float(np.sum(wk[run]))
    return (partial / total if total > 0 else 0.0), worst


__all__ = ["FlankGrid", "deposit", "deposit_many", "exposure_step", "limit_crossing", "sample",
           "sleeve_rows", "slip_runs", "slip_velocity"]
