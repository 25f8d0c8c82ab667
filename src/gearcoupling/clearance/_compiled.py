"""The clearance kernel compiled (numba): one turning angle after another, a row at a time.

Imported only through :func:`.fast.kernels`. :func:`minimise_rows` takes the steps of
:func:`.kernel.minimise` - coarse planes, second minima, the z search of
:class:`.kernel.ZSearch`, each measure's fold over its branches - for each turning angle,
every (virtual measure, turning angle) row on its own with scalar state: no numpy call per
step, nothing allocated per point. The z search evaluates the same planes as the numpy
path. Inside a plane the minimum over ``t`` is solved to convergence with the slopes
along ``t`` in closed form: Newton steps for the active interval's crossings (to 1e-11
relative), for an interior minimum the minimum of the cubic through the ends, then
secant steps on the exact slope (to 1e-7 in ``t``). The two paths agree to rounding
(``tests/test_sweep_frozen.py``, ``tests/test_sweep_kernel.py``; docs/sweep-speed.md).

Two flat arrays carry everything, so that a call passes two arrays: ``tab`` (read only)
holds the constants of :func:`.kernel._compiled_arrays` at the indices below, the table's
piece edges and its plane matrices ``(pieces, nt + 1, nz)``; ``ws`` is the work space:
the search state of a row, scratch, and the planes of the turning angle with the rows
found in them (:func:`evaluate`; a plane at offset ``po``: the ``nt`` coefficients of
``y`` in ``t``, ``r_form``, the span ``r_tip - r_form`` and ``z``). :func:`minimise_rows`
passes views of them without reference counting (:func:`_unmanaged`). Integer and
boolean constants are passed as ``np.int64``/``np.bool_``: a literal argument would
compile a function once per value.
"""

from __future__ import annotations

import math

import numpy as np
from numba.extending import intrinsic

from ..io.numba_cache import njit
from ..numeric import TINY

_jit = njit(nogil=True, error_model="numpy", fastmath={"contract"})  # cached, verified

# tab: constants (kernel._compiled_arrays), then the edges and the plane matrices
CI, SI, RB, C0, RFIL, RHO, CN, GC, CX, CY, RFORM, SHF, HF, RPITCH, TOL, TIPR, SPHERE, \
    POWER, NT, NZ, PIECES = range(21)
EDGES = 21
# contact kinds (kernel.KINDS)
INTERIOR, FACE_END, TIP_EDGE, FORM_EDGE, SLEEVE_TIP, SLEEVE_FILLET, SLEEVE_FACE, NONE = range(8)
# ws: a row's search state and its copy, scratch, then the coarse z, planes and minima
BV, BZ, BT, BK, EX, AZ, AV, BZB, BVB = range(9)  # slots of the search state
SAVED = 9  # the state of the first search while the second runs
ZS, VS, TS, KS = 18, 26, 34, 42  # up to 8 planes evaluated together
V, T, K = 50, 58, 66  # the 8 virtual measures' minima in a plane
ALLZ, ALLV = 74, 80  # a nested grid level with its bracket ends
TZ = 86  # T_j(x) of the plane's z, j < MAX_NZ
GRID, NDYN = 150, 151  # coarse planes; planes evaluated at this turning angle beyond them
MAX_NZ = GRID - TZ
ENTRIES = 160  # the planes of this turning angle (_entry), the coarse ones first
EZ, VALID, EV, ET, EK, EPL = 0, 1, 9, 17, 25, 33  # an entry: z, which rows are known, their
# value, t and kind, then the plane
MAX_DYN = 64  # planes kept beyond the coarse ones (then one more, kept for nothing)
D_SLOPE = 1e-6  # shortest interval searched inside, / 8 (as the numpy path's step)
REL = 1e-11  # crossings, relative to the target
# the branches (virtual measures) each measure folds, -1 padded (kernel._FOLD)
FOLD = ((0, 4, 6), (1, 5, 7), (2, -1, -1), (3, -1, -1))


def workspace_size(grid: int, nt: int) -> int:
    """Length of ``ws`` for ``grid`` coarse planes and ``nt`` coefficients in ``t``."""
    return ENTRIES + (grid + MAX_DYN + 1) * (EPL + nt + 3)


@intrinsic
def _unmanaged(typingctx, arr):
    """A view of ``arr`` without reference counting (a null meminfo), for the caller to
    pass on while it holds ``arr``. numba counts the references of an array passed to a
    call it does not inline with atomic operations: they took a third of the time; on a
    null meminfo the count is a skipped branch."""
    def codegen(context, builder, sig, args):
        src = context.make_array(sig.args[0])(context, builder, value=args[0])
        view = context.make_array(sig.return_type)(context, builder)
        context.populate_array(view, data=src.data, shape=src.shape, strides=src.strides,
                               itemsize=src.itemsize, meminfo=None)
        return view._getvalue()
    return arr(arr), codegen


@_jit
def _entry(tab, e):
    """Offset of plane entry ``e`` in ``ws``."""
    return ENTRIES + e * (EPL + int(tab[NT]) + 3)


@njit(nogil=True, error_model="numpy", fastmath={"contract", "reassoc"})
def plane_at(tab, ws, po, z):
    """Put the plane ``z`` at ``ws[po:]``: Chebyshev series in ``z`` (the sums
    reassociated, so vectorised: the same values to rounding)."""
    nt, nz, pieces = int(tab[NT]), int(tab[NZ]), int(tab[PIECES])
    k = 0
    for j in range(1, pieces):
        if tab[EDGES + j] <= z:
            k = j
    lo, hi = tab[EDGES + k], tab[EDGES + k + 1]
    x = (2.0 * z - (lo + hi)) / (hi - lo)
    ws[TZ] = 1.0
    ws[TZ + 1] = x
    half = 1  # T_(h + m) = 2 T_h T_m - T_(h - m): a block at a time, not one by one
    while half < nz - 1:
        th2 = 2.0 * ws[TZ + half]
        for m in range(1, min(half, nz - 1 - half) + 1):
            ws[TZ + half + m] = th2 * ws[TZ + m] - ws[TZ + half - m]
        half *= 2
    m0 = EDGES + pieces + 1 + k * (nt + 1) * nz
    for i in range(nt + 1):
        mi = m0 + i * nz
        acc = 0.0
        for j in range(nz):
            acc += tab[mi + j] * ws[TZ + j]
        ws[po + i] = acc
    r_form = ws[po + nt]
    if tab[SPHERE] != 0.0:
        tip = math.sqrt(max(tab[TIPR] * tab[TIPR] - z * z, 0.0))
    else:
        tip = tab[TIPR]
    ws[po + nt + 1] = tip - r_form
    ws[po + nt + 2] = z


@_jit
def point(tab, ws, po, ct, st, t):
    """The flank point at height ``t`` in the sleeve frame and its rate along ``t``:
    ``(qx, qy, zq, dqx, dqy, dzq)``. ``y`` by Horner's rule in ``s = 2 t - 1`` (power
    form), else by the Chebyshev recurrences of ``T_k(s)`` and ``T_k'(s)``."""
    nt = int(tab[NT])
    s = 2.0 * t - 1.0
    if tab[POWER] != 0.0:  # even and odd powers apart: two chains in s^2 at once
        u = s * s
        ke, ko = (nt - 1, nt - 2) if nt % 2 else (nt - 2, nt - 1)
        e, de, o, do = ws[po + ke], 0.0, ws[po + ko], 0.0
        for k in range(ke - 2, -1, -2):
            de = de * u + e
            e = e * u + ws[po + k]
        for k in range(ko - 2, 0, -2):
            do = do * u + o
            o = o * u + ws[po + k]
        y, dy = e + s * o, o + 2.0 * s * (de + s * do)
    else:
        t0, t1, d0, d1 = 1.0, s, 0.0, 1.0
        y, dy = ws[po] + ws[po + 1] * s, ws[po + 1]
        for k in range(2, nt):
            t0, t1, d0, d1 = t1, 2.0 * s * t1 - t0, d1, 2.0 * t1 + 2.0 * s * d1 - d0
            y += ws[po + k] * t1
            dy += ws[po + k] * d1
    dy *= 2.0
    ci, si = tab[CI], tab[SI]
    span = ws[po + nt + 1]
    r = ws[po + nt] + t * span
    z = ws[po + nt + 2]
    x = math.sqrt(r * r - y * y)
    dx = (r * span - y * dy) / x
    u, du = x * st + y * ct, dx * st + dy * ct
    v, dv = u * (ci - 1.0) - z * si, du * (ci - 1.0)
    return v * st + x, v * ct + y, u * si + z * ci, dv * st + dx, dv * ct + dy, du * si


@_jit
def radius_z(p):
    """``(rq, zq, drq/dt, dzq/dt)`` of a :func:`point`."""
    qx, qy, zq, dqx, dqy, dzq = p
    rq = math.sqrt(qx * qx + qy * qy)
    return rq, zq, (qx * dqx + qy * dqy) / rq, dzq


@_jit
def involute(tab, p):
    """``(circumferential, normal)`` gaps of a :func:`point` to the involute (its extension
    off the flank) and their slopes along ``t``: ``(circ, normal, dcirc, dnormal)``. The
    angle ``aq + sigma(rq)/2`` as one ``atan2``: of the point turned by the involute's
    pressure angle at ``rq``."""
    qx, qy, _, dqx, dqy, _ = p
    r_b = tab[RB]
    rq2 = qx * qx + qy * qy
    rq = math.sqrt(rq2)
    drq = (qx * dqx + qy * dqy) / rq
    w = math.sqrt(max(rq2 - r_b * r_b, 0.0))
    d = math.atan2(qy * r_b + qx * w, qx * r_b - qy * w) + tab[C0] - w / r_b
    dd = (qx * dqy - qy * dqx) / rq2 - w / (r_b * rq) * drq
    return rq * d, r_b * d, drq * d + rq * dd, r_b * dd


@_jit
def fillet(tab, p):
    """As :func:`involute`, to the root fillet."""
    qx, qy, _, dqx, dqy, _ = p
    rho, cn = tab[RHO], tab[CN]
    rq2 = qx * qx + qy * qy
    rq = math.sqrt(rq2)
    drq = (qx * dqx + qy * dqy) / rq
    cosb = min(max((rq2 + cn * cn - rho * rho) / (2.0 * rq * cn), -1.0), 1.0)
    a_b = math.atan2(qy, qx) - (tab[GC] - math.acos(cosb))
    dbeta = ((1.0 - (cn * cn - rho * rho) / rq2) / (2.0 * cn)
             / math.sqrt(max(1.0 - cosb * cosb, TINY)) * drq)
    ex, ey = qx - tab[CX], qy - tab[CY]
    dist = math.hypot(ex, ey)
    return (rq * a_b, rho - dist, drq * a_b + rq * ((qx * dqy - qy * dqx) / rq2 - dbeta),
            -(ex * dqx + ey * dqy) / dist)


@_jit
def gaps(tab, p):
    """The gaps of a :func:`point` (:func:`involute`; above ``r_fillet`` :func:`fillet`,
    as ``_Sleeve.gaps``)."""
    if tab[RHO] > 0.0 and p[0] * p[0] + p[1] * p[1] > tab[RFIL] * tab[RFIL]:
        return fillet(tab, p)
    return involute(tab, p)


@_jit
def cross(tab, ws, po, ct, st, use_z, target, a, b, fa, fb, dfa):
    """``t`` in ``[a, b]`` where ``rq`` (or ``zq``) equals ``target`` (``fa``, ``fb``: the
    values minus target at the ends, of opposite signs; ``dfa`` the slope at ``a``):
    Newton steps from ``a`` kept inside the shrinking bracket (regula falsi when they
    leave it), to ``REL`` relative. Returns ``t`` and the :func:`point` there."""
    tol = REL * (abs(target) + 1.0)
    t, ft, dft = a, fa, dfa
    p = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    for _ in range(60):
        t = t - ft / dft
        if not (t > min(a, b) and t < max(a, b)):
            t = a - fa * (b - a) / (fb - fa)
        p = point(tab, ws, po, ct, st, t)
        rq, zq, drq, dzq = radius_z(p)
        ft, dft = (zq - target, dzq) if use_z else (rq - target, drq)
        if abs(ft) <= tol:
            break
        if (ft > 0) == (fa > 0):
            a, fa = t, ft
        else:
            b, fb = t, ft
    return t, p


@_jit
def interval(tab, ws, po, ct, st):
    """The active interval of the plane (``_Planes.active_interval``): ``(feasible,
    t_lo, k_lo, p_lo, t_a, k_a, p_a, t_hi, k_hi, p_hi)``, with the :func:`point` at each
    end."""
    r_form, r_fil, hf = tab[RFORM], tab[RFIL], tab[SHF]
    p_lo = p0 = point(tab, ws, po, ct, st, 0.0)
    p_hi = p1 = point(tab, ws, po, ct, st, 1.0)
    rq0, zq0, drq0, dzq0 = radius_z(p0)
    rq1, zq1 = radius_z(p1)[:2]
    t_lo, k_lo, t_hi, k_hi = 0.0, FORM_EDGE, 1.0, TIP_EDGE
    feasible = rq1 > r_form
    if feasible and rq0 < r_form:
        t_lo, p_lo = cross(tab, ws, po, ct, st, np.bool_(False), r_form, 0.0, 1.0,
                           rq0 - r_form, rq1 - r_form, drq0)
        k_lo = SLEEVE_TIP
    for sign in (1.0, -1.0):  # sleeve face ends: sign * zq <= hf
        v0, v1 = sign * zq0 - hf, sign * zq1 - hf
        if v0 > 0 and v1 > 0:
            feasible = False
        if feasible and (v0 > 0) != (v1 > 0):
            tc, pc = cross(tab, ws, po, ct, st, np.bool_(True), sign * hf, 0.0, 1.0,
                           sign * v0, sign * v1, dzq0)
            if v0 > 0 and tc > t_lo:
                t_lo, k_lo, p_lo = tc, SLEEVE_FACE, pc
            if v0 <= 0 and tc < t_hi:
                t_hi, k_hi, p_hi = tc, SLEEVE_FACE, pc
    feasible = feasible and t_lo <= t_hi
    t_a, k_a, p_a = t_hi, k_hi, p_hi
    if feasible and radius_z(p_hi)[0] > r_fil:
        rql, _, drql, _ = radius_z(p_lo)
        t_a, p_a = t_lo, p_lo  # all of [t_lo, t_hi] above the fillet start
        if rql < r_fil:
            t_a, p_a = cross(tab, ws, po, ct, st, np.bool_(False), r_fil, t_lo, t_hi,
                             rql - r_fil, radius_z(p_hi)[0] - r_fil, drql)
        k_a = SLEEVE_FILLET
        k_hi = SLEEVE_FILLET
    return feasible, t_lo, k_lo, p_lo, t_a, k_a, p_a, t_hi, k_hi, p_hi


@_jit
def slope_root(tab, ws, po, ct, st, mi, a, b, fa, fb, ga, gb):
    """The interior minimum of gap ``mi`` in ``[a, b]`` (values ``fa``, ``fb`` and slopes
    ``ga < 0 < gb`` at the ends): from the minimum of the cubic through them, secant steps
    on the slope kept inside the shrinking bracket until the next would be shorter than
    1e-7 in ``t``: ``(t, gap)``."""
    h = b - a
    d = (fb - fa) / h
    qa, qb, qc = 3.0 * (ga + gb) - 6.0 * d, 6.0 * d - 4.0 * ga - 2.0 * gb, ga  # slope in u
    disc = qb * qb - 4.0 * qa * qc
    x = a + h * 2.0 * qc / (-qb - math.sqrt(disc)) if disc >= 0.0 else np.nan
    if not (x > a and x < b):
        x = a - ga * h / (gb - ga)
    g = gaps(tab, point(tab, ws, po, ct, st, x))
    val, gx = g[mi], g[2 + mi]
    x0, g0, x1, g1 = (a, ga, x, gx) if gx > 0 else (b, gb, x, gx)
    if gx > 0:
        b = x
    else:
        a = x
    for _ in range(40):
        step = g1 * (x1 - x0) / (g1 - g0)
        if abs(step) <= 1e-7 or g1 == 0.0:  # the next step would be below 1e-7: done
            break
        x = x1 - step
        if not (x > a and x < b):
            x = 0.5 * (a + b)
        g = gaps(tab, point(tab, ws, po, ct, st, x))
        val, gx = g[mi], g[2 + mi]
        if gx > 0:
            b = x
        else:
            a = x
        x0, g0, x1, g1 = x1, g1, x, gx
    return x1, val


@_jit
def over_t(tab, ws, po, ct, st, want0, want1):
    """``_Planes.minimum_over_t`` of the plane at ``po``: the whole-flank rows 0, 1 and
    the profile-end rows 4-7 of ``ws[V:], ws[T:], ws[K:]``; ``want0``, ``want1``: search
    the interior of the circumferential, normal gap."""
    feasible, t_lo, k_lo, p_lo, t_a, k_a, p_a, t_hi, k_hi, p_hi = interval(tab, ws, po, ct, st)
    if not feasible:
        for vm in (0, 1, 4, 5, 6, 7):
            ws[V + vm], ws[T + vm], ws[K + vm] = np.inf, t_lo, NONE
        return
    fa, fh = gaps(tab, p_lo), gaps(tab, p_hi)
    fb = fb_min = fh  # at the upper end of [t_lo, t_a]: the slope and the minimum there
    if t_a != t_hi:
        fb = fb_min = gaps(tab, p_a)
    if t_lo < t_a < t_hi:  # the fillet start: as _Sleeve.at_fillet_start
        fb = fb_min = involute(tab, p_a)
        if tab[RHO] > 0.0:
            fil = fillet(tab, p_a)
            fb_min = (min(fb[0], fil[0]), min(fb[1], fil[1]), 0.0, 0.0)
    ti, fi = (0.0, 0.0), (np.inf, np.inf)
    if t_a - t_lo > 8 * D_SLOPE:
        for mi in range(2):
            if (want0 if mi == 0 else want1) and fa[2 + mi] < 0 and fb[2 + mi] > 0:
                root, val = slope_root(tab, ws, po, ct, st, mi, t_lo, t_a, fa[mi], fb[mi],
                                       fa[2 + mi], fb[2 + mi])
                ti = (root, ti[1]) if mi == 0 else (ti[0], root)
                fi = (val, fi[1]) if mi == 0 else (fi[0], val)
    for mi in range(2):
        v, t, k = fa[mi], t_lo, k_lo
        if fb_min[mi] < v:
            v, t, k = fb_min[mi], t_a, k_a
        if fh[mi] < v:
            v, t, k = fh[mi], t_hi, k_hi
        if fi[mi] < v:
            v, t, k = fi[mi], ti[mi], INTERIOR
        ws[V + mi], ws[T + mi], ws[K + mi] = v, t, k
        ws[V + 4 + mi], ws[T + 4 + mi], ws[K + 4 + mi] = fa[mi], t_lo, k_lo
        ws[V + 6 + mi], ws[T + 6 + mi], ws[K + 6 + mi] = fh[mi], t_hi, k_hi


@_jit
def pitch_line(tab, ws, po, ct, st):
    """``_Planes.pitch_line``: rows 2, 3 of ``ws[V:], ws[T:], ws[K:]``."""
    nt = int(tab[NT])
    t = (tab[RPITCH] - ws[po + nt]) / ws[po + nt + 1]
    p = point(tab, ws, po, ct, st, min(max(t, 0.0), 1.0))
    rq, zq = radius_z(p)[:2]
    ok = t >= 0 and t <= 1 and rq >= tab[RFORM] and abs(zq) <= tab[SHF]
    circ, normal = gaps(tab, p)[:2]
    ws[V + 2], ws[V + 3] = (circ, normal) if ok else (np.inf, np.inf)
    ws[T + 2], ws[T + 3] = t, t
    ws[K + 2] = ws[K + 3] = INTERIOR if ok else NONE


@_jit
def find(tab, ws, z):
    """The entry of the plane ``z`` evaluated at this turning angle, -1 if none."""
    grid = int(ws[GRID])
    for e in range(grid + int(ws[NDYN]) - 1, grid - 1, -1):  # the latest first
        if ws[_entry(tab, e)] == z:
            return e
    z0, z1 = ws[_entry(tab, 0)], ws[_entry(tab, grid - 1)]  # a coarse plane
    g = int((z - z0) / (z1 - z0) * (grid - 1) + 0.5)
    for e in range(max(g - 1, 0), min(g + 2, grid)):
        if ws[_entry(tab, e)] == z:
            return e
    return -1


@_jit
def keep(ws, eo, vm):
    """Copy row ``vm``'s minimum from ``ws[V:], ws[T:], ws[K:]`` into the entry at ``eo``."""
    ws[eo + EV + vm], ws[eo + ET + vm], ws[eo + EK + vm] = ws[V + vm], ws[T + vm], ws[K + vm]
    ws[eo + VALID + vm] = 1.0


@_jit
def evaluate(tab, ws, z, vm, ct, st):
    """Minimum of virtual measure ``vm`` in the plane ``z``: ``(value, t, kind)``. Each plane
    is kept with the rows found in it (as in the numpy path, rows of a turning angle
    evaluate the same planes: the profile ends come with the whole flank, and a row whose
    values equal another's takes the same steps); a row already found is read, else found
    in the plane kept."""
    e = find(tab, ws, z)
    if e < 0:
        e = int(ws[GRID] + ws[NDYN])
        if ws[NDYN] < MAX_DYN:
            ws[NDYN] += 1.0
        eo = _entry(tab, e)
        ws[eo + EZ] = z
        for q in range(8):
            ws[eo + VALID + q] = 0.0
        plane_at(tab, ws, eo + EPL, z)
    else:
        eo = _entry(tab, e)
        if ws[eo + VALID + vm] != 0.0:
            return ws[eo + EV + vm], ws[eo + ET + vm], ws[eo + EK + vm]
    if vm == 2 or vm == 3:
        pitch_line(tab, ws, eo + EPL, ct, st)
        keep(ws, eo, np.int64(2))
        keep(ws, eo, np.int64(3))
    else:
        over_t(tab, ws, eo + EPL, ct, st, vm == 0, vm == 1)
        for q in range(4, 8):
            keep(ws, eo, q)
        if vm < 2:
            keep(ws, eo, vm)
    return ws[V + vm], ws[T + vm], ws[K + vm]


@_jit
def points(tab, ws, m, vm, ct, st):
    """Evaluate the planes ``ws[ZS:ZS + m]`` and keep the best where it improves the
    state: ``(index of the best, better)``."""
    for i in range(m):
        ws[VS + i], ws[TS + i], ws[KS + i] = evaluate(tab, ws, ws[ZS + i], vm, ct, st)
    jj = 0
    for i in range(1, m):
        if ws[VS + i] < ws[VS + jj]:
            jj = i
    better = ws[VS + jj] < ws[BV]
    if better:
        ws[BV], ws[BZ], ws[BT], ws[BK] = ws[VS + jj], ws[ZS + jj], ws[TS + jj], ws[KS + jj]
        ws[EX] = 1.0
    return jj, better


@_jit
def triple(tab, ws, zc, eps, vm, ct, st):
    """Evaluate ``zc - eps, zc, zc + eps``; where the middle is lowest it brackets."""
    ws[ZS], ws[ZS + 1], ws[ZS + 2] = zc - eps, zc, zc + eps
    jj, better = points(tab, ws, np.int64(3), vm, ct, st)
    if jj == 1 and better:
        ws[AZ], ws[AV], ws[BZB], ws[BVB] = ws[ZS], ws[VS], ws[ZS + 2], ws[VS + 2]


@_jit
def _clip(x, lo, hi):
    return min(max(x, lo), hi)


@_jit
def coarse_parabola(tab, ws, vm, ct, st):
    """``ZSearch.coarse_parabola`` of the row."""
    a_z, a_v, b_z, b_v, best_z, best_v = ws[AZ], ws[AV], ws[BZB], ws[BVB], ws[BZ], ws[BV]
    if not (a_z < best_z and best_z < b_z and math.isfinite(a_v) and math.isfinite(b_v)):
        return
    h = b_z - best_z
    curv = (a_v + b_v - 2.0 * best_v) / (h * h)
    if not curv > 0:
        return
    z1 = best_z - 0.5 * (b_v - a_v) / (h * curv)
    delta = min(math.sqrt(tab[TOL] / curv), 0.25 * h)
    triple(tab, ws, _clip(z1, a_z + delta, b_z - delta), delta, vm, ct, st)


@_jit
def parabola_step(tab, ws, jb, vm, ct, st):
    """``ZSearch.parabola_step`` of the row, on the level at ``ws[ALLZ:], ws[ALLV:]``."""
    if not (jb >= 1 and jb <= 4):
        return
    x0, x1, x2 = ws[ALLZ + jb - 1], ws[ALLZ + jb], ws[ALLZ + jb + 1]
    y0, y1, y2 = ws[ALLV + jb - 1], ws[ALLV + jb], ws[ALLV + jb + 1]
    d01, d12 = (y1 - y0) / (x1 - x0), (y2 - y1) / (x2 - x1)
    curv = 2.0 * (d12 - d01) / (x2 - x0)
    zp = x1 - (d01 * (x2 - x1) + d12 * (x1 - x0)) / (curv * (x2 - x0))
    if not (math.isfinite(zp) and curv > 0 and zp > x0 and zp < x2):
        return
    eps = _clip(math.sqrt(tab[TOL] / curv), 1e-12 * tab[HF], 0.25 * min(zp - x0, x2 - zp))
    triple(tab, ws, zp, eps, vm, ct, st)


@_jit
def v_step(tab, ws, jb, vm, ct, st):
    """``ZSearch.v_step`` of the row, on the level at ``ws[ALLZ:], ws[ALLV:]``."""
    if not (jb >= 2 and jb <= 3):
        return
    z0, z1, z2, z3 = ws[ALLZ + jb - 2], ws[ALLZ + jb - 1], ws[ALLZ + jb + 1], ws[ALLZ + jb + 2]
    v0, v1, v2, v3 = ws[ALLV + jb - 2], ws[ALLV + jb - 1], ws[ALLV + jb + 1], ws[ALLV + jb + 2]
    sl = (v1 - v0) / (z1 - z0)
    sr = (v3 - v2) / (z3 - z2)
    zk = (v2 - v1 + sl * z1 - sr * z2) / (sl - sr)
    if not (sl < 0 and sr > 0 and math.isfinite(zk) and zk > z1 and zk < z2):
        return
    eps = _clip(0.5 * tab[TOL] / max(-sl, sr), 1e-12 * tab[HF], 0.25 * min(zk - z1, z2 - zk))
    triple(tab, ws, zk, eps, vm, ct, st)


@_jit
def form_gap(tab, ws, z, ct, st):
    """``rq - r_form`` at the hub form circle (``t = 0``) in the plane ``z`` (put in the
    spare entry)."""
    po = _entry(tab, int(ws[GRID]) + MAX_DYN) + EPL
    plane_at(tab, ws, po, z)
    return radius_z(point(tab, ws, po, ct, st, 0.0))[0] - tab[RFORM]


@_jit
def corner_step(tab, ws, vm, ct, st):
    """``ZSearch.corner_step`` of the row: the form circle meets the sleeve tip edge."""
    if vm == 2 or vm == 3:
        return
    za, zb = ws[AZ], ws[BZB]
    ga, gb = form_gap(tab, ws, za, ct, st), form_gap(tab, ws, zb, ct, st)
    if not ((ga > 0 and gb < 0) or (ga < 0 and gb > 0)):
        return
    z0, g0, z1, g1 = za, ga, zb, gb
    zc = za
    for _ in range(30):
        zc = z1 - g1 * (z1 - z0) / (g1 - g0)
        zc = _clip(zc, za, zb) if math.isfinite(zc) else 0.5 * (za + zb)
        g = form_gap(tab, ws, zc, ct, st)
        z0, g0, z1, g1 = z1, g1, zc, g
        if abs(g) <= 1e-11 * tab[RFORM]:
            break
    hf = tab[HF]
    w_l = max(ws[BZ] - ws[AZ], 1e-12 * hf)
    w_r = max(ws[BZB] - ws[BZ], 1e-12 * hf)
    slope = max(abs(ws[AV] - ws[BV]) / w_l, abs(ws[BVB] - ws[BV]) / w_r)
    eps = _clip(0.5 * tab[TOL] / max(slope, 1e-12), 1e-12 * hf,
                0.25 * min(zc - ws[AZ], ws[BZB] - zc))
    if eps > 0:
        triple(tab, ws, zc, eps, vm, ct, st)


@_jit
def local_newton(tab, ws, vm, ct, st):
    """``ZSearch.local_newton`` of the row."""
    hf = tab[HF]
    a_z, b_z, x1, y1 = ws[AZ], ws[BZB], ws[BZ], ws[BV]
    h = min(1e-3 * hf, 0.25 * min(x1 - a_z, b_z - x1))
    if not h > 1e-9 * hf:
        return
    ws[ZS], ws[ZS + 1] = x1 - h, x1 + h
    points(tab, ws, np.int64(2), vm, ct, st)
    y0, y2 = ws[VS], ws[VS + 1]
    curv = (y0 + y2 - 2.0 * y1) / (h * h)
    zp = x1 - 0.5 * (y2 - y0) / (h * curv)
    if not (math.isfinite(zp) and curv > 0 and zp > a_z and zp < b_z):
        return
    eps = _clip(math.sqrt(tab[TOL] / curv), 1e-12 * hf, 0.25 * min(zp - a_z, b_z - zp))
    triple(tab, ws, zp, eps, vm, ct, st)


@_jit
def nested_grids(tab, ws, max_levels, vm, ct, st):
    """``ZSearch.nested_grids`` of the row (4 planes a level); the first level tries
    :func:`local_newton` and :func:`corner_step` first."""
    tol, hf = tab[TOL], tab[HF]
    for level in range(max_levels):
        if not (max(ws[AV], ws[BVB]) - ws[BV] > tol and ws[BZB] - ws[AZ] > 1e-12 * hf):
            return
        if level == 0:
            local_newton(tab, ws, vm, ct, st)
            if not max(ws[AV], ws[BVB]) - ws[BV] > tol:
                return
            corner_step(tab, ws, vm, ct, st)
            if not max(ws[AV], ws[BVB]) - ws[BV] > tol:
                return
        a_z, b_z = ws[AZ], ws[BZB]
        for i in range(4):
            ws[ZS + i] = a_z + (i + 1) / 5 * (b_z - a_z)
        points(tab, ws, np.int64(4), vm, ct, st)
        ws[ALLZ], ws[ALLV], ws[ALLZ + 5], ws[ALLV + 5] = a_z, ws[AV], b_z, ws[BVB]
        for i in range(4):
            ws[ALLZ + i + 1], ws[ALLV + i + 1] = ws[ZS + i], ws[VS + i]
        jb = 0
        for i in range(1, 6):
            if ws[ALLV + i] < ws[ALLV + jb]:
                jb = i
        jl, jr = max(jb - 1, 0), min(jb + 1, 5)
        ws[AZ], ws[AV], ws[BZB], ws[BVB] = ws[ALLZ + jl], ws[ALLV + jl], ws[ALLZ + jr], \
            ws[ALLV + jr]
        v_step(tab, ws, jb, vm, ct, st)
        parabola_step(tab, ws, jb, vm, ct, st)


@_jit
def final_parabola(tab, ws, vm, ct, st):
    """``ZSearch.final_parabola`` of the row."""
    x0, x1, x2 = ws[AZ], ws[BZ], ws[BZB]
    y0, y1, y2 = ws[AV], ws[BV], ws[BVB]
    if not (math.isfinite(y1) and math.isfinite(y0) and math.isfinite(y2) and x0 < x1 and x1 < x2):
        return
    num = (x1 - x0) ** 2 * (y1 - y2) - (x1 - x2) ** 2 * (y1 - y0)
    den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0)
    zp = x1 - 0.5 * num / den
    if math.isfinite(zp) and zp > x0 and zp < x2:
        ws[ZS] = zp
        points(tab, ws, np.int64(1), vm, ct, st)


@_jit
def settle(tab, ws, vm, ct, st):
    """``ZSearch.settle`` of the row: a minimum that crept to a face end sits on it; the
    minimum is evaluated exactly where it lies."""
    hf = tab[HF]
    bz = ws[BZ]
    near_end = abs(bz) >= hf * (1.0 - 1e-8)
    if near_end:
        ws[BZ] = math.copysign(hf, bz)
        ws[EX] = 0.0
    if ws[EX] == 0.0:
        ve, te, ke = evaluate(tab, ws, ws[BZ], vm, ct, st)
        if ve <= ws[BV] + 1e-7 * tab[TOL] or near_end:
            ws[BV], ws[BT], ws[BK] = ve, te, ke


@_jit
def search(tab, ws, j, max_levels, vm, ct, st):
    """``ZSearch`` of the row of virtual measure ``vm`` from its coarse plane ``j``: the
    best point in the state ``ws[BV:BVB + 1]``."""
    grid = int(ws[GRID])
    eo, el, er = _entry(tab, j), _entry(tab, max(j - 1, 0)), _entry(tab, min(j + 1, grid - 1))
    ws[BV], ws[BZ], ws[BT], ws[BK], ws[EX] = (ws[eo + EV + vm], ws[eo + EZ], ws[eo + ET + vm],
                                              ws[eo + EK + vm], 0.0)
    ws[AZ], ws[AV] = ws[el + EZ], ws[el + EV + vm]
    ws[BZB], ws[BVB] = ws[er + EZ], ws[er + EV + vm]
    if not math.isfinite(ws[BV]):
        return
    coarse_parabola(tab, ws, vm, ct, st)
    nested_grids(tab, ws, max_levels, vm, ct, st)
    final_parabola(tab, ws, vm, ct, st)
    settle(tab, ws, vm, ct, st)


@_jit
def second_minimum(tab, ws, vm):
    """``second_minima`` of row ``vm`` in the coarse planes: ``(j, j2, second)``."""
    grid = int(ws[GRID])
    cv, step = _entry(tab, 0) + EV + vm, _entry(tab, 1) - _entry(tab, 0)
    j = 0
    for i in range(1, grid):
        if ws[cv + i * step] < ws[cv + j * step]:
            j = i
    j2, v2min = 0, np.inf
    finite_max = -np.inf
    for i in range(grid):
        vi = ws[cv + i * step]
        if math.isfinite(vi):
            finite_max = max(finite_max, vi)
            left = ws[cv + (i - 1) * step] if i > 0 else np.inf
            right = ws[cv + (i + 1) * step] if i < grid - 1 else np.inf
            if vi <= left and vi <= right and abs(i - j) > 1 and vi < v2min:
                j2, v2min = i, vi
    vj = ws[cv + j * step]
    return j, j2, math.isfinite(v2min) and v2min - vj <= 0.25 * (finite_max - vj)


@_jit
def coarse_grid(tab, ws, pitch, whole, ct, st):
    """The coarse planes' minima over ``t`` (of the whole flank and its ends where
    ``whole``, of the pitch line where ``pitch``); the planes kept beyond them dropped."""
    ws[NDYN] = 0.0
    for g in range(int(ws[GRID])):
        eo = _entry(tab, g)
        for q in range(8):
            ws[eo + VALID + q] = 0.0
        if whole:
            over_t(tab, ws, eo + EPL, ct, st, np.bool_(True), np.bool_(True))
            for q in (0, 1, 4, 5, 6, 7):
                keep(ws, eo, q)
        if pitch:
            pitch_line(tab, ws, eo + EPL, ct, st)
            keep(ws, eo, np.int64(2))
            keep(ws, eo, np.int64(3))


@_jit
def at_minimum(tab, ws, z, t, ct, st):
    """Radius and turning rate (``kernel.turning_rate``) of the flank point ``(z, t)``."""
    e = find(tab, ws, z)
    if e >= 0:
        po = _entry(tab, e) + EPL
    else:
        po = _entry(tab, int(ws[GRID]) + MAX_DYN) + EPL
        plane_at(tab, ws, po, z)
    nt = int(tab[NT])
    qx, qy, zq = point(tab, ws, po, ct, st, t)[:3]
    ci, si = tab[CI], tab[SI]
    rq2 = qx * qx + qy * qy
    qk = -si * (qx * st + qy * ct) + zq * ci  # q . k_h, k_h = Rz(-theta) (0, -sin i, cos i)
    return ws[po + nt] + t * ws[po + nt + 1], ((rq2 + zq * zq) * ci - qk * zq) / rq2


@_jit
def minimise_rows(tab, ws, zg, theta, wanted, measures, max_levels, out):
    """Minima of ``measures (M,)`` (indices of ``kernel.MEASURES``) at every turning
    angle ``theta (n,)``, into ``out (6, M, n)``: value, ``z``, ``r``, ``t``, kind, rate.
    ``wanted`` are the virtual measures they fold, ``zg`` the coarse planes."""
    tab, ws = _unmanaged(tab), _unmanaged(ws)
    hf = tab[HF]
    ws[GRID] = zg.size
    whole = pitch = False
    for vm in wanted:
        if vm == 2 or vm == 3:
            pitch = True
        else:
            whole = True
    for g in range(zg.size):
        eo = _entry(tab, g)
        ws[eo + EZ] = zg[g]
        plane_at(tab, ws, eo + EPL, zg[g])
    best = np.empty((8, 4))  # per virtual measure: value, z, t, kind
    for i in range(theta.size):
        ct, st = math.cos(theta[i]), math.sin(theta[i])
        coarse_grid(tab, ws, pitch, whole, ct, st)
        for vm in wanted:
            j, j2, second = second_minimum(tab, ws, vm)
            search(tab, ws, j, max_levels, vm, ct, st)
            if second:  # the better of the two searches
                for q in range(9):
                    ws[SAVED + q] = ws[q]
                search(tab, ws, j2, max_levels, vm, ct, st)
                if not ws[BV] < ws[SAVED + BV]:
                    for q in range(9):
                        ws[q] = ws[SAVED + q]
            best[vm, 0], best[vm, 1], best[vm, 2], best[vm, 3] = ws[BV], ws[BZ], ws[BT], ws[BK]
        for mi in range(measures.size):
            fold = FOLD[measures[mi]]
            b = fold[0]
            for vm in fold[1:]:
                if vm >= 0 and best[vm, 0] < best[b, 0]:
                    b = vm
            v, z, t, k = best[b, 0], best[b, 1], best[b, 2], best[b, 3]
            if k != NONE and abs(abs(z) - hf) <= 1e-12 * hf:
                k = FACE_END
            r, rate = at_minimum(tab, ws, z, t, ct, st)
            out[0, mi, i], out[1, mi, i], out[2, mi, i] = v, z, r
            out[3, mi, i], out[4, mi, i], out[5, mi, i] = t, k, rate
