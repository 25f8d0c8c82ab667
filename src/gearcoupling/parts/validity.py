"""Validity of a part mesh: manifold3d status and volume, trimesh topology, triangle shape.

A triangle is *degenerate* when twice its area is below ``1e-12`` times its longest edge
squared (no usable normal), and a *sliver* when its largest angle exceeds
:data:`MAX_ANGLE_DEG` (a nearly collinear "cap", whose normal is ill-conditioned).
Thin but well-shaped needles (small smallest angle, largest angle well below 180°) are
expected on a tolerance-driven mesh: a chordal tolerance spends vertices along the
curved direction only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ArgumentError
from ..numeric import TINY

MAX_ANGLE_DEG = 178.0


@dataclass(frozen=True)
class PartCheck:
    """Result of :func:`check_part`; ``ok`` is the conjunction of every check."""

    manifold_status: str
    manifold_volume: float
    watertight: bool
    winding_consistent: bool
    volume: float
    bodies: int
    genus: int
    expected_genus: int | None
    degenerate: int
    slivers: int
    max_angle_deg: float
    min_angle_deg: float

    @property
    def ok(self) -> bool:
        return (self.manifold_status == "NoError" and self.manifold_volume > 0
                and self.watertight and self.winding_consistent and self.volume > 0
                and self.degenerate == 0 and self.slivers == 0
                and (self.expected_genus is None or self.genus == self.expected_genus))

    def problems(self) -> list[str]:
        out = []
        if self.manifold_status != "NoError" or self.manifold_volume <= 0:
            out.append(f"manifold3d: {self.manifold_status}, volume {self.manifold_volume:.6g}")
        if not (self.watertight and self.winding_consistent and self.volume > 0):
            out.append(f"trimesh: watertight {self.watertight}, winding consistent "
                       f"{self.winding_consistent}, volume {self.volume:.6g}")
        if self.degenerate or self.slivers:
            out.append(f"{self.degenerate} degenerate and {self.slivers} sliver triangles "
                       f"(largest angle {self.max_angle_deg:.3f}°)")
        if self.expected_genus is not None and self.genus != self.expected_genus:
            out.append(f"genus {self.genus}, expected {self.expected_genus}")
        return out


def triangle_angles(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Interior angles ``(m, 3)`` in degrees of triangles ``faces`` over ``vertices``."""
    p = vertices[faces]
    out = np.empty(faces.shape, dtype=float)
    for k in range(3):
        a = p[:, (k + 1) % 3] - p[:, k]
        b = p[:, (k + 2) % 3] - p[:, k]
        cos = np.sum(a * b, 1) / np.maximum(np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1),
                                              TINY)
        out[:, k] = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
    return out


def expected_genus(mesh) -> int | None:
    """Genus a part should have: 1 for the sleeve ring and a full hub with a bore, 0 for a
    solid hub and for every sector body; ``None`` if the metadata do not say."""
    meta = mesh.metadata
    if meta.get("part") not in ("hub", "sleeve"):
        return None
    if meta.get("teeth") is not None:
        return 0
    return 1 if meta.get("bore", True) else 0


def check_part(mesh, expected: int | None = None) -> PartCheck:
    """Check a closed part mesh with manifold3d and trimesh (see the module docstring).

    Parameters
    ----------
    mesh : trimesh.Trimesh
    expected : int, optional
        Expected genus per body; default from the mesh metadata (:func:`expected_genus`).
    """
    import manifold3d
    import trimesh

    if not (hasattr(mesh, "vertices") and hasattr(mesh, "faces")):
        raise ArgumentError("mesh", str(mesh)[:60], "a trimesh.Trimesh (gearcoupling.build_part)")
    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces, dtype=np.int64)
    man = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=v, tri_verts=f.astype(np.uint64)))
    status = man.status().name
    edges = v[f[:, [1, 2, 0]]] - v[f]
    longest = np.max(np.sum(edges**2, axis=2), axis=1)
    area2 = np.linalg.norm(np.cross(edges[:, 0], -edges[:, 2]), axis=1)
    angles = triangle_angles(v, f)
    t = trimesh.Trimesh(v, f, process=False, validate=False)
    # connected face sets (what ``t.split`` would return, without building the submeshes)
    bodies = len(trimesh.graph.connected_components(t.face_adjacency, nodes=np.arange(len(f)),
                                                    min_len=1)) if len(f) else 0
    euler = int(t.euler_number)
    genus = (2 * bodies - euler) // 2 if bodies else 0
    return PartCheck(
        manifold_status=status,
        manifold_volume=float(man.volume()),
        watertight=bool(t.is_watertight),
        winding_consistent=bool(t.is_winding_consistent),
        volume=float(t.volume),
        bodies=bodies,
        genus=genus // max(bodies, 1),
        expected_genus=expected_genus(mesh) if expected is None else expected,
        degenerate=int(np.sum(area2 <= 1e-12 * longest)),
        slivers=int(np.sum(angles.max(axis=1) > MAX_ANGLE_DEG)),
        max_angle_deg=float(angles.max()),
        min_angle_deg=float(angles.min()),
    )
