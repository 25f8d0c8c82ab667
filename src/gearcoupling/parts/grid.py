"""Tolerance-driven structured sampling of one tooth pitch over (z, profile parameter).

Every hub tooth is sampled on one grid of parameters that is the same in every transverse
plane: root arc polar angle, hob tip-round angle ``gamma`` (fillet), flank depth ``h``
normalised between ``m.h_form`` and ``h_top(z)`` (so the tip surface trims the flank
exactly in every plane) and the tip arc angle normalised to the tip corners. Rows of
equal parameters connect into quads, and the planes are spaced so that the chord error
along ``z`` is within the tolerance as well.

Each parameter set is refined by bisection until the exact curve at the 1/4, 1/2 and 3/4
points of every chord lies within ``SPLIT * tolerance`` of the chord in *every* plane
(profile direction) or for every column (axial direction), so that the two directions
together keep the triangles within the tolerance.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import GeometryError
from ..geometry import (
    HubModel,
    SleeveModel,
    envelope,
    flank_depth,
    flank_u,
    root_radius,
    round_point,
    sleeve_space_outline,
    tip_radius,
)
from ..numeric import TINY

SPLIT = 0.45  # share of the tolerance given to each of the two grid directions
MAX_PARAMS = 200_000  # parameter values per direction before giving up


def arc_step(radius: float, tol: float) -> float:
    """Largest angle step (rad) of a chord of a circle of ``radius`` with sagitta ``tol``."""
    if radius <= tol:
        return math.pi / 2
    return min(2.0 * math.acos(1.0 - tol / radius), math.pi / 2)


def arc_count(radius: float, span: float, tol: float) -> int:
    """Number of chords needed on an arc of ``span`` radians at chordal tolerance ``tol``."""
    return max(1, math.ceil(abs(span) / arc_step(radius, tol) * (1 + 1e-12)))


def _chord_error(f0: NDArray, f1: NDArray, probe: NDArray) -> NDArray:
    """Distance of ``probe`` points from the chords ``f0 -> f1`` (all ``(..., d)``)."""
    ab = f1 - f0
    ap = probe - f0
    ll = np.maximum(np.sum(ab * ab, axis=-1), TINY)
    t = np.clip(np.sum(ap * ab, axis=-1) / ll, 0.0, 1.0)
    return np.linalg.norm(ap - t[..., None] * ab, axis=-1)


def refine_params(f: Callable[[NDArray], NDArray], t: NDArray, tol: float) -> NDArray[np.float64]:
    """Refine increasing parameters ``t`` until every chord is within ``tol`` of ``f``.

    Parameters
    ----------
    f : callable
        ``f(t) -> (p, n, d)``: ``p`` curves (planes or columns) sampled at the ``n``
        parameters ``t``.
    t : (n,) float
        Starting parameters (kept).
    tol : float
        Largest allowed chord error in every curve.

    Returns
    -------
    t : (k,) float
        Refined parameters (a superset of the input).
    """
    t = np.asarray(t, dtype=float)
    p = f(t)
    for _ in range(60):
        dt = np.diff(t)
        dev = np.zeros(dt.size)
        for q in (0.25, 0.5, 0.75):
            probe = f(t[:-1] + q * dt)
            dev = np.maximum(dev, np.max(_chord_error(p[:, :-1], p[:, 1:], probe), axis=0))
        bad = np.flatnonzero(dev > tol)
        if bad.size == 0:
            return t
        if t.size + bad.size > MAX_PARAMS:
            raise GeometryError(f"tolerance {tol:g} mm needs more than {MAX_PARAMS} samples "
                                "along one direction; use a coarser tolerance")
        mid = t[bad] + 0.5 * dt[bad]
        t = np.insert(t, bad + 1, mid)
        p = f(t)
    raise GeometryError("tolerance-driven sampling did not converge")


# ------------------------------------------------------------------------------ hub


# surface kinds of the hub tooth columns, cw half then mirrored
ROOT, FILLET_CW, FLANK_CW, TIP, FLANK_CCW, FILLET_CCW = (
    "root", "fillet_cw", "flank_cw", "tip", "flank_ccw", "fillet_ccw")


@dataclass(frozen=True, eq=False)
class HubToothGrid:
    """Structured parameters of one hub tooth pitch.

    Attributes
    ----------
    z : (nz,) float
        Transverse planes from ``-b/2`` to ``b/2``, symmetric about the midplane.
    root : (nr,) float
        Polar angles of the root arc from ``-pi/N`` to ``-u_c/R``.
    gamma : (nf,) float
        Tip-round normal angles of the fillet from ``pi/2`` down to ``phi``.
    flank : (nh,) float
        Normalised flank depth from 0 (``h_form``) to 1 (``h_top(z)``).
    tip : (nt,) float
        Normalised tip angle from 0 (cw tip corner) to 1 (tooth centre line).
    """

    model: HubModel
    z: NDArray[np.float64]
    root: NDArray[np.float64]
    gamma: NDArray[np.float64]
    flank: NDArray[np.float64]
    tip: NDArray[np.float64]

    @property
    def columns(self) -> int:
        """Points per pitch from ``-pi/N`` to ``+pi/N``, both ends included."""
        half = self.root.size + self.gamma.size + self.flank.size + self.tip.size - 3
        return 2 * half - 1

    def kinds(self) -> list[str]:
        """Surface kind of each of the ``columns - 1`` segments of the pitch outline."""
        half = ([ROOT] * (self.root.size - 1) + [FILLET_CW] * (self.gamma.size - 1)
                + [FLANK_CW] * (self.flank.size - 1) + [TIP] * (self.tip.size - 1))
        mirror = {FILLET_CW: FILLET_CCW, FLANK_CW: FLANK_CCW}
        return half + [mirror.get(k, k) for k in reversed(half)]

    def points(self, z: NDArray | None = None) -> NDArray[np.float64]:
        """Pitch outline points ``(nz, columns, 2)`` in the planes ``z`` (default: rows)."""
        z = self.z if z is None else np.asarray(z, dtype=float)
        return _hub_pitch(self.model, z, self.root, self.gamma, self.flank, self.tip)


def tip_corner(m: HubModel, z: NDArray):
    """Tip radius, rack depth of the flank at the tip and tip-corner polar angle per plane."""
    r_tip = tip_radius(m, z)
    h_top = flank_depth(m, z, r_tip)
    p, _ = envelope(m, z, flank_u(m, h_top), h_top, m.phi)
    return r_tip, h_top, np.arctan2(p[..., 1], p[..., 0])


def _fillet(m: HubModel, z: NDArray, gamma: NDArray) -> NDArray:
    u, h = round_point(m, gamma)
    return envelope(m, z[:, None], u[None, :], h[None, :], gamma[None, :])[0][..., :2]


def _flank(m: HubModel, z: NDArray, s: NDArray, h_top: NDArray) -> NDArray:
    h = m.h_form + s[None, :] * (h_top[:, None] - m.h_form)
    return envelope(m, z[:, None], flank_u(m, h), h, m.phi)[0][..., :2]


def _arc(radius: NDArray, angle: NDArray) -> NDArray:
    return np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)


def _hub_pitch(m: HubModel, z, root, gamma, flank, tip) -> NDArray[np.float64]:
    z = np.atleast_1d(z)
    r_root = root_radius(m, z)
    r_tip, h_top, a_top = tip_corner(m, z)
    parts = [
        _arc(r_root[:, None], np.broadcast_to(root, (z.size, root.size))),
        _fillet(m, z, gamma)[:, 1:],
        _flank(m, z, flank, h_top)[:, 1:],
        _arc(r_tip[:, None], a_top[:, None] * (1.0 - tip[None, :]))[:, 1:],
    ]
    half = np.concatenate(parts, axis=1)
    mirror = half[:, -2::-1] * np.array([1.0, -1.0])
    return np.concatenate([half, mirror], axis=1)


def hub_tooth_grid(m: HubModel, tol: float) -> HubToothGrid:
    """Sample one hub tooth pitch so the mesh stays within the chordal tolerance ``tol``.

    The profile parameters are refined against every plane, then the planes against every
    profile column, then the profile once more against the final planes.
    """
    half_pitch = math.pi / m.teeth
    u_c, _ = m.round_centre
    zs = np.linspace(0.0, m.half_face, 5)
    target = SPLIT * tol

    def profile(z_half: NDArray):
        z_all = np.concatenate([-z_half[:0:-1], z_half])
        r_root = float(np.max(root_radius(m, z_all)))
        a_root = -u_c / m.R
        root = np.linspace(-half_pitch, a_root, arc_count(r_root, a_root + half_pitch, target) + 1)
        gamma = refine_params(lambda g: _fillet(m, z_half, g), np.linspace(math.pi / 2, m.phi, 5),
                              target)
        h_top = tip_corner(m, z_half)[1]
        flank = refine_params(lambda s: _flank(m, z_half, s, h_top), np.linspace(0.0, 1.0, 5),
                              target)
        r_tip, _, a_top = tip_corner(m, z_half)
        n_tip = max(arc_count(float(r), float(a), target) for r, a in zip(r_tip, a_top,
                                                                           strict=True))
        tip = np.linspace(0.0, 1.0, n_tip + 1)
        return root, gamma, flank, tip

    params = profile(zs)
    for _ in range(2):
        def axial(z, params=params):
            p = _hub_pitch(m, z, *params)  # (nz, columns, 2)
            pts = np.concatenate([p, np.broadcast_to(z[:, None, None], (*p.shape[:2], 1))],
                                 axis=-1)
            return np.swapaxes(pts, 0, 1)

        zs = refine_params(axial, zs, target)
        params = profile(zs)
    z = np.concatenate([-zs[:0:-1], zs])
    return HubToothGrid(m, z, *params)


# --------------------------------------------------------------------------- sleeve


def sleeve_pitch(sm: SleeveModel, tol: float) -> tuple[NDArray[np.float64], list[str]]:
    """Sleeve space-0 outline from ``-pi/N`` to ``+pi/N`` and the kind of each segment.

    Kinds: ``tip`` (minor circle), ``chamfer_cw``/``chamfer_ccw``, ``flank_cw``/``flank_ccw``
    (involute), ``fillet_cw``/``fillet_ccw`` and ``root`` (major circle). The outline is
    the same in every plane of the sleeve face.
    """
    pts = sleeve_space_outline(sm, 0.9 * tol)  # margin: the profile carries the whole error
    mid = 0.5 * (pts[1:] + pts[:-1])
    ends_r = np.hypot(pts[:, 0], pts[:, 1])
    r_lo, r_hi = np.minimum(ends_r[:-1], ends_r[1:]), np.maximum(ends_r[:-1], ends_r[1:])
    beta = np.arctan2(mid[:, 1], mid[:, 0])
    eps = 1e-9 * sm.r_major
    kinds = []
    for b, lo, hi in zip(beta, r_lo, r_hi, strict=True):
        side = "cw" if b < 0 else "ccw"
        if abs(b) < abs(sm.major_angle) - 1e-12:
            kinds.append("root")
        elif hi <= sm.r_minor + eps:
            kinds.append("tip")
        elif lo < sm.r_form - eps:
            kinds.append(f"chamfer_{side}")
        elif hi <= sm.r_fillet + eps:
            kinds.append(f"flank_{side}")
        else:
            kinds.append(f"fillet_{side}")
    return pts, kinds
