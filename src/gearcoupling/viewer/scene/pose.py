"""The pose: the hub's rotation into the sleeve frame (docs/conventions.md, Frames: a hub
point ``p`` lies in the sleeve frame at ``Rz(-psi) Rx(i) Rz(psi) p``) and what changes
with it (:func:`pose_state`: the exact clearance of every tooth and flank from one
:func:`gearcoupling.clearance.sweep` call, the contact points and the interfering teeth,
and the contact pressure of a :class:`~gearcoupling.loading.LoadResult` the caller
computed at that pose).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...arguments import real
from ...clearance import sweep
from ...errors import ArgumentError
from ...geometry import FLANKS, hub_flank_model, hub_model, hub_to_sleeve, rot_z
from ...loading import LoadResult
from ...spec import CouplingSpec, as_spec, check_misalignment_deg

VIEW_SWEEP_TOLERANCE_MM = 1e-5
"""Accuracy of the clearance minima the viewer shows (mm), far below what colours show."""


def check_pose(misalignment_deg: float, psi_deg: float,
               names: tuple[str, str] = ("misalignment_deg", "psi_deg")) -> tuple[float, float]:
    """Misalignment (0-6°) and rotation (within a million degrees) as floats, or an
    :class:`ArgumentError` naming the bad one by its entry in ``names``."""
    return (check_misalignment_deg(misalignment_deg, names[0], ArgumentError),
            real(psi_deg, names[1], -1e6, 1e6, unit="degrees"))


def hub_rotation(misalignment_deg: float, psi_deg: float) -> NDArray[np.float64]:
    """Rotation ``(3, 3)`` taking hub-frame points into the sleeve frame at a pose."""
    return hub_to_sleeve(math.radians(misalignment_deg), math.radians(psi_deg))


def quaternion_wxyz(rotation: ArrayLike) -> NDArray[np.float64]:
    """Unit quaternion ``(w, x, y, z)`` with ``w >= 0`` of a rotation matrix ``(3, 3)``."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(np.asarray(rotation, dtype=float)).as_quat()
    q = np.array([w, x, y, z])
    return -q if w < 0 else q


@dataclass(frozen=True)
class PoseState:
    """Everything that changes with the pose (arrays ``(flank, tooth)`` use ``(cw, ccw)``).

    Attributes
    ----------
    clearance_mm : (2, N) float
        Circumferential clearance (docs/conventions.md, Frames) of each flank and tooth;
        ``inf`` where no point of the flank faces the sleeve flank.
    normal_clearance_mm : (2, N) float
    theta_deg : (N,) float
        Turning angle of each tooth in ``[0, 360)``.
    contact_points : (n, 3) float
        Hub-frame points of first touch of the teeth in contact (within ``band_mm`` of
        their flank's smallest normal clearance, or interfering).
    contact_flank, contact_tooth : (n,) int
    interfering : (2, N) bool
        Negative clearance.
    backlash_mm : float
        Free turning at the pitch radius (both flanks) at this pose.
    pressure_MPa : (2, N) float or None
        Interior contact pressure of each flank and tooth from the ``loads`` given to
        :func:`pose_state` (0 on the unloaded flank and teeth); None without them.
    """

    misalignment_deg: float
    psi_deg: float
    band_mm: float
    clearance_mm: NDArray[np.float64]
    normal_clearance_mm: NDArray[np.float64]
    theta_deg: NDArray[np.float64]
    contact_points: NDArray[np.float64]
    contact_flank: NDArray[np.intp]
    contact_tooth: NDArray[np.intp]
    interfering: NDArray[np.bool_]
    backlash_mm: float
    pressure_MPa: NDArray[np.float64] | None = None

    @property
    def min_clearance_mm(self) -> NDArray[np.float64]:
        """Smallest clearance of each flank, ``(2,)``."""
        return np.min(self.clearance_mm, axis=1)

    def summary(self) -> str:
        """One line per flank for the GUI: smallest clearance, its tooth, contacts."""
        lines = []
        for f, name in enumerate(FLANKS):
            c = self.clearance_mm[f]
            k = int(np.argmin(c))
            n_contact = int(np.sum(self.contact_flank == f))
            n_int = int(np.sum(self.interfering[f]))
            lines.append(f"{name}: min {c[k]:+.4f} mm (tooth {k}, θ = {self.theta_deg[k]:.1f}°)"
                         f", {n_contact} in contact, {n_int} interfering")
        lines.append(f"backlash {self.backlash_mm:.4f} mm at the pitch radius")
        return "\n".join(lines)


def pose_state(spec: CouplingSpec,
               misalignment_deg: float, psi_deg: float, *, band_mm: float = 0.005,
               tolerance_mm: float = VIEW_SWEEP_TOLERANCE_MM,
               loads: LoadResult | None = None) -> PoseState:
    """Exact clearances, contact points and interference at one pose.

    Solves no loads: the contact pressure comes from ``loads`` computed by the caller.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg, psi_deg : float
        Misalignment ``i`` (0-6°) and rotation ``psi`` (degrees).
    band_mm : float
        A tooth counts as in contact when its normal clearance is within this of the
        smallest on its flank (Renzo's separation ``z`` below the band), or negative.
    tolerance_mm : float
        Accuracy of the clearance minima (see :func:`gearcoupling.clearance.sweep`).
    loads : LoadResult, optional
        Loads of this spec at this pose (one rotation), e.g. ``gc.load(spec,
        misalignment_deg, [psi_deg], model="surface")``: their interior contact pressure
        becomes ``pressure_MPa``.
    """
    spec = as_spec(spec)
    mis, psi = check_pose(misalignment_deg, psi_deg)
    real(band_mm, "band_mm", 0.0, unit="mm")
    res = sweep(spec, mis, [psi], tolerance_mm=tolerance_mm)
    clear = res.clearance_mm[:, :, 0]
    normal = res.normal_clearance_mm[:, :, 0]
    interfering = clear < 0
    low = np.min(normal, axis=1, keepdims=True)
    touching = (np.isfinite(normal) & (normal <= low + band_mm)) | interfering
    flank_idx, tooth_idx = np.nonzero(touching)
    z = res.contact_z_mm[:, :, 0][touching]
    r = res.contact_r_mm[:, :, 0][touching]
    points = np.zeros((flank_idx.size, 3))
    m = hub_model(spec)
    for f, name in enumerate(FLANKS):
        sel = flank_idx == f
        if np.any(sel):
            p, _, _ = hub_flank_model(m, name, z[sel], r[sel], check=False)
            rot = rot_z(2.0 * np.pi * tooth_idx[sel] / spec.tooth.teeth)
            points[sel] = np.einsum("nij,nj->ni", rot, p)
    backlash = float(res.backlash_mm[0])
    return PoseState(mis, psi, float(band_mm), clear, normal, res.theta_deg[:, 0], points,
                     flank_idx, tooth_idx, interfering, backlash if math.isfinite(backlash)
                     else 0.0, None if loads is None else pose_pressure(loads, spec, mis, psi))


def pose_pressure(loads: LoadResult, spec: CouplingSpec, misalignment_deg: float,
                  psi_deg: float) -> NDArray[np.float64]:
    """Interior contact pressure ``(2, N)`` of the loaded flank's teeth (0 on the other
    flank and on unloaded teeth), or :class:`ArgumentError` when ``loads`` are not of this
    spec at this pose (one rotation)."""
    angles = np.asarray(loads.angles_deg, dtype=float)
    if not (loads.spec == spec and angles.size == 1
            and math.isclose(loads.misalignment_deg, misalignment_deg, abs_tol=1e-12)
            and math.isclose(float(angles[0]), psi_deg, abs_tol=1e-9)):
        raise ArgumentError("loads", f"{loads.spec.name} at {loads.misalignment_deg:g}° over "
                            f"{angles.size} rotation(s)", f"must be loads of {spec.name} at "
                            f"{misalignment_deg:g}°, rotation {psi_deg:g}° only")
    p = np.zeros((2, spec.tooth.teeth))
    p[FLANKS.index(loads.loaded_flank)] = loads.interior_pressure_MPa[:, 0]
    return p
