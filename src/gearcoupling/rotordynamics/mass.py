"""Mass, centre of gravity and inertia of the hub, the sleeve and the coupling they make.

From the closed part meshes (:func:`gearcoupling.build_part`, the exact surfaces within a
chordal tolerance) by the divergence theorem over their triangles (trimesh), times the
part's ``[material]`` density. Both parts in the aligned coupling: the hub frame on the
sleeve frame, origin ``O`` in the midplane of the hub teeth, ``z`` along the axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..parts import build_part
from ..spec import CouplingSpec

MM3_TO_M3 = 1e-9
MM5_TO_M5 = 1e-15
ROUND_OFF_MM = 1e-9


@dataclass(frozen=True, eq=False)
class MassProperties:
    """Mass properties of one body (a part, or the whole coupling).

    Attributes
    ----------
    name : str
        ``hub``, ``sleeve`` or ``coupling``.
    mass_kg : float
    centre_of_gravity_mm : (3,) float
        In the coupling frame (origin ``O``, ``z`` along the axis).
    inertia_kg_m2 : (3, 3) float
        Inertia tensor about the centre of gravity, coupling axes.
    volume_mm3 : float
    """

    name: str
    mass_kg: float
    centre_of_gravity_mm: NDArray[np.float64]
    inertia_kg_m2: NDArray[np.float64]
    volume_mm3: float

    @property
    def polar_inertia_kg_m2(self) -> float:
        """About the axis through the centre of gravity (``I_zz``; ``W R²`` over g)."""
        return float(self.inertia_kg_m2[2, 2])

    @property
    def transverse_inertia_kg_m2(self) -> float:
        """About a transverse axis through the centre of gravity (mean of ``I_xx``, ``I_yy``;
        equal for a body of revolution or of N >= 3 alike teeth)."""
        return float(0.5 * (self.inertia_kg_m2[0, 0] + self.inertia_kg_m2[1, 1]))

    def as_dict(self) -> dict:
        return {"mass_kg": self.mass_kg,
                "centre_of_gravity_mm": [float(c) for c in self.centre_of_gravity_mm],
                "polar_inertia_kg_m2": self.polar_inertia_kg_m2,
                "transverse_inertia_kg_m2": self.transverse_inertia_kg_m2,
                "volume_mm3": self.volume_mm3}


def mesh_mass_properties(mesh, density_kg_per_m3: float, name: str) -> MassProperties:
    """Mass properties of a closed, outward-wound triangle mesh in mm (a trimesh mesh)."""
    volume = float(mesh.volume)
    rho = float(density_kg_per_m3)
    cg = np.asarray(mesh.center_mass, float)
    cg = np.where(np.abs(cg) < ROUND_OFF_MM, 0.0, cg)  # symmetric parts: exactly on O
    return MassProperties(name, rho * volume * MM3_TO_M3, cg,
                          rho * np.asarray(mesh.moment_inertia, float) * MM5_TO_M5, volume)


def combine(parts: list[MassProperties], name: str = "coupling") -> MassProperties:
    """The bodies as one: masses add, the inertias move to the common centre of gravity
    (parallel axes)."""
    m = sum(p.mass_kg for p in parts)
    cg = np.sum([p.mass_kg * p.centre_of_gravity_mm for p in parts], axis=0) / m
    inertia = np.zeros((3, 3))
    for p in parts:
        d = (p.centre_of_gravity_mm - cg) * 1e-3
        inertia += p.inertia_kg_m2 + p.mass_kg * (d @ d * np.eye(3) - np.outer(d, d))
    return MassProperties(name, m, cg, inertia, sum(p.volume_mm3 for p in parts))


def mass_properties(spec: CouplingSpec, tolerance_mm: float | None = None
                    ) -> dict[str, MassProperties]:
    """Hub, sleeve and coupling mass properties (``{"hub", "sleeve", "coupling"}``).

    Parameters
    ----------
    spec : CouplingSpec
    tolerance_mm : float, optional
        Chordal tolerance of the part meshes (default module / 200): the accuracy knob.

    Raises
    ------
    SpecError
        A part whose material has no density (``[material] density_kg_per_m3``).
    """
    rho = {p: getattr(spec.material, p).mass_density_kg_per_m3() for p in ("hub", "sleeve")}
    parts = [mesh_mass_properties(build_part(spec, p, tolerance_mm=tolerance_mm), rho[p], p)
             for p in ("hub", "sleeve")]
    return {"hub": parts[0], "sleeve": parts[1], "coupling": combine(parts)}


__all__ = ["MassProperties", "combine", "mass_properties", "mesh_mass_properties"]
