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
sleeve-edge crossings solved to 1e-12, and the interior stationary point by a parabola and
a Newton step), then over ``z`` by nested grids that stop when the bracket cannot hide
more than the tolerance, and a final parabolic step. The active interval in ``t`` is cut
where the sleeve flank begins (tip chamfer edge) and at the sleeve face ends; the tip
chamfer itself recedes at 45° and never holds the minimum.

``contact_kind`` codes (:data:`KINDS`) name where the minimum lies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..geometry.involute import inv
from ..geometry.sleeve import SleeveModel
from .flank_table import FlankTable
from .pose import map_polar

KINDS = ("interior", "face end", "tip edge", "form edge", "sleeve tip edge",
         "sleeve root fillet", "sleeve face end", "no contact")
INTERIOR, FACE_END, TIP_EDGE, FORM_EDGE, SLEEVE_TIP, SLEEVE_FILLET, SLEEVE_FACE, NONE = range(8)
MEASURES = ("circumferential", "normal", "pitch_circumferential", "pitch_normal")
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
        x = np.minimum(self.r_b / rq, 1.0)
        return aq + self.c0 - inv(np.arccos(x))

    def gap(self, rq, aq, normal):
        """Gap (mm) at sleeve radius ``rq``: circumferential, or normal where ``normal``."""
        d = self.delta(rq, aq)
        val = np.where(normal, self.r_b, rq) * d
        fil = rq > self.r_fillet
        if self.rho > 0 and np.any(fil):
            r, a = rq[fil], aq[fil]
            cosb = np.clip((r * r + self.cn**2 - self.rho**2) / (2 * r * self.cn), -1.0, 1.0)
            beta = self.gc - np.arccos(cosb)
            circ = r * (a - beta)
            nor = self.rho - np.hypot(r * np.cos(a) - self.cx, r * np.sin(a) - self.cy)
            val[fil] = np.where(normal[fil], nor, circ)
        return val


class _Planes:
    """A batch of (plane z, pose theta, measure) whose gaps are minimised over ``t``."""

    def __init__(self, table: FlankTable, sl: _Sleeve, mis: float, z, theta, normal):
        self.table, self.sl, self.mis = table, sl, mis
        self.z, self.theta, self.normal = z, theta, normal
        self.kz = table.z_coefficients(z)
        self.lo, hi = table.radii(z)
        self.span = hi - self.lo

    def at(self, t, idx=None):
        """``(rq, aq, zq)`` at heights ``t`` (for the rows ``idx``, all when None)."""
        if idx is None:
            z, th, kz, lo, sp = self.z, self.theta, self.kz, self.lo, self.span
        else:
            z, th, kz = self.z[idx], self.theta[idx], self.kz[idx]
            lo, sp = self.lo[idx], self.span[idx]
        r = lo + t * sp
        return map_polar(r, self.table.alpha_at(kz, t), z, self.mis, th)

    def f(self, t, idx=None):
        rq, aq, _ = self.at(t, idx)
        normal = self.normal if idx is None else self.normal[idx]
        return self.sl.gap(rq, aq, normal)

    def cross(self, which: str, target: float, a, b, fa, fb, idx):
        """``t`` in ``[a, b]`` where ``rq`` (or ``zq``) equals ``target``; ``fa``, ``fb``
        are the values minus target at the ends (opposite signs). Regula falsi (Illinois)."""
        for _ in range(40):
            t = np.clip(a - fa * (b - a) / (fb - fa), a, b)
            rq, _, zq = self.at(t, idx)
            ft = (rq if which == "r" else zq) - target
            left = np.sign(ft) == np.sign(fa)
            a, fa, fb = (np.where(left, t, a), np.where(left, ft, fa),
                         np.where(left, 0.5 * fb, fb))
            b, fb, fa = (np.where(left, b, t), np.where(left, fb, ft),
                         np.where(left, fa, 0.5 * fa))
            if np.all(np.abs(ft) <= 1e-11 * (abs(target) + 1.0)):
                return t
        return t

    def minimum_over_t(self):
        """Exact minimum over the active ``t`` interval: value, t, kind (each ``(n,)``)."""
        n = self.z.shape[0]
        sl = self.sl
        zeros, ones = np.zeros(n), np.ones(n)
        rq0, _, zq0 = self.at(zeros)
        rq1, _, zq1 = self.at(ones)
        t_lo, k_lo = zeros.copy(), np.full(n, FORM_EDGE, np.int8)
        t_hi, k_hi = ones.copy(), np.full(n, TIP_EDGE, np.int8)
        feasible = rq1 > sl.r_form
        idx = np.flatnonzero(feasible & (rq0 < sl.r_form))
        if idx.size:
            t_lo[idx] = self.cross("r", sl.r_form, zeros[idx], ones[idx],
                                   rq0[idx] - sl.r_form, rq1[idx] - sl.r_form, idx)
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
        t_a, k_a = t_hi.copy(), k_hi.copy()  # end of the involute piece
        rqh, _, _ = self.at(t_hi)
        idx = np.flatnonzero(feasible & (rqh > sl.r_fillet))
        if idx.size:
            rql, _, _ = self.at(t_lo[idx], idx)
            tf = self.cross("r", sl.r_fillet, t_lo[idx], t_hi[idx], rql - sl.r_fillet,
                            rqh[idx] - sl.r_fillet, idx)
            t_a[idx], k_a[idx] = tf, SLEEVE_FILLET
            k_hi[idx] = SLEEVE_FILLET
        fa, fb, fh = self.f(t_lo), self.f(t_a), self.f(t_hi)
        cand_t = [t_lo, t_a, t_hi]
        cand_f = [fa, fb, fh]
        cand_k = [k_lo, k_a, k_hi]
        # interior stationary point of the involute piece: parabola, then one Newton step
        tm = 0.5 * (t_lo + t_a)
        fm = self.f(tm)
        h = 0.5 * (t_a - t_lo)
        curv = fa + fb - 2.0 * fm
        with np.errstate(divide="ignore", invalid="ignore"):
            s = -(fb - fa) * h / (2.0 * curv)
        ok = feasible & (curv > 0) & (np.abs(s) < h) & (h > 0)
        idx = np.flatnonzero(ok)
        ti = tm.copy()
        fi = fm.copy()
        if idx.size:
            a, b = t_lo[idx], t_a[idx]
            t = tm[idx] + s[idx]
            d = 1e-4 * h[idx]
            f0 = self.f(t, idx)
            fp, fn = self.f(np.minimum(t + d, b), idx), self.f(np.maximum(t - d, a), idx)
            g1 = (fp - fn) / (2 * d)
            g2 = (fp + fn - 2 * f0) / (d * d)
            step = np.where(g2 > 0, g1 / np.where(g2 > 0, g2, 1.0), 0.0)
            t2 = np.clip(t - step, a, b)
            f2 = self.f(t2, idx)
            better = f2 < f0
            ti[idx] = np.where(better, t2, t)
            fi[idx] = np.where(better, f2, f0)
        cand_t += [tm, ti]
        cand_f += [fm, fi]
        cand_k += [np.full(n, INTERIOR, np.int8)] * 2
        F = np.stack(cand_f)
        j = np.argmin(F, axis=0)
        cols = np.arange(n)
        value = F[j, cols]
        t_best = np.stack(cand_t)[j, cols]
        kind = np.stack(cand_k)[j, cols]
        value = np.where(feasible, value, np.inf)
        kind = np.where(feasible, kind, NONE).astype(np.int8)
        return value, t_best, kind

    def pitch_line(self, R: float):
        """Gap on the pitch circle ``r = R`` of each plane: value, t, kind."""
        t = (R - self.lo) / self.span
        rq, aq, zq = self.at(np.clip(t, 0.0, 1.0))
        ok = (t >= 0) & (t <= 1) & (rq >= self.sl.r_form) & (np.abs(zq) <= self.sl.half_face)
        val = np.where(ok, self.sl.gap(rq, aq, self.normal), np.inf)
        kind = np.where(ok, INTERIOR, NONE).astype(np.int8)
        return val, t, kind


def _plane_minimum(table, sl, mis, z, theta, normal, pitch_R):
    planes = _Planes(table, sl, mis, z, theta, normal)
    return planes.pitch_line(pitch_R) if pitch_R is not None else planes.minimum_over_t()


def minimise(table: FlankTable, sm: SleeveModel, misalignment: float, theta, normal,
             *, pitch_radius: float | None = None, tolerance_mm: float = DEFAULT_TOLERANCE_MM,
             grid: int = DEFAULT_GRID, max_levels: int = 30) -> Minimum:
    """Minimum gap of tooth 0's cw flank to space 0 at turning angles ``theta``.

    Parameters
    ----------
    table : FlankTable
        The hub flank.
    sm : SleeveModel
    misalignment : float
        Tilt ``i`` (radians).
    theta : (n,) float
        Turning angles (radians).
    normal : (n,) bool
        Per row: minimise the normal gap (True) or the circumferential gap (False).
    pitch_radius : float, optional
        If given, minimise only along the pitch line ``r = pitch_radius`` of the hub flank.
    tolerance_mm : float
        Stop refining a row when its bracket cannot hide a lower value by more than this.
    grid : int
        Coarse planes over the face width (>= 3); more finds narrow minima more surely.

    Returns
    -------
    Minimum
    """
    if grid < 3:
        raise ValueError(f"grid must be at least 3 planes, got {grid}")
    if not tolerance_mm > 0:
        raise ValueError(f"tolerance_mm must be > 0, got {tolerance_mm!r}")
    theta = np.asarray(theta, dtype=float).ravel()
    normal = np.broadcast_to(np.asarray(normal, dtype=bool), theta.shape).copy()
    n = theta.size
    sl = _Sleeve(sm)
    hf = table.half_face
    zg = np.linspace(-hf, hf, grid)
    Z = np.broadcast_to(zg, (n, grid)).ravel()
    TH = np.repeat(theta, grid)
    NM = np.repeat(normal, grid)
    v, t, k = _plane_minimum(table, sl, misalignment, Z, TH, NM, pitch_radius)
    v, t, k = v.reshape(n, grid), t.reshape(n, grid), k.reshape(n, grid)
    j = np.argmin(v, axis=1)
    rows = np.arange(n)
    best_v, best_z, best_t, best_k = v[rows, j], zg[j], t[rows, j], k[rows, j]
    jl, jr = np.maximum(j - 1, 0), np.minimum(j + 1, grid - 1)
    a_z, a_v = zg[jl], v[rows, jl]
    b_z, b_v = zg[jr], v[rows, jr]
    active = np.flatnonzero(np.isfinite(best_v))
    inner = 6
    for _ in range(max_levels):
        if active.size == 0:
            break
        excess = np.maximum(a_v[active], b_v[active]) - best_v[active]
        width = b_z[active] - a_z[active]
        keep = (excess > tolerance_mm) & (width > 1e-12 * hf)
        active = active[keep]
        if active.size == 0:
            break
        frac = np.arange(1, inner + 1) / (inner + 1)
        zz = a_z[active, None] + frac[None, :] * (b_z - a_z)[active, None]
        m = active.size
        v2, t2, k2 = _plane_minimum(table, sl, misalignment, zz.ravel(),
                                    np.repeat(theta[active], inner),
                                    np.repeat(normal[active], inner), pitch_radius)
        v2, t2, k2 = v2.reshape(m, inner), t2.reshape(m, inner), k2.reshape(m, inner)
        # candidates: left end, inner points, right end and the old best
        allz = np.concatenate([a_z[active, None], zz, b_z[active, None]], axis=1)
        allv = np.concatenate([a_v[active, None], v2, b_v[active, None]], axis=1)
        jj = np.argmin(v2, axis=1)
        r2 = np.arange(m)
        better = v2[r2, jj] < best_v[active]
        upd = active[better]
        best_v[upd] = v2[r2, jj][better]
        best_z[upd] = zz[r2, jj][better]
        best_t[upd] = t2[r2, jj][better]
        best_k[upd] = k2[r2, jj][better]
        # new bracket: neighbours of the best of the inner points (or of the old best)
        jb = np.argmin(allv, axis=1)
        jl2, jr2 = np.maximum(jb - 1, 0), np.minimum(jb + 1, inner + 1)
        a_z[active], a_v[active] = allz[r2, jl2], allv[r2, jl2]
        b_z[active], b_v[active] = allz[r2, jr2], allv[r2, jr2]
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
            vp, tp, kp = _plane_minimum(table, sl, misalignment, zp, theta[fin], normal[fin],
                                        pitch_radius)
            better = vp < best_v[fin]
            upd = fin[better]
            best_v[upd], best_z[upd], best_t[upd], best_k[upd] = (vp[better], zp[better],
                                                                  tp[better], kp[better])
    at_end = (np.abs(np.abs(best_z) - hf) <= 1e-12 * hf) & (best_k != NONE)
    best_k = np.where(at_end, FACE_END, best_k).astype(np.int8)
    lo, hi = table.radii(best_z)
    r = lo + best_t * (hi - lo)
    rate = turning_rate(table, misalignment, best_z, best_t, theta)
    return Minimum(best_v, best_z, r, best_t, best_k, rate)


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
