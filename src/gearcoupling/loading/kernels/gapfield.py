"""The initial gap field of a hub flank against its sleeve flank, on a grid of the patch.

The grid lies on the **sleeve** flank, developed: the straight internal involute flank is a
cylinder over the involute, so it develops isometrically onto the plane of the axial
position ``z`` (sleeve frame) and the arc length along the involute from the base circle
``s = (r^2 - r_b^2) / (2 r_b)``. Every cell centre ``(z, s)`` is a sleeve flank point; the
hub flank point facing it (same sleeve radius and axial position) is found on the exact
hub flank (the hob envelope of :mod:`gearcoupling.geometry.hub`, through the sweep's
Chebyshev table of it, whose measured error is below 1e-7 mm), posed by ``P(theta)`` as
the sweep does (docs/conventions.md, Frames), pulled back by ``P(theta)^T`` in three fixed-point
steps
(the polar angle of the hub flank moves by far less than a micrometre per step). The gap
there is the hub rotation that closes it: ``G = (a_q + sigma(r_q)/2) / rate`` (rad;
``r_b G`` is the normal gap, as in the sweep).

Cells are **masked** (cannot carry pressure) where the real flanks end: below the sleeve
flank's first radius (the tip chamfer edge), above the sleeve root fillet, beyond the
sleeve face ends, and where the facing hub point would lie above the hub tip surface
(sphere or cylinder), below the hub form radius or beyond the hub face ends.

Arrays are ``(n_teeth, n_face, n_depth)``: one grid per tooth (turning angle), the face
axis first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...arguments import GAP_TOLERANCE_MM
from ...clearance import flank_table
from ...errors import ArgumentError
from ...geometry import (
    FLANKS,
    developed_arc,
    hub_model,
    hub_to_sleeve,
    sleeve_model,
    tip_radius,
)
from ...spec import CouplingSpec

FIXED_POINT_STEPS = 3


@dataclass(frozen=True, eq=False)
class GapField:
    """Gap of each cell of the developed sleeve flank patch at each tooth's pose.

    Attributes
    ----------
    z_mm : (n, n_face) float
        Axial cell centres (sleeve frame) of each tooth's window.
    s_mm : (n_depth,) float
        Cell centres along the developed involute (arc length from the base circle).
    r_mm : (n_depth,) float
        Sleeve radius of each depth row.
    dz, ds : float
        Cell sizes (mm).
    gap_rad : (n, n_face, n_depth) float
        Hub rotation that closes each cell (finite everywhere; meaningful where ``mask``).
    mask : (n, n_face, n_depth) bool
        Cells where both flanks exist (contactable).
    face_cut : (n, n_face, n_depth) bool
        Masked cells that are masked by a face end (hub or sleeve), not by a profile end.
    hub_z_mm, hub_r_mm : (n, n_face, n_depth) float
        Hub-frame flank coordinates of the hub point facing each cell.
    base_radius : float
    local_compliance_mm_per_MPa : (n, n_face, n_depth) float or None
        A compliance of each cell of its own in series with the contact (a worn depth
        that grows with the cell's pressure over a wear step), or None.
    """

    z_mm: NDArray[np.float64]
    s_mm: NDArray[np.float64]
    r_mm: NDArray[np.float64]
    dz: float
    ds: float
    gap_rad: NDArray[np.float64]
    mask: NDArray[np.bool_]
    face_cut: NDArray[np.bool_]
    hub_z_mm: NDArray[np.float64]
    hub_r_mm: NDArray[np.float64]
    base_radius: float
    local_compliance_mm_per_MPa: NDArray[np.float64] | None = None


def depth_range(spec: CouplingSpec, misalignment: float) -> tuple[float, float]:
    """Sleeve radii ``(lo, hi)`` the patch spans: from the sleeve flank's first radius (the
    tip chamfer edge) to the lower of the sleeve root fillet and the hub tip (its largest
    radius, plus the radial shift a tilt can give it)."""
    sm = sleeve_model(spec)
    hm = hub_model(spec)
    top = float(tip_radius(hm, 0.0)) + hm.half_face * math.sin(misalignment)
    return sm.r_form, min(sm.r_fillet, top)


def face_range(spec: CouplingSpec, misalignment: float) -> float:
    """Largest ``|z|`` (sleeve frame) a contactable cell can have: the smaller face, plus
    what the tilt can move the hub's face end axially."""
    sm = sleeve_model(spec)
    hm = hub_model(spec)
    shift = float(tip_radius(hm, 0.0)) * math.sin(misalignment)
    return min(sm.half_face, hm.half_face + shift)


def windows(spec: CouplingSpec, misalignment: float, z_centre_mm: ArrayLike, length_mm: float,
            n_face: int) -> NDArray[np.float64]:
    """Axial cell centres ``(n, n_face)`` of windows of ``length_mm`` centred on each
    ``z_centre_mm``, shifted inward so they end at most one cell past the face range
    (:func:`face_range`); a window that reaches a face end so holds a cell beyond it, which
    is masked as face cut. Longer windows cover the face range and one cell either side."""
    zc = np.atleast_1d(np.asarray(z_centre_mm, dtype=float))
    Z = face_range(spec, misalignment)
    L = min(float(length_mm), 2.0 * Z * n_face / (n_face - 2))
    dz = L / n_face
    lo = np.clip(zc - 0.5 * L, -Z - dz, Z + dz - L)
    return lo[:, None] + (np.arange(n_face) + 0.5)[None, :] * dz


WINDOW_RATIO = 2.0 ** 0.25  # window lengths: the full face range over about powers of this
MAX_LEVEL = 64  # shortest window: about the full one / WINDOW_RATIO**64 (1/65536)


def _cells_per_half_face(level: int, n_face: int) -> int:
    """Cells over the half face range at window ``level``: ``(n_face - 2) // 2`` at level 0
    (the window spans the face range and a cell either side), then about
    :data:`WINDOW_RATIO` more per level (at least one)."""
    m0 = max((n_face - 2) // 2, 1)
    m = m0
    for k in range(1, int(level) + 1):
        m = max(m + 1, round(m0 * WINDOW_RATIO**k))
    return m


def window_length(spec: CouplingSpec, misalignment: float, level: int, n_face: int) -> float:
    """Length (mm) of the windows of ``level``: ``n_face`` cells of ``Z / m`` (``Z`` the
    face range, ``m`` cells over it per side); level 0 covers the face range and one cell
    either side, each level is about :data:`WINDOW_RATIO` shorter."""
    return n_face * face_range(spec, misalignment) / _cells_per_half_face(level, n_face)


def window_level(spec: CouplingSpec, misalignment: float, length_mm: float, n_face: int) -> int:
    """The shortest level whose windows are at least ``length_mm`` long (0: the full face)."""
    if not length_mm > 0:
        return MAX_LEVEL
    cells = n_face * face_range(spec, misalignment) / length_mm  # most cells per half face
    level = 0
    while level < MAX_LEVEL and _cells_per_half_face(level + 1, n_face) <= cells:
        level += 1
    return level


def lattice_windows(spec: CouplingSpec, misalignment: float, level: int, z_centre_mm: ArrayLike,
                    n_face: int) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """Windows of ``level`` as runs of ``n_face`` cells of one lattice, nearest to centred
    on each ``z_centre_mm``: the axial cell centres ``(n, n_face)`` and each window's first
    lattice cell ``(n,)``.

    The lattice of a level has cell edges at whole multiples of ``Z / m`` (``Z`` the face
    range, :func:`face_range`): symmetric about the midplane, with the face range's ends
    on cell edges, one cell beyond either end (masked as face cut). Two windows of one
    level share the cells where they overlap, so a patch inside both gets the same
    discrete problem wherever the windows were placed: the answer does not depend on the
    start. Level 0 equals :func:`windows` of infinite length.
    """
    zc = np.atleast_1d(np.asarray(z_centre_mm, dtype=float))
    Z = face_range(spec, misalignment)
    m = _cells_per_half_face(level, n_face)
    dz = Z / m
    origin = -(m + 1) * dz
    last = max(2 * m + 2 - n_face, 0)
    start = np.clip(np.round((zc - 0.5 * n_face * dz - origin) / dz), 0, last).astype(np.intp)
    cells = start[:, None] + np.arange(n_face)[None, :]
    return (origin + (cells + 0.5) * dz).astype(float), start


def touch_z(spec: CouplingSpec, misalignment: float, theta: ArrayLike, flank: str, z_mm: ArrayLike,
            r_mm: ArrayLike) -> NDArray[np.float64]:
    """Sleeve-frame axial position of hub flank points ``(z_mm, r_mm)`` (hub frame, e.g.
    the sweep's first touch) of teeth at turning angles ``theta`` (broadcast): where along
    the face their windows must lie. ``nan`` stays ``nan``."""
    theta = np.asarray(theta, dtype=float)
    if flank == "ccw":
        theta = np.pi - theta
    z, r = np.asarray(z_mm, dtype=float), np.asarray(r_mm, dtype=float)
    a = -sleeve_model(spec).half_angle(r)  # the flank's polar angle, near enough
    P = hub_to_sleeve(misalignment, theta)
    return P[..., 2, 0] * r * np.cos(a) + P[..., 2, 1] * r * np.sin(a) + P[..., 2, 2] * z


def gap_field(spec: CouplingSpec,
              misalignment: float, theta: ArrayLike, flank: str, z_mm: ArrayLike,
              n_depth: int, *, gap_offset_rad: ArrayLike | None = None) -> GapField:
    """The gap field of the hub flank ``flank`` of the teeth at turning angles ``theta``.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment : float
        Tilt ``i`` (radians).
    theta : (n,) float
        Turning angle of each tooth (radians).
    flank : {"cw", "ccw"}
        The hub flank; the ccw flank at ``theta`` is the cw flank at ``pi - theta``
        (mirror ``y -> -y``, as in the sweep).
    z_mm : (n, n_face) float
        Axial cell centres of each tooth's window (equally spaced, see :func:`windows`).
    n_depth : int
        Cells across the active depth (:func:`depth_range`).
    gap_offset_rad : (n,) float, optional
        Added to each tooth's gap (index errors etc.).
    """
    if flank not in FLANKS:
        raise ArgumentError("loaded_flank", flank, f"must be one of {FLANKS}")
    if n_depth < 2:
        raise ArgumentError("grid", n_depth, "needs at least 2 cells across the depth")
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    if flank == "ccw":
        theta = np.pi - theta
    z = np.asarray(z_mm, dtype=float).reshape(theta.size, -1)
    dz = float(z[0, 1] - z[0, 0]) if z.shape[1] > 1 else 2.0 * face_range(spec, misalignment)
    hm, sm = hub_model(spec), sleeve_model(spec)
    table = flank_table(spec, GAP_TOLERANCE_MM)
    r_b = sm.r_base
    r_lo, r_hi = depth_range(spec, misalignment)
    s_lo, s_hi = developed_arc(r_lo, r_b), developed_arc(r_hi, r_b)
    ds = (s_hi - s_lo) / n_depth
    s = s_lo + (np.arange(n_depth) + 0.5) * ds
    r = np.sqrt(r_b * r_b + 2.0 * r_b * s)
    n, nf = z.shape
    P = hub_to_sleeve(misalignment, theta)  # (n, 3, 3)
    zq = np.broadcast_to(z[:, :, None], (n, nf, n_depth))
    rq = np.broadcast_to(r[None, None, :], (n, nf, n_depth))
    half = sm.half_angle(r)[None, None, :]  # the sleeve cw flank lies at polar angle -half
    # first guess for the facing hub point: the sleeve flank point (one per depth row)
    qx, qy = r * np.cos(half), -r * np.sin(half)
    for _ in range(FIXED_POINT_STEPS):  # FIXED_POINT_STEPS >= 1 sets zh, rh
        px, py, zh = _apply(P, qx, qy, zq, transpose=True)
        rh = np.hypot(px, py)
        a, r_form, r_tip = _hub_angle(table, hm, zh, rh)
        hx, hy, _ = _apply(P, rh * np.cos(a), rh * np.sin(a), zh)
        aq = np.arctan2(hy, hx)
        qx, qy = rq * np.cos(aq), rq * np.sin(aq)  # the cell's point at that polar angle
    # the hub point facing the cell: its polar angle at the cell's (r, z)
    gap = (aq + half) / _turning_rate(P, rq, qx, qy, zq)
    if gap_offset_rad is not None:
        off = np.broadcast_to(np.asarray(gap_offset_rad, dtype=float), (n,))
        gap = gap + off[:, None, None]
    eps = 1e-9 * (sm.R + 1.0)
    hub_face = np.abs(zh) > hm.half_face + eps
    sleeve_face = np.abs(zq) > sm.half_face + eps
    profile = ((rh > r_tip + eps) | (rh < r_form - eps)
               | (rq < sm.r_form - eps) | (rq > sm.r_fillet + eps))
    mask = ~(hub_face | sleeve_face | profile)
    if not np.all(np.isfinite(gap[mask])):
        raise ArgumentError("gap field", "non-finite", "the flank geometry gave no finite gap")
    gap = np.where(np.isfinite(gap), gap, 0.0)
    return GapField(z, s, r, dz, float(ds), gap, mask, (hub_face | sleeve_face) & ~mask,
                    zh, rh, r_b)


def _hub_angle(table, hm, zh, rh):
    """Polar angle of the hub cw flank at ``(zh, rh)``, clipped onto the flank (cells off
    it are masked by the caller; clipping keeps the evaluation on the flank), and the
    form and tip radii at the clipped ``zh``; one table product for all three."""
    zc = np.clip(zh, -hm.half_face, hm.half_face)
    coef, lo, hi = table.plane_coefficients(zc.ravel())
    lo, hi = lo.reshape(zc.shape), hi.reshape(zc.shape)
    t = np.clip((rh - lo) / (hi - lo), 0.0, 1.0)
    r = lo + t * (hi - lo)
    y = table.plane_y(coef, t.ravel()).reshape(zc.shape)
    return np.arcsin(y / r), lo, hi


def _apply(P, x, y, z, transpose=False):
    """``P @ (x, y, z)`` (or ``P^T``) per tooth: ``P (n, 3, 3)``, coordinates ``(n, ...)``."""
    M = np.swapaxes(P, -1, -2) if transpose else P
    c = [[M[:, i, j][:, None, None] for j in range(3)] for i in range(3)]
    return tuple(c[i][0] * x + c[i][1] * y + c[i][2] * z for i in range(3))


def _turning_rate(P, rq, x, y, zq):
    """Sleeve polar angle change per unit hub turn about its tilted axis ``k = P e_z`` at
    the points ``(x, y, zq)`` (radius ``rq``)."""
    k = P[:, :, 2]  # (n, 3)
    kx, ky, kz = (k[:, j][:, None, None] for j in range(3))
    vx = ky * zq - kz * y
    vy = kz * x - kx * zq
    return (x * vy - y * vx) / (rq * rq)
