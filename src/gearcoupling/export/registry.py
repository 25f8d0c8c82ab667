"""Part writers by file extension: one explicit table, no registration on import.

A writer is ``writer(job, path)``; it receives a :class:`~.job.PartJob` and a temporary
path with the right suffix, which :func:`export_part` renames onto the target only when
the writer succeeded. Add a format by adding it to :data:`EXPORTERS`.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..arguments import choice
from ..errors import ArgumentError
from ..geometry import PARTS
from ..io import atomic_path, writable_file
from ..spec import CouplingSpec, as_spec
from . import meshes, step
from .job import PartJob

EXPORTERS: dict[str, Callable[[PartJob, Path], None]] = {
    "stl": meshes.write_stl,
    "ply": meshes.write_ply,
    "obj": meshes.write_obj,
    "glb": meshes.write_glb,
    "3mf": meshes.write_3mf,
    "vtu": meshes.write_vtu,
    "vtk": meshes.write_vtk,
    "msh": meshes.write_msh,
    "inp": meshes.write_inp,
    "step": step.write_step_job,
    "stp": step.write_step_job,
}
"""File extension (lower case, no dot) -> writer."""


def formats() -> list[str]:
    """Supported file extensions."""
    return sorted(EXPORTERS)


def extension(path: str | Path) -> str:
    """Lower-case extension of ``path``; :class:`SpecError` naming the allowed ones."""
    ext = Path(path).suffix.lower().lstrip(".")
    if ext not in EXPORTERS:
        raise ArgumentError("file", str(path), f"an extension from {', '.join(formats())} "
                        f"({ext!r} is not a supported format)")
    return ext


def export_part(spec: CouplingSpec,
                part: str, path: str | Path, *, tolerance_mm: float | None = None,
                teeth=None, mesh=None) -> Path:
    """Write a part to ``path`` in the format of its extension, atomically.

    Parameters
    ----------
    spec : CouplingSpec
    part : {"hub", "sleeve"}
    path : str or Path
        Target file; its extension picks the writer (see :func:`formats`).
    tolerance_mm : float, optional
        Chordal tolerance of the mesh and of the STEP surfaces.
    teeth : iterable of int, optional
        Tooth selection (sectors).
    mesh : trimesh.Trimesh, optional
        A mesh already built with these settings (saves rebuilding it per format).
    """
    spec = as_spec(spec)
    writable_file(path, "path")
    ext = extension(path)
    choice(part, "part", PARTS)
    job = PartJob(spec, part, tolerance_mm, teeth, mesh)
    with atomic_path(path) as tmp:
        EXPORTERS[ext](job, tmp)
    return Path(path)
