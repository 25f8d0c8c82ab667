"""Part meshes prepared once and posed many times (docs/conventions.md, Frames).

A hub body point ``p`` lies in the sleeve body frame at ``Rz(-psi) Rx(i) Rz(psi) Rz(delta)
p``, where ``delta`` is an optional extra turn of the hub about its own axis (positive
toward increasing polar angle: it closes the ``ccw`` flanks). A :class:`PreparedPart` holds
the mesh arrays, its manifold3d solid and its python-fcl bounding-volume tree, each built
once; a pose only changes a 3x3 matrix (``Manifold.transform`` is lazy, ``fcl.Transform`` is
a matrix), so nothing is rebuilt across angles.

Window frames: the ideal coupling repeats every tooth, so a sector built around tooth 0
and posed by :func:`window_pose` for tooth ``c`` stands for the teeth around ``c``; points
found in the window frame map to the sleeve frame by :func:`window_to_sleeve`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ..errors import BackendError
from ..geometry import hub_to_sleeve, rot_z
from ..interrupts import reraise as reraise_interrupt
from ..parts import SURFACE_KINDS


def hub_pose(misalignment: float, psi: float, hub_rotation: float = 0.0) -> NDArray:
    """``Rz(-psi) Rx(i) Rz(psi) Rz(delta)``: hub frame to sleeve frame, ``(3, 3)``.

    Parameters
    ----------
    misalignment : float
        Tilt ``i`` about the sleeve ``x`` axis (radians).
    psi : float
        Rotation of the coupling (radians).
    hub_rotation : float
        Extra turn ``delta`` of the hub about its own axis (radians).
    """
    return hub_to_sleeve(misalignment, psi) @ rot_z(hub_rotation)


def window_pose(misalignment: float, psi: float, centre: int, teeth: int,
                hub_rotation: float = 0.0) -> NDArray:
    """Pose of a hub sector built around tooth 0 that stands for the teeth around ``centre``.

    Equals ``Rz(-c) hub_pose(psi) Rz(c)`` with ``c = 2 pi centre / N``, i.e. the reduced pose
    ``P(theta_c) Rz(delta)`` at the centre tooth's turning angle ``theta_c = psi + c``.
    """
    theta = psi + 2.0 * math.pi * centre / teeth
    return hub_to_sleeve(misalignment, theta) @ rot_z(hub_rotation)


def window_to_sleeve(points: NDArray, centre: int, teeth: int) -> NDArray:
    """Map window-frame points ``(..., 3)`` of the window at ``centre`` to the sleeve frame."""
    return np.asarray(points, dtype=float) @ rot_z(2.0 * math.pi * centre / teeth).T


def affine(matrix: NDArray) -> NDArray:
    """The 3x4 affine matrix manifold3d's ``transform`` takes (4x4 raises there)."""
    return np.hstack([np.asarray(matrix, dtype=float), np.zeros((3, 1))])


def _fcl():
    try:
        import fcl
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("distance queries need python-fcl: pip install "
                           "'gearcoupling[interference]'") from err
    return fcl


def _manifold3d():
    import manifold3d

    return manifold3d


@dataclass(frozen=True, eq=False)
class PreparedPart:
    """A part mesh with its solid and distance structures, built once and posed by matrices.

    Attributes
    ----------
    part : str
        ``"hub"`` or ``"sleeve"``.
    vertices : (n, 3) float
        In the part's own frame (mm).
    faces : (m, 3) int
    kind, tooth : (m,) int
        Per-face surface kind codes (:data:`gearcoupling.parts.SURFACE_KINDS`) and tooth
        index (``-1`` for body, bore, side walls).
    shell : (s,) int
        Faces of the tooth surfaces (everything but body, bore and sector side walls):
        the flank-only shell that distance queries use, so a sector's cut walls can never
        pose as the closest point.
    tolerance_mm : float
        Chordal tolerance the mesh was built with.
    """

    part: str
    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]
    kind: NDArray[np.int16]
    tooth: NDArray[np.int32]
    shell: NDArray[np.int64]
    tolerance_mm: float
    build_seconds: float = 0.0
    _cache: dict = field(default_factory=dict, repr=False)

    @classmethod
    def from_trimesh(cls, mesh, shell_kinds: tuple[str, ...]) -> PreparedPart:
        """From a :func:`gearcoupling.parts.build_part` mesh; ``shell_kinds`` are excluded."""
        kind = np.asarray(mesh.face_attributes["kind"], dtype=np.int16)
        drop = [SURFACE_KINDS.index(k) for k in shell_kinds]
        return cls(part=mesh.metadata.get("part", "?"),
                   vertices=np.ascontiguousarray(mesh.vertices, dtype=np.float64),
                   faces=np.ascontiguousarray(mesh.faces, dtype=np.int64),
                   kind=kind, tooth=np.asarray(mesh.face_attributes["tooth"], dtype=np.int32),
                   shell=np.flatnonzero(~np.isin(kind, drop)),
                   tolerance_mm=float(mesh.metadata.get("tolerance_mm", 0.0)),
                   build_seconds=float(mesh.metadata.get("build_seconds", 0.0)))

    @property
    def triangles(self) -> int:
        return len(self.faces)

    @cached_property
    def manifold(self):
        """The closed solid as a ``manifold3d.Manifold`` (float64 input), checked once."""
        m3d = _manifold3d()
        mesh = m3d.Mesh64(vert_properties=self.vertices,
                          tri_verts=self.faces.astype(np.uint64))
        solid = m3d.Manifold(mesh)
        if solid.status() != m3d.Error.NoError or not solid.volume() > 0:
            raise BackendError(f"{self.part} mesh is not a valid closed solid for manifold3d "
                               f"(status {solid.status()}, volume {solid.volume():.6g})")
        return solid

    def posed_manifold(self, matrix: NDArray):
        """The solid turned by ``matrix`` (3x3); lazy until a volume or mesh is asked for."""
        return self.manifold.transform(affine(matrix))

    @cached_property
    def shell_bvh(self):
        """python-fcl bounding-volume tree of the shell, built once (in the part frame)."""
        return self._bvh(self.shell)

    def _bvh(self, faces_idx: NDArray):
        fcl = _fcl()
        faces = self.faces[faces_idx]
        model = fcl.BVHModel()
        model.beginModel(len(self.vertices), len(faces))
        model.addSubModel(self.vertices, faces)
        model.endModel()
        return model

    def side(self, flank: str) -> NDArray[np.int64]:
        """Faces of one flank side (``"cw"``/``"ccw"``: flank, fillet, chamfer of that side)."""
        key = ("side", flank)
        if key not in self._cache:
            codes = [SURFACE_KINDS.index(f"{k}_{flank}") for k in ("flank", "fillet", "chamfer")]
            self._cache[key] = np.flatnonzero(np.isin(self.kind, codes))
        return self._cache[key]

    def side_bvh(self, flank: str):
        """python-fcl tree of one flank side, built once."""
        key = ("bvh", flank)
        if key not in self._cache:
            self._cache[key] = self._bvh(self.side(flank))
        return self._cache[key]

    def fcl_object(self, matrix: NDArray | None = None, flank: str | None = None):
        """An fcl collision object of the shell (or of one flank side) at pose ``matrix``
        (3x3, identity if None)."""
        fcl = _fcl()
        rot = np.eye(3) if matrix is None else np.asarray(matrix, dtype=float)
        bvh = self.shell_bvh if flank is None else self.side_bvh(flank)
        return fcl.CollisionObject(bvh, fcl.Transform(rot, np.zeros(3)))

    def shell_face(self, index: int, flank: str | None = None) -> int:
        """Face index in :attr:`faces` of the ``index``-th triangle of the shell (or side)."""
        faces = self.shell if flank is None else self.side(flank)
        return int(faces[index])
