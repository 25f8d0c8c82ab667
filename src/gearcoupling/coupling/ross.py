"""The whole coupling as pieces of a ROSS train (``ross-rotordynamics``, the
``rotordynamics`` extra): two coupling elements and the spacer (or one-piece tube) as a
shaft element with the sleeve halves as its disks (docs/coupling.md, ROSS).

Numbered from element ``n``: coupling A joins node ``n`` (hub A: its mass and inertias) to
``n + 1``; the spacer joins ``n + 1`` to ``n + 2``; coupling B joins ``n + 2`` to ``n + 3``
(hub B). The disks at ``n + 1`` and ``n + 2`` are each half-sleeve (its ring and flange).
Without a tube between the rings (a one-piece sleeve whose rings touch) coupling B joins
``n + 1`` to ``n + 2`` and the whole sleeve is one disk at ``n + 1``. Each coupling
element's torsion is its side's parts in series (hub body, mesh, sleeve ring, flange;
tangent stiffness); its lateral stiffness the diagonal of its mesh's 6 x 6 turned into
the coupling frame (ROSS's element is diagonal: cross terms are left out, as
:func:`gearcoupling.rotordynamics.coupling_element` says). SI units.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..errors import ArgumentError
from ..rotordynamics import combine, import_ross, write_ross

MM_TO_M = 1e-3


class CouplingMasses(Protocol):
    """What :func:`ross_pieces` reads of a :class:`~.massdata.WholeCouplingData` (a
    protocol, so that this module does not import the one that calls it)."""

    @property
    def geometry(self) -> Any: ...

    @property
    def parts(self) -> Any: ...

    @property
    def matrices(self) -> Any: ...

    @property
    def torsion(self) -> Any: ...


@dataclass(frozen=True, eq=False)
class RossPieces:
    """ROSS elements of the whole coupling (module docstring): ``elements`` go with a
    rotor's shaft elements (in order), ``disks`` with its disk elements; ``first_node``
    is hub A's node and ``last_node`` hub B's."""

    elements: list[Any] = field(repr=False)
    disks: list[Any] = field(repr=False)
    first_node: int
    last_node: int

    def summary(self) -> dict[str, Any]:
        return {"elements": [type(e).__name__ for e in self.elements],
                "disks": len(self.disks), "first_node": self.first_node,
                "last_node": self.last_node}

    def write(self, path: str | os.PathLike) -> Path:
        """Every piece in one file of ROSS's own format (``.toml`` or ``.json``: ROSS's
        ``save``, one entry per element and disk keyed by its class and tag), atomically;
        ``ross.CouplingElement.load`` reads the first (coupling A)."""
        return write_ross([*self.elements, *self.disks], path)


def lateral_diagonal(matrix: np.ndarray, azimuth_deg: float) -> tuple[float, ...]:
    """``(kt_x, kt_y, kr_x, kr_y)`` of a 6 x 6 (or torque-held 5 x 5) in a mesh frame whose
    ``x`` lies at ``azimuth_deg`` about the axis: its translation and tilt blocks turned
    into the coupling frame, their diagonals."""
    c, s = math.cos(math.radians(azimuth_deg)), math.sin(math.radians(azimuth_deg))
    R = np.array([[c, -s], [s, c]])
    out = []
    for block in (slice(0, 2), slice(3, 5)):
        turned = R @ matrix[block, block] @ R.T
        out += [float(turned[0, 0]), float(turned[1, 1])]
    return tuple(out)


def ross_pieces(data: CouplingMasses, n: int = 0, *,
                held_torque: bool = False) -> RossPieces:
    """:class:`RossPieces` of the coupling's data from element ``n`` (module docstring);
    ``held_torque``: the lateral stiffness with the torque held (the wind-up free)."""
    if isinstance(n, bool) or not isinstance(n, int) or n < 0:
        raise ArgumentError("n", n, "a whole number >= 0 (ROSS's first element number)")
    if not data.matrices:
        raise ArgumentError("matrices", False, "True: a ROSS train needs each mesh's 6 x 6")
    rs = import_ross()
    geom = data.geometry
    sleeve = geom.spec_a.material.sleeve
    material = rs.Material(name="gearcoupling-floating-member",
                           rho=sleeve.mass_density_kg_per_m3(),
                           E=sleeve.youngs_modulus_MPa * 1e6, G_s=sleeve.shear_modulus_MPa * 1e6)
    tubes = [p for p in geom.annuli if p.name in ("spacer", "tube")]
    halves = {m: combine([v for k, v in data.parts.items() if k.endswith(m)
                          and not k.startswith("hub")], f"half-sleeve {m}")
              for m in geom.meshes}
    lengths = {"A": (tubes[0].z0_mm if tubes else 0.5 * geom.span_mm),
               "B": (geom.span_mm - tubes[0].z1_mm if tubes else 0.5 * geom.span_mm)}
    couplings = {}
    for m in geom.meshes:
        K = data.matrices[m]
        lateral = K.at_constant_torque() if held_torque else K.matrix
        kt_x, kt_y, kr_x, kr_y = lateral_diagonal(lateral, geom.tilt_axis_deg(m))
        hub = data.parts[f"hub {m}"]
        station = {"m": hub.mass_kg, "Ip": hub.polar_inertia_kg_m2,
                   "Id": hub.transverse_inertia_kg_m2}
        side = "l" if m == "A" else "r"
        other = "r" if m == "A" else "l"
        couplings[m] = rs.CouplingElement(
            **{f"{k}_{side}": v for k, v in station.items()},
            **{f"{k}_{other}": 0.0 for k in station},
            kt_x=kt_x, kt_y=kt_y, kr_x=kr_x, kr_y=kr_y,
            kr_z=data.torsion.side_Nm_per_rad(m),
            o_d=geom.spec(m).sleeve.outer_diameter * MM_TO_M, L=lengths[m] * MM_TO_M,
            n=n if m == "A" else n + (2 if tubes else 1), tag=f"coupling mesh {m}")
    if tubes:
        t = tubes[0]
        spacer = rs.ShaftElement(t.length_mm * MM_TO_M, idl=2 * t.inner_mm * MM_TO_M,
                                 odl=2 * t.outer_mm * MM_TO_M, material=material, n=n + 1,
                                 tag=f"coupling {t.name}")
        disks = [_disk(rs, n + 1 + k, halves[m], m) for k, m in enumerate(geom.meshes)]
        return RossPieces([couplings["A"], spacer, couplings["B"]], disks, n, n + 3)
    whole = combine(list(halves.values()), "sleeve")
    return RossPieces([couplings["A"], couplings["B"]], [_disk(rs, n + 1, whole, "")], n,
                      n + 2)


def _disk(rs, node: int, mp, mesh: str):
    return rs.DiskElement(n=node, m=mp.mass_kg, Id=mp.transverse_inertia_kg_m2,
                          Ip=mp.polar_inertia_kg_m2, tag=f"coupling sleeve {mesh}".strip())


__all__ = ["RossPieces", "lateral_diagonal", "ross_pieces"]
