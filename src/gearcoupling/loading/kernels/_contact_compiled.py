"""Polonsky & Keer's per-grid conjugate gradients compiled (numba), for small grids.

Imported only through :func:`.halfspace.compiled`. :func:`per_grid_cg` does for each grid
what :func:`.halfspace._per_grid_loads` does for a batch with a rigid-body compliance
(uniform behind each grid, so it does not change the grid's contact under its load): the
same steps, stops and resets, one grid after the other with scalar state. The half-space
displacement is the direct sum over the cells in contact (the search direction and the
pressure vanish elsewhere) with the influence coefficients by offset
(:func:`.halfspace.offset_influence`), in double precision: no transform, no numpy call
per step. It pays on the load studies' 12 x 8 grids, where the batched path is mostly
numpy's per-call overhead; on larger grids the batched single-precision transforms win
(:data:`.halfspace.COMPILED_MAX_CELLS`, docs/load-surface.md).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ...io.numba_cache import njit

_jit = njit(nogil=True, error_model="numpy", fastmath={"contract"})  # cached, verified
_inline = numba.njit(inline="always", error_model="numpy", fastmath={"contract"})


@_inline
def _apply(K, q, n1, n2, out):
    """``out (n1, n2)`` = the displacement of ``q (n1, n2)`` (its nonzero cells only),
    ``K (2 n1 - 1, 2 n2 - 1)`` the influence at offset ``(i - k, j - l)`` stored at
    ``(i - k + n1 - 1, j - l + n2 - 1)``."""
    out[:, :] = 0.0
    for k in range(n1):
        for li in range(n2):
            w = q[k, li]
            if w == 0.0:
                continue
            for i in range(n1):
                row = K[i - k + n1 - 1]
                o = n2 - 1 - li
                for j in range(n2):
                    out[i, j] += w * row[o + j]


@_inline
def _solve_one(K, g0, m, W, p, u, t, r, pn, scale, tol, max_iter, area, tau_self, gmin):
    """One grid (``(n1, n2)`` arrays; ``p`` the start, scaled to ``W``; ``u``, ``t``, ``r``,
    ``pn`` work space) to ``tol``: returns the iterations (``max_iter + 1``: not
    converged) and the last relative change; ``p`` and ``u`` (its displacement) in place."""
    n1, n2 = p.shape
    _apply(K, p, n1, n2, u)
    t[:, :] = 0.0
    g_old, delta, res = 1.0, 0.0, 0.0
    for it in range(1, max_iter + 1):
        n_on, s = 0, 0.0
        for i in range(n1):
            for j in range(n2):
                if p[i, j] > 0.0:
                    n_on += 1
                    s += u[i, j] + g0[i, j]
        n_on = max(n_on, 1)
        al = s / n_on
        G = 0.0
        for i in range(n1):
            for j in range(n2):
                g = (u[i, j] + g0[i, j] - al) if m[i, j] else 0.0
                pn[i, j] = g  # the gap, kept for the overlap test below
                if p[i, j] > 0.0:
                    G += g * g
        beta = delta * G / g_old if g_old > 0.0 else 0.0
        for i in range(n1):
            for j in range(n2):
                t[i, j] = t[i, j] * beta + pn[i, j] if p[i, j] > 0.0 else 0.0
        g_old = G
        _apply(K, t, n1, n2, r)
        rs = 0.0
        for i in range(n1):
            for j in range(n2):
                if p[i, j] > 0.0:
                    rs += r[i, j]
        rm = rs / n_on
        den, num = 0.0, 0.0
        for i in range(n1):
            for j in range(n2):
                if p[i, j] > 0.0:  # t is 0 elsewhere
                    den += (r[i, j] - rm) * t[i, j]
                    num += pn[i, j] * t[i, j]
        tau = num / den if den > 0.0 else 0.0
        has_over, projected = False, False
        kick = tau if tau > 0.0 else tau_self
        tot = 0.0
        for i in range(n1):
            for j in range(n2):
                g = pn[i, j]
                step = p[i, j] - tau * t[i, j]
                v = step if step > 0.0 else 0.0
                if step < 0.0:
                    projected = True
                if v == 0.0 and g < 0.0:  # overlapped: joins the contact set
                    has_over = True
                    v = -kick * g
                pn[i, j] = v
                tot += v
        tot *= area
        if has_over:
            projected = True
        delta = 0.0 if has_over else 1.0
        if tot <= 0.0:
            tot = 0.0
            for i in range(n1):
                for j in range(n2):
                    v = 1.0 if (m[i, j] and g0[i, j] <= gmin + 1e-15) else 0.0
                    pn[i, j] = v
                    tot += v
            tot *= area
            projected = True
        sc = W / tot
        change, total = 0.0, 0.0
        for i in range(n1):
            for j in range(n2):
                v = pn[i, j] * sc
                change += abs(v - p[i, j])
                total += v
                p[i, j] = v
        if projected:
            _apply(K, p, n1, n2, u)
        else:  # no cell left or joined the contact set: the step is linear, and so is u
            for i in range(n1):
                for j in range(n2):
                    u[i, j] = (u[i, j] - tau * r[i, j]) * sc
        res = change / total
        gap_err = math.sqrt(G / n_on) / scale
        if res <= tol and gap_err <= tol and not has_over:
            return it, res
    return max_iter + 1, res


@_jit
def per_grid_cg(K, g0, m, W, p, scale, gmin, tol, max_iter, area, tau_self):
    """Each grid ``b`` with ``W[b] > 0`` of ``g0, m, p (B, n1, n2)`` under its load (module
    docstring); ``p`` in place. Returns the half-space displacement ``(B, n1, n2)`` of
    ``p``, each grid's iterations ``(B,)`` (0: unloaded; ``max_iter + 1``: not
    converged) and last relative change ``(B,)``."""
    B, n1, n2 = p.shape
    u = np.zeros_like(p)
    its = np.zeros(B, dtype=np.int64)
    res = np.zeros(B)
    t = np.empty((n1, n2))
    r = np.empty((n1, n2))
    pn = np.empty((n1, n2))
    for b in range(B):
        if W[b] > 0.0:
            its[b], res[b] = _solve_one(K, g0[b], m[b], W[b], p[b], u[b], t, r, pn,
                                        scale[b], tol, max_iter, area, tau_self, gmin[b])
    return u, its, res
