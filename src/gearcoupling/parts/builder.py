"""Assembling structured vertex grids into one closed, consistently wound triangle mesh.

A part is built pitch by pitch: grids of one pitch (tooth outline rows, circles) are
rotated to every requested tooth, neighbouring pitches share their boundary column, and
surfaces between grids are quad strips (tooth band, cylinders, annuli), zipper strips
between two chains (end faces) or triangulated planar walls (sector sides). Every face
carries a surface kind and a tooth index (``-1`` where no tooth owns it).
"""

from __future__ import annotations

import itertools
import math
import numbers
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError, GeometryError
from ..numeric import TINY

SURFACE_KINDS = ("flank_cw", "flank_ccw", "fillet_cw", "fillet_ccw", "root", "tip",
                 "chamfer_cw", "chamfer_ccw", "end", "body", "bore", "side")
"""Surface kinds, in the order of their integer codes (``SURFACE_KINDS.index(kind)``)."""
KIND_CODE = {k: i for i, k in enumerate(SURFACE_KINDS)}
MIN_RING = 8  # circle segments per pitch at least: end faces need vertices to fan from


@dataclass(frozen=True)
class Run:
    """Cyclically contiguous teeth ``start, start + 1, ...`` (``count`` of ``teeth``)."""

    start: int
    count: int
    teeth: int

    @property
    def closed(self) -> bool:
        return self.count == self.teeth

    def tooth(self, p: int) -> int:
        return (self.start + p) % self.teeth


def tooth_runs(teeth: int, selection) -> list[Run]:
    """Split a tooth selection (``None`` = all) into cyclically contiguous runs."""
    if selection is None:
        return [Run(0, teeth, teeth)]
    allowed = f"a non-empty selection of whole tooth indices from 0 to {teeth - 1}"
    if isinstance(selection, str | bytes) or not hasattr(selection, "__iter__"):
        raise ArgumentError("teeth", str(selection)[:60], allowed)
    picked = list(itertools.islice(selection, 2 * teeth + 1))  # an endless one is refused
    if len(picked) > 2 * teeth or not all(
            isinstance(k, numbers.Integral) and not isinstance(k, bool) for k in picked):
        raise ArgumentError("teeth", str(picked)[:60], allowed)
    sel = sorted({int(k) for k in picked})
    if not sel or sel[0] < 0 or sel[-1] >= teeth:
        raise ArgumentError("teeth", list(selection), "a non-empty selection of tooth "
                            f"indices from 0 to {teeth - 1}")
    if len(sel) == teeth:
        return [Run(0, teeth, teeth)]
    present = set(sel)
    starts = [k for k in sel if (k - 1) % teeth not in present]
    runs = []
    for s in starts:
        n = 1
        while (s + n) % teeth in present:
            n += 1
        runs.append(Run(s, n, teeth))
    return runs


def tile(pitch: NDArray, run: Run) -> NDArray[np.float64]:
    """Rotate a pitch grid ``(rows, C + 1, 2)`` (both ends included) to the run's teeth.

    Returns ``(rows, count * C [+ 1 if open], 2)``.
    """
    one = pitch[:, :-1]
    k = 2 * math.pi * (run.start + np.arange(run.count)) / run.teeth
    c, s = np.cos(k)[:, None, None], np.sin(k)[:, None, None]
    x = c * one[None, :, :, 0] - s * one[None, :, :, 1]
    y = s * one[None, :, :, 0] + c * one[None, :, :, 1]
    out = np.stack([x, y], axis=-1)  # (count, rows, C, 2)
    out = np.swapaxes(out, 0, 1).reshape(pitch.shape[0], -1, 2)
    if not run.closed:
        a = 2 * math.pi * (run.start + run.count - 1) / run.teeth  # last pitch's end
        last = pitch[:, -1]
        end = np.stack([math.cos(a) * last[:, 0] - math.sin(a) * last[:, 1],
                        math.sin(a) * last[:, 0] + math.cos(a) * last[:, 1]], axis=-1)
        out = np.concatenate([out, end[:, None]], axis=1)
    return out


def ring_pitch(radius: float, teeth: int, count: int) -> NDArray[np.float64]:
    """``count + 1`` points of a circle over one pitch ``-pi/N .. pi/N``, shape ``(count+1, 2)``."""
    a = -math.pi / teeth + 2 * math.pi / teeth * np.arange(count + 1) / count
    return np.stack([radius * np.cos(a), radius * np.sin(a)], axis=-1)


def _shape_cost(p: NDArray, q: NDArray, r: NDArray) -> NDArray:
    """Penalty of triangles ``(p, q, r)`` (``(..., 2)`` each): ``inf`` unless counter-clockwise,
    growing without bound as the largest angle approaches 180°."""
    area2 = (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - \
        (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])
    worst = np.full(area2.shape, -1.0)
    for a, b, c in ((p, q, r), (q, r, p), (r, p, q)):
        u, w = b - a, c - a
        cos = np.sum(u * w, -1) / np.maximum(np.linalg.norm(u, axis=-1)
                                             * np.linalg.norm(w, axis=-1), TINY)
        worst = np.maximum(worst, -cos)
    scale = np.maximum(np.sum((q - p) ** 2, -1), np.sum((r - p) ** 2, -1))
    good = area2 > 1e-12 * scale
    with np.errstate(divide="ignore"):
        cost = 1.0 / np.maximum(1.0 - worst, TINY) ** 2
    return np.where(good, cost, np.inf)


def zipper(outer: NDArray, inner: NDArray) -> NDArray[np.intp]:
    """Triangulate the planar strip between two chains that run counter-clockwise.

    The triangulation is the best strip triangulation (dynamic programming over the
    ``na x nb`` ways to advance along the two chains) under an additive penalty that
    forbids clockwise or degenerate triangles and grows steeply as the largest angle
    of a triangle approaches 180°.

    Parameters
    ----------
    outer, inner : (na, 2), (nb, 2) float
        Chains with common first and last polar angles; the strip lies between them.

    Returns
    -------
    triangles : (na + nb - 2, 3) int
        Counter-clockwise (normal +z); indices ``< na`` are outer points, ``>= na`` inner.

    Raises
    ------
    GeometryError
        If no strip triangulation has only counter-clockwise triangles.
    """
    outer, inner = np.asarray(outer, dtype=float), np.asarray(inner, dtype=float)
    na, nb = len(outer), len(inner)
    # move A: (inner j, outer i, outer i+1); move B: (inner j, outer i, inner j+1)
    cost_a = _shape_cost(inner[None, :], outer[:-1, None], outer[1:, None])  # (na-1, nb)
    cost_b = _shape_cost(inner[None, :-1], outer[:, None], inner[None, 1:])  # (na, nb-1)
    best = np.full((na, nb), np.inf)
    came_a = np.zeros((na, nb), dtype=bool)
    for i in range(na):
        row = np.full(nb, np.inf)
        if i == 0:
            row[0] = 0.0
        else:
            row = best[i - 1] + cost_a[i - 1]
        from_a = np.isfinite(row)
        for j in range(1, nb):
            via_b = row[j - 1] + cost_b[i, j - 1]
            if via_b < row[j]:
                row[j] = via_b
                from_a[j] = False
        best[i], came_a[i] = row, from_a
    if not np.isfinite(best[-1, -1]):
        raise GeometryError("end face cannot be triangulated between its outlines")
    tris = []
    i, j = na - 1, nb - 1
    while i > 0 or j > 0:
        if came_a[i, j]:
            tris.append((na + j, i - 1, i))
            i -= 1
        else:
            tris.append((na + j - 1, i, na + j))
            j -= 1
    return np.array(tris[::-1], dtype=np.intp)


def with_z(xy: NDArray, z: NDArray | float) -> NDArray:
    """Append the axial coordinate ``z`` (broadcast) to 2-D points ``(..., 2)``."""
    z = np.broadcast_to(np.asarray(z, dtype=float)[..., None], (*xy.shape[:-1], 1))
    return np.concatenate([xy, z], axis=-1)


def add_cap(b: MeshBuilder, cap: NDArray, outer: NDArray, inner: NDArray, run: Run,
            n_outer: int, n_inner: int, *, flip: bool) -> None:
    """Add the pitch end-face triangulation ``cap`` to every tooth of the run.

    ``outer``/``inner`` are the run's index chains; a pitch spans ``n_outer``/``n_inner``
    segments of them; local indices ``< n_outer + 1`` are outer points.
    """
    p = np.arange(run.count)[:, None, None]
    is_outer = cap < n_outer + 1
    glob_o = (p * n_outer + cap) % len(outer) if run.closed else p * n_outer + cap
    local_i = cap - (n_outer + 1)
    glob_i = (p * n_inner + local_i) % len(inner) if run.closed else p * n_inner + local_i
    tris = np.where(is_outer, outer[np.where(is_outer, glob_o, 0)],
                    inner[np.where(is_outer, 0, glob_i)])
    if flip:
        tris = tris[..., ::-1]
    tooth = np.repeat([run.tooth(k) for k in range(run.count)], len(cap))
    b.faces(tris.reshape(-1, 3), "end", tooth)


class MeshBuilder:
    """Collects vertices and labelled triangles of one part."""

    def __init__(self) -> None:
        self._verts: list[NDArray] = []
        self._faces: list[NDArray] = []
        self._kind: list[NDArray] = []
        self._tooth: list[NDArray] = []
        self.count = 0

    def vertices(self, points: NDArray) -> NDArray[np.intp]:
        """Add points ``(..., 3)``; returns their indices with shape ``points.shape[:-1]``."""
        pts = np.asarray(points, dtype=float)
        idx = self.count + np.arange(pts.size // 3).reshape(pts.shape[:-1])
        self._verts.append(pts.reshape(-1, 3))
        self.count += pts.size // 3
        return idx

    def faces(self, tris: NDArray, kind, tooth) -> None:
        """Add triangles ``(k, 3)`` with a kind name (or code array) and tooth index/array."""
        tris = np.asarray(tris, dtype=np.int64).reshape(-1, 3)
        k = np.broadcast_to(np.asarray(KIND_CODE[kind] if isinstance(kind, str) else kind,
                                       dtype=np.int16), (len(tris),))
        self._faces.append(tris)
        self._kind.append(np.array(k))
        self._tooth.append(np.array(np.broadcast_to(np.asarray(tooth, dtype=np.int32),
                                                    (len(tris),))))

    def strip(self, a: NDArray, b: NDArray, kind, tooth, *, closed: bool = False,
              flip: bool = False) -> None:
        """Quads between two index chains; normal ``(a[i+1] - a[i]) x (b[i] - a[i])``.

        ``kind`` and ``tooth`` are per quad (scalar or ``(n - 1,)``, ``(n,)`` if closed);
        each quad is split along its shorter diagonal.
        """
        if closed:
            a = np.append(a, a[0])
            b = np.append(b, b[0])
        a0, a1, b0, b1 = a[:-1], a[1:], b[:-1], b[1:]
        v = np.concatenate(self._verts) if len(self._verts) > 1 else self._verts[0]
        self._verts = [v]
        d1 = np.sum((v[a0] - v[b1]) ** 2, axis=1)
        d2 = np.sum((v[a1] - v[b0]) ** 2, axis=1)
        use1 = (d1 <= d2)[:, None]
        t1 = np.where(use1, np.stack([a0, a1, b1], 1), np.stack([a0, a1, b0], 1))
        t2 = np.where(use1, np.stack([a0, b1, b0], 1), np.stack([a1, b1, b0], 1))
        tris = np.stack([t1, t2], axis=1).reshape(-1, 3)
        if flip:
            tris = tris[:, ::-1]
        n = len(a0)
        kind = np.repeat(np.broadcast_to(KIND_CODE[kind] if isinstance(kind, str) else kind,
                                         (n,)), 2)
        self.faces(tris, kind, np.repeat(np.broadcast_to(tooth, (n,)), 2))

    def wall(self, top: NDArray, bottom: NDArray, *, start: bool) -> None:
        """Planar sector side wall between two index chains running toward ``+z``.

        ``top`` is the chain farther from the axis; the wall at the ``start`` of a run faces
        decreasing polar angle, the one at its end increasing polar angle.
        """
        v = np.concatenate(self._verts)
        self._verts = [v]

        def uv(idx):
            p = v[np.asarray(idx)]
            return np.stack([p[:, 2], -np.hypot(p[:, 0], p[:, 1])], axis=-1)

        tri = zipper(uv(top), uv(bottom))  # counter-clockwise in (z, -r): normal -e_beta
        ids = np.concatenate([np.asarray(top), np.asarray(bottom)])[tri]
        self.faces(ids if start else ids[:, ::-1], "side", -1)

    def arrays(self):
        """``vertices (n, 3)``, ``faces (m, 3)``, ``kind (m,)``, ``tooth (m,)``."""
        return (np.concatenate(self._verts), np.concatenate(self._faces),
                np.concatenate(self._kind), np.concatenate(self._tooth))
