"""Watertight hub and sleeve solids as triangle meshes at a chosen chordal tolerance, and
as exact OpenCASCADE solids (:func:`part_solid`, the ``step`` extra).

:func:`build_part` returns a :class:`trimesh.Trimesh` whose ``face_attributes`` hold the
surface kind (``"kind"``, codes into :data:`SURFACE_KINDS`) and the tooth index
(``"tooth"``, ``-1`` for body, bore, outer diameter and sector side walls) of every
triangle. This package sits after the geometry kernels in the data flow; the kernels
never import it (nor trimesh or manifold3d).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..arguments import choice, is_real
from ..errors import ArgumentError, GeometryError
from ..geometry import PARTS
from ..spec import CouplingSpec, as_spec
from .builder import SURFACE_KINDS, MeshBuilder, Run, tile, tooth_runs
from .deviation import measure_deviation
from .hub import build_hub_run, hub_layout, hub_triangles
from .size import PartSize, check_memory
from .sleeve import build_sleeve_run, sleeve_layout, sleeve_triangles
from .solid import hub_solid, part_solid, shape_volume, sleeve_solid
from .validity import PartCheck, check_part

if TYPE_CHECKING:
    import trimesh

# part -> (layout(spec, tol), add_run(builder, layout, run), triangles(layout, run))
_BUILDERS: dict[str, tuple[Callable[..., Any], Callable[..., None], Callable[..., int]]] = {
    "hub": (hub_layout, build_hub_run, hub_triangles),
    "sleeve": (sleeve_layout, build_sleeve_run, sleeve_triangles)}

#: the chordal tolerance's range in modules; its ends are met within a relative 1e-9, so
#: that a tolerance written as the end in mm (0.0006 for module 60) is not refused by the
#: rounding of ``module * 1e-5``
TOLERANCE_RANGE_MODULES = (1e-5, 0.1)


def default_tolerance(spec: CouplingSpec) -> float:
    """Default chordal tolerance: module / 200 (0.0127 mm for renzo-1967), in mm."""
    return spec.tooth.module / 200.0


def check_tolerance(spec: CouplingSpec, tolerance_mm) -> float:
    """The tolerance as a float (default :func:`default_tolerance`), or an
    :class:`~gearcoupling.errors.ArgumentError` naming the range
    (:data:`TOLERANCE_RANGE_MODULES`)."""
    tol = default_tolerance(spec) if tolerance_mm is None else tolerance_mm
    if not is_real(tol):
        raise ArgumentError("tolerance_mm", tolerance_mm, "must be a number (mm)")
    tol = float(tol)
    lo, hi = (spec.tooth.module * k for k in TOLERANCE_RANGE_MODULES)
    if not (math.isfinite(tol) and lo * (1 - 1e-9) <= tol <= hi * (1 + 1e-9)):
        raise ArgumentError("tolerance_mm", tolerance_mm, f"must be from {lo:.3g} to {hi:.3g} mm "
                        "(1e-5 to 0.1 module) for this spec")
    return tol


def build_part(spec: CouplingSpec, part: str, *, tolerance_mm: float | None = None,
               teeth=None) -> trimesh.Trimesh:
    """Closed triangle mesh of the hub or the sleeve within a chordal tolerance.

    Parameters
    ----------
    spec : CouplingSpec
    part : {"hub", "sleeve"}
        ``hub`` in the hub frame, ``sleeve`` in the sleeve frame (mm).
    tolerance_mm : float, optional
        Largest distance from the exact surface to the mesh (default
        :func:`default_tolerance`). Vertex spacing follows the local curvature of every
        surface (profile, crown, fillet, tip sphere, circles).
    teeth : iterable of int, optional
        Only these teeth (a sector per cyclic run, closed by planar side walls through the
        middle of the neighbouring spaces/teeth); default all.

    Returns
    -------
    trimesh.Trimesh
        Watertight, outward wound; ``face_attributes["kind"]`` (int16 codes into
        :data:`SURFACE_KINDS`) and ``face_attributes["tooth"]`` (int32);
        ``metadata`` holds part, tolerance, spec name and build time.

    Raises
    ------
    ArgumentError
        On ``tolerance_mm`` before anything is built, where the part's memory
        (:func:`part_size`) exceeds the budget of :mod:`gearcoupling.parts.size`; the
        message names a tolerance that fits.
    """
    import trimesh

    spec = as_spec(spec)
    choice(part, "part", PARTS)
    tol = check_tolerance(spec, tolerance_mm)
    runs = tooth_runs(spec.tooth.teeth, teeth)
    t0 = time.perf_counter()
    check_memory(_size(spec, part, tol, runs), lambda t: _size(spec, part, t, runs).triangles,
                 spec.tooth.module * TOLERANCE_RANGE_MODULES[1])
    layout, add_run, _ = _BUILDERS[part]
    lay = layout(spec, tol)  # cached per (spec, tolerance)
    builder = MeshBuilder()
    for run in runs:
        add_run(builder, lay, run)
    verts, faces, kind, tooth = builder.arrays()
    if not np.all(np.isfinite(verts)):
        raise GeometryError(f"{part} mesh of spec {spec.name!r} has non-finite vertices")
    mesh = trimesh.Trimesh(verts, faces, face_attributes={"kind": kind, "tooth": tooth},
                           process=False, validate=False)
    mesh.units = "mm"
    mesh.metadata.update(part=part, tolerance_mm=tol, spec=spec.name,
                         bore=part == "sleeve" or spec.hub.body.bore_diameter > 0,
                         teeth=None if runs[0].closed else sorted({int(k) for k in teeth}),
                         build_seconds=time.perf_counter() - t0, units="mm")
    return mesh


def part_size(spec: CouplingSpec, part: str, *, tolerance_mm: float | None = None,
              teeth=None) -> PartSize:
    """The triangle count (and memory) of :func:`build_part` with the same arguments,
    from the part's layout alone: nothing is meshed. :func:`build_part` refuses a part
    whose memory exceeds the budget (:mod:`gearcoupling.parts.size`)."""
    spec = as_spec(spec)
    choice(part, "part", PARTS)
    tol = check_tolerance(spec, tolerance_mm)
    return _size(spec, part, tol, tooth_runs(spec.tooth.teeth, teeth))


def _size(spec: CouplingSpec, part: str, tol: float, runs: list[Run]) -> PartSize:
    layout, _, triangles = _BUILDERS[part]
    lay = layout(spec, tol)  # cached per (spec, tolerance): the build reuses it
    return PartSize(part, tol, sum(triangles(lay, run) for run in runs))


__all__ = [
    "PARTS",
    "SURFACE_KINDS",
    "PartCheck",
    "PartSize",
    "Run",
    "build_part",
    "check_part",
    "check_tolerance",
    "default_tolerance",
    "hub_layout",
    "hub_solid",
    "measure_deviation",
    "part_size",
    "part_solid",
    "shape_volume",
    "sleeve_layout",
    "sleeve_solid",
    "tile",
    "tooth_runs",
]
