"""The volume mesh container: quadratic tetrahedra with named boundary regions."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError

# corner nodes of the four faces of a C3D10 (Abaqus/CalculiX face numbers S1..S4)
TET_FACES = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])

AGGREGATES = {
    "FLANK_CW": ("_FLANK_CW",), "FLANK_CCW": ("_FLANK_CCW",),
    "FILLET": ("_FILLET_CW", "_FILLET_CCW"), "CUT": ("CUT_CW", "CUT_CCW"),
}
"""Named unions of regions written beside them: name -> region-name endings."""


@dataclass(frozen=True, eq=False)
class VolumeMesh:
    """A quadratic tetrahedral mesh of a part or sector with named boundary regions.

    Attributes
    ----------
    part : str
        ``"hub"`` or ``"sleeve"`` (its own frame, mm).
    nodes : (n, 3) float
        Node coordinates, mm.
    tets : (m, 10) int
        0-based node indices in CalculiX/Abaqus C3D10 (= VTK) order: four corners, then
        edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
    regions : dict of str -> (k, 6) int
        Boundary faces of each named region (6-node triangles, corners first); regions are
        disjoint: ``T<k>_FLANK_CW``, ``T<k>_FLANK_CCW``, ``T<k>_FILLET_CW``, ``...ROOT``,
        ``...TIP``, ``...CHAMFER_CW/CCW``, ``END``, ``BODY``, ``BORE``, ``OUTER`` (sleeve
        outside diameter), ``CUT_CW`` / ``CUT_CCW`` (sector cut planes at the smaller /
        larger polar angle).
    faces : dict of str -> (k, 2) int
        The same faces as (0-based element index, face number 1..4).
    teeth : list of int or None
        Teeth of the sector (``None``: the whole part).
    size_mm : float
        Element size on the teeth.
    quality : dict
        ``min_scaled_jacobian``, ``max_aspect_ratio``, ``p99_aspect_ratio``, counts, times.
    """

    part: str
    nodes: NDArray[np.float64]
    tets: NDArray[np.int64]
    regions: dict[str, NDArray[np.int64]]
    faces: dict[str, NDArray[np.int64]]
    teeth: list[int] | None
    size_mm: float
    quality: dict = field(default_factory=dict)

    def region_names(self, name: str) -> list[str]:
        """Regions of a region or aggregate name (``FLANK_CW``, ``FILLET``, ``CUT``)."""
        if name in self.regions:
            return [name]
        ends = AGGREGATES.get(name)
        if ends is None:
            raise KeyError(f"no region or aggregate named {name!r}")
        return [r for r in self.regions if r.endswith(ends) or r in ends]

    def node_set(self, name: str) -> NDArray[np.int64]:
        """Sorted 0-based indices of the nodes (corner and mid-edge) of a region/aggregate."""
        names = self.region_names(name)
        if not names:
            return np.zeros(0, dtype=np.int64)
        return np.unique(np.concatenate([self.regions[r].ravel() for r in names]))

    def face_set(self, name: str) -> NDArray[np.int64]:
        """``(k, 2)`` (element index, face number) of a region or aggregate."""
        names = self.region_names(name)
        if not names:
            return np.zeros((0, 2), dtype=np.int64)
        return np.concatenate([self.faces[r] for r in names])

    def set_names(self) -> list[str]:
        """Regions, then the non-empty aggregates."""
        out = list(self.regions)
        out += [a for a in AGGREGATES if a not in self.regions and self.region_names(a)]
        return out


def tet_volumes(nodes: NDArray, tets: NDArray) -> NDArray[np.float64]:
    """Signed volumes ``(m,)`` of the corner tetrahedra (positive: C3D10 orientation)."""
    a, b, c, d = (nodes[tets[:, i]] for i in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6.0


def aspect_ratios(nodes: NDArray, tets: NDArray) -> NDArray[np.float64]:
    """Aspect ratio ``(m,)`` of the corner tetrahedra: longest edge / (2 sqrt(6) inradius);
    1 for a regular tetrahedron."""
    p = [nodes[tets[:, i]] for i in range(4)]
    edges = np.stack([np.linalg.norm(p[j] - p[i], axis=1)
                      for i, j in ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))])
    area = sum(0.5 * np.linalg.norm(np.cross(p[j] - p[i], p[k] - p[i]), axis=1)
               for i, j, k in TET_FACES)
    vol = np.abs(tet_volumes(nodes, tets))
    r_in = 3.0 * vol / np.maximum(area, np.finfo(float).tiny)
    with np.errstate(divide="ignore"):
        return np.where(r_in > 0, edges.max(axis=0) / (2.0 * np.sqrt(6.0) * r_in), np.inf)


def match_faces(tets: NDArray, tris: NDArray) -> NDArray[np.int64]:
    """(element index, face number 1..4) ``(k, 2)`` of the boundary triangles ``tris (k, >=3)``
    (matched by their corner nodes)."""
    n = int(max(tets.max(), tris.max())) + 1
    corners = np.sort(tets[:, TET_FACES], axis=2).reshape(-1, 3).astype(np.int64)
    key = (corners[:, 0] * n + corners[:, 1]) * n + corners[:, 2]
    order = np.argsort(key)
    t = np.sort(tris[:, :3], axis=1).astype(np.int64)
    want = (t[:, 0] * n + t[:, 1]) * n + t[:, 2]
    pos = np.searchsorted(key[order], want)
    pos = np.minimum(pos, len(key) - 1)
    hit = order[pos]
    if not np.all(key[hit] == want):
        raise ArgumentError("tris", f"{len(tris)} triangles", "boundary triangles that are "
                            "element faces of tets")
    return np.stack([hit // 4, hit % 4 + 1], axis=1)
