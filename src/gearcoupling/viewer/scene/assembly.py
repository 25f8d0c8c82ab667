"""The whole coupling's pose (a double-engagement spec, docs/coupling.md): every part placed
at the shaft alignment and the coupling's rotation, and each mesh's pose state at its angle
and rotation (its clearance colours), as plain arrays.

A mesh's hub sits in its sleeve ring as the single engagement at the mesh's angle and
rotation (``psi`` less its tilt axis azimuth), so each mesh's colours are those of
:func:`~.pose.pose_state` there.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ...arguments import flag, real
from ...coupling import CouplingGeometry, coupling_assembly, mesh_torque_Nm, spec_geometry
from ...loading import load, resolve_torque_Nm
from ...spec import CouplingSpec, as_spec
from .pose import VIEW_SWEEP_TOLERANCE_MM, PoseState, pose_state

#: the alignment fields a viewer changes (of :class:`~gearcoupling.coupling.ShaftAlignment`)
ALIGNMENT_FIELDS = ("offset_mm", "offset_azimuth_deg", "angle_deg", "angle_azimuth_deg")


@dataclass(frozen=True, eq=False)
class AssemblyPose:
    """The coupling at one alignment and rotation.

    Attributes
    ----------
    geometry : CouplingGeometry
    psi_deg : float
        The coupling's rotation (shaft A's turn).
    placements : dict of str -> (4, 4) float
        Each part's placement (its own frame into the coupling frame, mm), by part name
        (``hub A``, ``sleeve A``, flanges, spacer or tube, ``sleeve B``, ``hub B``).
    kinds : dict of str -> str
        Each part's kind: ``hub``, ``sleeve`` or ``annulus``.
    states : dict of str -> PoseState
        Each mesh's pose state (``"A"``, ``"B"``) at its angle and rotation.
    """

    geometry: CouplingGeometry = field(repr=False)
    psi_deg: float
    placements: dict[str, NDArray[np.float64]]
    kinds: dict[str, str]
    states: dict[str, PoseState] = field(repr=False)

    def mesh_of(self, part: str) -> str | None:
        """The mesh a hub or sleeve ring belongs to (None for the plain parts)."""
        return part[-1] if self.kinds[part] in ("hub", "sleeve") else None


def assembly_pose(spec: CouplingSpec, psi_deg: float = 0.0,
                  changes: dict[str, float] | None = None, *, band_mm: float = 0.005,
                  pressure: bool = False,
                  tolerance_mm: float = VIEW_SWEEP_TOLERANCE_MM) -> AssemblyPose:
    """The whole coupling of a double-engagement ``spec`` at its ``[alignment]`` with
    ``changes`` (fields of :data:`ALIGNMENT_FIELDS`) and the rotation ``psi_deg``.

    ``pressure``: each mesh's contact pressure too, from the surface model at the spec's
    torque at its pose (hub B at the negative: the sleeve drives it; about a second each).
    """
    spec = as_spec(spec)
    psi = real(psi_deg, "psi_deg", -1e6, 1e6, unit="degrees")
    flag(pressure, "pressure")
    geom = spec_geometry(spec, changes)
    asm = coupling_assembly(spec, geom.layout, geom.alignment, psi)
    states = {}
    for m in geom.meshes:
        mis, rot = geom.misalignment_deg(m), float(geom.mesh_rotations_deg(m, psi))
        loads = None
        if pressure:
            T = mesh_torque_Nm(m, resolve_torque_Nm(geom.spec(m), None))
            loads = load(geom.spec(m), mis, [rot], torque_Nm=T, model="surface",
                         tolerance_mm=tolerance_mm)
        states[m] = pose_state(geom.spec(m), mis, rot, band_mm=band_mm,
                               tolerance_mm=tolerance_mm, loads=loads)
    return AssemblyPose(geom, psi, {p.name: p.placement for p in asm.parts},
                        {p.name: p.kind for p in asm.parts}, states)


__all__ = ["ALIGNMENT_FIELDS", "AssemblyPose", "assembly_pose"]
