"""Writing a :class:`VolumeMesh`: any volume format of the writers' table
(:func:`gearcoupling.export.writer_for`: INP, MSH, VTU), atomically."""

from __future__ import annotations

from pathlib import Path

from ..errors import ArgumentError
from ..export import inp_mesh_lines, region_ids, write_inp_text, writer_for
from ..io import atomic_path, writable_file
from .volume import VolumeMesh

__all__ = ["inp_mesh_lines", "region_ids", "write_inp", "write_mesh"]


def write_inp(vm: VolumeMesh, path, extra: list[str] | None = None) -> Path:
    """The mesh as a CalculiX/Abaqus input file, followed by the ``extra`` deck lines."""
    with atomic_path(path) as tmp:
        write_inp_text(vm, tmp, extra)
    return Path(path)


def write_mesh(vm: VolumeMesh, path, fmt: str | None = None) -> Path:
    """Write the mesh in the volume format ``fmt`` (default: the extension of ``path``):
    ``inp``, ``msh`` (gmsh 2.2 with physical groups) or ``vtu`` (``region`` ids)."""
    if not isinstance(vm, VolumeMesh):
        raise ArgumentError("vm", str(vm)[:60], "a VolumeMesh (gearcoupling.mesh_part)")
    path = writable_file(path, "path")
    writer = writer_for(fmt or path.suffix, "volume", "format")
    with atomic_path(path) as tmp:
        writer.write(vm, tmp)
    return path
