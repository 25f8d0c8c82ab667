"""Writers of a tetrahedral volume mesh (:class:`gearcoupling.fea.VolumeMesh`, or any
object with its attributes: :class:`VolumeLike`): CalculiX/Abaqus INP, gmsh MSH, VTU.

Each is ``writer(vm, path)`` of the writers' table (:mod:`.registry`), which writes to a
temporary path and renames it onto the target.
"""

from __future__ import annotations

from pathlib import Path
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from ..io import inp_element_lines, inp_id_lines, inp_node_lines


class VolumeLike(Protocol):
    """What the volume writers read of a :class:`gearcoupling.fea.VolumeMesh`."""

    @property
    def nodes(self) -> NDArray[np.float64]: ...

    @property
    def tets(self) -> NDArray[np.int64]: ...

    @property
    def regions(self) -> dict[str, NDArray[np.int64]]: ...

    def node_set(self, name: str) -> NDArray[np.int64]: ...

    def face_set(self, name: str) -> NDArray[np.int64]: ...

    def set_names(self) -> list[str]: ...


def inp_mesh_lines(vm: VolumeLike) -> list[str]:
    """``*NODE``, ``*ELEMENT`` (C3D10, ELSET=EALL) and, for every region and aggregate,
    ``*NSET`` (its nodes), ``*ELSET`` (elements with a face on it) and ``*SURFACE``
    (``S_<name>``, element faces) lines; numbers are 1-based."""
    lines = inp_node_lines(vm.nodes)
    lines += inp_element_lines(vm.tets, "C3D10" if vm.tets.shape[1] == 10 else "C3D4")
    for name in vm.set_names():
        faces = vm.face_set(name)
        lines.append(f"*NSET, NSET={name}")
        lines += inp_id_lines(vm.node_set(name) + 1)
        lines.append(f"*ELSET, ELSET={name}")
        lines += inp_id_lines(np.unique(faces[:, 0]) + 1)
        lines.append(f"*SURFACE, NAME=S_{name}, TYPE=ELEMENT")
        lines += [f"{e + 1}, S{f}" for e, f in faces]
    return lines


def write_inp_text(vm: VolumeLike, path: Path, extra: list[str] | None = None) -> None:
    """The mesh as a CalculiX/Abaqus input file at ``path``, then the ``extra`` deck lines."""
    path.write_text("\n".join(["** gearcoupling volume mesh", *inp_mesh_lines(vm),
                               *(extra or [])]) + "\n")


def region_ids(vm: VolumeLike) -> dict[str, int]:
    """Region id of every boundary region (the volume is 1, regions from 2)."""
    return {"VOLUME": 1} | {name: i + 2 for i, name in enumerate(vm.regions)}


def to_meshio(vm: VolumeLike, *, gmsh_tags: bool = False):
    """meshio.Mesh of the tetrahedra and the region triangles with ``region`` cell data
    (or ``gmsh:physical`` / ``gmsh:geometrical`` and ``field_data`` names for MSH)."""
    import meshio

    quadratic = vm.tets.shape[1] == 10
    ids = region_ids(vm)
    cells = [("tetra10" if quadratic else "tetra", vm.tets)]
    tags = [np.full(len(vm.tets), 1)]
    for name, tri in vm.regions.items():
        cells.append(("triangle6" if quadratic else "triangle", tri))
        tags.append(np.full(len(tri), ids[name]))
    if gmsh_tags:
        data = {"gmsh:physical": tags, "gmsh:geometrical": tags}
        field = {name: np.array([i, 3 if name == "VOLUME" else 2]) for name, i in ids.items()}
        return meshio.Mesh(vm.nodes, cells, cell_data=data, field_data=field)
    return meshio.Mesh(vm.nodes, cells, cell_data={"region": tags})


def write_msh(vm: VolumeLike, path: Path) -> None:
    """gmsh 2.2 (ASCII) with physical groups named by region."""
    to_meshio(vm, gmsh_tags=True).write(path, file_format="gmsh22", binary=False)


def write_vtu(vm: VolumeLike, path: Path) -> None:
    """VTU with ``region`` ids as cell data (:func:`region_ids`)."""
    to_meshio(vm).write(path, file_format="vtu")
