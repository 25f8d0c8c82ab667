"""Slow, independent reference minima for validating the sweep kernel.

Uses only the exact hub flank (:func:`~gearcoupling.geometry.hub.hub_flank_model`), the
sleeve's space half-angle and the pose matrices - not the Chebyshev flank table nor the
kernel's minimiser. :func:`brute_force` evaluates a dense grid of exact flank points
between the exact ends of the active interval of every plane, steps to the parabolic
vertex in ``t`` and searches ``z`` by golden sections around the best plane, so that
corners of the active region (sleeve tip edge meeting a sleeve face end) are resolved.
Slow by design: for tests and benchmarks, not for sweeps.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry import hub_flank_model, hub_model, hub_to_sleeve, sleeve_model
from ..spec import CouplingSpec
from .flank_table import exact_alpha


def exact_gap(spec: CouplingSpec, mis: float, theta: float, z, r, normal: bool):
    """Gap (mm) of tooth 0's exact cw flank point ``(z, r)`` to space 0 at turning angle
    ``theta``: ``(gap, rq, zq)`` (normal or circumferential)."""
    m, sm = hub_model(spec), sleeve_model(spec)
    pts, _, _ = hub_flank_model(m, "cw", z, r, check=False)
    q = pts @ hub_to_sleeve(mis, theta).T
    rq = np.hypot(q[..., 0], q[..., 1])
    a = np.arctan2(q[..., 1], q[..., 0])
    d = a + sm.half_angle(rq)
    return (sm.r_base if normal else rq) * d, rq, q[..., 2]


def _plane_min(spec: CouplingSpec, mis, theta, z, normal, nt):
    """Exact minimum over a dense t grid in each plane ``z`` (array); the active interval's
    ends (sleeve tip edge, sleeve face ends) solved by bisection on the exact flank."""
    m, sm = hub_model(spec), sleeve_model(spec)
    z = np.atleast_1d(np.asarray(z, dtype=float))

    def mapped(t):
        r, a = exact_alpha(m, z, t)
        return exact_gap_from_polar(spec, mis, theta, r, a, z, normal)

    def crossing(fun, f0, f1):
        """Bisection for fun(t) = 0 on [0, 1] per plane (where f0, f1 differ in sign)."""
        lo, hi = np.zeros(z.shape), np.ones(z.shape)
        for _ in range(34):
            mid = 0.5 * (lo + hi)
            same = np.sign(fun(mid)) == np.sign(f0)
            lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
        return 0.5 * (lo + hi)

    # each constraint is monotone in t (rq grows with t, zq moves one way): its feasible
    # part is [c, 1] or [0, c]; the active interval is their intersection
    zero, one = np.zeros(z.shape), np.ones(z.shape)
    _, rq0, zq0 = mapped(zero)
    _, rq1, zq1 = mapped(one)
    lo_in, hi_in = zero.copy(), one.copy()
    empty = rq1 < sm.r_form
    cut = (rq0 < sm.r_form) & ~empty
    tc = crossing(lambda t: mapped(t)[1] - sm.r_form, rq0 - sm.r_form, rq1 - sm.r_form)
    lo_in = np.where(cut, tc, lo_in)
    for sign in (1.0, -1.0):
        v0, v1 = sign * zq0 - sm.half_face, sign * zq1 - sm.half_face
        empty |= (v0 > 0) & (v1 > 0)
        tf = crossing(lambda t, sign=sign: sign * mapped(t)[2] - sm.half_face, v0, v1)
        lo_in = np.where((v0 > 0) & (v1 <= 0), np.maximum(lo_in, tf), lo_in)
        hi_in = np.where((v1 > 0) & (v0 <= 0), np.minimum(hi_in, tf), hi_in)
    any_ok = ~empty & (lo_in <= hi_in)
    t = lo_in[:, None] + np.linspace(0.0, 1.0, nt)[None, :] * (hi_in - lo_in)[:, None]
    zz = np.broadcast_to(z[:, None], t.shape)
    r, a = exact_alpha(m, zz, t)
    g, rq, zq = exact_gap_from_polar(spec, mis, theta, r, a, zz, normal)
    ok = (rq >= sm.r_form - 1e-9) & (np.abs(zq) <= sm.half_face + 1e-9)
    g = np.where(ok, g, np.inf)
    j = np.argmin(g, axis=1)
    rows = np.arange(z.size)
    best = g[rows, j]
    # parabolic vertex through the best grid point and its neighbours, evaluated exactly
    jm, jp = np.clip(j - 1, 0, nt - 1), np.clip(j + 1, 0, nt - 1)
    y0, y1, y2 = g[rows, jm], best, g[rows, jp]
    h = (hi_in - lo_in) / (nt - 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        curv = y0 - 2 * y1 + y2
        tv = t[rows, j] + 0.5 * h * (y0 - y2) / curv
        inside = (j > 0) & (j < nt - 1) & np.isfinite(tv) & (curv > 0)
    tv = np.where(inside, np.clip(tv, lo_in, hi_in), t[rows, j])
    rv, av = exact_alpha(m, z, tv)
    gv, rqv, zqv = exact_gap_from_polar(spec, mis, theta, rv, av, z, normal)
    okv = inside & (rqv >= sm.r_form - 1e-9) & (np.abs(zqv) <= sm.half_face + 1e-9)
    best = np.where(okv, np.minimum(best, gv), best)
    return np.where(any_ok, best, np.inf)


def brute_force(spec: CouplingSpec, mis: float, theta: float, normal: bool, nz: int = 401,
                nt: int = 121) -> float:
    """Dense exact grid (``nz`` planes x ``nt`` heights between the exact ends of the
    active interval, with a parabolic step in ``t``), then golden-section search over
    ``z`` around the best plane to resolve corners of the active region."""
    m = hub_model(spec)
    z = np.linspace(-m.half_face, m.half_face, nz)
    g = _plane_min(spec, mis, theta, z, normal, nt)
    j = int(np.argmin(g))
    a, b = z[max(j - 1, 0)], z[min(j + 1, nz - 1)]
    best = float(g[j])
    ratio = (math.sqrt(5.0) - 1.0) / 2.0  # golden section: copes with inf past a corner
    x1, x2 = b - ratio * (b - a), a + ratio * (b - a)
    f1, f2 = (float(_plane_min(spec, mis, theta, x, normal, nt)[0]) for x in (x1, x2))
    while b - a > 1e-6:  # value error below slope * 1e-6 mm
        if f1 <= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - ratio * (b - a)
            f1 = float(_plane_min(spec, mis, theta, x1, normal, nt)[0])
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + ratio * (b - a)
            f2 = float(_plane_min(spec, mis, theta, x2, normal, nt)[0])
    return min(best, f1, f2)


def exact_gap_from_polar(spec: CouplingSpec,
                         mis: float, theta: float, r, a, z, normal: bool = False):
    """:func:`exact_gap` for hub points given in cylinder coordinates ``(r, a, z)``."""
    sm = sleeve_model(spec)
    p = np.stack(np.broadcast_arrays(r * np.cos(a), r * np.sin(a), z), axis=-1)
    q = p @ hub_to_sleeve(mis, theta).T
    rq = np.hypot(q[..., 0], q[..., 1])
    d = np.arctan2(q[..., 1], q[..., 0]) + sm.half_angle(rq)
    return (sm.r_base if normal else rq) * d, rq, q[..., 2]
