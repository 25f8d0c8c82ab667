"""Poses of docs/conventions.md, Frames: the hub tilted by ``i`` about the sleeve ``x`` axis, both
turning.

A hub body point ``p`` lies in the sleeve body frame at ``Rz(-psi) Rx(i) Rz(psi) p``. For
hub tooth ``k`` in sleeve space ``k`` this equals ``Rz(2 pi k / N) P(theta_k) p0`` with
``p0`` the same point on tooth 0 and ``theta_k = psi + 2 pi k / N``, so the gap of tooth
``k`` to space ``k`` depends on ``theta_k`` only: :func:`reduced_pose` ``P(theta)``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray


def rot_z(a: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrices about ``z``: ``(..., 3, 3)``."""
    a = np.asarray(a, dtype=float)
    c, s = np.cos(a), np.sin(a)
    if a.ndim == 0:  # one matrix (the poses of a check: thousands), without the stacking
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1),
                     np.stack([z, z, o], -1)], -2)


def rot_x(a: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrices about ``x``: ``(..., 3, 3)``."""
    a = np.asarray(a, dtype=float)
    c, s = np.cos(a), np.sin(a)
    if a.ndim == 0:
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1),
                     np.stack([z, s, c], -1)], -2)


def hub_to_sleeve(misalignment: float, psi: ArrayLike) -> NDArray[np.float64]:
    """``Rz(-psi) Rx(i) Rz(psi)``: hub body frame to sleeve body frame, ``(..., 3, 3)``."""
    psi = np.asarray(psi, dtype=float)
    return rot_z(-psi) @ rot_x(misalignment) @ rot_z(psi)


def reduced_pose(misalignment: float, theta: ArrayLike) -> NDArray[np.float64]:
    """``P(theta)``: tooth 0's points to space 0's frame for a tooth at turning angle theta."""
    return hub_to_sleeve(misalignment, theta)


def turning_angles(teeth: int, psi: ArrayLike) -> NDArray[np.float64]:
    """``theta[k, j] = psi[j] + 2 pi k / N`` (radians), shape ``(N, n_psi)``."""
    psi = np.atleast_1d(np.asarray(psi, dtype=float))
    return psi[None, :] + 2.0 * np.pi * np.arange(teeth)[:, None] / teeth


def map_polar(r, alpha, z, misalignment: float, theta):
    """Map hub points given in cylinder coordinates ``(r, alpha, z)`` by ``P(theta)``.

    Returns
    -------
    rq, aq, zq : (...) float
        Radius, polar angle (in ``(-pi, pi]`` about the space centre) and axial position in
        the sleeve frame.
    """
    return map_point(r * np.cos(alpha), r * np.sin(alpha), z, misalignment, theta)


def map_point(x, y, z, misalignment: float, theta):
    """:func:`map_polar` for points given by ``(x, y, z)`` (closed form of ``P(theta) p``,
    cheaper than matrices in a batch)."""
    return map_point_cs(x, y, z, math.cos(misalignment), math.sin(misalignment),
                        np.cos(theta), np.sin(theta))


def map_point_cs(x, y, z, ci: float, si: float, ct, st):
    """:func:`map_point` with the cosines and sines of ``i`` and ``theta`` given (callers
    that map many batches at the same turning angles compute them once)."""
    u = x * st + y * ct  # y after Rz(theta)
    v = u * (ci - 1.0) - z * si  # its change by the tilt
    qx = x + v * st
    qy = y + v * ct
    zq = u * si + z * ci
    rq = np.sqrt(qx * qx + qy * qy)
    aq = np.arctan2(qy, qx)
    return rq, aq, zq
