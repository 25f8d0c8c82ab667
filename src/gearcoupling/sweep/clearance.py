"""The clearance kernel: smallest gap of a hub flank to the sleeve, over the whole flank.

For a hub flank point in the sleeve frame at radius ``rq``, polar angle ``aq`` (about the
centre of the sleeve space it sits in) and axial position ``zq``, the sleeve surface at
that radius is the straight involute flank (``sm.r_form <= rq <= sm.r_fillet``), the root
fillet above it or the tip chamfer below it. Against the involute the gaps are exact:

- circumferential ``rq * (aq + sigma(rq)/2)`` (DESIGN.md §2, Wei eq. 9),
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

from ..errors import ArgumentError
from ..geometry.involute import inv
from ..geometry.sleeve import SleeveModel
from .flank_table import FlankTable
from .pose import map_point_cs, map_polar

KINDS = ("interior", "face end", "tip edge", "form edge", "sleeve tip edge",
         "sleeve root fillet", "sleeve face end", "no contact")
INTERIOR, FACE_END, TIP_EDGE, FORM_EDGE, SLEEVE_TIP, SLEEVE_FILLET, SLEEVE_FACE, NONE = range(8)
MEASURES = ("circumferential", "normal", "pitch_circumferential", "pitch_normal")
CIRC, NORMAL, PITCH_CIRC, PITCH_NORMAL = range(4)
DEFAULT_TOLERANCE_MM = 1e-7
DEFAULT_GRID = 17  # coarse planes over the face width


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
        x = np.minimum(self.r_b / rq, 1.0)
        return aq + self.c0 - (np.sqrt(np.maximum(rq * rq - self.r_b**2, 0.0)) / self.r_b
                               - np.arccos(x))

    def gaps(self, rq, aq):
        """``(circumferential, normal)`` gaps (mm) at sleeve radius ``rq``, polar angle
        ``aq``; above ``r_fillet`` against the root fillet."""
        d = self.delta(rq, aq)
        circ, normal = rq * d, self.r_b * d
        fil = rq > self.r_fillet
        if self.rho > 0 and np.any(fil):
            r, a = rq[fil], aq[fil]
            cosb = np.clip((r * r + self.cn**2 - self.rho**2) / (2 * r * self.cn), -1.0, 1.0)
            beta = self.gc - np.arccos(cosb)
            circ[fil] = r * (a - beta)
            normal[fil] = self.rho - np.hypot(r * np.cos(a) - self.cx, r * np.sin(a) - self.cy)
        return circ, normal


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
        return map_point_cs(np.sqrt(r * r - y * y), y, self.z, self.ci, self.si, self.ct,
                            self.st)

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
        return map_point_cs(np.sqrt(r * r - y * y), y, z, self.ci, self.si, ct, st)

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
        ``interior`` (bool or ``(n,)`` bool) selects the rows searched inside the interval
        (the others, profile-end branch rows, want only the ends).
        ``exact=False`` (for the coarse search) solves the sleeve tip edge to 1e-7 only:
        values at real points, so never below the exact minimum. (Cutting the interior
        search short there misled the bracket: it must converge.)"""
        n = self.z.shape[0]
        feasible, (t_lo, k_lo), (t_a, k_a), (t_hi, k_hi) = self.active_interval(
            1e-11 if exact else 1e-7)
        fa = self._f_or(t_lo, 0.0, self.g0)
        fh = self._f_or(t_hi, 1.0, self.g1)
        want = np.broadcast_to(np.asarray(interior, dtype=bool), (n,))
        fb = fh.copy()  # the upper end of [t_lo, t_a] (only the interior search uses it)
        sub = np.flatnonzero(want & (t_a != t_hi))
        if sub.size:
            fb[:, sub] = np.stack(self.f(t_a[sub], sub))
        # rows not searched keep t = 0, f = inf: only their ends count
        TI, FI = self._interior(t_lo, t_a, fa, fb, feasible & want, iters=12)
        interior = np.full(n, INTERIOR, np.int8)
        cols = np.arange(n)
        V, T, K = [], [], []
        for mi in range(2):
            F = np.stack([fa[mi], fb[mi], fh[mi], FI[mi]])
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
        kept inside the shrinking bracket, to 1e-7 in ``t``. Returns ``t, f`` each
        ``(2, n)`` (``inf`` where the minimum is at an end)."""
        n = t_lo.shape[0]
        T, F = np.zeros((2, n)), np.full((2, n), np.inf)
        d = 1e-6
        idx0 = np.flatnonzero(feasible & (t_a - t_lo > 8 * d))
        if idx0.size == 0:
            return T, F
        a0, b0 = t_lo[idx0], t_a[idx0]
        fab = np.stack(self.f(np.stack([a0 + d, b0 - d]), idx0))  # (2 gaps, 2 ends, m0)
        GA = (fab[:, 0] - fa[:, idx0]) / d
        GB = (fb[:, idx0] - fab[:, 1]) / d
        # both gaps' searches in one batch: row j searches gap mis[j] of plane idx[j]
        inner = (GA < 0) & (GB > 0)  # (2, m0)
        mis, pos = np.nonzero(inner)
        if mis.size == 0:
            return T, F
        idx, a, b = idx0[pos], a0[pos], b0[pos]
        x0, g0, x1, g1 = a, GA[mis, pos], b, GB[mis, pos]
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
        T[mis, idx] = res
        F[mis, idx] = np.stack(self.f(res, idx))[mis, np.arange(idx.size)]
        return T, F

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


def minimise(table: FlankTable, sm: SleeveModel, misalignment: float, theta, *,
             pitch_radius: float, tolerance_mm: float = DEFAULT_TOLERANCE_MM,
             grid: int = DEFAULT_GRID, max_levels: int = 40,
             measures: tuple[str, ...] = MEASURES) -> dict[str, Minimum]:
    """Minimum gaps of tooth 0's cw flank to space 0 at turning angles ``theta``.

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
        raise ArgumentError(f"grid must be at least 3 planes, got {grid}")
    if not tolerance_mm > 0:
        raise ArgumentError(f"tolerance_mm must be > 0, got {tolerance_mm!r}")
    unknown = set(measures) - set(MEASURES)
    if unknown or not measures:
        raise ArgumentError(f"measures must be among {MEASURES}, got {measures!r}")
    theta = np.asarray(theta, dtype=float).ravel()
    n = theta.size
    # the virtual measures (rows of _plane_minima) the requested measures fold from
    wanted = sorted({vm for m in measures for vm in _FOLD[MEASURES.index(m)]})
    pos = {vm: j for j, vm in enumerate(wanted)}
    W = len(wanted)
    sl = _Sleeve(sm)
    hf = table.half_face
    zg = np.linspace(-hf, hf, grid)
    kz_g, lo_g, hi_g = table.plane_coefficients(zg)
    tile = np.tile(np.arange(grid), n)
    y_ends = (table.plane_y(kz_g, np.zeros(grid))[tile], table.plane_y(kz_g, np.ones(grid))[tile])
    planes = (kz_g[:, tile], lo_g[tile], (hi_g - lo_g)[tile], y_ends)
    need = (any(vm not in (2, 3) for vm in wanted), any(vm in (2, 3) for vm in wanted))
    V, T, K = _plane_minima(table, sl, misalignment, zg[tile], np.repeat(theta, grid),
                            pitch_radius, planes, need=need, exact=False)
    # rows = (virtual measure, theta) pairs
    meas = np.repeat(np.array(wanted), n)
    th_of = np.tile(np.arange(n), W)
    v, t, k = (X[wanted].reshape(W * n, grid) for X in (V, T, K))
    rows_all = np.arange(W * n)

    def evaluate(z, rows):
        """Minima of each row's own measure in the planes ``z`` (whole-flank rows and
        pitch-line rows evaluated apart)."""
        m = meas[rows]
        out = np.empty(rows.size), np.empty(rows.size), np.empty(rows.size, np.int8)
        pitch = (m == 2) | (m == 3)
        ends = m >= 4  # profile-end branch rows: no interior search
        for need, sel in (((True, False), ~pitch), ((False, True), pitch)):
            idx = np.flatnonzero(sel)
            if idx.size:
                Vr, Tr, Kr = _plane_minima(table, sl, misalignment, z[idx],
                                           theta[th_of[rows[idx]]], pitch_radius, need=need,
                                           interior=~ends[idx])
                c = np.arange(idx.size)
                for o, X in zip(out, (Vr, Tr, Kr), strict=True):
                    o[idx] = X[m[idx], c]
        return out

    j = np.argmin(v, axis=1)
    # a second coarse local minimum nearly as low as the best is refined too, as an extra
    # row (two nearly equal minima, e.g. tip edge and form circle on a swing tooth)
    pad = np.full((W * n, 1), np.inf)
    left, right = np.hstack([pad, v[:, :-1]]), np.hstack([v[:, 1:], pad])
    cols = np.arange(grid)[None, :]
    local = (v <= left) & (v <= right) & (np.abs(cols - j[:, None]) > 1) & np.isfinite(v)
    v2 = np.where(local, v, np.inf)
    j2 = np.argmin(v2, axis=1)
    vmin = v[rows_all, j]
    finite_max = np.max(np.where(np.isfinite(v), v, -np.inf), axis=1)
    v2min = v2[rows_all, j2]
    second = np.isfinite(v2min)  # then vmin is finite too
    second[second] = (v2min[second] - vmin[second]
                      <= 0.25 * (finite_max[second] - vmin[second]))
    extra = rows_all[second]
    origin = np.concatenate([rows_all, extra])
    meas, th_of = meas[origin], th_of[origin]
    v, t, k = v[origin], t[origin], k[origin]
    j = np.concatenate([j, j2[second]])
    rows_all = np.arange(origin.size)
    best_v, best_z = v[rows_all, j], zg[j]
    best_t, best_k = t[rows_all, j], k[rows_all, j]
    exact_val = np.zeros(origin.size, dtype=bool)  # coarse values are upper bounds
    jl, jr = np.maximum(j - 1, 0), np.minimum(j + 1, grid - 1)
    a_z, a_v = zg[jl], v[rows_all, jl]
    b_z, b_v = zg[jr], v[rows_all, jr]
    active = np.flatnonzero(np.isfinite(best_v))

    def take(rows, zz, vv, tt, kk):
        """Keep the best of the evaluated points ``(len(rows), m)`` where it improves."""
        r = np.arange(rows.size)
        jj = np.argmin(vv, axis=1)
        better = vv[r, jj] < best_v[rows]
        upd = rows[better]
        best_v[upd], best_z[upd] = vv[r, jj][better], zz[r, jj][better]
        best_t[upd], best_k[upd] = tt[r, jj][better], kk[r, jj][better]
        exact_val[upd] = True
        return jj, better

    # smooth minima: step to the vertex of the coarse parabola and bracket it by +-delta,
    # delta = sqrt(tol / g'') so that a bracket around the true minimum closes at once
    par = active[(a_z[active] < best_z[active]) & (best_z[active] < b_z[active])
                 & np.isfinite(a_v[active]) & np.isfinite(b_v[active])]
    if par.size:
        h = b_z[par] - best_z[par]  # uniform coarse grid: equal spacing on both sides
        curv = (a_v[par] + b_v[par] - 2.0 * best_v[par]) / (h * h)
        ok = curv > 0
        par, h, curv = par[ok], h[ok], curv[ok]
        z1 = best_z[par] - 0.5 * (b_v[par] - a_v[par]) / (h * curv)
        delta = np.minimum(np.sqrt(tolerance_mm / curv), 0.25 * h)
        z1 = np.clip(z1, a_z[par] + delta, b_z[par] - delta)
        zz = np.stack([z1 - delta, z1, z1 + delta], axis=1)
        m = par.size
        out = evaluate(zz.ravel(), np.repeat(par, 3))
        v3, t3, k3 = (X.reshape(m, 3) for X in out)
        jj, better = take(par, zz, v3, t3, k3)
        mid = (jj == 1) & better  # the small triple brackets the minimum
        sel = par[mid]
        a_z[sel], a_v[sel] = zz[mid, 0], v3[mid, 0]
        b_z[sel], b_v[sel] = zz[mid, 2], v3[mid, 2]
    def _triple(rows, zc, eps):
        """Evaluate ``zc - eps, zc, zc + eps``; where the middle is lowest it brackets."""
        zz3 = np.stack([zc - eps, zc, zc + eps], axis=1)
        out3 = evaluate(zz3.ravel(), np.repeat(rows, 3))
        v3_, t3_, k3_ = (X.reshape(rows.size, 3) for X in out3)
        jj, better = take(rows, zz3, v3_, t3_, k3_)
        mid = (jj == 1) & better
        sel = rows[mid]
        a_z[sel], a_v[sel] = zz3[mid, 0], v3_[mid, 0]
        b_z[sel], b_v[sel] = zz3[mid, 2], v3_[mid, 2]

    def _parabola_step(rows, allz, allv, jb):
        """Smooth minima: vertex of the parabola through the best point and its neighbours,
        bracketed by +-sqrt(tol / g'')."""
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
        eps = np.sqrt(tolerance_mm / curv[good])
        zc = zp[good]
        eps = np.clip(eps, 1e-12 * hf, 0.25 * np.minimum(zc - x0[good], x2[good] - zc))
        _triple(rows[good], zc, eps)

    def _v_step(rows, allz, allv, jb):
        """Corner minima (the active interval's end switches, e.g. from the form circle to
        the sleeve tip edge): intersect the secants of the two branches either side of the
        best point and bracket the intersection by +-eps, eps = tol / slope."""
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
        eps = 0.5 * tolerance_mm / np.maximum(-sl[good], sr[good])
        eps = np.clip(eps, 1e-12 * hf, 0.25 * np.minimum(zk - z1[good], z2[good] - zk))
        _triple(rows, zk, eps)

    def _corner_step(rows):
        """Corner minima where the active interval's lower end switches from the hub form
        circle to the sleeve tip edge: solve ``rq(z, t=0) = r_form`` in the bracket
        (secant) and bracket the corner by +-eps, eps = tol / (2 slope)."""
        rows = rows[(meas[rows] != 2) & (meas[rows] != 3)]
        if rows.size == 0:
            return
        th = theta[th_of[rows]]

        def g(z):
            planes = _Planes(table, sl, misalignment, z, th_sel)
            return planes.at_end(0)[0] - sl.r_form

        th_sel = th
        za, zb = a_z[rows].copy(), b_z[rows].copy()
        ga, gb = g(za), g(zb)
        ok = np.sign(ga) * np.sign(gb) < 0
        if not np.any(ok):
            return
        rows, za, zb, ga, gb, th_sel = rows[ok], za[ok], zb[ok], ga[ok], gb[ok], th[ok]
        z0, g0, z1, g1 = za, ga, zb, gb
        for _ in range(30):
            with np.errstate(divide="ignore", invalid="ignore"):
                zc = z1 - g1 * (z1 - z0) / (g1 - g0)
            zc = np.where(np.isfinite(zc), np.clip(zc, za, zb), 0.5 * (za + zb))
            gc_ = g(zc)
            z0, g0, z1, g1 = z1, g1, zc, gc_
            if np.all(np.abs(gc_) <= 1e-11 * sl.r_form):
                break
        w_l = np.maximum(best_z[rows] - a_z[rows], 1e-12 * hf)
        w_r = np.maximum(b_z[rows] - best_z[rows], 1e-12 * hf)
        slope = np.maximum(np.abs(a_v[rows] - best_v[rows]) / w_l,
                           np.abs(b_v[rows] - best_v[rows]) / w_r)
        eps = 0.5 * tolerance_mm / np.maximum(slope, 1e-12)
        eps = np.clip(eps, 1e-12 * hf, 0.25 * np.minimum(zc - a_z[rows], b_z[rows] - zc))
        good = eps > 0
        if np.any(good):
            _triple(rows[good], zc[good], eps[good])

    def _local_newton(rows):
        """Smooth minima next to a kink that spoiled the coarse parabola: a parabola from
        the best point and two close neighbours (+-1e-3 of the half face), then a triple
        around its vertex, +-sqrt(tol / g'')."""
        if rows.size == 0:
            return
        h = np.minimum(1e-3 * hf, 0.25 * np.minimum(best_z[rows] - a_z[rows],
                                                    b_z[rows] - best_z[rows]))
        ok = h > 1e-9 * hf
        rows, h = rows[ok], h[ok]
        if rows.size == 0:
            return
        x1 = best_z[rows]
        y1 = best_v[rows]
        zz = np.stack([x1 - h, x1 + h], axis=1)
        out = evaluate(zz.ravel(), np.repeat(rows, 2))
        v2, t2, k2 = (X.reshape(rows.size, 2) for X in out)
        y0, y2 = v2[:, 0], v2[:, 1]
        take(rows, zz, v2, t2, k2)
        with np.errstate(divide="ignore", invalid="ignore"):
            curv = (y0 + y2 - 2.0 * y1) / (h * h)
            zp = x1 - 0.5 * (y2 - y0) / (h * curv)
        good = np.isfinite(zp) & (curv > 0) & (zp > a_z[rows]) & (zp < b_z[rows])
        if not np.any(good):
            return
        rows, zp, curv = rows[good], zp[good], curv[good]
        eps = np.sqrt(tolerance_mm / curv)
        eps = np.clip(eps, 1e-12 * hf, 0.25 * np.minimum(zp - a_z[rows], b_z[rows] - zp))
        _triple(rows, zp, eps)

    # nested grids until the bracket cannot hide more than the tolerance
    inner = 4
    first = True
    frac = np.arange(1, inner + 1) / (inner + 1)
    for _ in range(max_levels):
        if active.size == 0:
            break
        excess = np.maximum(a_v[active], b_v[active]) - best_v[active]
        width = b_z[active] - a_z[active]
        active = active[(excess > tolerance_mm) & (width > 1e-12 * hf)]
        if active.size == 0:
            break
        if first:
            first = False
            _local_newton(active)
            excess = np.maximum(a_v[active], b_v[active]) - best_v[active]
            active = active[excess > tolerance_mm]
            _corner_step(active)
            excess = np.maximum(a_v[active], b_v[active]) - best_v[active]
            active = active[excess > tolerance_mm]
            if active.size == 0:
                break
        m = active.size
        zz = a_z[active, None] + frac[None, :] * (b_z - a_z)[active, None]
        out = evaluate(zz.ravel(), np.repeat(active, inner))
        v2, t2, k2 = (X.reshape(m, inner) for X in out)
        take(active, zz, v2, t2, k2)
        allz = np.concatenate([a_z[active, None], zz, b_z[active, None]], axis=1)
        allv = np.concatenate([a_v[active, None], v2, b_v[active, None]], axis=1)
        r2 = np.arange(m)
        jb = np.argmin(allv, axis=1)
        jl2, jr2 = np.maximum(jb - 1, 0), np.minimum(jb + 1, inner + 1)
        a_z[active], a_v[active] = allz[r2, jl2], allv[r2, jl2]
        b_z[active], b_v[active] = allz[r2, jr2], allv[r2, jr2]
        _v_step(active, allz, allv, jb)
        _parabola_step(active, allz, allv, jb)

    # final parabolic step through the bracket (smooth minima)
    fin = np.flatnonzero(np.isfinite(best_v) & np.isfinite(a_v) & np.isfinite(b_v)
                         & (a_z < best_z) & (best_z < b_z))
    if fin.size:
        x0, x1, x2 = a_z[fin], best_z[fin], b_z[fin]
        y0, y1, y2 = a_v[fin], best_v[fin], b_v[fin]
        num = (x1 - x0) ** 2 * (y1 - y2) - (x1 - x2) ** 2 * (y1 - y0)
        den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0)
        with np.errstate(divide="ignore", invalid="ignore"):
            zp = x1 - 0.5 * num / den
        good = np.isfinite(zp) & (zp > x0) & (zp < x2)
        fin, zp = fin[good], zp[good]
        if fin.size:
            out = evaluate(zp, fin)
            take(fin, zp[:, None], *(X[:, None] for X in out))
    # minima that crept to a face end sit on it: snap (the value moves by slope * 1e-8 hf)
    near_end = np.isfinite(best_v) & (np.abs(best_z) >= hf * (1.0 - 1e-8))
    best_z = np.where(near_end, np.sign(best_z) * hf, best_z)
    exact_val &= ~near_end
    # the reported minimum is evaluated exactly where it lies (the coarse values are
    # upper bounds; a refined value is kept where lower)
    ex = np.flatnonzero(np.isfinite(best_v) & ~exact_val)
    if ex.size:
        ve, te, ke = evaluate(best_z[ex], ex)
        use = (ve <= best_v[ex] + 1e-7 * tolerance_mm) | near_end[ex]
        best_v[ex] = np.where(use, ve, best_v[ex])
        best_t[ex] = np.where(use, te, best_t[ex])
        best_k[ex] = np.where(use, ke, best_k[ex])
    # each row keeps the better of its own and its extra row's minimum
    R = W * n
    if origin.size > R:
        ex_rows = np.arange(R, origin.size)
        won = best_v[ex_rows] < best_v[origin[ex_rows]]
        dst, src = origin[ex_rows][won], ex_rows[won]
        best_v[dst], best_z[dst], best_t[dst], best_k[dst] = (best_v[src], best_z[src],
                                                              best_t[src], best_k[src])
        best_v, best_z, best_t, best_k = best_v[:R], best_z[:R], best_t[:R], best_k[:R]
        th_of = th_of[:R]
    at_end = (np.abs(np.abs(best_z) - hf) <= 1e-12 * hf) & (best_k != NONE)
    best_k = np.where(at_end, FACE_END, best_k).astype(np.int8)
    lo, hi = table.radii(best_z)
    r = lo + best_t * (hi - lo)
    rate = turning_rate(table, misalignment, best_z, best_t, theta[th_of])
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
