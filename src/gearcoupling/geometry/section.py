"""Transverse sections of hub and sleeve as polygons within a chordal tolerance.

Every piece of the outline (root arc, fillet, flank, tip arc, chamfer) is an exact curve;
arcs are split where their sagitta reaches the tolerance, other curves are refined by
bisection until the exact curve at the 1/4, 1/2 and 3/4 points of every chord lies
within ``0.9 * tolerance`` of it. Vertices lie on the exact curve.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ..arguments import real
from ..errors import ArgumentError, GeometryError
from ..numeric import TINY
from .hub import HubModel, envelope, flank_depth, flank_u, hub_model, root_radius, round_point
from .hub import tip_radius as hub_tip_radius
from .sleeve import SleeveModel, flank_point, sleeve_model
from .speclike import SpecLike, as_spec_like

PARTS = ("hub", "sleeve")
_MAX_POINTS = 2_000_000


def _chord_distance(p: NDArray, a: NDArray, b: NDArray) -> NDArray:
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab),
                                                              TINY), 0.0, 1.0)
    return np.hypot(*(p - a - t[:, None] * ab).T)


def adaptive_curve(f: Callable[[NDArray], NDArray], t0: float, t1: float, tol: float,
                   n0: int = 8) -> NDArray[np.float64]:
    """Sample the parametric curve ``f(t) -> (n, 2)`` on ``[t0, t1]`` to a chordal tolerance.

    Returns
    -------
    points : (n, 2) float
        Points on the curve from ``f(t0)`` to ``f(t1)``.
    """
    t = np.linspace(t0, t1, n0 + 1)
    p = f(t)
    for _ in range(60):
        a, b = p[:-1], p[1:]
        dt = np.diff(t)
        probes = [t[:-1] + q * dt for q in (0.25, 0.5, 0.75)]
        dev = np.max([_chord_distance(f(tp), a, b) for tp in probes], axis=0)
        bad = np.flatnonzero(dev > 0.9 * tol)
        if bad.size == 0:
            return p
        if t.size + bad.size > _MAX_POINTS:
            raise GeometryError(f"tolerance {tol:g} mm needs more than {_MAX_POINTS} points")
        t = np.insert(t, bad + 1, probes[1][bad])
        p = np.insert(p, bad + 1, f(probes[1][bad]), axis=0)
    raise GeometryError("adaptive sampling did not converge")


def arc(radius: float, a0: float, a1: float, tol: float, centre=(0.0, 0.0)) -> NDArray:
    """Points on a circular arc from angle ``a0`` to ``a1`` with sagitta below ``tol``."""
    step = 2.0 * math.acos(max(1.0 - tol / radius, -1.0)) if radius > 0 else math.pi
    n = max(1, math.ceil(abs(a1 - a0) / step * (1 + 1e-12)))
    a = np.linspace(a0, a1, n + 1)
    return np.stack([centre[0] + radius * np.cos(a), centre[1] + radius * np.sin(a)], axis=-1)


def _join(pieces: list[NDArray]) -> NDArray:
    out = [pieces[0]]
    for piece in pieces[1:]:
        out.append(piece[1:])
    return np.concatenate(out)


def _mirror(p: NDArray) -> NDArray:
    return (p * np.array([1.0, -1.0]))[::-1]


def _polar(p: NDArray) -> float:
    return math.atan2(p[1], p[0])


def hub_tooth_outline(m: HubModel, z: float, tol: float) -> NDArray[np.float64]:
    """Outline of hub tooth 0 in the plane ``z`` from polar angle ``-pi/N`` to ``+pi/N``.

    Pieces in counter-clockwise order: root arc, cw fillet, cw flank, tip arc, ccw flank,
    ccw fillet, root arc. Returns ``(n, 2)`` points including both end points.
    """
    half_pitch = math.pi / m.teeth
    zz = np.float64(z)
    r_root = float(root_radius(m, zz))
    u_c, _ = m.round_centre
    r_tip = float(hub_tip_radius(m, zz))
    h_top = float(flank_depth(m, zz, r_tip))

    def fillet(g):
        u, h = round_point(m, g)
        return envelope(m, zz, u, h, g)[0][:, :2]

    def flank(h):
        return envelope(m, zz, flank_u(m, h), h, m.phi)[0][:, :2]

    root = arc(r_root, -half_pitch, -u_c / m.R, tol)
    fil = adaptive_curve(fillet, math.pi / 2, m.phi, tol)
    fl = adaptive_curve(flank, m.h_form, h_top, tol)
    a_top = _polar(fl[-1])
    if a_top >= 0:
        raise GeometryError(f"hub tooth is pointed at z = {z:.6g} mm")
    cw = _join([root, fil, fl])
    return _join([cw, arc(r_tip, a_top, -a_top, tol), _mirror(cw)])


def sleeve_space_outline(m: SleeveModel, tol: float) -> NDArray[np.float64]:
    """Outline of sleeve space 0 from polar angle ``-pi/N`` to ``+pi/N`` (2-D, ``(n, 2)``).

    Pieces in counter-clockwise order: tip (minor) arc, chamfer, cw flank, root fillet,
    major arc, and their mirror images.
    """
    half_pitch = math.pi / m.teeth
    tip = arc(m.r_minor, -half_pitch, m.chamfer_tip_angle, tol)
    fl = adaptive_curve(lambda r: flank_point(m, r)[0], m.r_form, m.r_fillet, tol)
    pieces = [tip, np.stack([tip[-1], fl[0]]), fl] if m.chamfer > 0 else [tip, fl]
    if m.fillet > 0:
        cx, cy = m.fillet_centre
        a0 = math.atan2(fl[-1, 1] - cy, fl[-1, 0] - cx)
        a1 = math.atan2(cy, cx)
        a1 = a0 + math.remainder(a1 - a0, 2 * math.pi)
        pieces.append(arc(m.fillet, a0, a1, tol, centre=(cx, cy)))
    half = _join(pieces)
    major = arc(m.r_major, m.major_angle, -m.major_angle, tol)
    return _join([half, major, _mirror(half)])


def _tile(outline: NDArray, teeth: int) -> NDArray[np.float64]:
    """Repeat a one-pitch outline (both ends included) round the circle, counter-clockwise."""
    one = outline[:-1]
    k = 2 * math.pi * np.arange(teeth) / teeth
    c, s = np.cos(k)[:, None], np.sin(k)[:, None]
    x = c * one[None, :, 0] - s * one[None, :, 1]
    y = s * one[None, :, 0] + c * one[None, :, 1]
    return np.stack([x.ravel(), y.ravel()], axis=-1)


def transverse_section(spec: SpecLike,
                       part: str, z_mm: float, tolerance_mm: float) -> NDArray[np.float64]:
    """Closed section polygon of all teeth of ``part`` at axial position ``z_mm``.

    Parameters
    ----------
    spec : CouplingSpec
    part : {"hub", "sleeve"}
        ``hub``: the outer toothed outline of the hub (root circle, fillets, flanks, tip)
        in the hub frame. ``sleeve``: the inner toothed outline of the sleeve (the boundary
        of its bore) in the sleeve frame. Bore and outer circles are plain circles.
    z_mm : float
        Axial position within the part's face width.
    tolerance_mm : float
        Largest distance between the polygon and the exact curve (chordal tolerance).

    Returns
    -------
    polygon : (n, 2) float
        Vertices counter-clockwise, first vertex not repeated at the end.
    """
    spec = as_spec_like(spec)
    if part not in PARTS:
        raise ArgumentError("part", part, f"one of {', '.join(PARTS)}")
    m_ = spec.tooth.module  # the polygon has ~1/sqrt(tolerance) vertices: bounded
    tol = real(tolerance_mm, "tolerance_mm", 1e-6 * m_, m_, unit="mm (1e-6 to 1 module)")
    z = real(z_mm, "z_mm", unit="mm")
    if part == "hub":
        m = hub_model(spec)
        if not abs(z) <= m.half_face * (1 + 1e-12):
            raise GeometryError(f"z = {z:.6g} mm is outside the hub face |z| <= {m.half_face:.6g}")
        return _tile(hub_tooth_outline(m, z, tol), m.teeth)
    sm = sleeve_model(spec)
    if not abs(z) <= sm.half_face * (1 + 1e-12):
        raise GeometryError(f"z = {z:.6g} mm is outside the sleeve face |z| <= {sm.half_face:.6g}")
    return _tile(sleeve_space_outline(sm, tol), sm.teeth)
