"""Optional compiled point evaluation of the clearance kernel (extra ``fast``: numba).

:func:`gaps_kernel` returns a numba function that fuses what
:meth:`~.clearance._Planes.f` does in ~30 numpy passes (flank ``y`` by Horner's rule, the
pose, the involute and root-fillet gaps) into one loop over the points, or None when numba
is not installed (the numpy path is then used; both give the same minima, to rounding:
``tests/test_sweep_frozen.py`` runs both). Set ``GEARCOUPLING_NUMBA=0`` to force numpy.
"""

from __future__ import annotations

import math
import os
from functools import lru_cache

import numpy as np


def _gaps(t, idx, kz, lo, span, z, ct, st, c):
    """Both gaps at heights ``t (L, m)`` of the rows ``idx (m,)``: ``(circ, normal)``.

    ``kz (nt, n)`` power coefficients in ``2 t - 1``; ``lo, span, z, ct, st (n,)``;
    ``c`` = (cos i, sin i, r_b, c0, r_fillet, rho, cn, gc, cx, cy)."""
    ci, si, r_b, c0, r_fil, rho, cn, gc, cx, cy = c
    L, m = t.shape
    nt = kz.shape[0]
    circ = np.empty((L, m))
    normal = np.empty((L, m))
    for j in range(m):
        row = idx[j]
        for i in range(L):
            tt = t[i, j]
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
            rq = math.sqrt(qx * qx + qy * qy)
            aq = math.atan2(qy, qx)
            if rho > 0.0 and rq > r_fil:
                cosb = (rq * rq + cn * cn - rho * rho) / (2.0 * rq * cn)
                cosb = min(max(cosb, -1.0), 1.0)
                circ[i, j] = rq * (aq - (gc - math.acos(cosb)))
                normal[i, j] = rho - math.hypot(rq * math.cos(aq) - cx, rq * math.sin(aq) - cy)
            else:
                w = max(rq * rq - r_b * r_b, 0.0)
                d = aq + c0 - (math.sqrt(w) / r_b - math.acos(min(r_b / rq, 1.0)))
                circ[i, j] = rq * d
                normal[i, j] = r_b * d
    return circ, normal


@lru_cache(maxsize=1)
def gaps_kernel():
    """The compiled :func:`_gaps`, or None without numba (or with ``GEARCOUPLING_NUMBA=0``)."""
    if os.environ.get("GEARCOUPLING_NUMBA", "1") == "0":
        return None
    try:
        import numba
    except ImportError:
        return None
    return numba.njit(cache=True, nogil=True)(_gaps)
