"""Mesh writers: STL (binary), PLY, OBJ, GLB, 3MF through trimesh; VTU, VTK, Gmsh MSH and
Abaqus INP through meshio with the tooth index and surface kind of every triangle.

meshio formats carry cell data ``tooth`` (``-1`` off the teeth) and ``kind`` (codes into
:data:`~gearcoupling.parts.SURFACE_KINDS`, listed in the field data / physical names);
Gmsh files also carry the kind as the physical group (code + 1) and Abaqus files one
element set per surface kind (``FLANK_CW`` ...) and per tooth (``TOOTH_0`` ...).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import BackendError
from ..parts.builder import SURFACE_KINDS
from .registry import PartJob, exporter

_TRIMESH_TYPES = {"stl": "stl", "ply": "ply", "obj": "obj", "glb": "glb", "3mf": "3mf"}


@exporter(*_TRIMESH_TYPES)
def write_trimesh(job: PartJob, path: Path) -> None:
    """STL (binary), PLY (binary), OBJ, GLB and 3MF via trimesh."""
    ext = path.suffix.lower().lstrip(".")
    if ext == "3mf":
        try:
            import lxml  # noqa: F401
            import networkx  # noqa: F401
        except ImportError as err:
            raise BackendError("3MF export needs lxml and networkx: pip install "
                               "'gearcoupling[mesh3mf]'") from err
    job.mesh.export(str(path), file_type=_TRIMESH_TYPES[ext])


def _meshio_mesh(job: PartJob, *, gmsh: bool = False, sets: bool = False):
    import meshio

    mesh = job.mesh
    kind = np.asarray(mesh.face_attributes["kind"], dtype=np.int32)
    tooth = np.asarray(mesh.face_attributes["tooth"], dtype=np.int32)
    cell_data = {"kind": [kind], "tooth": [tooth]}
    field_data = {name: np.array([code, 2]) for code, name in enumerate(SURFACE_KINDS)}
    if gmsh:
        cell_data["gmsh:physical"] = [kind + 1]
        cell_data["gmsh:geometrical"] = [kind + 1]
        field_data = {name: np.array([code + 1, 2]) for code, name in enumerate(SURFACE_KINDS)}
    cell_sets = None
    if sets:
        cell_sets = {name.upper(): [np.flatnonzero(kind == code)]
                     for code, name in enumerate(SURFACE_KINDS) if np.any(kind == code)}
        cell_sets.update({f"TOOTH_{k}": [np.flatnonzero(tooth == k)]
                          for k in np.unique(tooth[tooth >= 0])})
        cell_data = {}
    return meshio.Mesh(np.asarray(mesh.vertices, dtype=float),
                       [("triangle", np.asarray(mesh.faces, dtype=np.int64))],
                       cell_data=cell_data, field_data=field_data, cell_sets=cell_sets)


@exporter("vtu")
def write_vtu(job: PartJob, path: Path) -> None:
    """VTK XML unstructured grid (zlib-compressed binary)."""
    _meshio_mesh(job).write(str(path), file_format="vtu")


@exporter("vtk")
def write_vtk(job: PartJob, path: Path) -> None:
    """Legacy VTK (binary)."""
    _meshio_mesh(job).write(str(path), file_format="vtk", binary=True)


@exporter("msh")
def write_msh(job: PartJob, path: Path) -> None:
    """Gmsh MSH 4.1 (binary); the surface kind is the physical group."""
    _meshio_mesh(job, gmsh=True).write(str(path), file_format="gmsh", binary=True)


@exporter("inp")
def write_inp(job: PartJob, path: Path) -> None:
    """Abaqus INP with element sets per surface kind and per tooth."""
    _meshio_mesh(job, sets=True).write(str(path), file_format="abaqus")


def read_mesh(path: str | Path):
    """Read a written part back: ``(vertices, faces, cell_data, cell_sets)``.

    For trimesh formats ``cell_data``/``cell_sets`` are empty; vertices are merged.
    """
    import meshio
    import trimesh

    path = Path(path)
    ext = path.suffix.lower().lstrip(".")
    if ext in _TRIMESH_TYPES:
        m = trimesh.load(str(path), force="mesh", file_type=ext)
        return np.asarray(m.vertices), np.asarray(m.faces), {}, {}
    m = meshio.read(str(path), file_format={"msh": "gmsh", "inp": "abaqus"}.get(ext))
    tri = [c for c in m.cells if c.type == "triangle"]
    faces = np.concatenate([c.data for c in tri])
    data = {k: np.concatenate(v) for k, v in m.cell_data.items()}
    sets = {k: np.concatenate(v) for k, v in m.cell_sets.items()}
    return np.asarray(m.points), faces, data, sets
