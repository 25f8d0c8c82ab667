"""The default tooth springs: the FE tooth table's far field, by a fit shipped with the package.

The FE tooth-spring table (:func:`gearcoupling.fea.tooth_compliance_table`, ``[load]
stiffness = "fe"``) is what the load models were validated with against the CalculiX contact
reference, but it needs gmsh, CalculiX and minutes per spec. This is its fit, with no
solver at run time (``stiffness = "fe-fit"``, the default): for each part (hub, sleeve) the
far field at a load point ``(z, r)`` of the hub flank is

    c_part(z, r) = c_bend(r) / y_F · exp(sum_i a_i f_i(z, r)) - b c_patch exp(-y_F / (l m))

with ``c_bend`` the bending of the tapered tooth of the real thickness per unit width (the
bending term of :meth:`.cantilever.CantileverCompliance.components`; its shear, compression
and foundation terms are local deformation that the far field leaves to the contact's half-
space), spread over a width of the order of the load height ``y_F`` above the part's root
circle, and ``f_i`` dimensionless features of the load point and the part
(:func:`features`): how high the load sits on the tooth against its root thickness, how
near it is to a face end and to the tooth's free edge along the depth (where a plate's free
edge makes it softer), and how much thinner the crown makes the hub tooth there (the hob's
infeed ``delta(z)`` along the face takes ``delta tan(phi)`` off each flank; the
cantilever's bending is that of mid-face), and the pressure angle, alone and with the
load height (``c_bend`` has only part of the pressure angle's effect: without these
features the fit's error ran with it, to -17 % at 25-29°). The tooth's shape and tooth
count enter through ``c_bend``; the rim, the fillets and the tooth count were tried as
features too and made the fit worse on specs left out of it (``benchmarks/bench_springs.py
--holdout``), so the ranges of the data set in them, and in the tooth depth, are checked
instead (:attr:`FittedCompliance.outside`). The last term is the root's confinement: near its root
circle a tooth is stiffer under a patch than the half-space the far field was split from
(an internal tooth's concave root most), so the far field there is below zero; ``c_patch``
is the half-space work of the table's load patch (a square of side module / 2), ``b`` and
``l`` fitted per part. The pair's far field is the sum of the two parts', turned to Renzo's
measure (circumferential at the pitch point per tangential load there) by ``1 / cos² phi``
like the cantilever's, times a correction (:meth:`FittedCompliance.correction`): ``exp`` of
the mean of a Gaussian process fitted to the log error the parts' fit leaves at the data
set's load points (squared-exponential kernel over 14 of the features, both parts',
standardised; lengths, variance and noise by maximum marginal likelihood, the noise at
least (2 %)²; :func:`gp_mean`), evaluated by a spline per spec. Away from the data set it
fades to a factor of 1; along the face it is held beyond the tables' last load row, whose
patch is flush with the face end. The
coefficients ``a_i``, ``b``, ``l`` and the correction are fitted to FE tables of the
bundled templates and of seeded random specs over the supported range and shipped as
``fitted.json`` (``benchmarks/bench_springs.py --fit`` regenerates the data set, fits and
prints the error at every load point of every table; docs/load.md has the table).

Accuracy and range (docs/load.md, "Tooth springs", has the table per spec): against the 40
FE tables it was fitted on (4 rows along the face, the last at the face end), the pair's
far field is within −7.4 … +7.8 % at every load point (the parts' fit alone: −21.9 …
+22.9 %, most at the face end), the whole compliance within −2.9 … +2.6 %; on random specs
left out of the fit (``--holdout 2``, 3, 4) within −15.8 … +20.2 % (8/6/4 specs) where they
lie inside the ranges of the rest, the whole compliance within 7.5 %. Between the
tables' rows, against FE solved there on four specs, within −8.4 … +4.7 %. The ranges
(``fitted.json``, ``spec_ranges``): 14–260 teeth, module 0.22–48.7 mm, pressure angle
14.6–29.0°, face / module 3.5–19.3, tooth depth / module 1.14–2.33, and the rim, ring
and fillet ratios of the data set. Where a spec lies outside them
(:attr:`FittedCompliance.outside`), the fit is still evaluated (each feature held at the
nearest edge of its fitted range) and the result and the report name what lies outside.
The load models read it held along the face at 0.8 of the half face
(:class:`gearcoupling.loading.springs.HeldAlongFace`).
"""

from __future__ import annotations

import json
import math
from functools import cached_property, lru_cache
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...fea import default_patch_mm, load_rows_mm, rectangle_halfspace_work_mm_per_N
from ...geometry import hub_model
from ...spec import CouplingSpec
from .cantilever import CantileverCompliance

PARTS = ("hub", "sleeve")
CORRECTION_GRID = (25, 25)
"""Knots of the correction's spline per spec: along ``|z|`` from mid-face to the FE tables'
last load row, closer toward it (``sin``), and across the flank's radii, closer toward
both ends (``cos``) (:meth:`FittedCompliance.correction`)."""
FLOOR = 0.05  # the pair's far field, at least this share of its bending at the pitch point
FEATURES = ("one", "height", "height_squared", "face_end", "face_end_height", "other_end",
            "tip_edge", "crown_thinning", "pressure_angle", "pressure_angle_height")


def features(y_F: ArrayLike, to_face_ends: tuple[ArrayLike, ArrayLike], to_tip: ArrayLike,
             thinning: ArrayLike, *, module: float, root_thickness: float,
             pressure_angle: float) -> NDArray[np.float64]:
    """Features ``(..., len(FEATURES))`` of load points of one part (:data:`FEATURES`):
    ``1``, ``ln(y_F / S_f)`` and its square, ``exp(-d1 / m)``, ``exp(-d1 / y_F)``,
    ``exp(-d2 / m)``, ``exp(-d_t / m)``, ``ln(1 - t_c / S_f)``, ``a = (phi - 20°) / 10°``
    and ``a ln(y_F / S_f)``.

    Parameters
    ----------
    y_F : (...) float
        Load height above the part's root circle (mm).
    to_face_ends : ((...) float, (...) float)
        Distances ``d1 <= d2`` from the load point to the part's nearer and farther face
        end (mm).
    to_tip : (...) float
        Distance ``d_t`` from the load point to the tooth's free edge along the depth (the
        hub tip, the sleeve minor circle), mm.
    thinning : (...) float
        ``t_c``: how much thinner the crown makes the tooth at the load's face position,
        ``2 delta(z) tan(phi)`` for the hub's crown drop ``delta``, 0 for the straight
        sleeve (mm); held below 0.9 ``S_f``.
    module : float
    root_thickness : float
        The tooth's thickness ``S_f`` at its root circle (mm).
    pressure_angle : float
        ``phi`` (radians).
    """
    m = module
    y = np.maximum(np.asarray(y_F, dtype=float), 1e-3 * m)
    d1, d2, dt = (np.maximum(np.asarray(v, dtype=float), 0.0) for v in (*to_face_ends, to_tip))
    thin = np.clip(np.asarray(thinning, dtype=float) / root_thickness, 0.0, 0.9)
    y, d1, d2, dt, thin = np.broadcast_arrays(y, d1, d2, dt, thin)
    h = np.log(y / root_thickness)
    a = (math.degrees(pressure_angle) - 20.0) / 10.0
    return np.stack([np.ones(y.shape), h, h * h, np.exp(-d1 / m), np.exp(-d1 / y),
                     np.exp(-d2 / m), np.exp(-dt / m), np.log1p(-thin), np.full(y.shape, a),
                     a * h], axis=-1)


def gp_mean(x: ArrayLike, gp: dict[str, Any]) -> NDArray[np.float64]:
    """The mean ``(n,)`` of a Gaussian process with a squared-exponential kernel at inputs
    ``x (n, d)``: ``variance exp(-|(x' - X) / length|^2 / 2) @ weights`` with ``x'`` the
    inputs standardised by ``mean`` and ``scale`` and ``X (N, d)`` the standardised
    ``points`` it was fitted on (the keys of ``gp``; ``benchmarks/bench_springs.py``)."""
    length = np.asarray(gp["length"], dtype=float)
    a = (np.asarray(x, dtype=float) - gp["mean"]) / gp["scale"] / length
    b = np.asarray(gp["points"], dtype=float) / length
    d2 = np.sum(a * a, axis=1)[:, None] + np.sum(b * b, axis=1)[None, :] - 2.0 * a @ b.T
    # beyond a distance of 30 lengths a point adds nothing (exp(-450)); held there, exp
    # stays clear of subnormal numbers (an order of magnitude slower)
    k = np.exp(-0.5 * np.clip(d2, 0.0, 900.0))
    return gp["variance"] * k @ np.asarray(gp["weights"], dtype=float)


@lru_cache(maxsize=1)
def load_fit() -> dict[str, Any]:
    """The shipped coefficients and fitted ranges (``fitted.json`` beside this module; read
    once, shared: do not change it)."""
    text = resources.files("gearcoupling.loading.kernels").joinpath("fitted.json").read_text()
    return json.loads(text)


def _as_arrays(gp: dict[str, Any]) -> dict[str, Any]:
    return {k: np.asarray(v, dtype=float) if isinstance(v, list) else v
            for k, v in gp.items() if k != "inputs"}


@lru_cache(maxsize=1)
def _shipped_correction() -> dict[str, Any]:
    return _as_arrays(load_fit()["correction"])


class FittedCompliance(CantileverCompliance):
    """Far-field tooth-pair compliance of a spec from the shipped fit (module docstring);
    the same protocol as the cantilever and the FE table:
    :meth:`pair_compliance_mm_per_N`."""

    def __init__(self, spec: CouplingSpec, *, fit: dict[str, Any] | None = None,
                 n_radii: int = 64, n_quad: int = 201):
        super().__init__(spec, n_radii=n_radii, n_quad=n_quad)
        self.fit = load_fit() if fit is None else fit
        t = spec.tooth
        self.module, self.teeth = t.module, t.teeth
        bore = 0.5 * spec.hub.body.bore_diameter
        self.rim = {"hub": self.r_root_hub - bore,
                    "sleeve": 0.5 * spec.sleeve.outer_diameter - self.r_root_sleeve}
        self.root_thickness = {p: 2.0 * float(self.half_thickness(p, self._heights(p, 0.0)[0]))
                               for p in PARTS}
        self.fillet = {"hub": spec.hub.root.fillet_radius,
                       "sleeve": spec.sleeve.root_fillet_radius}
        #: the tooth's free edge along the depth: hub tip and sleeve minor radius
        self.tip_radius = {"hub": 0.5 * spec.hub.tip.diameter,
                           "sleeve": 0.5 * spec.sleeve.minor_diameter}
        #: the hub tooth's depth, tip to root circle (mm)
        self.depth = self.tip_radius["hub"] - self._heights("hub", 0.0)[0]
        self.bend = {p: self.terms[p][0] for p in PARTS}
        self.crown = hub_model(spec).path  # the hub's crown drop along the face
        side = 0.5 * self.module  # the table's load patch, a square (module docstring)
        self.patch = {p: rectangle_halfspace_work_mm_per_N(
            1.0, side, side, getattr(self.materials, p).youngs_modulus_MPa,
            getattr(self.materials, p).poisson_ratio) for p in PARTS}
        #: ``|z|`` of the FE table's last load row (mm; :func:`~gearcoupling.fea.load_rows_mm`)
        self.last_row_mm = float(load_rows_mm(spec, default_patch_mm(spec))[-1])
        #: the columns of :data:`FEATURES` the fit uses (``fit["features"]``, by name)
        self.columns = [FEATURES.index(name) for name in self.fit["features"]]
        #: per part: coefficients (F,), the features' fitted low and high ends (F,),
        #: the confinement's factor and length (modules)
        self.coefficients = {p: tuple(np.asarray(self.fit["parts"][p][k], dtype=float)
                                      for k in ("coefficients", "low", "high"))
                             for p in PARTS}

    def part_features(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """:func:`features` of ``part`` at hub flank points ``(z, r)``."""
        r = np.clip(np.asarray(r_mm, dtype=float), self.r_table[0], self.r_table[-1])
        root, _ = self._heights(part, 0.0)
        half = self.half_face_hub if part == "hub" else self.half_face_sleeve
        z = np.abs(np.asarray(z_mm, dtype=float))
        thinning = (2.0 * math.tan(self.phi) * self.crown.drop(np.minimum(z, half))
                    if part == "hub" else np.zeros_like(z))
        return features(np.abs(r - root), (half - z, half + z),
                        np.abs(self.tip_radius[part] - r), thinning, module=self.module,
                        root_thickness=self.root_thickness[part], pressure_angle=self.phi)

    def bending(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """``c_bend / y_F`` of ``part`` at hub flank points ``(z, r)`` (mm/N; module
        docstring)."""
        r, y_F = self._height(part, r_mm)
        return np.broadcast_to(np.interp(r, self.r_table, self.bend[part]) / y_F,
                               np.broadcast_shapes(np.shape(z_mm), np.shape(r)))

    def confinement(self, part: str, r_mm: ArrayLike, length: float) -> NDArray:
        """``c_patch exp(-y_F / (length m))`` of ``part`` (mm/N; module docstring)."""
        _, y_F = self._height(part, r_mm)
        return self.patch[part] * np.exp(-y_F / (length * self.module))

    def _height(self, part: str, r_mm: ArrayLike):
        r = np.clip(np.asarray(r_mm, dtype=float), self.r_table[0], self.r_table[-1])
        root, _ = self._heights(part, 0.0)
        return r, np.maximum(np.abs(r - root), 1e-3 * self.module)

    def spread_bending(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike,
                       features: NDArray | None = None) -> NDArray:
        """The first, positive term of :meth:`part_compliance_mm_per_N` (mm/N);
        ``features``: the part's :meth:`part_features` at these points, if known."""
        f = self.part_features(part, z_mm, r_mm) if features is None else features
        a, lo, hi = self.coefficients[part]
        return self.bending(part, z_mm, r_mm) * np.exp(np.clip(f[..., self.columns], lo, hi) @ a)

    def part_compliance_mm_per_N(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """Normal far-field compliance of one part at hub flank points ``(z, r)`` (mm/N),
        with the pair's :meth:`correction`.

        Only the two parts' sum is fitted to FE: one part alone is not its FE far field
        (against the 40 tables, the hub's share up to 79 % of the pair's far field too high
        and the sleeve's up to 84 % too low, in opposite senses)."""
        return self.normal_compliance_mm_per_N(z_mm, r_mm)[PARTS.index(part)]

    def correction(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """The pair's factor on the parts' fit at hub flank points ``(z, r)``: ``exp`` of
        the Gaussian-process mean of the fit's log error over the data set (module
        docstring), 1 without one in the fit; it fades to 1 away from the data set.
        Beyond the tables' last load row along the face (:attr:`last_row_mm`, the patch
        flush with the face end) it is held at its value there, as the table is: the
        process has no data there. Evaluated by a bicubic spline of the log of
        :meth:`exact_correction` on :data:`CORRECTION_GRID` knots over ``|z|`` and ``r``
        (the process itself is costly per point; docs/load.md has the spline's error)."""
        shape = np.broadcast_shapes(np.shape(z_mm), np.shape(r_mm))
        spline = self._correction_spline
        if spline is None:
            return np.ones(shape)
        z = np.minimum(np.abs(np.broadcast_to(np.asarray(z_mm, dtype=float), shape)),
                       self.last_row_mm)
        r = np.clip(np.broadcast_to(np.asarray(r_mm, dtype=float), shape),
                    self.r_table[0], self.r_table[-1])
        return np.exp(spline(z.ravel(), r.ravel(), grid=False)).reshape(shape)

    def exact_correction(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """:meth:`correction` from the Gaussian process itself, at every point."""
        shape = np.broadcast_shapes(np.shape(z_mm), np.shape(r_mm))
        if self._gp is None:
            return np.ones(shape)
        gp, columns = self._gp
        z = np.clip(np.asarray(z_mm, dtype=float), -self.last_row_mm, self.last_row_mm)
        features = {p: self.part_features(p, z, r_mm) for p in PARTS}
        x = np.concatenate([np.broadcast_to(features[p], (*shape, len(FEATURES)))[..., columns[p]]
                            for p in PARTS], axis=-1).reshape(-1, gp["mean"].size)
        return np.exp(gp_mean(x, gp)).reshape(shape)

    @cached_property
    def _correction_spline(self):
        """The bicubic spline of :meth:`correction` (scipy ``RectBivariateSpline``), None
        without a correction in the fit."""
        if self._gp is None:
            return None
        from scipy.interpolate import RectBivariateSpline

        nz, nr = CORRECTION_GRID
        z = self.last_row_mm * np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, nz))
        lo, hi = self.r_table[0], self.r_table[-1]
        r = lo + 0.5 * (hi - lo) * (1.0 - np.cos(np.pi * np.linspace(0.0, 1.0, nr)))
        log = np.log(self.exact_correction(z[:, None], r[None, :]))
        return RectBivariateSpline(z, r, log, kx=3, ky=3)

    @cached_property
    def _gp(self) -> tuple[dict[str, Any], dict[str, list[int]]] | None:
        """The fit's correction as arrays, and the feature columns of its inputs per part."""
        gp = self.fit.get("correction")
        if gp is None:
            return None
        arrays = _shipped_correction() if self.fit is load_fit() else _as_arrays(gp)
        return arrays, {p: [FEATURES.index(n) for n in gp["inputs"][p]] for p in PARTS}

    def normal_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike):
        """Hub and sleeve normal far-field compliances at the load (mm/N), broadcast."""
        f = {p: self.part_features(p, z_mm, r_mm) for p in PARTS}
        factor = self.correction(z_mm, r_mm)
        out = []
        for p in PARTS:
            c = self.fit["parts"][p]
            base = (self.spread_bending(p, z_mm, r_mm, f[p])
                    - c["confinement"] * self.confinement(p, r_mm, c["confinement_length"]))
            out.append(base * factor)
        return tuple(out)

    def pair_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """The pair's far field (Renzo's measure, mm/N), at least :data:`FLOOR` of its
        bending terms at mid-face and the pitch radius: near a root circle, beyond the load
        points the fit was made on, or on a spec outside its range, its confinement term
        could take it below zero (the FE table's pair far field is positive)."""
        pair = super().pair_compliance_mm_per_N(z_mm, r_mm)
        return np.maximum(pair, FLOOR * self._pitch_point)

    @cached_property
    def _pitch_point(self) -> float:
        bend = sum(float(self.spread_bending(p, 0.0, self.R)) for p in PARTS)
        return bend / math.cos(self.phi) ** 2

    @property
    def mesh_stiffness_N_per_mm(self) -> float:
        """Renzo's C of one tooth pair, as the FE table defines it (the linear model's
        default): 1 / (the far field at mid-face and the pitch radius + the local
        deformation under the table's load patch, a uniform pressure on a square of side
        module / 2 of an elastic half-space, each part, under the normal force of a unit
        tangential load)."""
        side, force = 0.5 * self.module, 1.0 / math.cos(self.phi)
        near = sum(rectangle_halfspace_work_mm_per_N(force, side, side, m.youngs_modulus_MPa,
                                                     m.poisson_ratio)
                   for m in (self.materials.hub, self.materials.sleeve))
        return 1.0 / (float(self.pair_compliance_mm_per_N(0.0, self.R)) + near)

    @cached_property
    def outside(self) -> list[str]:
        """What of this spec lies outside the fitted ranges (empty: inside)."""
        notes = []
        spec_ranges = self.fit.get("spec_ranges", {})
        values = {"teeth": self.teeth, "module_mm": self.module,
                  "pressure_angle_deg": math.degrees(self.phi),
                  "face_over_module": 2.0 * self.half_face_hub / self.module,
                  "depth_over_module": self.depth / self.module,
                  "hub_rim_over_module": self.rim["hub"] / self.module,
                  "sleeve_ring_over_module": self.rim["sleeve"] / self.module,
                  "hub_fillet_over_module": self.fillet["hub"] / self.module,
                  "sleeve_fillet_over_module": self.fillet["sleeve"] / self.module}
        for key, v in values.items():
            if key in spec_ranges:
                lo, hi = spec_ranges[key]
                if not lo <= v <= hi:
                    notes.append(f"{key} = {v:.3g} outside the fitted {lo:.3g}-{hi:.3g}")
        return notes
