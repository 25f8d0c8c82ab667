"""Contact of one tooth pair from the relative curvatures of the exact flanks.

Hub and sleeve have the same tooth number, so across the tooth depth the hub involute
(convex, radius ``rho = sqrt(r² - r_b²)``) nearly conforms to the sleeve involute (concave,
the same ``rho`` when aligned): the relative profile curvature ``A_p`` is tiny and the
Hertz ellipse is long across the depth. Along the face the sleeve is straight and the hub
crowned, ``A_f`` = the hub's normal curvature along the face. Both are measured on the
exact hub flank (finite differences of :func:`gearcoupling.hub_flank` normals, tabulated
over ``(|z|, depth)`` once per spec).

Regimes (per tooth, reported as ``contact_regime``):

- ``hertz`` while the ellipse semi-axis across the depth fits in the active profile (the
  involute's arc length from the lower to the upper end of contact, ``(r_hi² - r_lo²) /
  (2 r_b)``; the contact line lies on the flank): Hamrock-Brewe closed forms of the
  elliptic Hertz contact, ``delta ∝ W^(2/3)``;
- ``line`` beyond the load ``W*`` where it stops fitting: a line contact of the active
  profile length ``L`` (cylinder of radius ``1/A_f`` on a plane), half-width
  ``b = sqrt(4 W R / (pi L E*))``, ``p0 = 2 W / (pi b L)``; its compliance increments follow
  Weber-Banaschek ``delta = 2 W / (pi L) sum (1 - nu²)/E (ln(2 h / b) - nu / (2 (1 - nu)))``
  (``h`` the half tooth thickness; the bracket is floored at 1 to stay monotone), added to
  the Hertz approach at ``W*`` so the load-approach curve is continuous and increasing.
  Weber's depth ``h`` is where the cantilever's beam takes over. With the FE table's far
  field (``[load] stiffness = "fe"``, the FE compliance less the half-space work of its
  load) the local part must be the half-space's too: the mean approach of a half-space
  under a thin strip ``L x w``, ``(1 - nu²) W / (pi E) (2 / L) (ln(2 L / w) + 1/2)``, with
  ``w = 1.745 b`` the uniform width of the same logarithmic energy as the semi-elliptic
  pressure of half-width ``b``; i.e. the same law with ``ln(2 L / b) - ln 1.745 + 1/2`` in
  the bracket.

A patch that reaches a face end is flagged ``edge_contact``; ``edge_load_share`` is the
share of the (semi-elliptic) pressure distribution beyond the face end, and
``max_pressure_MPa`` the truncated estimate ``p0 / (1 - share)``; ``interior_pressure_MPa``
is ``p0`` (grid-independent).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from ..geometry import developed_arc, form_radius, hub_flank_model, hub_model, tip_radius
from ..numeric import TINY, divide
from ..spec import CouplingSpec
from .inputs import nominal_root_stress_MPa
from .kernels.cantilever import CantileverCompliance
from .springs import springs_of

LN_FLOOR = 1.0
ELLIPTIC_STRIP_WIDTH = 0.5 * math.exp(1.25)
"""Uniform strip width per half-width ``b`` with the log energy of a semi-elliptic
pressure: ``ln(w) - 3/2 = ln(b / 2) - 1/4`` gives ``w = (b / 2) e^(5/4) = 1.745 b``."""
REGIMES = ("none", "hertz", "line")  # contact_regime codes: no load, elliptic, truncated line
REGIME = {name: code for code, name in enumerate(REGIMES)}


def patch_centre_radius(r_lo, r_hi):
    """Radius of the middle (by arc length) of the involute from ``r_lo`` to ``r_hi``:
    where a load spread over the whole active profile acts."""
    return np.sqrt(0.5 * (np.square(r_lo) + np.square(r_hi)))


class ContactModel:
    """Curvature tables and contact laws of one spec (see the module docstring).

    Parameters
    ----------
    spec : CouplingSpec
    n_z, n_r : int
        Table points over ``|z|`` (midplane to face end) and over the depth.
    """

    def __init__(self, spec: CouplingSpec, n_z: int = 17, n_r: int = 13):
        self.spec = spec
        m = hub_model(spec)
        t = spec.tooth
        self.r_b, self.half_face = t.base_radius, m.half_face
        self.E_star = spec.material.contact_modulus_MPa
        self.mats = (spec.material.hub, spec.material.sleeve)
        sl = spec.sleeve
        self.r_sleeve_form = 0.5 * sl.minor_diameter + sl.tip_chamfer
        self.r_sleeve_top = 0.5 * sl.major_diameter - sl.root_fillet_radius
        self.z_tab = np.linspace(0.0, m.half_face, n_z)
        self.t_tab = np.linspace(0.0, 1.0, n_r)
        self.r_lo = np.maximum(form_radius(m, self.z_tab), self.r_sleeve_form)
        self.r_hi = np.minimum(tip_radius(m, self.z_tab), self.r_sleeve_top)
        self.A_f, self.A_p = self._curvatures(m)

    def _curvatures(self, m):
        z = self.z_tab[:, None]
        span = self.r_hi - self.r_lo
        r = self.r_lo[:, None] + span[:, None] * self.t_tab[None, :]
        dr = 1e-4 * span[:, None] + 1e-9
        dz = 1e-3 * self.half_face
        r = np.clip(r, self.r_lo[:, None] + dr, self.r_hi[:, None] - dr)

        def pn(zz, rr):
            zz = np.clip(zz, -self.half_face, self.half_face)
            p, n, _ = hub_flank_model(m, "cw", zz, rr, check=False)
            return p, n

        p1, n1 = pn(z + 0 * r, r - dr)
        p2, n2 = pn(z + 0 * r, r + dr)
        dp, dn = p2 - p1, n2 - n1
        k_prof = np.sum(dn * dp, -1) / np.sum(dp * dp, -1)
        zl = np.where(z > 0, z - dz, z)
        p1, n1 = pn(zl + 0 * r, r)
        p2, n2 = pn(z + dz + 0 * r, r)
        dp, dn = p2 - p1, n2 - n1
        k_face = np.sum(dn * dp, -1) / np.sum(dp * dp, -1)
        rho = np.sqrt(np.maximum(r**2 - self.r_b**2, 1e-30))
        A_p = np.maximum(k_prof - 1.0 / rho, 0.0)  # hub convex minus sleeve concave
        return np.maximum(k_face, 0.0), A_p

    def _lookup(self, table, z, r):
        az = np.clip(np.abs(z), 0.0, self.half_face)
        fz = np.interp(az, self.z_tab, np.arange(self.z_tab.size))
        i0 = np.clip(np.floor(fz).astype(int), 0, self.z_tab.size - 2)
        wz = fz - i0
        lo, hi = self.depth_limits(z)
        t = np.clip((r - lo) / np.maximum(hi - lo, 1e-12), 0.0, 1.0)
        ft = t * (self.t_tab.size - 1)
        j0 = np.clip(np.floor(ft).astype(int), 0, self.t_tab.size - 2)
        wt = ft - j0
        v = ((1 - wz) * ((1 - wt) * table[i0, j0] + wt * table[i0, j0 + 1])
             + wz * ((1 - wt) * table[i0 + 1, j0] + wt * table[i0 + 1, j0 + 1]))
        return v, lo, hi

    def depth_limits(self, z: NDArray) -> tuple[NDArray, NDArray]:
        """Lower and upper radius of the active profile at face positions ``z`` (mm)."""
        az = np.clip(np.abs(np.asarray(z, dtype=float)), 0.0, self.half_face)
        return np.interp(az, self.z_tab, self.r_lo), np.interp(az, self.z_tab, self.r_hi)

    def geometry(self, z: NDArray, r: NDArray) -> dict[str, NDArray]:
        """Per-contact constants (arrays like ``z``): curvatures, profile length ``L``,
        Hertz constants and the switch load ``W*`` (N) from elliptic to line contact."""
        z = np.asarray(z, dtype=float)
        r = np.asarray(r, dtype=float)
        A_f, lo, hi = self._lookup(self.A_f, z, r)
        A_p, _, _ = self._lookup(self.A_p, z, r)
        A_f = np.maximum(A_f, 1e-9)
        A_p = np.minimum(A_p, A_f)  # A_p <= A_f: profile is the long axis
        L = np.maximum(developed_arc(hi, self.r_b) - developed_arc(lo, self.r_b), 1e-6)
        ratio = np.where(A_p > 0, divide(A_f, A_p), np.inf)  # R_y / R_x >= 1
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            k = ratio ** (2 / math.pi)
            eps = 1 + (math.pi / 2 - 1) / ratio
            Rp = 1.0 / (A_f + A_p)
            E2 = 2.0 * self.E_star  # Hamrock-Brewe E'
            # semi-axis across the depth a = (6 k² eps W R'/(pi E'))^(1/3) = L/2 at W*
            w_star = (0.5 * L) ** 3 * math.pi * E2 / (6 * k**2 * eps * Rp)
        w_star = np.where(np.isfinite(w_star) & (ratio < 1e12), w_star, 0.0)
        return {"A_f": A_f, "A_p": A_p, "L": L, "k": np.where(np.isfinite(k), k, 1.0),
                "eps": np.where(np.isfinite(eps), eps, 1.0), "Rp": Rp, "ratio": ratio,
                "w_star": w_star, "r": r, "z": z}

    # ------------------------------------------------------------------ contact laws
    def _hertz(self, W, g):
        """Semi-axes (across the depth, along the face) and p0 of the elliptic contact."""
        E2 = 2.0 * self.E_star
        k, eps, Rp = g["k"], g["eps"], g["Rp"]
        with np.errstate(divide="ignore", invalid="ignore"):
            a = np.cbrt(6 * k**2 * eps * W * Rp / (math.pi * E2))
            b = np.cbrt(6 * eps * W * Rp / (math.pi * k * E2))
            p0 = np.where(W > 0, 1.5 * W / (math.pi * a * b), 0.0)
        return a, b, p0

    def _line(self, W, g):
        """Half-width along the face and p0 of the line contact."""
        L = g["L"]
        b = np.sqrt(4 * W / (g["A_f"] * math.pi * L * self.E_star))
        with np.errstate(divide="ignore", invalid="ignore"):
            p0 = np.where(W > 0, 2 * W / (math.pi * np.maximum(b, TINY) * L), 0.0)
        return b, p0

    def _half_thickness(self, r):
        c = _geometry_only(self.spec, CantileverCompliance)
        return c.half_thickness("hub", r), c.half_thickness("sleeve", r)

    def laws(self, g: dict) -> dict[str, NDArray]:
        """Constants of the load-approach law at each contact (precomputed once):
        ``delta_h = a_h W^(2/3)`` and ``delta_l = W sum_i kappa_i max(lam_i - ln(W)/2, 1)``."""
        E2 = 2.0 * self.E_star
        with np.errstate(divide="ignore", invalid="ignore"):
            F = math.pi / 2 + (math.pi / 2 - 1) * np.log(np.minimum(g["ratio"], 1e12))
            a_h = F * np.cbrt(9 / (2 * g["eps"] * g["Rp"]) / (math.pi * g["k"] * E2) ** 2)
        beta = np.sqrt(4 / (g["A_f"] * math.pi * g["L"] * self.E_star))  # b = beta sqrt(W)
        kap, lam = [], []
        halfspace = springs_of(self.spec).far_field  # the strip's bracket (docstring)
        strip = np.log(2 * g["L"] / beta) - math.log(ELLIPTIC_STRIP_WIDTH) + 0.5 if halfspace \
            else None
        for mat, h in zip(self.mats, self._half_thickness(g["r"]), strict=True):
            nu, E = mat.poisson_ratio, mat.youngs_modulus_MPa
            kap.append(2 * (1 - nu**2) / (math.pi * g["L"] * E))
            lam.append(strip if halfspace else
                       np.log(2 * np.maximum(h, 1e-9) / beta) - nu / (2 * (1 - nu)))
        law = {"a_h": np.where(np.isfinite(a_h), a_h, 0.0), "w_star": g["w_star"],
               "kap": kap, "lam": lam}
        law["d_star"] = law["a_h"] * np.cbrt(g["w_star"] ** 2)
        law["l_star"] = self._line_approach(g["w_star"], law)[0]
        return law

    @staticmethod
    def _line_approach(W, law):
        with np.errstate(divide="ignore"):
            half_ln = 0.5 * np.log(np.maximum(W, TINY))
        d = np.zeros_like(W)
        s = np.zeros_like(W)
        for kap, lam in zip(law["kap"], law["lam"], strict=True):
            br = lam - half_ln
            free = br > LN_FLOOR
            d = d + kap * np.where(free, br, LN_FLOOR)
            s = s + kap * np.where(free, br - 0.5, LN_FLOOR)
        return W * d, s

    def approach_mm(self, W: NDArray, law: dict) -> tuple[NDArray, NDArray]:
        """Normal approach (mm) under normal load ``W`` (N) and its slope (mm/N): Hertz up to
        ``W*``, then Hertz(W*) plus the line-contact increment (continuous, increasing)."""
        W = np.maximum(W, 0.0)
        hertz = W < law["w_star"]
        with np.errstate(divide="ignore"):
            dh = law["a_h"] * np.cbrt(W) ** 2  # not cbrt(W * W): no overflow at huge loads
            sh = np.where(W > 0, (2 / 3) * law["a_h"] / np.cbrt(np.maximum(W, TINY)), np.inf)
        dl, sl = self._line_approach(W, law)
        delta = np.where(hertz, dh, law["d_star"] + dl - law["l_star"])
        slope = np.where(hertz, sh, sl)
        return delta, slope

    def _first_load(self, target, g, hertz_value, line_coeff, line_power):
        """Smallest load at which a quantity increasing as ``value(W*) (W/W*)^(1/3)`` up to
        ``W*`` (Hertz), then ``line_coeff W^line_power`` (line), reaches ``target``."""
        ws = g["w_star"]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            w_h = ws * (target / hertz_value) ** 3
            w_l = (target / line_coeff) ** (1.0 / line_power)
        hertz = (ws > 0) & (target <= hertz_value)
        return np.where(hertz, w_h, np.maximum(w_l, ws))

    def pressure_limit_load(self, p_MPa: float, g: dict) -> NDArray:
        """Normal load (N) at which the interior pressure first reaches ``p_MPa``."""
        ws = np.maximum(g["w_star"], TINY)
        _, _, p_h = self._hertz(ws, g)
        beta = np.sqrt(4 / (g["A_f"] * math.pi * g["L"] * self.E_star))
        line = 2 / (math.pi * beta * g["L"])  # p0 = line sqrt(W)
        return self._first_load(np.full(ws.shape, p_MPa), g, p_h, line, 0.5)

    def half_length_limit_load(self, half_mm: NDArray, g: dict) -> NDArray:
        """Normal load (N) at which the patch half-length along the face reaches ``half_mm``."""
        ws = np.maximum(g["w_star"], TINY)
        _, b_h, _ = self._hertz(ws, g)
        beta = np.sqrt(4 / (g["A_f"] * math.pi * g["L"] * self.E_star))
        return self._first_load(np.asarray(half_mm, dtype=float), g, b_h, beta, 0.5)

    def estimates(self, W: NDArray, g: dict) -> dict[str, NDArray]:
        """Pressures and patch sizes at normal load ``W`` (arrays named as in LoadResult)."""
        W = np.maximum(np.asarray(W, dtype=float), 0.0)
        hertz = (W <= g["w_star"]) & (W > 0)
        a, b_h, p_h = self._hertz(W, g)
        b_l, p_l = self._line(W, g)
        half_len = np.where(hertz, b_h, b_l)  # along the face
        width = np.where(hertz, 2 * a, g["L"])  # across the depth
        p0 = np.where(hertz, p_h, p_l)
        room = self.half_face - np.abs(g["z"])
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.clip(np.where(half_len > 0, room / half_len, 1.0), -1.0, 1.0)
        share = (np.arccos(u) - u * np.sqrt(1 - u**2)) / math.pi
        share = np.where(W > 0, share, 0.0)
        edge = (W > 0) & (u < 1.0)
        p_max = np.where(edge, p0 / np.maximum(1 - share, 1e-3), p0)
        regime = np.where(W > 0, np.where(hertz, REGIME["hertz"], REGIME["line"]),
                          REGIME["none"]).astype(np.int8)
        return {"max_pressure_MPa": np.nan_to_num(p_max), "interior_pressure_MPa":
                np.nan_to_num(p0), "edge_load_share": share, "edge_contact": edge,
                "patch_length_mm": np.where(W > 0, 2 * np.minimum(half_len, self.half_face), 0),
                "patch_width_mm": np.where(W > 0, width, 0.0), "contact_regime": regime}


@lru_cache(maxsize=32)
def contact_model(spec: CouplingSpec) -> ContactModel:
    """The cached :class:`ContactModel` of a spec."""
    return ContactModel(spec)


@lru_cache(maxsize=32)
def _geometry_only(spec: CouplingSpec, cls):
    return cls(spec, n_radii=2, n_quad=3)


def contact_estimates(spec: CouplingSpec, normal_force_N: NDArray, z_mm: NDArray,
                      r_mm: NDArray) -> dict[str, NDArray]:
    """Pressures, patch and regime at given normal loads, plus the root stress."""
    cm = contact_model(spec)
    g = cm.geometry(z_mm, r_mm)
    out = cm.estimates(normal_force_N, g)
    out["root_stress_MPa"] = nominal_root_stress_MPa(spec, normal_force_N, z_mm, r_mm)
    return out
