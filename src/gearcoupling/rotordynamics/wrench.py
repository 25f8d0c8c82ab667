"""The force and moment the sleeve puts on the hub, as vectors, from a load result.

Every loaded tooth pushes the hub with ``-W n`` (``n`` the exact outward hub flank normal
at the tooth's load point) plus Coulomb friction ``-mu W t`` against the hub's sliding
velocity ``t`` there (hub and sleeve turning at the same speed about their own axes, so
the sliding per unit speed is ``(a_hub - a_sleeve) x p``, projected onto the flank).
Summed over the teeth and taken about ``O``: the same sums as the machine loads of
``load_summary.json`` (docs/load.md), kept as vectors in the hub frame with ``x`` along
the tilt axis, ``z`` along the hub axis.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..geometry import form_radius, hub_flank_model, hub_model, tip_radius


def rotate_about_z(v: NDArray, angle_rad: NDArray | float) -> NDArray[np.float64]:
    """Vectors ``(..., 3)`` turned by ``angle_rad`` (broadcast over the leading axes) about z."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1], v[..., 2]],
                    axis=-1)


def contact_frames(spec, flank: str, theta_deg: NDArray, z_mm: NDArray,
                   r_mm: NDArray) -> tuple[NDArray, NDArray]:
    """Points and outward unit hub flank normals ``(N, M, 3)`` in the hub frame (``x`` along
    the tilt axis) of the teeth at turning angles ``theta_deg`` and flank points
    ``(z_mm, r_mm)``, all ``(N, M)``; points off the flank are moved onto its edge."""
    m = hub_model(spec)
    z = np.clip(z_mm, -m.half_face, m.half_face)
    r = np.clip(r_mm, form_radius(m, z), tip_radius(m, z))
    p, n, _ = hub_flank_model(m, flank, z, r, check=False)
    th = np.radians(theta_deg)
    return rotate_about_z(p, th), rotate_about_z(n, th)


def sliding_direction(misalignment_rad: float, p: NDArray, n: NDArray) -> NDArray[np.float64]:
    """Unit sliding direction of the hub on the sleeve in the flank plane, ``(..., 3)``; zero
    where the hub does not slide (aligned, or on the tilt axis)."""
    i = misalignment_rad
    axis_diff = np.array([0.0, 0.0, 1.0]) - np.array([0.0, math.sin(i), math.cos(i)])
    v = np.cross(axis_diff, p)
    v = v - np.sum(v * n, axis=-1, keepdims=True) * n
    speed = np.linalg.norm(v, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(speed > 1e-12, v / speed, 0.0)


def hub_wrench(res, friction: float | None = None) -> tuple[NDArray, NDArray]:
    """Force (N) and moment about ``O`` (N·m) on the hub per rotation, ``(M, 3)`` each, in
    the hub frame with ``x`` along the tilt axis.

    Parameters
    ----------
    res : LoadResult
    friction : float, optional
        Coulomb coefficient; default the spec's ``[load] friction``.
    """
    mu = res.spec.load.friction if friction is None else float(friction)
    p, n = contact_frames(res.spec, res.loaded_flank, res.theta_deg, res.contact_z_mm,
                          res.contact_r_mm)
    t = sliding_direction(math.radians(res.misalignment_deg), p, n)
    f = -res.normal_force_N[..., None] * (n + mu * t)
    return np.sum(f, axis=0), np.sum(np.cross(p, f), axis=0) * 1e-3


__all__ = ["contact_frames", "hub_wrench", "rotate_about_z", "sliding_direction"]
