"""Small changes of the hub's pose relative to the sleeve, as the sweep and the load models
take them (docs/rotordynamics.md, "The pose").

The pose has six coordinates ``q = (x, y, z, a, b, chi)`` in the sleeve frame whose ``x``
axis is the operating tilt axis:

- ``(x, y, z)`` translate the hub (mm);
- ``v = (i + a, b, 0)`` is the hub's tilt as a rotation vector (radians): its length is
  the misalignment and its direction the tilt axis, so a tilt ``b`` about ``y`` at a
  misalignment ``i`` about ``x`` turns the tilt axis by ``atan(b / i)`` and grows the
  misalignment only to second order;
- ``chi`` turns the hub about its own axis (the wind-up).

The hub is ``exp([v]) Rz(psi + chi)`` and the sleeve ``Rz(psi)`` at the rotation ``psi``:
a tilt vector of length ``A`` at direction ``phi`` is the sweep's pose ``(A, psi - phi)``
turned by ``phi`` about the sleeve axis, exactly (the teeth are all alike). A translation
``d`` closes tooth ``k``'s gap by ``d . n_k`` (``n_k`` the sleeve flank normal at its
first-touch point ``p_k``), so its gap angle changes by ``-(d . n_k) / |(a x p_k) . n_k|``
to first order (``a`` the hub axis); the sleeve's straight teeth have transverse normals,
so an axial shift changes no gap, exactly.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from .wrench import contact_frames, rotate_about_z


def rot_x(angle_rad: float) -> NDArray[np.float64]:
    """The rotation ``(3, 3)`` about ``x``."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def tilt_pose(misalignment_rad: float, a: float, b: float) -> tuple[float, float]:
    """Misalignment ``A`` and tilt-axis direction ``phi`` (radians) of the tilt vector
    ``(misalignment + a, b)``."""
    ax = misalignment_rad + a
    return math.hypot(ax, b), math.atan2(b, ax)


def left_jacobian(v: NDArray) -> NDArray[np.float64]:
    """The left Jacobian ``(3, 3)`` of the rotation vector ``v``: the space angular
    velocity is ``J(v) dv`` (so the moment conjugate to ``v`` is ``J(v)^T M``)."""
    v = np.asarray(v, dtype=float)
    a = float(np.linalg.norm(v))
    S = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    if a < 1e-8:
        return np.eye(3) + 0.5 * S
    return (np.eye(3) + (1.0 - math.cos(a)) / a**2 * S
            + (a - math.sin(a)) / a**3 * S @ S)


def generalized_forces(force_hub: NDArray, moment_hub: NDArray, misalignment_rad: float,
                       phi_rad: float) -> NDArray[np.float64]:
    """``(M, 5)``: the force on the hub in the sleeve frame (N) and the moment conjugate to
    the tilt vector ``(a, b)`` (N·m), from the hub-frame force and moment ``(M, 3)`` of the
    sweep pose ``(A, psi - phi)`` (``x`` along its tilt axis)."""
    R = rot_x(misalignment_rad)
    F = rotate_about_z(force_hub @ R.T, phi_rad)
    M = rotate_about_z(moment_hub @ R.T, phi_rad)
    v = misalignment_rad * np.array([math.cos(phi_rad), math.sin(phi_rad), 0.0])
    Q = M @ left_jacobian(v)  # rows: J^T M
    return np.concatenate([F, Q[:, :2]], axis=1)


def sleeve_normals(spec, points: NDArray, flank: str) -> NDArray[np.float64]:
    """Unit normals ``(..., 3)`` of the straight involute sleeve flank facing the hub's
    ``flank`` at sleeve-frame ``points`` ``(..., 3)``, pointing from the hub toward it: the
    normal gap falls by ``n . dp`` when a hub point moves by ``dp``. Transverse (the
    sleeve's teeth are straight), tangent to the base circle: ``+-cos(phi_r) e_beta +
    sin(phi_r) e_r`` with ``cos(phi_r) = r_b / r`` (``+`` for ``ccw``)."""
    x, y = points[..., 0], points[..., 1]
    rho = np.hypot(x, y)
    c = np.clip(spec.tooth.base_radius / rho, -1.0, 1.0)
    s = np.sqrt(1.0 - c * c)
    sign = 1.0 if flank == "ccw" else -1.0
    e_r = np.stack([x / rho, y / rho, np.zeros_like(x)], axis=-1)
    e_b = np.stack([-y / rho, x / rho, np.zeros_like(x)], axis=-1)
    return sign * c[..., None] * e_b + s[..., None] * e_r


def translation_gap_offsets(spec, sweep_result, flank: str, column: int,
                            d_mm: NDArray) -> NDArray[np.float64]:
    """Per-tooth gap-angle change ``(N,)`` of the loaded ``flank`` when the hub moves by
    ``d_mm`` (3,) in the sleeve frame, at rotation ``column`` of ``sweep_result``: the
    normal gap at the first-touch point ``p`` falls by ``n . d`` (``n`` the sleeve flank
    normal there, also at a touch on a profile end) and a turn ``chi`` of the hub about its
    axis ``a`` closes it by ``chi |n . (a x p)|``; zero where a tooth has no first touch."""
    f = 0 if flank == "cw" else 1
    z = sweep_result.contact_z_mm[f][:, column]
    r = sweep_result.contact_r_mm[f][:, column]
    ok = np.isfinite(z) & np.isfinite(r)
    th = sweep_result.theta_deg[:, column]
    p, _ = contact_frames(spec, flank, th[:, None], np.where(ok, z, 0.0)[:, None],
                          np.where(ok, r, spec.tooth.pitch_radius)[:, None])
    R = rot_x(math.radians(sweep_result.misalignment_deg))
    p = p[:, 0] @ R.T  # the sleeve frame, x along the tilt axis
    n = sleeve_normals(spec, p, flank)
    rate = np.abs(np.sum(n * np.cross(R[:, 2], p), axis=-1))
    return np.where(ok, -(n @ np.asarray(d_mm, float)) / rate, 0.0)


__all__ = ["generalized_forces", "left_jacobian", "sleeve_normals", "tilt_pose",
           "translation_gap_offsets"]
