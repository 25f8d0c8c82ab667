"""One table of file writers (as meshio and trimesh keep theirs): every format is one
:class:`Writer` in :data:`WRITERS`, with its name, file suffixes, kind (a part's surface
mesh or solid, or an FE volume mesh), its writer and the extra its back-end needs. Nothing
is registered on import, and a writer's module is imported only when it writes (OCP,
meshio and trimesh load then).

A ``surface`` writer is ``writer(job, path)`` (a :class:`~.job.PartJob`); a ``volume``
writer ``writer(vm, path)`` (a :class:`gearcoupling.fea.VolumeMesh`). Either receives a
temporary path with the right suffix, renamed onto the target only when it succeeded.
Add a format by adding its entry to :data:`WRITERS` (docs/export.md).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..arguments import choice
from ..errors import ArgumentError, BackendError
from ..geometry import PARTS
from ..interrupts import reraise as reraise_interrupt
from ..io import atomic_path, writable_file
from ..spec import CouplingSpec, as_spec
from .job import PartJob

KINDS = ("surface", "volume")


@dataclass(frozen=True)
class Writer:
    """One file format.

    Attributes
    ----------
    name : str
        The format's name.
    suffixes : tuple of str
        File extensions that pick it (lower case, no dot).
    kind : {"surface", "volume"}
        What it writes: a part (``writer(job, path)``) or an FE volume mesh
        (``writer(vm, path)``).
    writer : str or callable
        ``"module:function"`` of a module of :mod:`gearcoupling.export`, imported at the
        call, or the callable itself.
    extra : str or None
        The ``pip install 'gearcoupling[extra]'`` its back-end comes with (None: core).
    """

    name: str
    suffixes: tuple[str, ...]
    kind: str
    writer: str | Callable[[Any, Path], Any]
    extra: str | None = None

    def __post_init__(self):
        choice(self.kind, "kind", KINDS)

    def write(self, obj: Any, path: Path) -> None:
        """Write ``obj`` (a :class:`PartJob` or a volume mesh) to ``path`` (not atomic: the
        callers write to a temporary path); a missing back-end names its extra."""
        write = self.writer
        if isinstance(write, str):
            module, _, name = write.partition(":")
            write = getattr(importlib.import_module(f"{__package__}.{module}"), name)
        try:
            write(obj, path)
        except ModuleNotFoundError as e:
            reraise_interrupt(e)  # a signal during the import
            if self.extra is None:
                raise
            raise BackendError(f"{self.name} files need {e.name}: pip install "
                               f"'gearcoupling[{self.extra}]'") from e


WRITERS: tuple[Writer, ...] = (
    Writer("stl", ("stl",), "surface", "meshes:write_stl"),
    Writer("ply", ("ply",), "surface", "meshes:write_ply"),
    Writer("obj", ("obj",), "surface", "meshes:write_obj"),
    Writer("glb", ("glb",), "surface", "meshes:write_glb"),
    Writer("3mf", ("3mf",), "surface", "meshes:write_3mf"),
    Writer("vtu", ("vtu",), "surface", "meshes:write_vtu"),
    Writer("vtk", ("vtk",), "surface", "meshes:write_vtk"),
    Writer("msh", ("msh",), "surface", "meshes:write_msh"),
    Writer("inp", ("inp",), "surface", "meshes:write_inp"),
    Writer("step", ("step", "stp"), "surface", "step:write_step_job", extra="step"),
    Writer("inp", ("inp",), "volume", "volume:write_inp_text"),
    Writer("msh", ("msh",), "volume", "volume:write_msh"),
    Writer("vtu", ("vtu",), "volume", "volume:write_vtu"),
)
"""Every format; the first entry of a kind with a suffix writes it."""


def formats(kind: str = "surface") -> list[str]:
    """The file extensions of ``kind`` (``surface``: parts; ``volume``: FE meshes)."""
    return sorted({s for w in WRITERS if w.kind == kind for s in w.suffixes})


def writer_for(path: str | Path, kind: str = "surface", field: str = "file") -> Writer:
    """The :class:`Writer` of ``kind`` for the extension of ``path`` (or a bare extension);
    :class:`ArgumentError` naming ``field`` and the allowed extensions."""
    text = str(path)
    p = Path(text)
    ext = (p.suffix or (text if p.name == text else "")).lower().lstrip(".")
    for w in WRITERS:
        if w.kind == kind and ext in w.suffixes:
            return w
    raise ArgumentError(field, text, f"an extension from {', '.join(formats(kind))} "
                        f"({ext!r} is not a supported format)")


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
    writer = writer_for(path)
    choice(part, "part", PARTS)
    job = PartJob(spec, part, tolerance_mm, teeth, mesh)
    with atomic_path(path) as tmp:
        writer.write(job, tmp)
    return Path(path)
