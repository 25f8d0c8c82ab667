"""numba kernels of :mod:`.fast` (imported only through :func:`.fast.kernels`)."""

from __future__ import annotations

import math

import numba
import numpy as np

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")


@_jit
def point_pose(tt, row, kz, lo, span, z, ct, st, c):
    """``(rq, aq, zq)`` of row ``row`` at height ``tt``: the operations of
    ``_Planes.at`` in their order (the same values)."""
    ci, si = c[0], c[1]
    nt = kz.shape[0]
    s = 2.0 * tt - 1.0
    b = kz[nt - 1, row] * s
    for k in range(nt - 2, 0, -1):
        b += kz[k, row]
        b *= s
    y = b + kz[0, row]
    r = lo[row] + tt * span[row]
    x = math.sqrt(r * r - y * y)
    u = x * st[row] + y * ct[row]
    v = u * (ci - 1.0) - z[row] * si
    qx = v * st[row] + x
    qy = v * ct[row] + y
    return math.sqrt(qx * qx + qy * qy), math.atan2(qy, qx), u * si + z[row] * ci


@_jit
def point_gaps(tt, row, kz, lo, span, z, ct, st, c):
    """``(circumferential, normal)`` gaps of row ``row`` at height ``tt``: ``_Planes.at``
    + ``_Sleeve.gaps`` in their order of operations."""
    r_b, c0, r_fil, rho, cn, gc, cx, cy = c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9]
    rq, aq, _ = point_pose(tt, row, kz, lo, span, z, ct, st, c)
    if rho > 0.0 and rq > r_fil:
        cosb = min(max((rq * rq + cn * cn - rho * rho) / (2.0 * rq * cn), -1.0), 1.0)
        return (rq * (aq - (gc - math.acos(cosb))),
                rho - math.hypot(rq * math.cos(aq) - cx, rq * math.sin(aq) - cy))
    w = max(rq * rq - r_b * r_b, 0.0)
    d = aq + c0 - (math.sqrt(w) / r_b - math.acos(min(r_b / rq, 1.0)))
    return rq * d, r_b * d


@_jit
def gaps(t, idx, kz, lo, span, z, ct, st, c):
    """Both gaps at heights ``t (L, m)`` of the rows ``idx (m,)``: ``(circ, normal)``."""
    L, m = t.shape
    circ = np.empty((L, m))
    normal = np.empty((L, m))
    for j in range(m):
        for i in range(L):
            circ[i, j], normal[i, j] = point_gaps(t[i, j], idx[j], kz, lo, span, z, ct, st, c)
    return circ, normal


@_jit
def slope_roots(idx, gap, a, b, x0, g0, x1, g1, iters, d, kz, lo, span, z, ct, st, c):
    """``_Planes._interior``'s secant search on the central-difference slope of gap
    ``gap[j]`` (0 circumferential, 1 normal) of row ``idx[j]`` in ``[a, b]``, per row,
    in its order of operations: the roots ``(k,)``."""
    res = np.empty(idx.size)
    for j in range(idx.size):
        row, g = idx[j], gap[j]
        aj, bj, x0j, g0j, x1j, g1j = a[j], b[j], x0[j], g0[j], x1[j], g1[j]
        for _ in range(iters):
            x = x1j - g1j * (x1j - x0j) / (g1j - g0j)
            if not np.isfinite(x) or x <= aj or x >= bj:
                x = 0.5 * (aj + bj)
            xc = min(max(x, aj + d), bj - d)
            fp = point_gaps(xc + d, row, kz, lo, span, z, ct, st, c)[g]
            fm = point_gaps(xc - d, row, kz, lo, span, z, ct, st, c)[g]
            gx = (fp - fm) / (2 * d)
            if gx > 0:
                bj = xc
            else:
                aj = xc
            x0j, g0j, x1j, g1j = x1j, g1j, xc, gx
            if abs(x1j - x0j) <= 1e-7:
                break
        res[j] = x1j
    return res


@_jit
def cross(use_z, target, a, b, fa, fb, idx, rel, kz, lo, span, z, ct, st, c):
    """``_Planes.cross``: all rows step together until every row has converged, in its
    order of operations (the same values)."""
    m = idx.size
    a, b, fa, fb = a.copy(), b.copy(), fa.copy(), fb.copy()
    x0, f0, x1, f1 = a.copy(), fa.copy(), b.copy(), fb.copy()
    t, ft = a.copy(), np.empty(m)
    tol = rel * (abs(target) + 1.0)
    for _ in range(60):
        converged = True
        for j in range(m):
            tj = x1[j] - f1[j] * (x1[j] - x0[j]) / (f1[j] - f0[j])
            if not np.isfinite(tj) or tj <= min(a[j], b[j]) or tj >= max(a[j], b[j]):
                tj = a[j] - fa[j] * (b[j] - a[j]) / (fb[j] - fa[j])
            rq, _, zq = point_pose(tj, idx[j], kz, lo, span, z, ct, st, c)
            t[j], ft[j] = tj, (zq if use_z else rq) - target
            if not abs(ft[j]) <= tol:
                converged = False
        if converged:
            return t
        for j in range(m):
            if np.sign(ft[j]) == np.sign(fa[j]):
                a[j], fa[j] = t[j], ft[j]
            else:
                b[j], fb[j] = t[j], ft[j]
            x0[j], f0[j], x1[j], f1[j] = x1[j], f1[j], t[j], ft[j]
    return t
