"""The clearance kernel compiled (numba): one turning angle after another, a row at a time.

Imported only through :func:`.fast.kernels`; the one implementation of the search
(:func:`.kernel.minimise` packs its arguments). :func:`minimise_rows` takes the turning
angles in turn, every (virtual measure, turning angle) row on its own with scalar state -
no numpy call per step, nothing allocated per point:

- **afresh** (:func:`afresh`; at the first angle, after a step above :data:`MAX_TURN`, or
  where a minimum was lost): the coarse planes, the best and a second coarse minimum
  searched over ``z`` (:func:`search`), each result then converged by :func:`track`;
- **followed** (:func:`follow`): each minimum from the place its last two places put it,
  by Newton steps on the slope along ``z`` (in closed form: :func:`slope`), corners by
  the tangents either side (:func:`track`); then :func:`safeguard` checks the coarse
  planes for another minimum, evaluating only those whose kept values and rate bounds
  (:func:`keep_coarse`) leave one possible. A profile-end row that cannot hold its
  measure's minimum is not followed at that angle (:func:`above_best`).

Each measure folds its branches. Inside a plane the minimum over ``t`` is solved to
convergence with the slopes along ``t`` in closed form: Newton steps for the active
interval's crossings (to 1e-11 relative), for an interior minimum the minimum of the
cubic through the ends, then secant steps on the exact slope (to 1e-7 in ``t``). Tested
against the exact reference (:mod:`.reference`), against fresh searches at every angle
(``tests/test_sweep_kernel.py``) and against its frozen outputs
(``tests/test_sweep_frozen.py``; docs/sweep-speed.md).

Two flat arrays carry everything, so that a call passes two arrays: ``tab`` (read only)
holds the constants of :func:`.kernel._compiled_arrays` at the indices below, the table's
piece edges and its plane matrices ``(pieces, nt + 1, nz)``; ``ws`` is the work space:
the search state of a row, scratch, the minima followed, and the planes of the turning
angle with the rows found in them (:func:`evaluate`; a plane at offset ``po``: the ``nt``
coefficients of ``y`` in ``t``, ``r_form``, the span ``r_tip - r_form`` and ``z``, then
their derivatives in ``z`` and whether they are there), then the coarse planes' values
kept over the turning angles. :func:`minimise_rows` passes views of them without
reference counting (:func:`_unmanaged`). Integer and boolean constants are passed as
``np.int64``/``np.bool_``: a literal argument would compile a function once per value.
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
MAX_NZ = 64
TZ, TZD = 86, 150  # T_j(x) of the plane's z and its derivative dT_j/dz, j < MAX_NZ
GRID, NDYN, THETA = 214, 215, 216  # coarse planes; planes evaluated at this turning angle
# beyond them; the turning angle
BASINS = 220  # per virtual measure two minima followed over the turning angles:
B_LIVE, B_Z, B_V, B_T, B_K, B_C, B_ZS, B_ZSP, B_TH, B_THP, B_ZL = range(11)  # followed (1)
# or not; z, value, t, kind; the curvature d2/dz2 there (nan: unknown); where the minimum
# lies by the last step (Newton's, else the tangents') and that of the previous turning
# angle; the turning angles; z at the previous turning angle
BSTRIDE = 11
MODE = BASINS + 16 * BSTRIDE  # per virtual measure: 1 where its minima are followed
COUNTS = MODE + 8  # counts over a call: rows searched afresh, minima lost, planes
# evaluated, of them by the safeguard, searches started by it, plane evaluations tracking
AFRESH, LOST, PLANES, GUARD, GUARD_SEARCH, TRACKED = range(6)
GT, CT = COUNTS + 8, COUNTS + 16  # the 8 rows' slopes along t in a plane: of the gap and
# of the crossing's condition (rq r_form at the sleeve tip edge, zq at a sleeve face end)
TAN_LO, ATAN_LO, TAN_BETA, MARGIN = COUNTS + 24, COUNTS + 25, COUNTS + 26, COUNTS + 27  # of
# the rate bounds (:func:`keep_coarse`): the sleeve's pressure angle at its tip edge, the
# hub profile's largest angle to the radial, the window with the points' polar angles
ENTRIES = COUNTS + 28  # the planes of this turning angle (_entry), the coarse ones first
EZ, VALID, EV, ET, EK, ED, EGT, ECT, EPL = 0, 1, 9, 17, 25, 33, 41, 49, 57  # an entry: z,
# which rows are known, their value, t, kind, slope d/dz and slopes along t, the plane
L_TH, L_V, L_D, L_RHO = 0, 8, 16, 24  # a coarse plane's last values (:func:`keep_coarse`):
# per row the turning angle, value, bound on its rate and the angle span the bound holds
L_FACE = 32  # whether the plane stays within the sleeve face (whole flank, pitch point)
L_RMAX = 34  # a bound on the sleeve radius of its points
L_TAN = 35  # tan and the angle of the sleeve's largest pressure angle its points meet
LSTRIDE = 37
MAX_DYN = 256  # planes kept beyond the coarse ones (then one more, kept for nothing)
D_SLOPE = 1e-6  # shortest interval searched inside, / 8
REL = 1e-11  # crossings, relative to the target
MAX_TURN = 0.1  # turning angle step (rad) beyond which a row is searched afresh
WINDOW = 0.1  # turning angles (rad) either side over which a coarse plane's bound holds
MAX_TRACK = 12  # planes of one followed minimum before it is searched afresh
# the branches (virtual measures) each measure folds, -1 padded: the whole flank (0, 1),
# the pitch line (2, 3), the lower (4, 5) and the upper (6, 7) end of the profile
FOLD = ((0, 4, 6), (1, 5, 7), (2, -1, -1), (3, -1, -1))


def workspace_size(grid: int, nt: int) -> int:
    """Length of ``ws`` for ``grid`` coarse planes and ``nt`` coefficients in ``t``."""
    return ENTRIES + (grid + MAX_DYN + 1) * (EPL + 2 * nt + 7) + grid * LSTRIDE


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
    return ENTRIES + e * (EPL + 2 * int(tab[NT]) + 7)


@_jit
def _lazy(tab, ws, g):
    """Offset of coarse plane ``g``'s last values in ``ws``."""
    return _entry(tab, int(ws[GRID]) + MAX_DYN + 1) + g * LSTRIDE


@njit(nogil=True, error_model="numpy", fastmath={"contract", "reassoc"})
def plane_at(tab, ws, po, z, deriv):
    """Put the plane ``z`` at ``ws[po:]``: Chebyshev series in ``z`` (the sums
    reassociated, so vectorised: the same values to rounding); with ``deriv`` also their
    derivatives in ``z`` at ``ws[po + nt + 3:]`` (:func:`with_slopes`)."""
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
    _sums(tab, ws, m0, TZ, po)
    r_form = ws[po + nt]
    dtip = 0.0
    if tab[SPHERE] != 0.0:
        tip = math.sqrt(max(tab[TIPR] * tab[TIPR] - z * z, 0.0))
        dtip = -z / max(tip, TINY)
    else:
        tip = tab[TIPR]
    ws[po + nt + 1] = tip - r_form
    ws[po + nt + 2] = z
    pd = po + nt + 3
    ws[pd + nt + 2] = 1.0 if deriv else 0.0
    if not deriv:
        return
    # T_j'(x) = j U_(j-1)(x): U_0 = 1, U_1 = 2 x, U_(n+1) = 2 x U_n - U_(n-1)
    scale = 2.0 / (hi - lo)
    ws[TZD] = 0.0
    u0, u1 = 1.0, 2.0 * x
    for j in range(1, nz):
        ws[TZD + j] = j * u0 * scale
        u0, u1 = u1, 2.0 * x * u1 - u0
    _sums(tab, ws, m0, TZD, pd)
    ws[pd + nt + 1] = dtip - ws[pd + nt]


@njit(nogil=True, error_model="numpy", fastmath={"contract", "reassoc"})
def _sums(tab, ws, m0, tz, out):
    """``ws[out + i] = sum_j tab[m0 + i nz + j] ws[tz + j]`` for the ``nt + 1`` rows of a
    piece's plane matrix (the sums reassociated, so vectorised)."""
    nt, nz = int(tab[NT]), int(tab[NZ])
    for i in range(nt + 1):
        mi = m0 + i * nz
        acc = 0.0
        for j in range(nz):
            acc += tab[mi + j] * ws[tz + j]
        ws[out + i] = acc


@_jit
def with_slopes(tab, ws, po):
    """The plane at ``po`` with its derivatives in ``z`` (computed where missing)."""
    nt = int(tab[NT])
    if ws[po + 2 * nt + 5] == 0.0:
        plane_at(tab, ws, po, ws[po + nt + 2], np.bool_(True))


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
def point_dz(tab, ws, po, ct, st, t):
    """:func:`point` with its rate along ``z`` at fixed ``t`` instead (the plane's
    derivatives: :func:`with_slopes`); ``y`` and ``dy/dz`` side by side by Horner's rule
    (power form) or Clenshaw's recurrence (Chebyshev form)."""
    nt = int(tab[NT])
    pd = po + nt + 3
    s = 2.0 * t - 1.0
    if tab[POWER] != 0.0:
        y, dy = ws[po + nt - 1], ws[pd + nt - 1]
        for k in range(nt - 2, -1, -1):
            y, dy = y * s + ws[po + k], dy * s + ws[pd + k]
    else:  # b_k = c_k + 2 s b_(k+1) - b_(k+2); the sum is c_0 + s b_1 - b_2
        b1, b2, d1, d2 = 0.0, 0.0, 0.0, 0.0
        for k in range(nt - 1, 0, -1):
            b1, b2 = ws[po + k] + 2.0 * s * b1 - b2, b1
            d1, d2 = ws[pd + k] + 2.0 * s * d1 - d2, d1
        y, dy = ws[po] + s * b1 - b2, ws[pd] + s * d1 - d2
    ci, si = tab[CI], tab[SI]
    r = ws[po + nt] + t * ws[po + nt + 1]
    dr = ws[pd + nt] + t * ws[pd + nt + 1]
    z = ws[po + nt + 2]
    x = math.sqrt(r * r - y * y)
    dx = (r * dr - y * dy) / x
    u, du = x * st + y * ct, dx * st + dy * ct
    v, dv = u * (ci - 1.0) - z * si, du * (ci - 1.0) - si
    return v * st + x, v * ct + y, u * si + z * ci, dv * st + dx, dv * ct + dy, du * si + ci


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
    the circumferential gap ``rq (aq + sigma(rq)/2)``, the normal ``r_b (aq + sigma/2)``)."""
    if tab[RHO] > 0.0 and p[0] * p[0] + p[1] * p[1] > tab[RFIL] * tab[RFIL]:
        return fillet(tab, p)
    return involute(tab, p)


@_jit
def gap_field(tab, rq, aq, circ, normal):
    """:func:`gaps` of the points at sleeve radii ``rq (n,)``, polar angles ``aq (n,)``
    into ``circ``, ``normal`` (``tab``: the sleeve's constants only)."""
    for i in range(rq.size):
        g = gaps(tab, (rq[i] * math.cos(aq[i]), rq[i] * math.sin(aq[i]), 0.0, 0.0, 0.0, 0.0))
        circ[i], normal[i] = g[0], g[1]


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
    """The active interval of the plane: ``(feasible, t_lo, k_lo, p_lo, t_a, k_a, p_a,
    t_hi, k_hi, p_hi)``, with the :func:`point` at each end. ``[t_lo, t_a]`` faces the
    involute, ``[t_a, t_hi]`` the root fillet (empty unless the hub reaches it); the
    interval is cut where the sleeve flank begins (its tip edge, ``r_form``) and at the
    sleeve face ends (the tip chamfer recedes at 45° and never holds the minimum)."""
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
    """Minima over the active interval (:func:`interval`) of the plane at ``po``: the
    whole-flank rows 0, 1 (circumferential, normal) and the profile-end rows 4-7 (both
    gaps at the lower end, then at the upper end alone: branches minimised apart over
    ``z``) into ``ws[V:], ws[T:], ws[K:]``; ``want0``, ``want1``: search the interior of
    the circumferential, normal gap (else only the ends count)."""
    feasible, t_lo, k_lo, p_lo, t_a, k_a, p_a, t_hi, k_hi, p_hi = interval(tab, ws, po, ct, st)
    if not feasible:
        for vm in (0, 1, 4, 5, 6, 7):
            ws[V + vm], ws[T + vm], ws[K + vm] = np.inf, t_lo, NONE
            ws[GT + vm], ws[CT + vm] = 0.0, 0.0
        return
    fa, fh = gaps(tab, p_lo), gaps(tab, p_hi)
    fb = fb_min = fh  # at the upper end of [t_lo, t_a]: the slope and the minimum there
    if t_a != t_hi:
        fb = fb_min = gaps(tab, p_a)
    # the fillet start: the lower of the gaps to the involute and to the fillet (they
    # differ off the sleeve surface, in deep interference; the lower is the limit of the
    # fillet part's minimum)
    if t_lo < t_a < t_hi:
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
    # the slopes along t of the ends' conditions: rq drq/dt at the sleeve tip edge, dzq/dt
    # at a sleeve face end (the slope of a row's minimum along z needs them: slope())
    c_lo = p_lo[0] * p_lo[3] + p_lo[1] * p_lo[4] if k_lo == SLEEVE_TIP else p_lo[5]
    c_hi = p_hi[5]
    for mi in range(2):
        v, t, k, gt, cs = fa[mi], t_lo, k_lo, fa[2 + mi], c_lo
        if fb_min[mi] < v:
            v, t, k, gt, cs = fb_min[mi], t_a, k_a, 0.0, 0.0
        if fh[mi] < v:
            v, t, k, gt, cs = fh[mi], t_hi, k_hi, fh[2 + mi], c_hi
        if fi[mi] < v:
            v, t, k, gt, cs = fi[mi], ti[mi], INTERIOR, 0.0, 0.0
        ws[V + mi], ws[T + mi], ws[K + mi], ws[GT + mi], ws[CT + mi] = v, t, k, gt, cs
        ws[V + 4 + mi], ws[T + 4 + mi], ws[K + 4 + mi] = fa[mi], t_lo, k_lo
        ws[GT + 4 + mi], ws[CT + 4 + mi] = fa[2 + mi], c_lo
        ws[V + 6 + mi], ws[T + 6 + mi], ws[K + 6 + mi] = fh[mi], t_hi, k_hi
        ws[GT + 6 + mi], ws[CT + 6 + mi] = fh[2 + mi], c_hi


@_jit
def pitch_line(tab, ws, po, ct, st):
    """Both gaps on the pitch circle ``r = R`` of the plane (rows 2, 3 of ``ws[V:],
    ws[T:], ws[K:]``; inf where it does not face the sleeve flank)."""
    nt = int(tab[NT])
    t = (tab[RPITCH] - ws[po + nt]) / ws[po + nt + 1]
    p = point(tab, ws, po, ct, st, min(max(t, 0.0), 1.0))
    rq, zq = radius_z(p)[:2]
    ok = t >= 0 and t <= 1 and rq >= tab[RFORM] and abs(zq) <= tab[SHF]
    circ, normal, dcirc, dnormal = gaps(tab, p)
    ws[V + 2], ws[V + 3] = (circ, normal) if ok else (np.inf, np.inf)
    ws[T + 2], ws[T + 3] = t, t
    ws[GT + 2], ws[GT + 3] = dcirc, dnormal
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
    ws[eo + EGT + vm], ws[eo + ECT + vm] = ws[GT + vm], ws[CT + vm]
    ws[eo + VALID + vm] = 1.0


@_jit
def evaluate(tab, ws, z, vm, ct, st, deriv):
    """Minimum of virtual measure ``vm`` in the plane ``z``: ``(value, t, kind, entry
    offset)``. Each plane is kept with the rows found in it (rows of a turning angle
    evaluate the same planes: the profile ends come with the whole flank, and a row whose
    values equal another's takes the same steps); a row already found is read, else found
    in the plane kept (a new plane with its derivatives in ``z`` where ``deriv``). The
    rows found in a coarse plane are kept beyond the turning angle too
    (:func:`keep_coarse`)."""
    e = find(tab, ws, z)
    if e < 0:
        e = int(ws[GRID] + ws[NDYN])
        if ws[NDYN] < MAX_DYN:
            ws[NDYN] += 1.0
        eo = _entry(tab, e)
        ws[eo + EZ] = z
        for q in range(8):
            ws[eo + VALID + q] = 0.0
        plane_at(tab, ws, eo + EPL, z, deriv)
        ws[COUNTS + PLANES] += 1.0
    else:
        eo = _entry(tab, e)
        if ws[eo + VALID + vm] != 0.0:
            return ws[eo + EV + vm], ws[eo + ET + vm], ws[eo + EK + vm], eo
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
    if e < int(ws[GRID]):
        keep_coarse(tab, ws, e, vm, ct, st)
    return ws[V + vm], ws[T + vm], ws[K + vm], eo


@_jit
def points(tab, ws, m, vm, ct, st):
    """Evaluate the planes ``ws[ZS:ZS + m]`` and keep the best where it improves the
    state: ``(index of the best, better)``."""
    for i in range(m):
        ws[VS + i], ws[TS + i], ws[KS + i] = evaluate(tab, ws, ws[ZS + i], vm, ct, st,
                                                      np.bool_(False))[:3]
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
    """Smooth minima: a step to the vertex of the coarse parabola, bracketed by
    ``+-delta``, ``delta = sqrt(tol / g'')``, so that a bracket around the true minimum
    closes at once."""
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
    """Smooth minima: the vertex of the parabola through the best point of the level at
    ``ws[ALLZ:], ws[ALLV:]`` and its neighbours, bracketed by ``+-sqrt(tol / g'')``."""
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
    """Corner minima (an end of the active interval switches kind): the secants of the
    two branches either side of the best point of the level intersected and bracketed by
    ``+-eps``, ``eps = tol / slope``."""
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
    plane_at(tab, ws, po, z, np.bool_(False))
    return radius_z(point(tab, ws, po, ct, st, 0.0))[0] - tab[RFORM]


@_jit
def corner_step(tab, ws, vm, ct, st):
    """Corner minima where the lower end switches from the hub form circle to the sleeve
    tip edge: ``rq(z, t=0) = r_form`` solved in the bracket (secant), bracketed by
    ``+-eps``, ``eps = tol / (2 slope)``."""
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
    """Smooth minima next to a kink that spoiled the coarse parabola: a parabola from
    the best point and two close neighbours (+-1e-3 of the half face), then a triple
    around its vertex, ``+-sqrt(tol / g'')``."""
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
    """Nested grids of 4 planes in the bracket, with a corner and a parabola step at each
    level, until the bracket cannot hide more than the tolerance; the first level tries
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
    """A last parabolic step through the bracket (smooth minima)."""
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
    """A minimum that crept to a face end sits on it (the value moves by slope * 1e-8
    hf); the minimum is evaluated exactly where it lies (coarse values are upper bounds;
    a refined value is kept where lower)."""
    hf = tab[HF]
    bz = ws[BZ]
    near_end = abs(bz) >= hf * (1.0 - 1e-8)
    if near_end:
        ws[BZ] = math.copysign(hf, bz)
        ws[EX] = 0.0
    if ws[EX] == 0.0:
        ve, te, ke = evaluate(tab, ws, ws[BZ], vm, ct, st, np.bool_(False))[:3]
        if ve <= ws[BV] + 1e-7 * tab[TOL] or near_end:
            ws[BV], ws[BT], ws[BK] = ve, te, ke


@_jit
def search(tab, ws, j, max_levels, vm, ct, st):
    """The search over ``z`` of the row of virtual measure ``vm`` from its coarse plane
    ``j``, its bracket the neighbouring planes: parabolic steps bracketed by
    ``+-sqrt(tol / g'')``, a local parabola for minima beside a kink, corner steps, nested
    grids, until the bracket cannot hide more than the tolerance. The best point in the
    state ``ws[BV:BVB + 1]`` (value, ``z``, ``t``, kind, whether evaluated; the bracket
    ``a_z, a_v, b_z, b_v``)."""
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
    """The best coarse plane ``j`` of row ``vm``, and a second coarse local minimum
    ``j2`` nearly as low (two nearly equal minima, e.g. tip edge and form circle on a
    swing tooth), refined too where ``second``: ``(j, j2, second)``."""
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
def abs_cos_max(a, b):
    """The largest ``|cos|`` on ``[a, b]`` (``b - a < pi``)."""
    if math.floor(b / math.pi) > math.floor(a / math.pi):
        return 1.0
    return max(abs(math.cos(a)), abs(math.cos(b)))


@_jit
def abs_sin_max(a, b):
    """The largest ``|sin|`` on ``[a, b]`` (``b - a < pi``)."""
    return abs_cos_max(a - 0.5 * math.pi, b - 0.5 * math.pi)


@_jit
def keep_coarse(tab, ws, g, vm, ct, st):
    """Keep the rows just found in coarse plane ``g`` (those of ``vm``'s group) beyond
    this turning angle: each row's value with a bound ``D`` on its rate over the turning
    angle and the angle span ``rho`` (at most :data:`WINDOW`) over which that bound
    holds, so that at an angle ``theta`` its value is at least ``value - D |theta -
    theta_g|`` while ``|theta - theta_g| < rho`` (:func:`safeguard`).

    The gaps depend on the point's sleeve-frame ``(qx, qy)`` only. Turning by ``d theta``
    moves a hub point there by ``v (cos theta, -sin theta) + v' (sin theta, cos theta)``
    (``|v| <= r (1 - cos i) + |z| sin i``, ``|v'| <= r (1 - cos i)``); with ``phi = theta +
    aq`` the gaps' gradients give the rates ``|(delta - tan alpha) cos phi - sin phi|``
    (circumferential, ``delta`` the gap angle, ``alpha`` the sleeve's pressure angle at
    the point) and ``|sin(phi + alpha)|`` (normal) per unit ``|v|``, bounded over the
    window's ``phi`` and the flank's ``alpha``. The lower end may instead lie on the
    sleeve tip edge (``rq = r_form``), which it follows: there the gaps change with the
    tangential motion alone, the point's and that of the shift along the profile, at most
    ``|v| (|sin phi| + tan beta |cos phi|) + |v'| (1 + tan beta)`` (``beta`` the hub
    profile's angle to the radial); a minimum over the active interval, or at its lower
    end, takes the larger bound. The bound holds where the plane stays within the sleeve
    face (``rho = 0`` else), off the root fillet and, where no point faces the sleeve
    flank, until one may."""
    lo = _lazy(tab, ws, g)
    eo = _entry(tab, g)
    po = eo + EPL
    nt = int(tab[NT])
    ci, si = tab[CI], tab[SI]
    z = ws[po + nt + 2]
    rt = ws[po + nt] + ws[po + nt + 1]
    v_r = rt * (1.0 - ci)
    v_z = v_r + abs(z) * si
    rate = v_r + v_z
    r_fil, r_form = tab[RFIL], tab[RFORM]
    tan_hi, tan_beta = ws[lo + L_TAN], ws[TAN_BETA]
    phi_lo, phi_hi = ws[THETA] - ws[MARGIN], ws[THETA] + ws[MARGIN]
    cos_m, sin_m = abs_cos_max(phi_lo, phi_hi), abs_sin_max(phi_lo, phi_hi)
    sin_n = abs_sin_max(phi_lo + ws[ATAN_LO], phi_hi + ws[lo + L_TAN + 1])
    pitch = vm == 2 or vm == 3
    rq1 = -1.0  # the sleeve radius at the profile's top (the pitch point), where needed
    for q in range(8):
        if (q == 2 or q == 3) != pitch or ws[eo + VALID + q] == 0.0:
            continue
        val = ws[eo + EV + q]
        ws[lo + L_TH + q], ws[lo + L_V + q] = ws[THETA], val
        span = WINDOW
        if ws[lo + L_FACE + (1 if pitch else 0)] == 0.0:
            span = 0.0
        delta = abs(val) / r_form + 0.01 if math.isfinite(val) else 0.01
        if delta > 0.2:
            span = 0.0
        if q % 2:
            d = v_z * sin_n + v_r
        else:
            d = v_z * ((tan_hi + delta) * cos_m + sin_m) + v_r * math.sqrt(
                1.0 + (tan_hi + delta) ** 2)
        if not (q == 2 or q == 3 or q >= 6):  # the lower end on the tip edge's crossing
            d = max(d, v_z * (sin_m + tan_beta * cos_m) + v_r * (1.0 + tan_beta))
        if not math.isfinite(val) or (tab[RHO] > 0.0 and ws[lo + L_RMAX] >= r_fil):
            if rq1 < 0.0:
                t1 = 1.0
                if pitch:
                    t1 = min(max((tab[RPITCH] - ws[po + nt]) / ws[po + nt + 1], 0.0), 1.0)
                p1 = point(tab, ws, po, ct, st, t1)
                rq1 = math.sqrt(p1[0] * p1[0] + p1[1] * p1[1])
            if not math.isfinite(val):  # none faces the sleeve flank until rq1 reaches it
                span = min(span, max(r_form - rq1, 0.0) / max(rate, TINY))
            if tab[RHO] > 0.0 and ws[lo + L_RMAX] >= r_fil:
                span = min(span, max(r_fil - rq1, 0.0) / max(rate, TINY))
        ws[lo + L_D + q] = d
        ws[lo + L_RHO + q] = span if rate > 0.0 else np.inf


@_jit
def init_coarse(tab, ws, zg):
    """The coarse planes (with their derivatives in ``z``), none of their rows known yet,
    and what of them holds at every turning angle: whether the plane stays within the
    sleeve face (whole flank, pitch point) and a bound on its points' sleeve radius."""
    nt = int(tab[NT])
    ci, si, shf = tab[CI], tab[SI], tab[SHF]
    r_b = tab[RB]
    ws[GRID] = zg.size
    ws[TAN_LO] = math.sqrt(max(tab[RFORM] ** 2 - r_b * r_b, 0.0)) / r_b
    ws[ATAN_LO] = math.atan(ws[TAN_LO])
    ws[TAN_BETA] = math.sqrt(max(tab[TIPR] ** 2 - r_b * r_b, 0.0)) / r_b + 0.05
    ws[MARGIN] = WINDOW + abs(tab[C0]) + 0.05  # the window and the points' polar angles
    for g in range(zg.size):
        eo = _entry(tab, g)
        ws[eo + EZ] = zg[g]
        plane_at(tab, ws, eo + EPL, zg[g], np.bool_(True))
        lo = _lazy(tab, ws, g)
        for q in range(L_FACE):
            ws[lo + q] = np.nan
        rt = ws[eo + EPL + nt] + ws[eo + EPL + nt + 1]
        z = abs(zg[g])
        ws[lo + L_FACE] = 1.0 if z * ci + rt * si < shf else 0.0
        ws[lo + L_FACE + 1] = 1.0 if z * ci + tab[RPITCH] * si < shf else 0.0
        # |q| = |p| and |zq| >= |z| cos i - r sin i
        ws[lo + L_RMAX] = math.sqrt(rt * rt + z * z - max(z * ci - rt * si, 0.0) ** 2)
        ws[lo + L_TAN] = math.sqrt(max(max(tab[RFIL], rt) ** 2 - r_b * r_b, 0.0)) / r_b
        ws[lo + L_TAN + 1] = math.atan(ws[lo + L_TAN])


@_jit
def new_angle(tab, ws, theta):
    """Start turning angle ``theta``: no plane evaluated at it yet."""
    ws[THETA] = theta
    ws[NDYN] = 0.0
    for g in range(int(ws[GRID])):
        eo = _entry(tab, g)
        for q in range(8):
            ws[eo + VALID + q] = 0.0


@_jit
def row_at(tab, ws, z, vm, ct, st):
    """Row ``vm``'s minimum in the plane ``z`` with its slope along ``z``: ``(value, t,
    kind, slope)``; the slope nan where it is not known in closed form (the root fillet)."""
    ws[COUNTS + TRACKED] += 1.0
    v, t, k, eo = evaluate(tab, ws, z, vm, ct, st, np.bool_(True))
    if ws[eo + VALID + vm] != 2.0:  # the slope of this row not found yet
        d = slope(tab, ws, eo, vm, t, k, ct, st)
        for q in range(vm % 2, 8, 2):  # and of the rows of the gap with the same minimum
            if ws[eo + VALID + q] == 1.0 and ws[eo + ET + q] == t and ws[eo + EK + q] == k \
                    and (q == 2 or q == 3) == (vm == 2 or vm == 3):
                ws[eo + ED + q], ws[eo + VALID + q] = d, 2.0
        ws[eo + ED + vm], ws[eo + VALID + vm] = d, 2.0
    return v, t, k, ws[eo + ED + vm]


@_jit
def slope(tab, ws, eo, vm, t, k, ct, st):
    """``d/dz`` of row ``vm``'s minimum in the plane of entry ``eo``, found at ``(t, k)``:
    the gap's partial derivative in ``z`` at an interior minimum or a fixed end (``t`` = 0,
    1); at a crossing (sleeve tip edge, sleeve face end) and on the pitch line plus the
    gap's slope along ``t`` times ``dt/dz`` of the crossing's condition (the slopes along
    ``t`` as :func:`over_t` and :func:`pitch_line` found them)."""
    if k == NONE or k == SLEEVE_FILLET or k == FACE_END:
        return np.nan
    po = eo + EPL
    with_slopes(tab, ws, po)
    nt = int(tab[NT])
    pz = point_dz(tab, ws, po, ct, st, t)
    gz = gaps(tab, pz)[2 + vm % 2]
    gt = ws[eo + EGT + vm]
    if vm == 2 or vm == 3:
        pd = po + nt + 3
        return gz - gt * (ws[pd + nt] + t * ws[pd + nt + 1]) / ws[po + nt + 1]
    if k == SLEEVE_TIP:
        return gz - gt * (pz[0] * pz[3] + pz[1] * pz[4]) / ws[eo + ECT + vm]
    if k == SLEEVE_FACE:
        return gz - gt * pz[5] / ws[eo + ECT + vm]
    return gz


@_jit
def track(tab, ws, vm, z0, step, curv, kind, ct, st):
    """The minimum of row ``vm`` near ``z0`` over ``z``: ``(found, z, value, t, kind,
    curvature, place)`` (curvature nan where not known; place: where the minimum lies by
    the last Newton step or the tangents, not evaluated).

    From ``z0`` Newton steps on the slope (:func:`row_at`), the curvature from the last
    two planes of one kind (``curv`` of the minimum of ``kind`` to begin with), else
    steps of ``step`` growing fourfold; once planes either side of the minimum are known
    (slopes of opposite signs), a step leaving them falls back to their middle, and where
    their kinds differ (a corner: an end of the active interval switches kind) the step
    goes to where their tangents meet. Found when the tangents cannot hide a value lower
    by ``eps`` = 1e-3 of the tolerance, or the Newton step's decrease is below it, or a
    face end holds a slope pointing out of the face (the Newton step's decrease counts only
    within one piece of the table, :func:`one_piece`). Not found where a plane faces no
    sleeve flank, a slope is not known, the slopes are not those of one minimum, or
    after :data:`MAX_TRACK` planes."""
    hf = tab[HF]
    eps = max(1e-3 * tab[TOL], 1e-14)
    fail = (False, 0.0, np.inf, 0.0, float(NONE), np.nan, 0.0)
    z = min(max(z0, -hf), hf)
    v, t, k, d = row_at(tab, ws, z, vm, ct, st)
    if not (math.isfinite(v) and math.isfinite(d)):
        return fail
    zb, vb, tb, kb, db = z, v, t, k, d
    zl, vl, dl, kl, zh, vh, dh, kh = np.nan, 0.0, 0.0, -1.0, np.nan, 0.0, 0.0, -1.0
    if d < 0.0:
        zl, vl, dl, kl = z, v, d, k
    elif d > 0.0:
        zh, vh, dh, kh = z, v, d, k
    c, ck = (curv, kind) if curv > 0.0 else (np.nan, -1.0)
    ca = cb = z  # the planes the curvature was measured between
    zp, dp, kp = z, d, k
    h = max(step, 1e-9 * hf)
    for _ in range(MAX_TRACK):
        newton = c > 0.0 and ck == kb
        if db == 0.0 or (zb >= hf and db <= 0.0) or (zb <= -hf and db >= 0.0):
            return True, zb, vb, tb, kb, c if newton else np.nan, zb
        both = math.isfinite(zl) and math.isfinite(zh)
        zx = np.nan
        if both:
            zx = (vh - vl + dl * zl - dh * zh) / (dl - dh)
            if vb - (vl + dl * (zx - zl)) <= eps:
                place = min(max(zb - db / c, zl), zh) if newton and kl == kh else zx
                return True, zb, vb, tb, kb, c if newton else np.nan, place
        if newton and db * db <= 2.0 * c * eps and one_piece(
                tab, min(ca, cb, zb, zb - db / c), max(ca, cb, zb, zb - db / c)):
            return True, zb, vb, tb, kb, c, zb - db / c
        if newton:
            zn = zb - db / c
        else:
            zn = zb - math.copysign(h, db)
            h *= 4.0
        if both:
            if kl != kh and zl < zx < zh:
                zn = zx
            elif not (zl < zn < zh):
                zn = 0.5 * (zl + zh)
        zn = min(max(zn, -hf), hf)
        if zn == zb:
            return fail
        v, t, k, d = row_at(tab, ws, zn, vm, ct, st)
        if not (math.isfinite(v) and math.isfinite(d)):
            return fail
        if k == kp and zn != zp:
            c, ck, ca, cb = (d - dp) / (zn - zp), k, zn, zp
            if not c > 0.0:
                c, ck = np.nan, -1.0
        zp, dp, kp = zn, d, k
        if d < 0.0 and not zn <= zl:
            zl, vl, dl, kl = zn, v, d, k
        elif d > 0.0 and not zn >= zh:
            zh, vh, dh, kh = zn, v, d, k
        if zl >= zh:
            return fail  # a slope pointing down past one pointing up: not one minimum
        if v < vb or (v == vb and abs(d) < abs(db)):
            zb, vb, tb, kb, db = zn, v, t, k, d
    return fail


@_jit
def one_piece(tab, z0, z1):
    """Whether ``[z0, z1]`` lies inside one piece of the table wider than a tenth of the
    face (the narrow pieces carry a curvature jump inside, the others at their edges):
    there the flank is smooth and a Newton step's curvature holds."""
    pieces, hf = int(tab[PIECES]), tab[HF]
    for j in range(pieces):
        lo, hi = tab[EDGES + j], tab[EDGES + j + 1]
        if (j == 0 or z0 > lo) and (j == pieces - 1 or z1 < hi) and z0 >= lo and z1 <= hi:
            return hi - lo >= 0.2 * hf
    return False


@_jit
def smooth_around(tab, ws, vm, z, reach):
    """Whether the coarse planes within ``reach`` of ``z`` leave row ``vm`` smooth there:
    none may leave the sleeve face (its cut makes kinks and ends of the row's domain a
    fraction of a spacing apart, minima a Newton step from one does not see), none faced
    no sleeve flank or had no rate bound when last evaluated (the root fillet, deep
    interference): there the row is searched afresh at each turning angle, as the
    nested grids of :func:`search` look between the planes."""
    pitch = vm == 2 or vm == 3
    for g in range(int(ws[GRID])):
        if abs(ws[_entry(tab, g)] - z) <= reach:
            lo = _lazy(tab, ws, g)
            if ws[lo + L_FACE + (1 if pitch else 0)] == 0.0 or ws[lo + L_RHO + vm] == 0.0 \
                    or not math.isfinite(ws[lo + L_V + vm]):
                return False
    return True


@_jit
def across_edge(tab, ws, vm, found, z, v, t, k, c, place, near_edge, ct, st):
    """A minimum within ``near_edge`` of a piece edge of the table may have a twin just
    across it (the pieces meet within the table's error, not exactly): the lower of the
    two, :func:`track` from across the edge (the arguments: the minimum found)."""
    for j in range(1, int(tab[PIECES])):
        e = tab[EDGES + j]
        if abs(z - e) <= near_edge:
            other = e + math.copysign(abs(z - e) + 1e-6 * near_edge, e - z)
            r = track(tab, ws, vm, other, near_edge, np.nan, -1.0, ct, st)
            if r[0] and r[2] < v:
                return r
    return found, z, v, t, k, c, place


@_jit
def basin(vm, b):
    """Offset of followed minimum ``b`` (0, 1) of row ``vm`` in ``ws``."""
    return BASINS + (2 * vm + b) * BSTRIDE


@_jit
def set_basin(ws, bo, found, z, v, t, k, c, place):
    """Put a minimum found at this turning angle in the slot at ``bo``."""
    theta = ws[THETA]
    same = ws[bo + B_LIVE] != 0.0 and ws[bo + B_TH] != theta
    ws[bo + B_ZSP], ws[bo + B_THP] = (ws[bo + B_ZS], ws[bo + B_TH]) if same else (place, np.nan)
    ws[bo + B_ZL] = ws[bo + B_Z] if same else np.nan
    ws[bo + B_LIVE] = 1.0 if found else 0.0
    ws[bo + B_Z], ws[bo + B_V], ws[bo + B_T], ws[bo + B_K] = z, v, t, k
    ws[bo + B_C], ws[bo + B_ZS], ws[bo + B_TH] = c, place, theta


@_jit
def follow(tab, ws, vm, ct, st):
    """Follow row ``vm``'s minima to this turning angle, each from its last place moved on
    as its last two places moved (:func:`track`); False where the best one is lost (a
    second one lost is dropped, and one found farther from where it was expected than
    four times its move or a quarter of a coarse spacing, or where the planes around it
    are not smooth (:func:`smooth_around`), is lost). A row facing no sleeve flank has none
    to follow."""
    theta = ws[THETA]
    hf = tab[HF]
    spacing = 2.0 * hf / (ws[GRID] - 1.0)
    for b in range(2):
        bo = basin(vm, b)
        if ws[bo + B_LIVE] == 0.0:
            if b == 0 and math.isfinite(ws[bo + B_V]):
                return False
            continue
        z = ws[bo + B_ZS]
        if not smooth_around(tab, ws, vm, ws[bo + B_Z], 1.5 * spacing):
            found = False  # lost before a plane is spent on it
            ws[COUNTS + LOST] += 1.0
            if b == 0:
                return False
            ws[bo + B_LIVE] = 0.0
            continue
        move = 0.0
        if math.isfinite(ws[bo + B_THP]) and ws[bo + B_TH] != ws[bo + B_THP]:
            move = (z - ws[bo + B_ZSP]) * (theta - ws[bo + B_TH]) / (ws[bo + B_TH]
                                                                     - ws[bo + B_THP])
        z0 = shared_start(ws, vm, ws[bo + B_Z], theta)
        found, zn, v, t, k, c, place = track(tab, ws, vm, z + move if math.isnan(z0) else z0,
                                             max(abs(move), 1e-6 * hf), ws[bo + B_C],
                                             ws[bo + B_K], ct, st)
        # a minimum far from where its last two places put it is another one
        found = found and abs(zn - z - move) <= max(4.0 * abs(move), 0.25 * spacing) and \
            smooth_around(tab, ws, vm, zn, 1.5 * spacing)
        if found:
            found, zn, v, t, k, c, place = across_edge(tab, ws, vm, found, zn, v, t, k, c,
                                                       place, 0.01 * spacing, ct, st)
        if not found:
            ws[COUNTS + LOST] += 1.0
            if b == 0:
                return False
            ws[bo + B_LIVE] = 0.0
            continue
        set_basin(ws, bo, True, zn, v, t, k, c, place)
    order(tab, ws, vm)
    return True


@_jit
def shared_start(ws, vm, z_last, theta):
    """Where a row followed before ``vm`` at this turning angle (of its group: whole
    flank, pitch line), whose minimum lay at ``z_last`` too at the last one, found it now
    (its plane is kept: a row whose minimum is another's takes no plane of its own); nan
    where none."""
    for u in range(vm):
        if (u == 2 or u == 3) != (vm == 2 or vm == 3):
            continue
        for b in range(2):
            bo = basin(u, b)
            if ws[bo + B_LIVE] != 0.0 and ws[bo + B_TH] == theta and ws[bo + B_ZL] == z_last:
                return ws[bo + B_Z]
    return np.nan


@_jit
def order(tab, ws, vm):
    """The better minimum of row ``vm`` first (of those followed or found at this turning
    angle); a second one at the first's place dropped."""
    b0, b1 = basin(vm, 0), basin(vm, 1)
    if ws[b1 + B_LIVE] == 0.0 and ws[b1 + B_TH] != ws[THETA]:
        return
    if ws[b1 + B_LIVE] != 0.0 and ws[b0 + B_LIVE] != 0.0 and \
            abs(ws[b1 + B_Z] - ws[b0 + B_Z]) <= 1e-9 * tab[HF]:
        ws[b1 + B_LIVE] = 0.0
        return
    if ws[b1 + B_V] < ws[b0 + B_V]:
        for q in range(BSTRIDE):
            ws[b0 + q], ws[b1 + q] = ws[b1 + q], ws[b0 + q]


@_jit
def searched(tab, ws, j, max_levels, vm, ct, st):
    """:func:`search` from coarse plane ``j``, its minimum then converged by
    :func:`track`: ``(followed, z, value, t, kind, curvature, place)`` (not followed
    where :func:`track` did not converge: the search's own minimum)."""
    search(tab, ws, j, max_levels, vm, ct, st)
    z, v, t, k = ws[BZ], ws[BV], ws[BT], ws[BK]
    if not math.isfinite(v):
        return False, z, v, t, k, np.nan, z
    # the curvature of the parabola through the bracket, where it brackets
    za, va, zb, vb = ws[AZ], ws[AV], ws[BZB], ws[BVB]
    curv, step = np.nan, 1e-4 * tab[HF]
    if za < z < zb and math.isfinite(va) and math.isfinite(vb):
        curv = 2.0 * ((vb - v) / (zb - z) - (v - va) / (z - za)) / (zb - za)
        step = min(step, 0.25 * (zb - za))
    found, zn, vn, tn, kn, c, place = track(tab, ws, vm, z, step, curv, k, ct, st)
    if found and vn <= v:
        return True, zn, vn, tn, kn, c, place
    return False, z, v, t, k, np.nan, z


@_jit
def afresh(tab, ws, vm, max_levels, ct, st):
    """Row ``vm`` searched afresh: every coarse plane, the best and a second coarse
    minimum nearly as low (:func:`second_minimum`) searched (:func:`searched`), both kept
    to be followed."""
    ws[COUNTS + AFRESH] += 1.0
    for g in range(int(ws[GRID])):
        evaluate(tab, ws, ws[_entry(tab, g)], vm, ct, st, np.bool_(False))
    j, j2, second = second_minimum(tab, ws, vm)
    for b in range(2):
        ws[basin(vm, b) + B_LIVE] = 0.0
    found, z, v, t, k, c, place = searched(tab, ws, j, max_levels, vm, ct, st)
    set_basin(ws, basin(vm, 0), found, z, v, t, k, c, place)
    if second:
        found, z, v, t, k, c, place = searched(tab, ws, j2, max_levels, vm, ct, st)
        set_basin(ws, basin(vm, 1), found, z, v, t, k, c, place)
    order(tab, ws, vm)
    ws[MODE + vm] = 1.0 if ws[basin(vm, 0) + B_LIVE] != 0.0 or not math.isfinite(
        ws[basin(vm, 0) + B_V]) else 0.0


@_jit
def near(tab, ws, vm, z):
    """Whether ``z`` is within 1.5 coarse spacings of a minimum of row ``vm``."""
    h = 2.0 * tab[HF] / (ws[GRID] - 1.0)
    for b in range(2):
        bo = basin(vm, b)
        if (b == 0 or ws[bo + B_LIVE] != 0.0) and math.isfinite(ws[bo + B_V]) and \
                abs(z - ws[bo + B_Z]) <= 1.5 * h:
            return True
    return False


@_jit
def above(tab, ws, g, vm):
    """A bound from above on coarse plane ``g``'s value of row ``vm`` at this turning
    angle (inf where none holds)."""
    if g < 0 or g >= int(ws[GRID]):
        return np.inf
    eo = _entry(tab, g)
    if ws[eo + VALID + vm] != 0.0:
        return ws[eo + EV + vm]
    lo = _lazy(tab, ws, g)
    age = abs(ws[THETA] - ws[lo + L_TH + vm])
    if not age < ws[lo + L_RHO + vm]:
        return np.inf
    return ws[lo + L_V + vm] + ws[lo + L_D + vm] * age


@_jit
def safeguard(tab, ws, vm, max_levels, ct, st):
    """Row ``vm``'s minima its followed ones miss: a coarse plane away from
    them (more than 1.5 spacings) that is a local minimum of the coarse planes and within
    a quarter of their range above the best (as a second coarse minimum searched afresh,
    :func:`second_minimum`) is searched and followed from then on. A plane is evaluated
    only where its bounds (:func:`keep_coarse`) leave that possible: its value at least
    ``value - D age`` could be at or below the threshold and at or below both
    neighbours' values at most ``value + D age``."""
    grid = int(ws[GRID])
    best = ws[basin(vm, 0) + B_V]
    top = -np.inf
    for g in range(grid):
        val = ws[_lazy(tab, ws, g) + L_V + vm]
        if math.isfinite(val) and val > top:
            top = val
    limit = np.inf
    if math.isfinite(best):
        limit = best + 0.25 * max(top - best, 0.0) + tab[TOL]
    for g in range(grid):
        eo = _entry(tab, g)
        z = ws[eo + EZ]
        if near(tab, ws, vm, z):
            continue
        if ws[eo + VALID + vm] == 0.0:  # not evaluated at this turning angle yet
            lo = _lazy(tab, ws, g)
            age = abs(ws[THETA] - ws[lo + L_TH + vm])
            if age < ws[lo + L_RHO + vm]:
                val = ws[lo + L_V + vm]
                if not math.isfinite(val):
                    continue  # facing no sleeve flank until its span ends
                low = val - ws[lo + L_D + vm] * age
                if low > limit or low > above(tab, ws, g - 1, vm) or \
                        low > above(tab, ws, g + 1, vm):
                    continue
            ws[COUNTS + GUARD] += 1.0
            evaluate(tab, ws, z, vm, ct, st, np.bool_(False))
        v = ws[eo + EV + vm]
        if not v <= limit:
            continue
        for n in (g - 1, g + 1):  # a neighbour evaluated where its bound cannot tell
            if v <= above(tab, ws, g - 1, vm) and v <= above(tab, ws, g + 1, vm) and \
                    0 <= n < grid:
                evaluate(tab, ws, ws[_entry(tab, n)], vm, ct, st, np.bool_(False))
        if v <= above(tab, ws, g - 1, vm) and v <= above(tab, ws, g + 1, vm):
            ws[COUNTS + GUARD_SEARCH] += 1.0
            found, zn, vn, tn, kn, c, place = searched(tab, ws, g, max_levels, vm, ct, st)
            b1 = basin(vm, 1)
            if ws[b1 + B_LIVE] == 0.0 or vn < ws[b1 + B_V]:
                ws[b1 + B_LIVE] = 0.0
                set_basin(ws, b1, found, zn, vn, tn, kn, c, place)
                if not found and vn < best:
                    ws[MODE + vm] = 0.0  # the best not followed: afresh next time
                order(tab, ws, vm)
                best = ws[basin(vm, 0) + B_V]
                if math.isfinite(best):
                    limit = best + 0.25 * max(top - best, 0.0) + tab[TOL]


@_jit
def at_minimum(tab, ws, z, t, ct, st):
    """Radius and turning rate of the flank point ``(z, t)``: the rate of change of its
    sleeve polar angle per unit hub turn, ``(|q|^2 cos i - (q . k_h) zq) / rq^2`` (turning
    the hub by ``d`` about its tilted axis ``k_h`` moves ``q`` by ``d k_h x q``)."""
    e = find(tab, ws, z)
    if e >= 0:
        po = _entry(tab, e) + EPL
    else:
        po = _entry(tab, int(ws[GRID]) + MAX_DYN) + EPL
        plane_at(tab, ws, po, z, np.bool_(False))
    nt = int(tab[NT])
    qx, qy, zq = point(tab, ws, po, ct, st, t)[:3]
    ci, si = tab[CI], tab[SI]
    rq2 = qx * qx + qy * qy
    qk = -si * (qx * st + qy * ct) + zq * ci  # q . k_h, k_h = Rz(-theta) (0, -sin i, cos i)
    return ws[po + nt] + t * ws[po + nt + 1], ((rq2 + zq * zq) * ci - qk * zq) / rq2


@_jit
def above_best(tab, ws, vm):
    """Whether profile-end row ``vm`` (4-7) cannot hold its measure's minimum at this
    turning angle: its last minimum, less its largest rate bound over the coarse planes
    times the angle since (every plane facing the sleeve flank and within its bound's
    span), lies above the whole-flank row's minimum found at this angle (which the
    whole-flank row never exceeds: it includes the profile ends)."""
    best = ws[basin(vm % 2, 0) + B_V]
    bo = basin(vm, 0)
    age = abs(ws[THETA] - ws[bo + B_TH])
    if ws[basin(vm % 2, 0) + B_TH] != ws[THETA] or not math.isfinite(best):
        return False
    rate = 0.0
    for g in range(int(ws[GRID])):
        lo = _lazy(tab, ws, g)
        if not (math.isfinite(ws[lo + L_V + vm]) and abs(ws[THETA] - ws[lo + L_TH + vm])
                < ws[lo + L_RHO + vm]):
            return False
        rate = max(rate, ws[lo + L_D + vm])
    for b in range(2):
        bo = basin(vm, b)
        if (b == 0 or ws[bo + B_LIVE] != 0.0) and not ws[bo + B_V] - rate * age > best:
            return False
    return True


@_jit
def minimise_rows(tab, ws, zg, theta, wanted, measures, max_levels, out):
    """Minima of ``measures (M,)`` (indices of ``kernel.MEASURES``) at every turning
    angle ``theta (n,)``, into ``out (6, M, n)``: value, ``z``, ``r``, ``t``, kind, rate.
    ``wanted`` are the virtual measures they fold, ``zg`` the coarse planes.

    Each row is searched afresh (:func:`afresh`) at the first angle and where the step
    from the last is above :data:`MAX_TURN` or a followed minimum was lost; else its
    minima are followed (:func:`follow`) and checked for others (:func:`safeguard`)."""
    tab, ws = _unmanaged(tab), _unmanaged(ws)
    hf = tab[HF]
    init_coarse(tab, ws, zg)
    for q in range(8):
        ws[COUNTS + q] = 0.0
    for vm in range(8):
        ws[MODE + vm] = 0.0
        for b in range(2):
            bo = basin(vm, b)
            for q in range(BSTRIDE):
                ws[bo + q] = np.nan
            ws[bo + B_LIVE], ws[bo + B_V] = 0.0, np.inf
    for i in range(theta.size):
        ct, st = math.cos(theta[i]), math.sin(theta[i])
        new_angle(tab, ws, theta[i])
        for vm in wanted:
            near = ws[MODE + vm] != 0.0 and abs(theta[i] - ws[basin(vm, 0) + B_TH]) <= MAX_TURN
            if near and vm >= 4 and above_best(tab, ws, vm):
                continue
            if near and follow(tab, ws, vm, ct, st):
                safeguard(tab, ws, vm, max_levels, ct, st)
            else:
                afresh(tab, ws, vm, max_levels, ct, st)
        for mi in range(measures.size):
            fold = FOLD[measures[mi]]
            b = basin(fold[0], 0)
            for vm in fold[1:]:
                if vm >= 0 and ws[basin(vm, 0) + B_V] < ws[b + B_V]:
                    b = basin(vm, 0)
            v, z, t, k = ws[b + B_V], ws[b + B_Z], ws[b + B_T], ws[b + B_K]
            if k != NONE and abs(abs(z) - hf) <= 1e-12 * hf:
                k = FACE_END
            r, rate = at_minimum(tab, ws, z, t, ct, st)
            out[0, mi, i], out[1, mi, i], out[2, mi, i] = v, z, r
            out[3, mi, i], out[4, mi, i], out[5, mi, i] = t, k, rate
