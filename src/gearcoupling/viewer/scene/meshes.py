"""The meshes the viewer draws: hub and sleeve meshed once per level of detail, the hub
split into a body and one patch per (flank, tooth) so a pose change only recolours
patches, and the sleeve with its cutaways (manifold3d booleans, closed at the cuts).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentError
from ...geometry import FLANKS
from ...interference import PreparedPart
from ...parts import SURFACE_KINDS, build_part, check_tolerance
from ...spec import CouplingSpec

if TYPE_CHECKING:
    import trimesh

LOD_DIVISORS = {"coarse": 20.0, "medium": 100.0, "fine": 400.0}
"""Levels of detail: chordal tolerance = module / divisor."""
CUTAWAYS = ("none", "quarter", "half", "midplane")
"""Sleeve cutaways: nothing removed; the quadrant x < 0, y < 0 (facing the default
camera); the half y < 0 (the section through the tilt axis shows the pivot teeth); the
half z > 0 (the midplane section shows every tooth in its space)."""


@dataclass(frozen=True)
class Patch:
    """A triangle mesh: ``vertices (n, 3) float32`` (mm), ``faces (m, 3) uint32``."""

    vertices: NDArray[np.float32]
    faces: NDArray[np.uint32]


def submesh(vertices: NDArray, faces: NDArray) -> Patch:
    """The faces ``(m, 3)`` with only the vertices they use, re-indexed."""
    used, inverse = np.unique(faces.ravel(), return_inverse=True)
    return Patch(np.asarray(vertices[used], dtype=np.float32),
                 inverse.reshape(-1, 3).astype(np.uint32))


@dataclass(frozen=True)
class HubPieces:
    """The hub mesh split for colouring: ``body`` (every face but the flanks) and
    ``flanks[f][k]``, the flank ``f`` (0 cw, 1 ccw) of tooth ``k``, in the hub frame."""

    body: Patch
    flanks: tuple[tuple[Patch, ...], tuple[Patch, ...]]


def split_hub(mesh) -> HubPieces:
    """Split a hub mesh from :func:`gearcoupling.parts.build_part` by its face labels.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        With ``face_attributes["kind"]`` (codes into ``SURFACE_KINDS``) and
        ``face_attributes["tooth"]``.
    """
    verts = np.asarray(mesh.vertices)
    faces = np.asarray(mesh.faces)
    kind = np.asarray(mesh.face_attributes["kind"])
    tooth = np.asarray(mesh.face_attributes["tooth"])
    teeth = int(tooth.max()) + 1
    codes = [SURFACE_KINDS.index(f"flank_{f}") for f in FLANKS]
    flank = np.isin(kind, codes)
    body = submesh(verts, faces[~flank])
    pieces = []
    for code in codes:
        sel = np.flatnonzero(kind == code)
        order = sel[np.argsort(tooth[sel], kind="stable")]
        bounds = np.searchsorted(tooth[order], np.arange(teeth + 1))
        pieces.append(tuple(submesh(verts, faces[order[bounds[k]:bounds[k + 1]]])
                            for k in range(teeth)))
    return HubPieces(body, (pieces[0], pieces[1]))


def lod_tolerance(spec: CouplingSpec, lod: str) -> float:
    """Chordal tolerance (mm) of a level of detail (:data:`LOD_DIVISORS`)."""
    if lod not in LOD_DIVISORS:
        raise ArgumentError("lod", lod, f"one of {tuple(LOD_DIVISORS)}")
    return spec.tooth.module / LOD_DIVISORS[lod]


@dataclass(eq=False)
class SceneMeshes:
    """Hub and sleeve meshed once at one chordal tolerance, with what the viewer derives
    from them (hub pieces, sleeve cutaways, manifolds for the interference volume)."""

    spec: object
    tolerance_mm: float
    hub: trimesh.Trimesh  # hub frame
    sleeve: trimesh.Trimesh  # sleeve frame
    _cuts: dict = field(default_factory=dict)

    @cached_property
    def hub_pieces(self) -> HubPieces:
        return split_hub(self.hub)

    @cached_property
    def hub_manifold(self):
        return _manifold(self.hub)

    @cached_property
    def sleeve_manifold(self):
        return _manifold(self.sleeve)

    def sleeve_cut(self, cutaway: str) -> Patch:
        """The sleeve with a cutaway (:data:`CUTAWAYS`), cached."""
        if cutaway not in self._cuts:
            self._cuts[cutaway] = cut_sleeve(self.sleeve_manifold, cutaway)
        return self._cuts[cutaway]

    @property
    def triangles(self) -> int:
        return len(self.hub.faces) + len(self.sleeve.faces)


def view_tolerance(spec: CouplingSpec, tolerance_mm: float | None = None) -> float:
    """The meshes' chordal tolerance (mm; default ``coarse``), or :class:`SpecError`."""
    tol = lod_tolerance(spec, "coarse") if tolerance_mm is None else tolerance_mm
    try:
        return check_tolerance(spec, tol)
    except ValueError as err:
        raise ArgumentError("tolerance_mm", tolerance_mm, str(err).split(": ", 1)[-1]) from err


def build_scene_meshes(spec: CouplingSpec, tolerance_mm: float | None = None) -> SceneMeshes:
    """Mesh hub and sleeve for viewing (default: the ``coarse`` level of detail)."""
    tol = view_tolerance(spec, tolerance_mm)
    return SceneMeshes(spec, tol, build_part(spec, "hub", tolerance_mm=tol),
                       build_part(spec, "sleeve", tolerance_mm=tol))


def _manifold(mesh):
    """The closed solid of a part mesh (manifold3d, checked), via the interference stage."""
    return PreparedPart.from_trimesh(mesh, ()).manifold


def patch_from_manifold(man) -> Patch:
    out = man.to_mesh()
    verts = np.asarray(out.vert_properties, dtype=np.float32)[:, :3]
    return Patch(np.ascontiguousarray(verts),
                 np.asarray(out.tri_verts, dtype=np.uint32).reshape(-1, 3))


_CUT_PLANES = {
    "none": [],
    "quarter": None,  # union of two trims, below
    "half": [((0.0, 1.0, 0.0), 0.0)],
    "midplane": [((0.0, 0.0, -1.0), 0.0)],
}


def cut_sleeve(sleeve_manifold, cutaway: str) -> Patch:
    """The sleeve solid with the :data:`CUTAWAYS` region removed, closed at the cuts.

    Parameters
    ----------
    sleeve_manifold : manifold3d.Manifold
        The sleeve in its frame.
    cutaway : {"none", "quarter", "half", "midplane"}
    """
    if cutaway not in CUTAWAYS:
        raise ArgumentError("cutaway", cutaway, f"one of {CUTAWAYS}")
    man = sleeve_manifold
    planes = _CUT_PLANES[cutaway]
    if planes is None:  # quarter: keep x >= 0 or y >= 0
        man = man.trim_by_plane((1.0, 0.0, 0.0), 0.0) + man.trim_by_plane((0.0, 1.0, 0.0), 0.0)
    else:
        for normal, offset in planes:
            man = man.trim_by_plane(normal, offset)
    return patch_from_manifold(man)
