"""Sleeve with straight internal involute teeth (docs/conventions.md, Tooth geometry).

Space ``k`` is centred at polar angle ``2 pi k / N``; its half-angle at radius ``r`` is
``s/(2R) + inv(phi) - inv(arccos(r_b / r))``. The transverse section is the same at every
``z`` within the sleeve face. Tip corners carry a 45° chamfer of radial leg ``c`` and the
space root a circular fillet tangent to flank and major circle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ArgumentError, GeometryError
from .hub import FLANKS
from .involute import inv, real_array, roll_angle
from .speclike import SpecLike, as_spec_like


@dataclass(frozen=True)
class SleeveModel:
    """Constants of one sleeve, derived once from a spec (see :func:`sleeve_model`).

    ``r_form`` .. ``r_fillet`` is the involute flank; ``fillet_centre`` is ``(x, y)`` of the
    cw fillet of space 0 and ``chamfer_tip_angle`` the polar angle where the cw chamfer
    meets the minor circle.
    """

    R: float
    phi: float
    teeth: int
    space_width: float
    r_base: float
    r_minor: float
    r_major: float
    chamfer: float
    fillet: float
    half_face: float
    r_form: float
    r_fillet: float
    fillet_centre: tuple[float, float]

    def half_angle(self, r: ArrayLike) -> np.ndarray:
        """Space half-angle ``sigma(r)/2`` at radius ``r``."""
        return (0.5 * self.space_width / self.R + float(inv(self.phi))
                - inv(roll_angle(r, self.r_base)))

    @property
    def chamfer_tip_angle(self) -> float:
        return -float(self.half_angle(self.r_form)) - self.chamfer / self.r_minor

    @property
    def major_angle(self) -> float:
        """Polar angle where the cw fillet meets the major circle (negative)."""
        cx, cy = self.fillet_centre
        return math.atan2(cy, cx)


def flank_point(m: SleeveModel, r: ArrayLike):
    """Points and unit normals of space 0's cw flank at radii ``r`` (2-D, ``(..., 2)``).

    Normals point out of the sleeve material, into the space (toward the hub tooth).
    """
    r = np.asarray(r, dtype=float)
    beta = -m.half_angle(r)
    alpha = roll_angle(r, m.r_base)
    cb, sb = np.cos(beta), np.sin(beta)
    pts = np.stack([r * cb, r * sb], axis=-1)
    sa, ca = np.sin(alpha), np.cos(alpha)
    nrm = np.stack([-sa * cb - ca * sb, -sa * sb + ca * cb], axis=-1)
    return pts, nrm


@lru_cache(maxsize=128)
def sleeve_model(spec: SpecLike) -> SleeveModel:
    """The :class:`SleeveModel` of a spec (cached); raises ``GeometryError`` if it cannot fit."""
    t, sl = spec.tooth, spec.sleeve
    R, phi = t.pitch_radius, t.pressure_angle
    r_b = t.base_radius
    r_minor, r_major = 0.5 * sl.minor_diameter, 0.5 * sl.major_diameter
    r_form = r_minor + sl.tip_chamfer
    if r_minor < r_b:
        raise GeometryError("sleeve minor circle lies below the base circle")
    base = SleeveModel(R, phi, t.teeth, sl.space_width, r_b, r_minor, r_major, sl.tip_chamfer,
                       sl.root_fillet_radius, 0.5 * sl.face_width, r_form, r_major, (r_major, 0.0))
    rho = sl.root_fillet_radius
    if rho == 0:
        p, _ = flank_point(base, r_major)
        centre = (float(p[0]), float(p[1]))
        r_fillet = r_major
    else:
        def gap(r):
            p, n = flank_point(base, r)
            return float(np.hypot(*(p + rho * n))) - (r_major - rho)

        lo = max(r_form, r_b * (1 + 1e-12))
        if gap(lo) >= 0 or gap(r_major) <= 0:
            raise GeometryError("sleeve root fillet does not fit between flank and major circle")
        from scipy.optimize import brentq  # lazy: keeps `import gearcoupling` fast

        r_fillet = brentq(gap, lo, r_major, xtol=1e-14 * r_major, rtol=1e-15)
        p, n = flank_point(base, r_fillet)
        c = p + rho * n
        centre = (float(c[0]), float(c[1]))
    return SleeveModel(R, phi, t.teeth, sl.space_width, r_b, r_minor, r_major, sl.tip_chamfer,
                       rho, 0.5 * sl.face_width, r_form, r_fillet, centre)


def sleeve_flank(spec: SpecLike, flank: str, z_mm: ArrayLike, r_mm: ArrayLike
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Points and unit normals of sleeve space 0's flank facing hub tooth 0's ``flank``.

    Parameters
    ----------
    spec : CouplingSpec
    flank : {"cw", "ccw"}
        The hub flank it faces: the ``cw`` sleeve flank bounds space 0 on its negative
        polar side.
    z_mm, r_mm : (...) float
        Axial positions and radii in the sleeve frame, broadcast together.

    Returns
    -------
    points, normals : (..., 3) float
        Normals point out of the sleeve material, into the space.
    """
    spec = as_spec_like(spec)
    if flank not in FLANKS:
        raise ArgumentError("flank", flank, f"one of {', '.join(FLANKS)}")
    m = sleeve_model(spec)
    z, r = np.broadcast_arrays(real_array(z_mm, "z_mm"), real_array(r_mm, "r_mm"))
    eps = 1e-9 * (m.R + 1.0)
    bad = (~np.isfinite(z) | ~np.isfinite(r) | (np.abs(z) > m.half_face + eps)
           | (r < m.r_form - eps) | (r > m.r_fillet + eps))
    if np.any(bad):
        i = np.flatnonzero(bad.ravel())[0]
        raise GeometryError(
            f"(z, r) = ({z.ravel()[i]:.6g}, {r.ravel()[i]:.6g}) mm is off the sleeve flank: "
            f"|z| <= {m.half_face:.6g} mm, r in [{m.r_form:.6g}, {m.r_fillet:.6g}] mm")
    p2, n2 = flank_point(m, r)
    pts = np.concatenate([p2, z[..., None]], axis=-1)
    nrm = np.concatenate([n2, np.zeros_like(z)[..., None]], axis=-1)
    if flank == "ccw":
        pts[..., 1] *= -1.0
        nrm[..., 1] *= -1.0
    return pts, nrm
