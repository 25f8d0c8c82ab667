"""Tooth-pair bending compliance: hub and sleeve teeth as tapered cantilevers (Wei et al.).

Each tooth is a Timoshenko cantilever of the real transverse thickness ``S(r)`` (involute
tooth thickness of hub and sleeve at each radius) clamped at its root circle and loaded at
the contact radius by the normal force along the line of action, at the load angle
``beta`` to the tooth's perpendicular. Per unit width the normal deflection at the load is

    c = cos²beta ∫ 12 (y_F - y)² / (E' S³) dy + cos²beta ∫ 1.2 / (G S) dy
        + sin²beta ∫ 1 / (E' S) dy + cos²beta / E (5.306 (u/S_f)² + 1.534 (1 + 0.4167 tan²beta))

(bending, shear, compression; the last term is the O'Donnell/Weber foundation:
rotation and translation of the rim under the root, its coupling term omitted). ``E' =
E / (1 - nu²)`` (plane strain, wide teeth). A load at face position ``z`` spreads at 45°
toward the root, so the loaded width is ``min(h, b/2 - z) + min(h, b/2 + z)`` (``h`` the
load height above the root), capped at the face width: a crowned tooth's patch is short.
Hub and sleeve act in series; :meth:`CantileverCompliance.pair_compliance_mm_per_N`
converts the normal compliance to Renzo's measure (circumferential at the pitch point per
tangential load at the pitch radius) by ``1 / cos²phi``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...geometry import inv
from ...spec import CouplingSpec

FOUNDATION_L, FOUNDATION_P, FOUNDATION_Q = 5.306, 1.534, 0.4167
SHEAR_FACTOR = 1.2  # 1 / kappa for a rectangular section


def beam_terms(y: NDArray[np.float64], S: NDArray[np.float64], y_F: ArrayLike, *,
               E: float, G: float, beta: ArrayLike = 0.0) -> NDArray[np.float64]:
    """Normal deflection per unit load and unit width of a cantilever of thickness ``S(y)``,
    in its terms: bending, shear and compression.

    Parameters
    ----------
    y : (..., n) float
        Heights from the clamped root to the load height ``y_F`` (increasing).
    S : (..., n) float
        Section thickness at ``y`` (mm).
    y_F : (...) float
        Load height (mm).
    E, G : float
        Young's modulus for bending and shear modulus (MPa).
    beta : (...) float
        Load angle from the perpendicular to the beam axis (radians).

    Returns
    -------
    (3, ...) float
        Deflection along the load per unit load per unit width (mm²/N) of bending, shear
        and compression, Simpson's rule.
    """
    from scipy.integrate import simpson

    yF = np.asarray(y_F, dtype=float)[..., None]
    b = np.asarray(beta, dtype=float)[..., None]
    cb2, sb2 = np.cos(b) ** 2, np.sin(b) ** 2
    f = np.stack(np.broadcast_arrays(cb2 * 12.0 * (yF - y) ** 2 / (E * S**3),
                                     cb2 * SHEAR_FACTOR / (G * S), sb2 / (E * S)))
    return simpson(f, x=np.broadcast_to(y, f.shape), axis=-1)


def beam_compliance(y: NDArray[np.float64], S: NDArray[np.float64], y_F: ArrayLike, *,
                    E: float, G: float, beta: ArrayLike = 0.0) -> NDArray[np.float64]:
    """The sum of :func:`beam_terms` (same arguments; ``(...)`` float, mm²/N)."""
    return beam_terms(y, S, y_F, E=E, G=G, beta=beta).sum(axis=0)


class CantileverCompliance:
    """Pair compliance of hub and sleeve teeth from the spec (tapered cantilevers).

    Parameters
    ----------
    spec : CouplingSpec
    n_radii : int
        Radii tabulated over the active depth (linear interpolation between); 64 keeps the
        interpolation error below 1e-4 relative (``benchmarks/bench_load.py``).
    n_quad : int
        Simpson points per cantilever integral.
    """

    def __init__(self, spec: CouplingSpec, *, n_radii: int = 64, n_quad: int = 201):
        t = spec.tooth
        self.R, self.r_b, self.phi = t.pitch_radius, t.base_radius, t.pressure_angle
        self.hub_t = spec.hub.tooth_thickness
        self.sleeve_t = t.circular_pitch - spec.sleeve.space_width
        self.r_root_hub = self.R - spec.hub.root.dedendum
        self.r_root_sleeve = 0.5 * spec.sleeve.major_diameter
        self.half_face_hub = 0.5 * spec.hub.face_width
        self.half_face_sleeve = 0.5 * spec.sleeve.face_width
        self.materials = spec.material
        r_lo = max(0.5 * spec.sleeve.minor_diameter, self.r_b * (1 + 1e-9))
        r_hi = min(0.5 * spec.hub.tip.diameter, self.r_root_sleeve)
        self.r_table = np.linspace(r_lo, r_hi, n_radii)
        self.n_quad = n_quad
        mats = {"hub": spec.material.hub, "sleeve": spec.material.sleeve}
        #: per part, the terms of the unit compliance at ``r_table`` (``(5, n_radii)``,
        #: mm²/N: :meth:`components`)
        self.terms = {p: np.stack(self.components(self.r_table, p, m))
                      for p, m in mats.items()}
        self.hub_unit = self.terms["hub"].sum(axis=0)
        self.sleeve_unit = self.terms["sleeve"].sum(axis=0)

    # ---------------------------------------------------------------- tooth geometry
    def half_thickness(self, part: str, r: ArrayLike) -> NDArray[np.float64]:
        """Half transverse tooth thickness (chord ~ arc) of ``part`` at radius ``r`` (mm);
        below the base circle the base-circle value (the fillet only adds material)."""
        rr = np.maximum(np.asarray(r, dtype=float), self.r_b)
        inv_r = inv(np.arccos(np.clip(self.r_b / rr, -1.0, 1.0)))
        inv_phi = float(inv(self.phi))
        if part == "hub":
            return rr * (0.5 * self.hub_t / self.R + inv_phi - inv_r)
        return rr * (0.5 * self.sleeve_t / self.R - inv_phi + inv_r)

    def load_angle(self, part: str, r: ArrayLike) -> NDArray[np.float64]:
        """Angle ``beta`` of the normal load to the tooth's perpendicular at radius ``r``."""
        rr = np.maximum(np.asarray(r, dtype=float), self.r_b)
        alpha = np.arccos(np.clip(self.r_b / rr, -1.0, 1.0))
        return np.abs(alpha - self.half_thickness(part, rr) / rr)

    def _heights(self, part: str, r_F: float | NDArray[np.float64]):
        """Root radius of ``part`` and the load height above it at radii ``r_F``."""
        if part == "hub":
            return self.r_root_hub, r_F - self.r_root_hub
        return self.r_root_sleeve, self.r_root_sleeve - r_F

    def components(self, r_F: ArrayLike, part: str, mat):
        """Normal compliance times width (mm²/N) of one tooth loaded at radii ``r_F``
        ``(...)``, in its terms: the beam's bending, shear and compression, the
        foundation's rotation and its translation (each ``(...)``)."""
        r_F = np.asarray(r_F, dtype=float)
        root, y_F = self._heights(part, r_F)
        y = y_F[..., None] * np.linspace(0.0, 1.0, self.n_quad)
        r = root + y if part == "hub" else root - y
        S = 2.0 * self.half_thickness(part, r)
        nu = mat.poisson_ratio
        E_ps = mat.youngs_modulus_MPa / (1 - nu**2)
        beta = self.load_angle(part, r_F)
        bend, shear, comp = beam_terms(y, S, y_F, E=E_ps, G=mat.shear_modulus_MPa, beta=beta)
        S_f = 2.0 * float(self.half_thickness(part, root))
        scale = np.cos(beta) ** 2 / mat.youngs_modulus_MPa
        return (bend, shear, comp, scale * FOUNDATION_L * (y_F / S_f) ** 2,
                scale * FOUNDATION_P * (1 + FOUNDATION_Q * np.tan(beta) ** 2))

    # ---------------------------------------------------------------- public protocol
    def loaded_width_mm(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """Width carrying a load at ``(z, r)``: 45° spread toward the root, within the face."""
        z = np.abs(np.asarray(z_mm, dtype=float))
        root, _ = self._heights(part, 0.0)
        h = np.abs(np.asarray(r_mm, dtype=float) - root)
        half = self.half_face_hub if part == "hub" else self.half_face_sleeve
        w = np.minimum(h, np.maximum(half - z, 0.0)) + np.minimum(h, half + z)
        return np.clip(w, 1e-3 * half, 2.0 * half)

    def normal_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike):
        """Hub and sleeve normal compliances at the load (mm/N), each broadcast to ``(z, r)``."""
        r = np.clip(np.asarray(r_mm, dtype=float), self.r_table[0], self.r_table[-1])
        hub = np.interp(r, self.r_table, self.hub_unit) / self.loaded_width_mm("hub", z_mm, r)
        sl = (np.interp(r, self.r_table, self.sleeve_unit)
              / self.loaded_width_mm("sleeve", z_mm, r))
        return hub, sl

    def pair_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """Circumferential displacement at the pitch point per tangential load at the pitch
        radius (mm/N) for a load at hub flank point ``(z, r)``, hub and sleeve in series."""
        hub, sl = self.normal_compliance_mm_per_N(z_mm, r_mm)
        return (hub + sl) / math.cos(self.phi) ** 2

    @property
    def mesh_stiffness_N_per_mm(self) -> float:
        """Renzo's C of one tooth pair: 1 / pair compliance at mid-face and the pitch radius."""
        return float(1.0 / self.pair_compliance_mm_per_N(0.0, self.R))

    def root_stress_MPa(self, normal_force_N: ArrayLike, z_mm: ArrayLike,
                        r_mm: ArrayLike) -> NDArray[np.float64]:
        """Larger root bending stress of hub and sleeve tooth, ``6 F cos(beta) y_F /
        (w S_root²)`` (the tension side; the compressive ``F sin(beta)`` part is left out)."""
        F = np.asarray(normal_force_N, dtype=float)
        out = np.zeros(np.broadcast_shapes(F.shape, np.shape(z_mm), np.shape(r_mm)))
        r = np.clip(np.asarray(r_mm, dtype=float), self.r_table[0], self.r_table[-1])
        for part in ("hub", "sleeve"):
            root, _ = self._heights(part, 0.0)
            y_F = np.abs(r - root)
            S = 2.0 * float(self.half_thickness(part, root))
            w = self.loaded_width_mm(part, z_mm, r)
            sigma = 6.0 * F * np.cos(self.load_angle(part, r)) * y_F / (w * S**2)
            out = np.maximum(out, sigma)
        return out
