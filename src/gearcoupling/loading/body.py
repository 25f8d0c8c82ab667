"""Torsion of the bodies that carry the teeth: the hub from its bore to the tooth root and
the sleeve from its tooth root to the outside diameter.

The load models work at the teeth: their wind-up is the rotation that closes the tooth
gaps. Between the bore and the sleeve's outside diameter the bodies twist as well. Each
is an annulus of radii ``a < b`` and length ``L`` in circumferential shear under the
torque: the shear stress ``T / (2 pi r² L)`` gives ``dtheta/dr = T / (2 pi G L r³)``, so

    theta = T / (4 pi G L) (1 / a² - 1 / b²)

(hub: ``a`` the bore radius, ``b`` the root radius, ``L`` the body length; sleeve: ``a``
the root radius, ``b`` the outside radius, ``L`` the sleeve face width). A hub without a
bore is held by its shaft or end faces: its body torsion depends on them and is not
counted (0). The FE contact reference, whose bore is fixed and whose sleeve outside
diameter is a rigid body, holds both parts in its wind-up.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import torque_Nm as check_torque_Nm
from ..errors import ArgumentError
from ..fea import body_influence_table
from ..spec import CouplingSpec, as_spec


def annulus_twist_rad(torque_Nmm: float, inner_mm: float, outer_mm: float, length_mm: float,
                      shear_modulus_MPa: float) -> float:
    """Twist of an annulus of radii ``inner_mm < outer_mm`` in circumferential shear."""
    return (torque_Nmm / (4.0 * math.pi * shear_modulus_MPa * length_mm)
            * (1.0 / inner_mm**2 - 1.0 / outer_mm**2))


def body_windup_rad(spec: CouplingSpec, torque_Nm: float) -> dict[str, float]:
    """Body torsion of hub and sleeve at ``torque_Nm`` (module docstring).

    Returns
    -------
    dict
        ``hub_rad``, ``sleeve_rad`` and their sum ``body_rad`` (signed like the torque).
    """
    spec = as_spec(spec)
    T = check_torque_Nm(torque_Nm) * 1e3
    hub, sleeve = spec.hub, spec.sleeve
    root = spec.tooth.pitch_radius - hub.root.dedendum
    bore = 0.5 * hub.body.bore_diameter
    length = max(hub.body.length, hub.face_width)
    hub_rad = (annulus_twist_rad(T, bore, root, length, spec.material.hub.shear_modulus_MPa)
               if bore > 0 else 0.0)
    sleeve_rad = annulus_twist_rad(T, 0.5 * sleeve.major_diameter, 0.5 * sleeve.outer_diameter,
                                   sleeve.face_width, spec.material.sleeve.shear_modulus_MPa)
    return {"hub_rad": hub_rad, "sleeve_rad": sleeve_rad, "body_rad": hub_rad + sleeve_rad}


# --- Tooth by tooth: the bodies' influence between teeth -------------------------------------
#
# Under unequal tooth loads (a misalignment) the bodies do not twist as one: tooth k's
# deflection at the pitch radius (mm, the tooth table's measure) from the bodies is
#
#     v_k = sum_j b((k - j) mod N) W_j
#
# with W_j the tangential tooth loads at the pitch radius (N) and b (N,) the body kernel
# (mm/N): the whole ring's deflection of tooth m under a unit load on tooth 0, less, on the
# loaded tooth itself, what the tooth table's 3-tooth sector with fixed cuts already holds
# (:class:`gearcoupling.fea.bodies.BodyInfluenceTable`, hub + sleeve). b is symmetric
# (reciprocity) and circulant (every tooth alike); its discrete Fourier transform
# lambda_n (:func:`kernel_harmonics`) is the body compliance per tooth for loads going as
# cos(2 pi n k / N): lambda_0 is the uniform torsion beyond what the table holds, the
# closed form's N R² theta/T when the table holds nothing of it. The load models' uniform
# body (:func:`body_windup_rad`, for the whole coupling) is the kernel R² theta/T on every
# tooth (lambda_n = 0 for n > 0); counted per tooth it is N R² theta/T on the loaded one
# only (lambda_n = lambda_0 for every n).


def kernel_matrix(kernel: ArrayLike) -> NDArray[np.float64]:
    """The circulant influence matrix ``(K, K)`` of a kernel ``(K,)``:
    ``B[k, j] = kernel[(k - j) mod K]`` (mm/N)."""
    b = _kernel(kernel)
    idx = (np.arange(b.size)[:, None] - np.arange(b.size)[None, :]) % b.size
    return b[idx]


def kernel_harmonics(kernel: ArrayLike) -> NDArray[np.float64]:
    """Body compliance per load harmonic ``lambda_n``, ``n = 0 .. K // 2`` ``(K // 2 + 1,)``
    (mm/N): the eigenvalues of :func:`kernel_matrix` (a symmetric kernel's are real)."""
    return np.fft.rfft(_kernel(kernel)).real


def periodic_kernel(kernel: ArrayLike, period: int) -> NDArray[np.float64]:
    """The kernel ``(period,)`` of loads that repeat every ``period`` teeth, as a sector of
    ``period`` teeth with cyclic cuts sees them: ``b_K(m) = sum_l b(m + l K)`` over the
    teeth of a chain, the ring kernel unrolled to ``|m| <= N / 2`` (it decays with the
    distance; ``period = N`` gives the kernel back, and every period the same uniform
    torsion ``sum b``)."""
    b = _kernel(kernel)
    N = b.size
    if not (isinstance(period, int | np.integer) and 1 <= period <= N):
        raise ArgumentError("period", period, f"a whole number of teeth from 1 to {N}")
    if period == N:
        return b.copy()
    m = np.arange(N)
    line = np.where(m <= N // 2, m, m - N)
    weight = np.where(2 * np.abs(line) == N, 0.5, 1.0)  # tooth N/2: half at +N/2, half at -N/2
    out = np.zeros(int(period))
    np.add.at(out, line % period, weight * b)
    if N % 2 == 0:
        out[(-(N // 2)) % period] += 0.5 * b[N // 2]
    return out


def convolve_loads(kernel: ArrayLike, loads: ArrayLike) -> NDArray[np.float64]:
    """``v_k = sum_j kernel[(k - j) mod K] W_j`` for loads ``(K,)`` or ``(K, M)`` (N): the
    same shape (mm)."""
    b = _kernel(kernel)
    W = np.asarray(loads, dtype=float)
    if W.ndim not in (1, 2) or W.shape[0] != b.size or not np.all(np.isfinite(W)):
        raise ArgumentError("loads", W.shape, f"finite, shaped ({b.size},) or ({b.size}, M)")
    fb = np.fft.rfft(b)
    fw = np.fft.rfft(W, axis=0)
    return np.fft.irfft(fb.reshape((-1,) + (1,) * (W.ndim - 1)) * fw, n=b.size, axis=0)


def _kernel(kernel: ArrayLike) -> NDArray[np.float64]:
    b = np.asarray(kernel, dtype=float)
    if b.ndim != 1 or b.size < 1 or not np.all(np.isfinite(b)):
        raise ArgumentError("kernel", b.shape, "a finite kernel shaped (K,) (mm/N)")
    return b


def influence_matrix(kernel: ArrayLike, z_grid_mm: ArrayLike | None = None,
                     z_mm: ArrayLike | None = None) -> NDArray[np.float64]:
    """The influence matrix ``(K, K)`` (mm/N) of a kernel tabulated over load positions.

    Parameters
    ----------
    kernel : (nz, K) or (K,) float
        Kernel rows at the axial load points ``z_grid_mm (nz,)`` (one row: no z).
    z_grid_mm : (nz,) float, optional
        Increasing ``|z|`` of the rows.
    z_mm : (K,) float, optional
        The teeth's load points (default 0): ``B[k, j]`` is the kernel at offset
        ``(k - j) mod K``, linear in ``|z|`` at the pair's mean ``(|z_k| + |z_j|) / 2``
        (held beyond the grid). Symmetric, like the ring it stands for.
    """
    b = np.atleast_2d(np.asarray(kernel, dtype=float))
    nz, K = b.shape
    if not np.all(np.isfinite(b)):
        raise ArgumentError("kernel", b.shape, "finite values (mm/N)")
    zg = np.zeros(1) if z_grid_mm is None else np.asarray(z_grid_mm, dtype=float).ravel()
    if zg.size != nz or np.any(np.diff(zg) <= 0):
        raise ArgumentError("z_grid_mm", zg.tolist(), f"{nz} increasing |z| (mm), one per "
                            "kernel row")
    z = np.zeros(K) if z_mm is None else np.abs(np.asarray(z_mm, dtype=float))
    if z.shape != (K,) or not np.all(np.isfinite(z)):
        raise ArgumentError("z_mm", z.shape, f"finite, shaped ({K},)")
    m = (np.arange(K)[:, None] - np.arange(K)[None, :]) % K
    if nz == 1:
        return b[0][m]
    zb = np.clip(0.5 * (z[:, None] + z[None, :]), zg[0], zg[-1])
    i = np.clip(np.searchsorted(zg, zb, side="right") - 1, 0, nz - 2)
    t = (zb - zg[i]) / (zg[i + 1] - zg[i])
    return (1.0 - t) * b[i, m] + t * b[i + 1, m]


def body_influence_matrix(spec: CouplingSpec, z_mm: ArrayLike | None = None, *,
                          period: int | None = None, table=None) -> NDArray[np.float64]:
    """The bodies' influence matrix ``(K, K)`` (mm/N) of a spec, tooth by tooth.

    ``B @ W`` is every tooth's body deflection at the pitch radius (mm) under the tooth
    loads ``W (K,)`` (N, tangential at the pitch radius) at load points ``z_mm (K,)``
    (default 0): the whole ring's bodies less the part the tooth table's 3-tooth sector
    already holds, hub + sleeve (the kernel comment above). It replaces the uniform body
    torsion (:func:`body_windup_rad`) in a model whose tooth springs are the FE table
    (``[load] stiffness = "fe"``): its harmonic 0 is the bodies' uniform torsion beyond
    the table's.

    Parameters
    ----------
    period : int, optional
        ``K``: loads repeating every ``period`` teeth, as a sector of ``period`` teeth with
        cyclic cuts sees them (:func:`periodic_kernel`); default N, the whole coupling.
    table : BodyInfluenceTable, optional
        Default :func:`gearcoupling.fea.body_influence_table` (FE, cached per spec).
    """
    table = _table(spec, table)
    kernel = table.kernel_mm_per_N
    if period is not None:
        kernel = np.stack([periodic_kernel(row, period) for row in kernel])
    return influence_matrix(kernel, table.z_mm, z_mm)


def body_deflection_mm(spec: CouplingSpec, loads: ArrayLike, z_mm: ArrayLike | None = None,
                       *, period: int | None = None, table=None) -> NDArray[np.float64]:
    """Every tooth's body deflection at the pitch radius (mm), shaped like ``loads``.

    Parameters
    ----------
    loads : (K,) or (K, M) float
        Tangential tooth loads at the pitch radius (N), one column per rotation.
    z_mm : like ``loads``, optional
        The teeth's load points (hub frame; default 0).
    period, table
        As :func:`body_influence_matrix`.
    """
    table = _table(spec, table)
    K = table.ring_mm_per_N.shape[-1] if period is None else period
    W = np.asarray(loads, dtype=float)
    z = np.zeros_like(W) if z_mm is None else np.asarray(z_mm, dtype=float)
    if (W.ndim not in (1, 2) or W.shape[0] != K or z.shape != W.shape
            or not np.all(np.isfinite(W))):
        raise ArgumentError("loads", W.shape, f"finite, shaped ({K},) or ({K}, M), and z_mm "
                            "shaped alike")
    cols = W.reshape(W.shape[0], -1)
    zc = z.reshape(cols.shape)
    out = np.column_stack([body_influence_matrix(spec, zc[:, j], period=period, table=table)
                           @ cols[:, j] for j in range(cols.shape[1])])
    return out.reshape(W.shape)


def _table(spec: CouplingSpec, table):
    """``table``, or the spec's FE body influence table (cached)."""
    return body_influence_table(spec) if table is None else table
