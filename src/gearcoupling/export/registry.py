"""Part exporters registered by file extension.

A writer is ``writer(job, path)``; it receives a :class:`PartJob` (spec, part, tolerance,
teeth and the mesh, built on first use) and a temporary path with the right suffix,
which :func:`export_part` renames onto the target only when the writer succeeded.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ..atomic import atomic_path
from ..errors import ArgumentError

EXPORTERS: dict[str, Callable[[PartJob, Path], None]] = {}
"""File extension (lower case, no dot) -> writer."""


def exporter(*extensions: str):
    """Decorator registering a writer for the given file extensions."""

    def register(fn):
        for ext in extensions:
            EXPORTERS[ext.lower().lstrip(".")] = fn
        return fn

    return register


@dataclass
class PartJob:
    """What a writer may need: the spec and the part, and its mesh (built lazily)."""

    spec: object
    part: str
    tolerance_mm: float | None = None
    teeth: object = None
    _mesh: object = field(default=None, repr=False)

    @property
    def mesh(self):
        if self._mesh is None:
            from ..parts import build_part

            self._mesh = build_part(self.spec, self.part, self.tolerance_mm, self.teeth)
        return self._mesh


def formats() -> list[str]:
    """Registered file extensions."""
    from . import meshes, step  # noqa: F401  (registration side effect)

    return sorted(EXPORTERS)


def extension(path: str | Path) -> str:
    """Lower-case extension of ``path``, or ``ValueError`` naming the allowed ones."""
    ext = Path(path).suffix.lower().lstrip(".")
    if ext not in formats():
        raise ArgumentError(f"file {str(path)!r}: extension {ext!r} is not a supported format; "
                         f"allowed: {', '.join(formats())}")
    return ext


def export_part(spec, part: str, path: str | Path, *, tolerance_mm: float | None = None,
                teeth=None, mesh=None) -> Path:
    """Write a part to ``path`` in the format of its extension, atomically.

    Parameters
    ----------
    spec : CouplingSpec
    part : {"hub", "sleeve"}
    path : str or Path
        Target file; its extension picks the writer (see :func:`formats`).
    tolerance_mm : float, optional
        Chordal tolerance of the mesh and of the STEP B-spline sampling.
    teeth : iterable of int, optional
        Tooth selection (sectors).
    mesh : trimesh.Trimesh, optional
        A mesh already built with these settings (saves rebuilding it per format).
    """
    ext = extension(path)
    job = PartJob(spec, part, tolerance_mm, teeth, mesh)
    with atomic_path(path) as tmp:
        EXPORTERS[ext](job, tmp)
    return Path(path)
