"""Writers of a :class:`VolumeMesh`: CalculiX/Abaqus INP, gmsh MSH, VTU (all atomic)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import ArgumentError
from ..io import atomic_path, inp_element_lines, inp_id_lines, inp_node_lines, writable_file
from .volume import VolumeMesh

FORMATS = ("inp", "msh", "vtu")


def inp_mesh_lines(vm: VolumeMesh) -> list[str]:
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


def write_inp(vm: VolumeMesh, path, extra: list[str] | None = None) -> Path:
    """The mesh as a CalculiX/Abaqus input file, followed by the ``extra`` deck lines."""
    with atomic_path(path) as tmp:
        tmp.write_text("\n".join(["** gearcoupling volume mesh", *inp_mesh_lines(vm),
                                  *(extra or [])]) + "\n")
    return Path(path)


def region_ids(vm: VolumeMesh) -> dict[str, int]:
    """Region id of every boundary region (the volume is 1, regions from 2)."""
    return {"VOLUME": 1} | {name: i + 2 for i, name in enumerate(vm.regions)}


def to_meshio(vm: VolumeMesh, *, gmsh_tags: bool = False):
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


def write_mesh(vm: VolumeMesh, path, fmt: str | None = None) -> Path:
    """Write ``inp``, ``msh`` (gmsh 2.2 with physical groups) or ``vtu`` (``region`` ids)."""
    if not isinstance(vm, VolumeMesh):
        raise ArgumentError("vm", str(vm)[:60], "a VolumeMesh (gearcoupling.mesh_part)")
    path = writable_file(path, "path")
    fmt = fmt or path.suffix.lstrip(".").lower()
    if fmt not in FORMATS:
        raise ArgumentError("format", fmt, f"one of {', '.join(FORMATS)}")
    if fmt == "inp":
        return write_inp(vm, path)
    with atomic_path(path) as tmp:
        if fmt == "msh":
            to_meshio(vm, gmsh_tags=True).write(tmp, file_format="gmsh22", binary=False)
        else:
            to_meshio(vm).write(tmp, file_format="vtu")
    return path
