"""The whole coupling placed at its shaft alignment: every part named and posed, as triangle
meshes, a glTF scene (GLB), a STEP assembly (AP214, the ``step`` extra) and the overlap of
each mesh's placed hub and sleeve ring (docs/coupling.md, Assembly).

Placements in the coupling frame at the coupling's rotation ``psi``: each hub on its shaft
at its midplane centre (hub A at ``O_A`` turned by ``psi`` about shaft A; hub B at ``O_B``,
the single-engagement pose of mesh B), the floating member (sleeve rings, flanges, spacer
or tube) on the floating axis, centred between the two mesh centres (with an offset the
mesh centres lie a little further apart than the span: the difference is the hubs' axial
float in their sleeve rings, half at each, :attr:`CouplingAssembly.axial_float_mm`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..arguments import real
from ..errors import ArgumentError
from ..export import write_step_assembly
from ..interference import PreparedPart
from ..io import atomic_path
from ..parts import build_part, check_tolerance, part_solid
from ..spec import CouplingSpec
from .geometry import Annulus, CouplingGeometry, coupling_geometry
from .layout import CouplingLayout, ShaftAlignment

if TYPE_CHECKING:
    import trimesh

#: overlap below this (mm³) is the intersection's rounding
MIN_OVERLAP_MM3 = 1e-9


@dataclass(frozen=True, eq=False)
class PlacedPart:
    """One part and where it sits: ``rotation (3, 3)`` and ``origin_mm (3,)`` take its own
    frame (hub or sleeve frame of its spec; an annulus's floating frame, its ``z`` along the
    floating axis from ring A's midplane) into the coupling frame."""

    name: str
    kind: str
    rotation: NDArray[np.float64]
    origin_mm: NDArray[np.float64]
    spec: CouplingSpec | None = field(default=None, repr=False)
    annulus: Annulus | None = None

    @property
    def placement(self) -> NDArray[np.float64]:
        """The ``(4, 4)`` rigid transform of its own frame (mm)."""
        out = np.eye(4)
        out[:3, :3], out[:3, 3] = self.rotation, self.origin_mm
        return out

    def place(self, points: NDArray) -> NDArray[np.float64]:
        """Own-frame points ``(..., 3)`` in the coupling frame."""
        return np.asarray(points, float) @ self.rotation.T + self.origin_mm


@dataclass(frozen=True, eq=False)
class CouplingAssembly:
    """The coupling's parts placed at one rotation (module docstring)."""

    geometry: CouplingGeometry = field(repr=False)
    psi_deg: float
    parts: tuple[PlacedPart, ...]
    axial_float_mm: float

    def part(self, name: str) -> PlacedPart:
        for p in self.parts:
            if p.name == name:
                return p
        raise ArgumentError("part", name, f"one of {', '.join(p.name for p in self.parts)}")

    def own_meshes(self, tolerance_mm: float | None = None,
                   names: tuple[str, ...] | None = None) -> dict[str, trimesh.Trimesh]:
        """Each part's closed mesh in its own frame (hub and sleeve rings within
        ``tolerance_mm`` of the exact surfaces, default module / 200); ``names``: only
        these parts."""
        out: dict[str, trimesh.Trimesh] = {}
        built: dict[tuple[int, str], trimesh.Trimesh] = {}
        for p in self.parts if names is None else [self.part(n) for n in names]:
            if p.annulus is not None:
                out[p.name] = annulus_mesh(p.annulus, _tolerance(self.geometry, tolerance_mm))
                continue
            assert p.spec is not None
            key = (id(p.spec), p.kind)
            if key not in built:
                built[key] = build_part(p.spec, p.kind, tolerance_mm=tolerance_mm)
            out[p.name] = built[key]
        return out

    def meshes(self, tolerance_mm: float | None = None) -> dict[str, trimesh.Trimesh]:
        """Each part's mesh placed in the coupling frame."""
        out = {}
        for name, mesh in self.own_meshes(tolerance_mm).items():
            placed = mesh.copy()
            placed.apply_transform(self.part(name).placement)
            out[name] = placed
        return out

    def write_glb(self, path: str | Path, tolerance_mm: float | None = None) -> Path:
        """A glTF binary scene: one node per part, named, its own-frame mesh placed by the
        node's transform; written atomically."""
        import trimesh

        scene = trimesh.Scene()
        for name, mesh in self.own_meshes(tolerance_mm).items():
            scene.add_geometry(mesh, node_name=name, geom_name=name,
                               transform=self.part(name).placement)
        data = scene.export(file_type="glb")
        with atomic_path(path) as tmp:
            tmp.write_bytes(data)
        return Path(path)

    def solids(self, tolerance_mm: float | None = None) -> dict[str, Any]:
        """Each part's OpenCASCADE solid in its own frame (the ``step`` extra)."""
        out: dict[str, Any] = {}
        built: dict[tuple[int, str], Any] = {}
        for p in self.parts:
            if p.annulus is not None:
                out[p.name] = annulus_solid(p.annulus)
                continue
            assert p.spec is not None
            key = (id(p.spec), p.kind)
            if key not in built:
                built[key] = part_solid(p.spec, p.kind, check_tolerance(p.spec, tolerance_mm))
            out[p.name] = built[key]
        return out

    def write_step(self, path: str | Path, tolerance_mm: float | None = None) -> Path:
        """A STEP assembly (AP214, mm): every part a named solid at its placement
        (:func:`gearcoupling.export.write_step_assembly`); written atomically."""
        solids = self.solids(tolerance_mm)
        with atomic_path(path) as tmp:
            write_step_assembly([(p.name, solids[p.name], p.placement) for p in self.parts],
                                tmp, name="coupling")
        return Path(path)

    def overlap_mm3(self, mesh: str, tolerance_mm: float | None = None) -> float:
        """Volume (mm³) common to the placed hub and sleeve ring of ``mesh`` (manifold3d
        booleans of the closed meshes): 0 where they are apart."""
        names = (f"hub {mesh}", f"sleeve {mesh}")
        own = self.own_meshes(tolerance_mm, names)
        solids = []
        for name in names:
            prepared = PreparedPart.from_trimesh(own[name], ())
            p = self.part(name)
            solids.append(prepared.manifold.transform(p.placement[:3]))
        volume = float((solids[0] ^ solids[1]).volume())
        return volume if volume > MIN_OVERLAP_MM3 else 0.0

    def summary(self) -> dict[str, Any]:
        return {"psi_deg": self.psi_deg, "axial_float_mm": self.axial_float_mm,
                "parts": {p.name: {"kind": p.kind, "origin_mm": p.origin_mm.tolist(),
                                   "axis": p.rotation[:, 2].tolist()} for p in self.parts}}


def _tolerance(geom: CouplingGeometry, tolerance_mm: float | None) -> float:
    return check_tolerance(geom.spec_a, tolerance_mm)


def annulus_mesh(part: Annulus, tolerance_mm: float) -> trimesh.Trimesh:
    """A closed mesh of an annulus (its own frame) within ``tolerance_mm`` of its circles."""
    import trimesh

    step = 2.0 * math.acos(max(1.0 - tolerance_mm / part.outer_mm, -1.0))
    sections = max(64, math.ceil(2.0 * math.pi / step))
    if part.inner_mm > 0:
        mesh = trimesh.creation.annulus(part.inner_mm, part.outer_mm, part.length_mm,
                                        sections=sections)
    else:
        mesh = trimesh.creation.cylinder(part.outer_mm, part.length_mm, sections=sections)
    mesh.apply_translation([0.0, 0.0, 0.5 * (part.z0_mm + part.z1_mm)])
    mesh.metadata.update(part=part.name, tolerance_mm=tolerance_mm, units="mm")
    return mesh


def annulus_solid(part: Annulus):
    """The OpenCASCADE solid of an annulus (its own frame): two circles' face, extruded."""
    from OCP.BRepBuilderAPI import (
        BRepBuilderAPI_MakeEdge,
        BRepBuilderAPI_MakeFace,
        BRepBuilderAPI_MakeWire,
    )
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pnt, gp_Vec

    def circle(r: float):
        c = gp_Circ(gp_Ax2(gp_Pnt(0, 0, part.z0_mm), gp_Dir(0, 0, 1)), r)
        return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(c).Edge()).Wire()

    face = BRepBuilderAPI_MakeFace(circle(part.outer_mm))
    if part.inner_mm > 0:
        inner = circle(part.inner_mm)
        inner.Reverse()
        face.Add(inner)
    return BRepPrimAPI_MakePrism(face.Face(), gp_Vec(0, 0, part.length_mm)).Shape()


def coupling_assembly(spec: CouplingSpec, layout: CouplingLayout, alignment: ShaftAlignment,
                      psi_deg: float = 0.0) -> CouplingAssembly:
    """The coupling's parts placed at the coupling rotation ``psi_deg`` (module docstring;
    two engagements)."""
    geom = coupling_geometry(spec, layout, alignment)
    if geom.layout.engagements != 2:
        raise ArgumentError("engagements", 1, "2: a single engagement's parts are its hub and "
                            "sleeve (gc.export_part)")
    psi = real(psi_deg, "psi_deg", -1e6, 1e6, unit="degrees")
    s, S = geom.sleeve_axis, geom.span_mm
    D = float(np.linalg.norm(geom.centre_b_mm))
    floating = 0.5 * geom.centre_b_mm - 0.5 * S * s
    R = geom.sleeve_pose(psi)
    parts = [PlacedPart("hub A", "hub", geom.hub_pose("A", psi), np.zeros(3), geom.spec_a),
             PlacedPart("sleeve A", "sleeve", R, floating.copy(), geom.spec_a)]
    parts += [PlacedPart(p.name, "annulus", R, floating.copy(), annulus=p) for p in geom.annuli]
    parts += [PlacedPart("sleeve B", "sleeve", R, floating + S * s, geom.spec_b),
              PlacedPart("hub B", "hub", geom.hub_pose("B", psi), geom.centre_b_mm.copy(),
                         geom.spec_b)]
    return CouplingAssembly(geom, psi, tuple(parts), D - S)


__all__ = ["CouplingAssembly", "PlacedPart", "annulus_mesh", "annulus_solid",
           "coupling_assembly"]
