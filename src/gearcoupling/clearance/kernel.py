"""The clearance kernel: smallest gap of a hub flank to the sleeve, over the whole flank.

For a hub flank point in the sleeve frame at radius ``rq``, polar angle ``aq`` (about the
centre of the sleeve space it sits in) and axial position ``zq``, the sleeve surface at
that radius is the straight involute flank (``sm.r_form <= rq <= sm.r_fillet``), the root
fillet above it or the tip chamfer below it. Against the involute the gaps are exact:

- circumferential ``rq * (aq + sigma(rq)/2)`` (docs/conventions.md, Frames, Wei eq. 9),
- normal ``r_b * (aq + sigma(rq)/2)``: involutes of one base circle are parallel curves.

The hub flank (tooth 0, cw) is parametrised by ``(z, t)`` (see :mod:`.flank_table`); at
turning angle ``theta`` the point maps by ``P(theta)`` (:mod:`.pose`). The minimum over the
flank is found per plane ``z`` exactly over ``t`` (ends of the active interval, its
sleeve-edge crossings solved by secant steps to 1e-11 relative, and an interior minimum,
where the end slopes point inward, by secant steps on the slope), then over ``z`` from a
coarse grid of planes: parabolic steps bracketed by +-sqrt(tol / g''), a local parabola
for minima beside a kink, a corner step where the profile end switches from the form
circle to the sleeve tip edge, secant intersections for other corners and nested grids,
until the bracket cannot hide more than the tolerance. The active interval in ``t`` is
cut where the sleeve flank begins (tip chamfer edge) and at the sleeve face ends; the tip
chamfer itself recedes at 45° and never holds the minimum.

``contact_kind`` codes (:data:`KINDS`) name where the minimum lies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..arguments import GAP_TOLERANCE_MM, SWEEP_GRID
from ..errors import ArgumentError
from ..geometry import SleeveModel, inv, map_polar
from .fast import kernels
from .flank_table import FlankTable

KINDS = ("interior", "face end", "tip edge", "form edge", "sleeve tip edge",
         "sleeve root fillet", "sleeve face end", "no contact")
INTERIOR, FACE_END, TIP_EDGE, FORM_EDGE, SLEEVE_TIP, SLEEVE_FILLET, SLEEVE_FACE, NONE = range(8)
MEASURES = ("circumferential", "normal", "pitch_circumferential", "pitch_normal")
CIRC, NORMAL, PITCH_CIRC, PITCH_NORMAL = range(4)


@dataclass(frozen=True)
class Minimum:
    """Minima of one measure for a batch of poses (all arrays ``(n,)``).

    ``value_mm`` is ``inf`` where no point of the flank faces the sleeve flank (``kind``
    is ``"no contact"``); ``z_mm`` and ``r_mm`` are hub-frame flank coordinates of the
    minimum and ``rate`` the turning rate of the sleeve polar angle per unit hub turn there.
    """

    value_mm: NDArray[np.float64]
    z_mm: NDArray[np.float64]
    r_mm: NDArray[np.float64]
    t: NDArray[np.float64]
    kind: NDArray[np.int8]
    rate: NDArray[np.float64]


class _Sleeve:
    """Sleeve constants of the cw flank of space 0, for vectorised gaps."""

    def __init__(self, sm: SleeveModel):
        self.r_b = sm.r_base
        self.r_form = sm.r_form
        self.r_fillet = sm.r_fillet
        self.half_face = sm.half_face
        self.c0 = 0.5 * sm.space_width / sm.R + float(inv(sm.phi))
        self.rho = sm.fillet
        cx, cy = sm.fillet_centre
        self.cx, self.cy = cx, cy
        self.cn = math.hypot(cx, cy)
        self.gc = math.atan2(cy, cx)

    def delta(self, rq, aq):
        """Angular gap ``aq + sigma(rq)/2`` to the involute (its extension off the flank)."""
        # inv(arccos(r_b / rq)) = tan - angle, with tan = sqrt(rq^2 - r_b^2) / r_b
        # in place, the same operations in the same order (one pass less per temporary)
        acos = np.divide(self.r_b, rq)
        np.minimum(acos, 1.0, out=acos)
        np.arccos(acos, out=acos)
        tan = rq * rq
        tan -= self.r_b**2
        np.maximum(tan, 0.0, out=tan)
        np.sqrt(tan, out=tan)
        tan /= self.r_b
        tan -= acos
        d = aq + self.c0
        d -= tan
        return d

    def gaps(self, rq, aq):
        """``(circumferential, normal)`` gaps (mm) at sleeve radius ``rq``, polar angle
        ``aq``; above ``r_fillet`` against the root fillet."""
        circ, normal = self.involute_gaps(rq, aq)
        fil = rq > self.r_fillet
        if self.rho > 0 and np.any(fil):
            circ[fil], normal[fil] = self.fillet_gaps(rq[fil], aq[fil])
        return circ, normal

    def involute_gaps(self, rq, aq):
        """``(circumferential, normal)`` gaps to the involute (its extension off the flank)."""
        d = self.delta(rq, aq)
        circ = rq * d
        d *= self.r_b
        return circ, d

    def fillet_gaps(self, r, a):
        """``(circumferential, normal)`` gaps to the root fillet."""
        cosb = np.clip((r * r + self.cn**2 - self.rho**2) / (2 * r * self.cn), -1.0, 1.0)
        beta = self.gc - np.arccos(cosb)
        return r * (a - beta), self.rho - np.hypot(r * np.cos(a) - self.cx,
                                                   r * np.sin(a) - self.cy)

    def at_fillet_start(self, rq, aq):
        """Gaps at the start of the root fillet (``rq`` at ``r_fillet`` to 1e-11): the
        lower of those to the involute and to the fillet. Off the sleeve surface the two
        differ (deep interference), and which one a point on the edge got depended on the
        side its crossing converged from; the lower is the limit of the fillet part's
        minimum, so it belongs to the minimum over the active interval."""
        circ, normal = self.involute_gaps(rq, aq)
        if self.rho > 0:
            fc, fn = self.fillet_gaps(rq, aq)
            circ, normal = np.minimum(circ, fc), np.minimum(normal, fn)
        return circ, normal


def _map_cs(r, y, z, ci: float, si: float, ct, st):
    """:func:`~.pose.map_point_cs` of the flank point at radius ``r``, ``y`` (``x =
    sqrt(r^2 - y^2)``), in place: the same operations in the same order, so the same
    values, with fewer temporaries. ``r``, ``y`` carry the full shape; ``z``, ``ct``,
    ``st`` broadcast against them."""
    x = r * r
    x -= y * y
    np.sqrt(x, out=x)
    u = x * st  # y after Rz(theta)
    u += y * ct
    v = u * (ci - 1.0)  # its change by the tilt
    v -= z * si
    qx = v * st
    qx += x
    v *= ct
    v += y  # qy
    zq = u * si
    zq += z * ci
    rq = qx * qx
    rq += v * v
    np.sqrt(rq, out=rq)
    return rq, np.arctan2(v, qx), zq


class _Planes:
    """A batch of (plane z, turning angle theta) rows whose gaps are minimised over ``t``."""

    def __init__(self, table: FlankTable, sl: _Sleeve, mis: float, z, theta, planes=None):
        self.table, self.sl, self.mis = table, sl, mis
        self.z, self.theta = z, theta
        self.ci, self.si = math.cos(mis), math.sin(mis)
        self.ct, self.st = np.cos(theta), np.sin(theta)  # once per batch, not per call
        if planes is None:
            # coefficients along the first axis: (nt, n), contiguous rows for Clenshaw
            self.kz, self.lo, hi = table.plane_coefficients(z)
            self.span = hi - self.lo
            self.y_ends = None
        else:  # precomputed per plane: coefficients (nt, n), radii and y at t = 0 and 1
            self.kz, self.lo, self.span, self.y_ends = planes

    def at_end(self, end: int):
        """``(rq, aq, zq)`` at ``t = end`` (0 or 1) for all rows."""
        if self.y_ends is None:
            return self.at(np.full(self.z.shape, float(end)))
        r = self.lo + end * self.span
        y = self.y_ends[end]
        return _map_cs(r, y, self.z, self.ci, self.si, self.ct, self.st)

    def at(self, t, idx=None):
        """``(rq, aq, zq)`` at heights ``t`` (for the rows ``idx``, all when None); ``t``
        may carry leading axes, e.g. ``(2, len(idx))`` for two heights per row."""
        if idx is None:
            z, ct, st, kz, lo, sp = self.z, self.ct, self.st, self.kz, self.lo, self.span
        else:
            z, ct, st, kz = self.z[idx], self.ct[idx], self.st[idx], self.kz[:, idx]
            lo, sp = self.lo[idx], self.span[idx]
        r = lo + t * sp
        y = self.table.plane_y(kz, t)
        return _map_cs(r, y, z, self.ci, self.si, ct, st)

    def f(self, t, idx=None):
        """``(circumferential, normal)`` gaps at heights ``t``."""
        rq, aq, _ = self.at(t, idx)
        return self.sl.gaps(rq, aq)

    def cross(self, which: str, target: float, a, b, fa, fb, idx, rel: float = 1e-11):
        """``t`` in ``[a, b]`` where ``rq`` (or ``zq``) equals ``target``; ``fa``, ``fb``
        are the values minus target at the ends (opposite signs). Secant steps on the two
        latest points, kept inside the shrinking bracket (regula falsi when they leave it);
        ``rq`` is nearly linear in ``t``, so 3-4 steps reach 1e-11 relative."""
        x0, f0 = a, fa
        x1, f1 = b, fb
        tol = rel * (abs(target) + 1.0)
        t = a
        for _ in range(60):
            with np.errstate(divide="ignore", invalid="ignore"):
                t = x1 - f1 * (x1 - x0) / (f1 - f0)
            out = ~np.isfinite(t) | (t <= np.minimum(a, b)) | (t >= np.maximum(a, b))
            if np.any(out):
                rf = a - fa * (b - a) / (fb - fa)
                t = np.where(out, rf, t)
            rq, _, zq = self.at(t, idx)
            ft = (rq if which == "r" else zq) - target
            if np.all(np.abs(ft) <= tol):
                return t
            left = np.sign(ft) == np.sign(fa)
            a, fa = np.where(left, t, a), np.where(left, ft, fa)
            b, fb = np.where(left, b, t), np.where(left, fb, ft)
            x0, f0, x1, f1 = x1, f1, t, ft
        return t

    def active_interval(self, rel: float = 1e-11):
        """The active ``t`` interval of each row and what bounds it.

        Returns ``feasible, (t_lo, k_lo), (t_a, k_a), (t_hi, k_hi)``: ``[t_lo, t_a]`` faces
        the involute, ``[t_a, t_hi]`` the root fillet (empty unless the hub reaches it).
        """
        n = self.z.shape[0]
        sl = self.sl
        zeros, ones = np.zeros(n), np.ones(n)
        rq0, aq0, zq0 = self.at_end(0)
        rq1, aq1, zq1 = self.at_end(1)
        self.g0, self.g1 = np.stack(self.sl.gaps(rq0, aq0)), np.stack(self.sl.gaps(rq1, aq1))
        t_lo, k_lo = zeros.copy(), np.full(n, FORM_EDGE, np.int8)
        t_hi, k_hi = ones.copy(), np.full(n, TIP_EDGE, np.int8)
        feasible = rq1 > sl.r_form
        idx = np.flatnonzero(feasible & (rq0 < sl.r_form))
        if idx.size:
            t_lo[idx] = self.cross("r", sl.r_form, zeros[idx], ones[idx],
                                   rq0[idx] - sl.r_form, rq1[idx] - sl.r_form, idx, rel)
            k_lo[idx] = SLEEVE_TIP
        hf = sl.half_face
        for sign in (1.0, -1.0):  # sleeve face ends: sign * zq <= hf
            v0, v1 = sign * zq0 - hf, sign * zq1 - hf
            feasible &= ~((v0 > 0) & (v1 > 0))
            for cut_low, mask in ((True, (v0 > 0) & (v1 <= 0)), (False, (v1 > 0) & (v0 <= 0))):
                idx = np.flatnonzero(mask & feasible)
                if idx.size:
                    tc = self.cross("z", sign * hf, zeros[idx], ones[idx],
                                    sign * (v0[idx]), sign * (v1[idx]), idx)
                    if cut_low:
                        upd = tc > t_lo[idx]
                        t_lo[idx[upd]], k_lo[idx[upd]] = tc[upd], SLEEVE_FACE
                    else:
                        upd = tc < t_hi[idx]
                        t_hi[idx[upd]], k_hi[idx[upd]] = tc[upd], SLEEVE_FACE
        feasible &= t_lo <= t_hi
        t_a, k_a = t_hi.copy(), k_hi.copy()
        rqh = rq1.copy()
        cut = np.flatnonzero(t_hi != 1.0)
        if cut.size:
            rqh[cut] = self.at(t_hi[cut], cut)[0]
        idx = np.flatnonzero(feasible & (rqh > sl.r_fillet))
        if idx.size:
            rql, _, _ = self.at(t_lo[idx], idx)
            tf = t_lo[idx].copy()  # all of [t_lo, t_hi] above the fillet start: t_a = t_lo
            below = rql < sl.r_fillet  # else no crossing to solve (both ends above it)
            if np.any(below):
                ib = idx[below]
                tf[below] = self.cross("r", sl.r_fillet, t_lo[ib], t_hi[ib],
                                       rql[below] - sl.r_fillet, rqh[ib] - sl.r_fillet, ib)
            t_a[idx], k_a[idx] = tf, SLEEVE_FILLET
            k_hi[idx] = SLEEVE_FILLET
        return feasible, (t_lo, k_lo), (t_a, k_a), (t_hi, k_hi)

    def minimum_over_t(self, exact: bool = True, interior=True):
        """Minima over the active ``t`` interval of both gaps: ``V, T, K`` each ``(6, n)``:
        (circumferential, normal) over the interval, then at its lower end and at its
        upper end alone (branches whose minima over ``z`` are found apart).
        ``interior`` (bool, ``(n,)`` or ``(2, n)`` bool: per row, or per gap and row)
        selects what is searched inside the interval (profile-end branch rows want only
        the ends; a row of one measure only its own gap).
        ``exact=False`` (for the coarse search) solves the sleeve tip edge to 1e-7 only:
        values at real points, so never below the exact minimum. (Cutting the interior
        search short there misled the bracket: it must converge.)"""
        n = self.z.shape[0]
        feasible, (t_lo, k_lo), (t_a, k_a), (t_hi, k_hi) = self.active_interval(
            1e-11 if exact else 1e-7)
        fa = self._f_or(t_lo, 0.0, self.g0)
        fh = self._f_or(t_hi, 1.0, self.g1)
        want = np.broadcast_to(np.asarray(interior, dtype=bool), (2, n))
        fb = fh.copy()  # the upper end of [t_lo, t_a] (only the interior search uses it)
        fb_min = fh.copy()  # the minimum there: at the fillet start, :meth:`at_fillet_start`
        sub = np.flatnonzero(np.any(want, axis=0) & (t_a != t_hi))
        if sub.size:
            rq, aq, _ = self.at(t_a[sub], sub)
            fb[:, sub] = fb_min[:, sub] = np.stack(self.sl.gaps(rq, aq))
            edge = t_a[sub] > t_lo[sub]  # a crossing of r_fillet, not [t_lo, t_hi] above it
            fb[:, sub[edge]] = np.stack(self.sl.involute_gaps(rq[edge], aq[edge]))
            fb_min[:, sub[edge]] = np.stack(self.sl.at_fillet_start(rq[edge], aq[edge]))
        # rows not searched keep t = 0, f = inf: only their ends count
        TI, FI = self._interior(t_lo, t_a, fa, fb, feasible & want, iters=12)
        interior = np.full(n, INTERIOR, np.int8)
        cols = np.arange(n)
        V, T, K = [], [], []
        for mi in range(2):
            F = np.stack([fa[mi], fb_min[mi], fh[mi], FI[mi]])
            j = np.argmin(F, axis=0)
            V.append(np.where(feasible, F[j, cols], np.inf))
            T.append(np.stack([t_lo, t_a, t_hi, TI[mi]])[j, cols])
            K.append(np.where(feasible, np.stack([k_lo, k_a, k_hi, interior])[j, cols], NONE))
        # the lower and upper ends on their own: smooth in z, one minimum each
        for t_e, k_e, f_e in ((t_lo, k_lo, fa), (t_hi, k_hi, fh)):
            for mi in range(2):
                V.append(np.where(feasible, f_e[mi], np.inf))
                T.append(t_e)
                K.append(np.where(feasible, k_e, NONE))
        return np.array(V), np.array(T), np.array(K, dtype=np.int8)

    def _f_or(self, t, known_t: float, known):
        """Both gaps at ``t``, taken from ``known`` (at ``known_t``) where ``t`` equals it."""
        out = known.copy()
        idx = np.flatnonzero(t != known_t)
        if idx.size:
            out[:, idx] = np.stack(self.f(t[idx], idx))
        return out

    def _interior(self, t_lo, t_a, fa, fb, feasible, iters: int = 12):
        """Interior minima of both gaps on ``[t_lo, t_a]``: where the one-sided slopes at
        the ends point inward, the root of the slope (central differences) by secant steps
        kept inside the shrinking bracket, to 1e-7 in ``t``; ``feasible (2, n)``: the
        gaps and rows to search. Returns ``t, f`` each ``(2, n)`` (``inf`` where the
        minimum is at an end or not searched)."""
        n = t_lo.shape[0]
        T, F = np.zeros((2, n)), np.full((2, n), np.inf)
        d = 1e-6
        idx0 = np.flatnonzero(np.any(feasible, axis=0) & (t_a - t_lo > 8 * d))
        if idx0.size == 0:
            return T, F
        a0, b0 = t_lo[idx0], t_a[idx0]
        fab = np.stack(self.f(np.stack([a0 + d, b0 - d]), idx0))  # (2 gaps, 2 ends, m0)
        GA = (fab[:, 0] - fa[:, idx0]) / d
        GB = (fb[:, idx0] - fab[:, 1]) / d
        # both gaps' searches in one batch: row j searches gap mis[j] of plane idx[j]
        inner = (GA < 0) & (GB > 0) & feasible[:, idx0]  # (2, m0)
        mis, pos = np.nonzero(inner)
        if mis.size == 0:
            return T, F
        idx, a, b = idx0[pos], a0[pos], b0[pos]
        x0, g0, x1, g1 = a, GA[mis, pos], b, GB[mis, pos]
        res = self._slope_roots(idx, mis, a, b, x0, g0, x1, g1, iters, d)
        T[mis, idx] = res
        F[mis, idx] = np.stack(self.f(res, idx))[mis, np.arange(idx.size)]
        return T, F

    def _slope_roots(self, idx, mis, a, b, x0, g0, x1, g1, iters: int, d: float):
        """The secant search of :meth:`_interior` on gap ``mis[j]`` of row ``idx[j]``."""
        res = np.empty(idx.size)
        live = np.arange(idx.size)  # rows still iterating (positions in idx)
        for _ in range(iters):
            with np.errstate(divide="ignore", invalid="ignore"):
                x = x1 - g1 * (x1 - x0) / (g1 - g0)
            bad = ~np.isfinite(x) | (x <= a) | (x >= b)
            x = np.where(bad, 0.5 * (a + b), x)
            xc = np.clip(x, a + d, b - d)
            fx = np.stack(self.f(np.stack([xc + d, xc - d]), idx[live]))  # (2, 2, k)
            fx = fx[mis[live], :, np.arange(live.size)]  # (k, 2): this row's gap
            gx = (fx[:, 0] - fx[:, 1]) / (2 * d)
            right = gx > 0
            a, b = np.where(right, a, xc), np.where(right, xc, b)
            x0, g0, x1, g1 = x1, g1, xc, gx
            done = np.abs(x1 - x0) <= 1e-7  # value error ~ f'' dt^2: negligible
            res[live[done]] = x1[done]
            keep = ~done
            live, a, b, x0, g0, x1, g1 = (live[keep], a[keep], b[keep], x0[keep],
                                          g0[keep], x1[keep], g1[keep])
            if live.size == 0:
                break
        res[live] = x1
        return res

    def pitch_line(self, R: float):
        """Both gaps on the pitch circle ``r = R`` of each plane: ``V, T, K`` ``(2, n)``."""
        t = (R - self.lo) / self.span
        rq, aq, zq = self.at(np.clip(t, 0.0, 1.0))
        ok = (t >= 0) & (t <= 1) & (rq >= self.sl.r_form) & (np.abs(zq) <= self.sl.half_face)
        circ, normal = self.sl.gaps(rq, aq)
        V = np.where(ok, np.stack([circ, normal]), np.inf)
        K = np.where(ok, INTERIOR, NONE).astype(np.int8)
        return V, np.stack([t, t]), np.stack([K, K])


def _plane_minima(table, sl, mis, z, theta, R, planes=None, need=(True, True), exact=True,
                  interior=True):
    """Minima in the planes ``z`` of the four measures (:data:`MEASURES`) and of the two
    profile-end branches: ``V, T, K`` ``(8, n)``; ``need`` = (whole flank, pitch line)
    skips what is not needed (inf)."""
    p = _Planes(table, sl, mis, z, theta, planes)
    n = z.shape[0]
    V, T, K = np.full((8, n), np.inf), np.zeros((8, n)), np.full((8, n), NONE, np.int8)
    if need[0]:
        v6, t6, k6 = p.minimum_over_t(exact, interior)
        V[_WHOLE], T[_WHOLE], K[_WHOLE] = v6, t6, k6
    if need[1]:
        V[2:4], T[2:4], K[2:4] = p.pitch_line(R)
    return V, T, K


# rows of the 8 "virtual measures": the four MEASURES, then the circumferential and normal
# gaps at the lower end of the active interval and at its upper end, minimised apart
_WHOLE = [0, 1, 4, 5, 6, 7]
_FOLD = {0: (0, 4, 6), 1: (1, 5, 7), 2: (2,), 3: (3,)}


class _PlaneEvaluator:
    """Evaluates rows of the z search: each row is a (virtual measure, turning angle) pair
    (:data:`_FOLD`), evaluated in planes ``z`` by :func:`_plane_minima`.

    ``meas : (m,) int`` virtual measure and ``theta : (m,) float`` turning angle of each row.
    """

    def __init__(self, table: FlankTable, sl: _Sleeve, misalignment: float, pitch_radius: float,
                 meas, theta):
        self.table, self.sl, self.mis, self.R = table, sl, misalignment, pitch_radius
        self.meas, self.theta = meas, theta

    def __call__(self, z, rows):
        """Minima ``(value, t, kind)``, each ``(len(rows),)``, of each row's own measure in
        the planes ``z`` (whole-flank rows and pitch-line rows evaluated apart)."""
        m = self.meas[rows]
        out = np.empty(rows.size), np.empty(rows.size), np.empty(rows.size, np.int8)
        pitch = (m == 2) | (m == 3)
        # the interior search of a row's own gap only (profile-end branch rows: none)
        own = np.stack([m == 0, m == 1])
        for need, sel in (((True, False), ~pitch), ((False, True), pitch)):
            idx = np.flatnonzero(sel)
            if idx.size:
                Vr, Tr, Kr = _plane_minima(self.table, self.sl, self.mis, z[idx],
                                           self.theta[rows[idx]], self.R, need=need,
                                           interior=own[:, idx])
                c = np.arange(idx.size)
                for o, X in zip(out, (Vr, Tr, Kr), strict=True):
                    o[idx] = X[m[idx], c]
        return out

    def form_gap(self, z, rows):
        """``rq - r_form`` at the hub form circle (``t = 0``) in the planes ``z``: where the
        active interval's lower end switches to the sleeve tip edge."""
        planes = _Planes(self.table, self.sl, self.mis, z, self.theta[rows])
        return planes.at_end(0)[0] - self.sl.r_form


def coarse_grid(table: FlankTable, sl: _Sleeve, misalignment: float, theta, pitch_radius: float,
                grid: int, wanted: list[int]):
    """Step 1: minima over ``t`` in ``grid`` planes spanning the face.

    Returns ``zg (grid,)`` and ``v, t, k`` each ``(len(wanted) * n, grid)``: rows are
    (virtual measure, theta) pairs, measure-major.
    """
    n = theta.size
    zg = np.linspace(-table.half_face, table.half_face, grid)
    kz_g, lo_g, hi_g = table.plane_coefficients(zg)
    tile = np.tile(np.arange(grid), n)
    y_ends = (table.plane_y(kz_g, np.zeros(grid))[tile], table.plane_y(kz_g, np.ones(grid))[tile])
    planes = (kz_g[:, tile], lo_g[tile], (hi_g - lo_g)[tile], y_ends)
    need = (any(vm not in (2, 3) for vm in wanted), any(vm in (2, 3) for vm in wanted))
    V, T, K = _plane_minima(table, sl, misalignment, zg[tile], np.repeat(theta, grid),
                            pitch_radius, planes, need=need, exact=False)
    W = len(wanted)
    return zg, *(X[wanted].reshape(W * n, grid) for X in (V, T, K))


def second_minima(v):
    """Step 2: the best coarse plane of each row, and a second coarse local minimum nearly
    as low (two nearly equal minima, e.g. tip edge and form circle on a swing tooth), which
    is refined too, as an extra row.

    ``v : (m, grid)``. Returns ``j (m,)`` best columns, ``j2 (m,)`` the second ones and
    ``second (m,) bool`` where that second minimum is refined.
    """
    m = v.shape[0]
    rows = np.arange(m)
    j = np.argmin(v, axis=1)
    pad = np.full((m, 1), np.inf)
    left, right = np.hstack([pad, v[:, :-1]]), np.hstack([v[:, 1:], pad])
    cols = np.arange(v.shape[1])[None, :]
    local = (v <= left) & (v <= right) & (np.abs(cols - j[:, None]) > 1) & np.isfinite(v)
    v2 = np.where(local, v, np.inf)
    j2 = np.argmin(v2, axis=1)
    vmin = v[rows, j]
    finite_max = np.max(np.where(np.isfinite(v), v, -np.inf), axis=1)
    v2min = v2[rows, j2]
    second = np.isfinite(v2min)  # then vmin is finite too
    second[second] = (v2min[second] - vmin[second]
                      <= 0.25 * (finite_max[second] - vmin[second]))
    return j, j2, second


class ZSearch:
    """Step 3: the search over ``z`` of every row, from its best coarse plane.

    State per row (all ``(m,)``): the best point ``best_v, best_z, best_t, best_k``
    (``exact_val``: its value was evaluated, not a coarse upper bound) and its bracket
    ``[a_z, b_z]`` with values ``a_v, b_v``. Each step evaluates a few planes per row
    (``evaluate(z, rows)``, a :class:`_PlaneEvaluator`) and keeps what improves; the steps
    can be run and profiled alone.
    """

    def __init__(self, evaluate: _PlaneEvaluator, zg, v, t, k, j, tolerance_mm: float,
                 half_face: float):
        rows = np.arange(v.shape[0])
        grid = zg.size
        self.evaluate, self.tol, self.hf = evaluate, tolerance_mm, half_face
        self.best_v, self.best_z = v[rows, j], zg[j]
        self.best_t, self.best_k = t[rows, j], k[rows, j]
        self.exact_val = np.zeros(rows.size, dtype=bool)  # coarse values are upper bounds
        jl, jr = np.maximum(j - 1, 0), np.minimum(j + 1, grid - 1)
        self.a_z, self.a_v = zg[jl], v[rows, jl]
        self.b_z, self.b_v = zg[jr], v[rows, jr]

    def take(self, rows, zz, vv, tt, kk):
        """Keep the best of the evaluated points ``(len(rows), m)`` where it improves."""
        r = np.arange(rows.size)
        jj = np.argmin(vv, axis=1)
        better = vv[r, jj] < self.best_v[rows]
        upd = rows[better]
        self.best_v[upd], self.best_z[upd] = vv[r, jj][better], zz[r, jj][better]
        self.best_t[upd], self.best_k[upd] = tt[r, jj][better], kk[r, jj][better]
        self.exact_val[upd] = True
        return jj, better

    def triple(self, rows, zc, eps):
        """Evaluate ``zc - eps, zc, zc + eps``; where the middle is lowest it brackets."""
        zz3 = np.stack([zc - eps, zc, zc + eps], axis=1)
        out3 = self.evaluate(zz3.ravel(), np.repeat(rows, 3))
        v3, t3, k3 = (X.reshape(rows.size, 3) for X in out3)
        jj, better = self.take(rows, zz3, v3, t3, k3)
        mid = (jj == 1) & better
        sel = rows[mid]
        self.a_z[sel], self.a_v[sel] = zz3[mid, 0], v3[mid, 0]
        self.b_z[sel], self.b_v[sel] = zz3[mid, 2], v3[mid, 2]

    def excess(self, rows):
        """How much lower than the best a minimum inside each row's bracket could be."""
        return np.maximum(self.a_v[rows], self.b_v[rows]) - self.best_v[rows]

    def coarse_parabola(self, active):
        """Smooth minima: step to the vertex of the coarse parabola and bracket it by
        ``+-delta``, ``delta = sqrt(tol / g'')``, so that a bracket around the true minimum
        closes at once."""
        a_z, a_v, b_z, b_v, best_z, best_v = (self.a_z, self.a_v, self.b_z, self.b_v,
                                              self.best_z, self.best_v)
        par = active[(a_z[active] < best_z[active]) & (best_z[active] < b_z[active])
                     & np.isfinite(a_v[active]) & np.isfinite(b_v[active])]
        if par.size == 0:
            return
        h = b_z[par] - best_z[par]  # uniform coarse grid: equal spacing on both sides
        curv = (a_v[par] + b_v[par] - 2.0 * best_v[par]) / (h * h)
        ok = curv > 0
        par, h, curv = par[ok], h[ok], curv[ok]
        z1 = best_z[par] - 0.5 * (b_v[par] - a_v[par]) / (h * curv)
        delta = np.minimum(np.sqrt(self.tol / curv), 0.25 * h)
        z1 = np.clip(z1, a_z[par] + delta, b_z[par] - delta)
        self.triple(par, z1, delta)

    def parabola_step(self, rows, allz, allv, jb):
        """Smooth minima: vertex of the parabola through the best point and its neighbours,
        bracketed by ``+-sqrt(tol / g'')``."""
        last = allz.shape[1] - 1
        ok = (jb >= 1) & (jb <= last - 1)
        rows, zz, vv, j = rows[ok], allz[ok], allv[ok], jb[ok]
        r = np.arange(rows.size)
        x0, x1, x2 = zz[r, j - 1], zz[r, j], zz[r, j + 1]
        y0, y1, y2 = vv[r, j - 1], vv[r, j], vv[r, j + 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            d01, d12 = (y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1)
            curv = 2.0 * (d12 - d01) / (x2 - x0)
            zp = x1 - (d01 * (x2 - x1) + d12 * (x1 - x0)) / (curv * (x2 - x0))
        good = np.isfinite(zp) & (curv > 0) & (zp > x0) & (zp < x2)
        if not np.any(good):
            return
        eps = np.sqrt(self.tol / curv[good])
        zc = zp[good]
        eps = np.clip(eps, 1e-12 * self.hf, 0.25 * np.minimum(zc - x0[good], x2[good] - zc))
        self.triple(rows[good], zc, eps)

    def v_step(self, rows, allz, allv, jb):
        """Corner minima (the active interval's end switches, e.g. from the form circle to
        the sleeve tip edge): intersect the secants of the two branches either side of the
        best point and bracket the intersection by ``+-eps``, ``eps = tol / slope``."""
        last = allz.shape[1] - 1
        ok = (jb >= 2) & (jb <= last - 2)
        if not np.any(ok):
            return
        rows, zz, vv, j = rows[ok], allz[ok], allv[ok], jb[ok]
        r = np.arange(rows.size)
        z0, z1, z2, z3 = zz[r, j - 2], zz[r, j - 1], zz[r, j + 1], zz[r, j + 2]
        v0, v1, v2, v3 = vv[r, j - 2], vv[r, j - 1], vv[r, j + 1], vv[r, j + 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            sl = (v1 - v0) / (z1 - z0)
            sr = (v3 - v2) / (z3 - z2)
            zk = (v2 - v1 + sl * z1 - sr * z2) / (sl - sr)
        good = (sl < 0) & (sr > 0) & np.isfinite(zk) & (zk > z1) & (zk < z2)
        if not np.any(good):
            return
        rows, zk = rows[good], zk[good]
        eps = 0.5 * self.tol / np.maximum(-sl[good], sr[good])
        eps = np.clip(eps, 1e-12 * self.hf, 0.25 * np.minimum(zk - z1[good], z2[good] - zk))
        self.triple(rows, zk, eps)

    def corner_step(self, rows):
        """Corner minima where the active interval's lower end switches from the hub form
        circle to the sleeve tip edge: solve ``rq(z, t=0) = r_form`` in the bracket
        (secant) and bracket the corner by ``+-eps``, ``eps = tol / (2 slope)``."""
        meas = self.evaluate.meas
        rows = rows[(meas[rows] != 2) & (meas[rows] != 3)]
        if rows.size == 0:
            return
        g = self.evaluate.form_gap
        za, zb = self.a_z[rows].copy(), self.b_z[rows].copy()
        ga, gb = g(za, rows), g(zb, rows)
        ok = np.sign(ga) * np.sign(gb) < 0
        if not np.any(ok):
            return
        rows, za, zb, ga, gb = rows[ok], za[ok], zb[ok], ga[ok], gb[ok]
        z0, g0, z1, g1 = za, ga, zb, gb
        r_form = self.evaluate.sl.r_form
        for _ in range(30):
            with np.errstate(divide="ignore", invalid="ignore"):
                zc = z1 - g1 * (z1 - z0) / (g1 - g0)
            zc = np.where(np.isfinite(zc), np.clip(zc, za, zb), 0.5 * (za + zb))
            gc_ = g(zc, rows)
            z0, g0, z1, g1 = z1, g1, zc, gc_
            if np.all(np.abs(gc_) <= 1e-11 * r_form):
                break
        hf = self.hf
        w_l = np.maximum(self.best_z[rows] - self.a_z[rows], 1e-12 * hf)
        w_r = np.maximum(self.b_z[rows] - self.best_z[rows], 1e-12 * hf)
        slope = np.maximum(np.abs(self.a_v[rows] - self.best_v[rows]) / w_l,
                           np.abs(self.b_v[rows] - self.best_v[rows]) / w_r)
        eps = 0.5 * self.tol / np.maximum(slope, 1e-12)
        eps = np.clip(eps, 1e-12 * hf, 0.25 * np.minimum(zc - self.a_z[rows],
                                                         self.b_z[rows] - zc))
        good = eps > 0
        if np.any(good):
            self.triple(rows[good], zc[good], eps[good])

    def local_newton(self, rows):
        """Smooth minima next to a kink that spoiled the coarse parabola: a parabola from
        the best point and two close neighbours (+-1e-3 of the half face), then a triple
        around its vertex, ``+-sqrt(tol / g'')``."""
        if rows.size == 0:
            return
        a_z, b_z, best_z = self.a_z, self.b_z, self.best_z
        h = np.minimum(1e-3 * self.hf, 0.25 * np.minimum(best_z[rows] - a_z[rows],
                                                         b_z[rows] - best_z[rows]))
        ok = h > 1e-9 * self.hf
        rows, h = rows[ok], h[ok]
        if rows.size == 0:
            return
        x1 = best_z[rows]
        y1 = self.best_v[rows]
        zz = np.stack([x1 - h, x1 + h], axis=1)
        out = self.evaluate(zz.ravel(), np.repeat(rows, 2))
        v2, t2, k2 = (X.reshape(rows.size, 2) for X in out)
        y0, y2 = v2[:, 0], v2[:, 1]
        self.take(rows, zz, v2, t2, k2)
        with np.errstate(divide="ignore", invalid="ignore"):
            curv = (y0 + y2 - 2.0 * y1) / (h * h)
            zp = x1 - 0.5 * (y2 - y0) / (h * curv)
        good = np.isfinite(zp) & (curv > 0) & (zp > a_z[rows]) & (zp < b_z[rows])
        if not np.any(good):
            return
        rows, zp, curv = rows[good], zp[good], curv[good]
        eps = np.sqrt(self.tol / curv)
        eps = np.clip(eps, 1e-12 * self.hf, 0.25 * np.minimum(zp - a_z[rows], b_z[rows] - zp))
        self.triple(rows, zp, eps)

    def nested_grids(self, active, max_levels: int, inner: int = 4):
        """Nested grids of ``inner`` planes in each bracket, with a corner and a parabola
        step at each level, until the bracket cannot hide more than the tolerance (the
        first level first tries :meth:`local_newton` and :meth:`corner_step`)."""
        first = True
        frac = np.arange(1, inner + 1) / (inner + 1)
        for _ in range(max_levels):
            if active.size == 0:
                break
            width = self.b_z[active] - self.a_z[active]
            active = active[(self.excess(active) > self.tol) & (width > 1e-12 * self.hf)]
            if active.size == 0:
                break
            if first:
                first = False
                self.local_newton(active)
                active = active[self.excess(active) > self.tol]
                self.corner_step(active)
                active = active[self.excess(active) > self.tol]
                if active.size == 0:
                    break
            m = active.size
            a_z, b_z = self.a_z, self.b_z
            zz = a_z[active, None] + frac[None, :] * (b_z - a_z)[active, None]
            out = self.evaluate(zz.ravel(), np.repeat(active, inner))
            v2, t2, k2 = (X.reshape(m, inner) for X in out)
            self.take(active, zz, v2, t2, k2)
            allz = np.concatenate([a_z[active, None], zz, b_z[active, None]], axis=1)
            allv = np.concatenate([self.a_v[active, None], v2, self.b_v[active, None]], axis=1)
            r2 = np.arange(m)
            jb = np.argmin(allv, axis=1)
            jl2, jr2 = np.maximum(jb - 1, 0), np.minimum(jb + 1, inner + 1)
            self.a_z[active], self.a_v[active] = allz[r2, jl2], allv[r2, jl2]
            self.b_z[active], self.b_v[active] = allz[r2, jr2], allv[r2, jr2]
            self.v_step(active, allz, allv, jb)
            self.parabola_step(active, allz, allv, jb)

    def final_parabola(self):
        """A last parabolic step through each bracket (smooth minima)."""
        a_z, best_z, b_z = self.a_z, self.best_z, self.b_z
        fin = np.flatnonzero(np.isfinite(self.best_v) & np.isfinite(self.a_v)
                             & np.isfinite(self.b_v) & (a_z < best_z) & (best_z < b_z))
        if fin.size == 0:
            return
        x0, x1, x2 = a_z[fin], best_z[fin], b_z[fin]
        y0, y1, y2 = self.a_v[fin], self.best_v[fin], self.b_v[fin]
        num = (x1 - x0) ** 2 * (y1 - y2) - (x1 - x2) ** 2 * (y1 - y0)
        den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0)
        with np.errstate(divide="ignore", invalid="ignore"):
            zp = x1 - 0.5 * num / den
        good = np.isfinite(zp) & (zp > x0) & (zp < x2)
        fin, zp = fin[good], zp[good]
        if fin.size:
            out = self.evaluate(zp, fin)
            self.take(fin, zp[:, None], *(X[:, None] for X in out))

    def settle(self):
        """Minima that crept to a face end sit on it (snapped: the value moves by slope *
        1e-8 hf); the reported minimum is evaluated exactly where it lies (coarse values
        are upper bounds; a refined value is kept where lower)."""
        hf = self.hf
        near_end = np.isfinite(self.best_v) & (np.abs(self.best_z) >= hf * (1.0 - 1e-8))
        self.best_z = np.where(near_end, np.sign(self.best_z) * hf, self.best_z)
        self.exact_val &= ~near_end
        ex = np.flatnonzero(np.isfinite(self.best_v) & ~self.exact_val)
        if ex.size:
            ve, te, ke = self.evaluate(self.best_z[ex], ex)
            use = (ve <= self.best_v[ex] + 1e-7 * self.tol) | near_end[ex]
            self.best_v[ex] = np.where(use, ve, self.best_v[ex])
            self.best_t[ex] = np.where(use, te, self.best_t[ex])
            self.best_k[ex] = np.where(use, ke, self.best_k[ex])

    def run(self, max_levels: int):
        """All steps, in order."""
        active = np.flatnonzero(np.isfinite(self.best_v))
        self.coarse_parabola(active)
        self.nested_grids(active, max_levels)
        self.final_parabola()
        self.settle()
        return self


def minimise(table: FlankTable, sm: SleeveModel, misalignment: float, theta, *,
             pitch_radius: float, tolerance_mm: float = GAP_TOLERANCE_MM,
             grid: int = SWEEP_GRID, max_levels: int = 40,
             measures: tuple[str, ...] = MEASURES) -> dict[str, Minimum]:
    """Minimum gaps of tooth 0's cw flank to space 0 at turning angles ``theta``.

    Steps: :func:`coarse_grid` (minima over ``t`` in ``grid`` planes), :func:`second_minima`
    (a second coarse minimum becomes an extra row), :class:`ZSearch` (refinement over
    ``z``), then each measure folds its branches (:data:`_FOLD`). The compiled kernel
    (:mod:`.fast`, numba) takes the same steps one turning angle at a time; without
    numba, or with ``GEARCOUPLING_NUMBA=0``, they run here in numpy (docs/sweep-speed.md).

    Parameters
    ----------
    table : FlankTable
        The hub flank.
    sm : SleeveModel
    misalignment : float
        Tilt ``i`` (radians).
    theta : (n,) float
        Turning angles (radians).
    pitch_radius : float
        Radius of the pitch line (``R``).
    tolerance_mm : float
        Stop refining a minimum when its bracket cannot hide a lower value by more than this
        (and the flank table error is below it).
    grid : int
        Coarse planes over the face width (>= 3); more finds narrow minima more surely.
    measures : tuple of str
        Which of :data:`MEASURES` to find (the others are not computed: the design
        searches want only ``normal``, a third of the rows).

    Returns
    -------
    dict of measure name -> Minimum
        For each of ``measures``.
    """
    if grid < 3:
        raise ArgumentError("grid", grid, "at least 3 planes")
    if not tolerance_mm > 0:
        raise ArgumentError("tolerance_mm", tolerance_mm, "must be > 0 mm")
    unknown = set(measures) - set(MEASURES)
    if unknown or not measures:
        raise ArgumentError("measures", measures, f"must be among {MEASURES}")
    theta = np.asarray(theta, dtype=float).ravel()
    n = theta.size
    # the virtual measures (rows of _plane_minima) the requested measures fold from
    wanted = sorted({vm for m in measures for vm in _FOLD[MEASURES.index(m)]})
    sl = _Sleeve(sm)
    compiled = kernels()
    if compiled is not None and table.y.shape[1] <= compiled.MAX_NZ:
        tab, ws = _compiled_arrays(compiled, table, sl, misalignment, pitch_radius,
                                   tolerance_mm, grid)
        out = np.empty((6, len(measures), n))
        compiled.minimise_rows(tab, ws, np.linspace(-table.half_face, table.half_face, grid),
                               theta, np.array(wanted, np.int64),
                               np.array([MEASURES.index(m) for m in measures], np.int64),
                               max_levels, out)
        v, z, r, t, k, rate = out
        return {m: Minimum(v[j], z[j], r[j], t[j], k[j].astype(np.int8), rate[j])
                for j, m in enumerate(measures)}
    best_v, best_z, best_t, best_k = _numpy_minima(table, sl, misalignment, theta, pitch_radius,
                                                   tolerance_mm, grid, max_levels, wanted)
    th_of = np.tile(np.arange(n), len(wanted))
    return _fold(table, misalignment, theta, th_of, wanted, measures, best_v, best_z, best_t,
                 best_k)


def _numpy_minima(table, sl, misalignment, theta, pitch_radius, tolerance_mm, grid,
                  max_levels, wanted):
    """Steps 1-3 in numpy, all rows of a step at once: ``best_v, best_z, best_t, best_k``
    each ``(len(wanted) * n,)``, measure-major."""
    n = theta.size
    zg, v, t, k = coarse_grid(table, sl, misalignment, theta, pitch_radius, grid, wanted)
    j, j2, second = second_minima(v)
    R = v.shape[0]  # rows: (virtual measure, theta) pairs, then the extra rows
    origin = np.concatenate([np.arange(R), np.flatnonzero(second)])
    meas = np.repeat(np.array(wanted), n)[origin]
    th_of = np.tile(np.arange(n), len(wanted))[origin]
    evaluate = _PlaneEvaluator(table, sl, misalignment, pitch_radius, meas, theta[th_of])
    s = ZSearch(evaluate, zg, v[origin], t[origin], k[origin],
                np.concatenate([j, j2[second]]), tolerance_mm, table.half_face).run(max_levels)
    best_v, best_z, best_t, best_k = s.best_v, s.best_z, s.best_t, s.best_k
    # each row keeps the better of its own and its extra row's minimum
    ex_rows = np.arange(R, origin.size)
    won = best_v[ex_rows] < best_v[origin[ex_rows]]
    dst, src = origin[ex_rows][won], ex_rows[won]
    best_v[dst], best_z[dst], best_t[dst], best_k[dst] = (best_v[src], best_z[src],
                                                          best_t[src], best_k[src])
    return best_v[:R], best_z[:R], best_t[:R], best_k[:R]


def _compiled_arrays(compiled, table: FlankTable, sl: _Sleeve, misalignment: float,
                     pitch_radius: float, tolerance_mm: float, grid: int):
    """``tab`` and ``ws`` of the compiled kernel (:mod:`._compiled`): the constants in the
    order of its indices (``CI, SI, RB, ...``), the table's edges and plane matrices; the
    work space."""
    mats = table._plane_matrices  # (pieces, nt + 1, nz)
    pieces, rows, nz = mats.shape
    consts = [math.cos(misalignment), math.sin(misalignment), sl.r_b, sl.c0, sl.r_fillet,
              float(sl.rho), sl.cn, sl.gc, sl.cx, sl.cy, sl.r_form, sl.half_face,
              table.half_face, pitch_radius, tolerance_mm, table.tip_radius,
              float(table.tip_kind != "cylinder"), float(table._power is not None),
              rows - 1, nz, pieces]
    tab = np.concatenate([consts, table.edges, mats.ravel()])
    return tab, np.empty(compiled.workspace_size(grid, rows - 1))


def _fold(table, misalignment, theta, th_of, wanted, measures, best_v, best_z, best_t,
          best_k) -> dict[str, Minimum]:
    """Step 4: each measure's minimum over its branches (:data:`_FOLD`), with the face-end
    kind, radius and turning rate at it."""
    n = theta.size
    hf = table.half_face
    at_end = (np.abs(np.abs(best_z) - hf) <= 1e-12 * hf) & (best_k != NONE)
    best_k = np.where(at_end, FACE_END, best_k).astype(np.int8)
    lo, hi = table.radii(best_z)
    r = lo + best_t * (hi - lo)
    rate = turning_rate(table, misalignment, best_z, best_t, theta[th_of])
    pos = {vm: j for j, vm in enumerate(wanted)}
    result = {}
    for name in measures:
        fold = [pos[vm] for vm in _FOLD[MEASURES.index(name)]]
        rows = np.array(fold)[:, None] * n + np.arange(n)[None, :]  # (branches, n)
        jb = np.argmin(best_v[rows], axis=0)
        sel = rows[jb, np.arange(n)]
        result[name] = Minimum(best_v[sel], best_z[sel], r[sel], best_t[sel], best_k[sel],
                               rate[sel])
    return result


def turning_rate(table: FlankTable, misalignment: float, z, t, theta):
    """Rate of change of the sleeve polar angle of a hub point per unit hub turn.

    Turning the hub by ``d`` about its own (tilted) axis ``k_h`` moves the point ``q`` by
    ``d * k_h x q``; the polar angle about the sleeve axis changes at
    ``(|q|^2 cos i - (q . k_h) zq) / rq^2``: 1 when aligned.
    """
    r, alpha = table.evaluate(z, t)
    rq, aq, zq = map_polar(r, alpha, z, misalignment, theta)
    # hub axis in space 0's frame: P(theta) e_z = Rz(-theta) (0, -sin i, cos i)
    si, ci = math.sin(misalignment), math.cos(misalignment)
    kx, ky = -si * np.sin(theta), -si * np.cos(theta)
    qk = rq * np.cos(aq) * kx + rq * np.sin(aq) * ky + zq * ci
    return ((rq * rq + zq * zq) * ci - qk * zq) / (rq * rq)
