"""The default tooth springs: the FE tooth table's far field, by a fit shipped with the package.

The FE tooth-spring table (:func:`gearcoupling.fea.tooth_compliance_table`, ``[load]
stiffness = "fe"``) is what the load models were validated with against the CalculiX contact
reference, but it needs gmsh, CalculiX and minutes per spec. This is its fit, with no
solver at run time (``stiffness = "fe-fit"``, the default): for each part (hub, sleeve) the
far field at a load point ``(z, r)`` of the hub flank is

    c_part(z, r) = c_beam(r) / (2 y_F) · exp(sum_i a_i f_i(z, r))

with ``c_beam`` the tapered Timoshenko beam of the real tooth thickness per unit width
(bending, shear and compression, :meth:`.cantilever.CantileverCompliance.components`),
``y_F`` the load's height above the part's root circle and ``f_i`` dimensionless features
of the load point and the part (:func:`features`): how high the load sits on the tooth
against its root thickness, how near it is to a face end (where a plate's free edge makes
it softer), the rim or ring under the teeth and the tooth count. The coefficients ``a_i``
per part are fitted to FE tables of the bundled templates and of seeded random specs over
the supported range and shipped as ``fitted.json`` (``benchmarks/bench_springs.py --fit``
regenerates the data set, fits and prints the error at every load point of every table;
docs/load.md has the table). The pair's far field is the sum of the two parts', turned to
Renzo's measure (circumferential at the pitch point per tangential load there) by
``1 / cos² phi`` like the cantilever's.

Where a spec lies outside the ranges the fit was made on (``FittedCompliance.outside``), the
fit is still evaluated (held at the nearest edge of each feature's fitted range) and the
result and the report name what lies outside.
"""

from __future__ import annotations

import json
import math
from functools import cached_property
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..fea import SQUARE_MEAN_INVERSE_DISTANCE
from ..spec import CouplingSpec
from .cantilever import CantileverCompliance

PARTS = ("hub", "sleeve")
FEATURES = ("one", "height", "height_squared", "root_thickness", "tooth_height",
            "edge_height", "edge_module", "rim", "teeth", "pressure_angle")


def features(y_F: ArrayLike, to_face_end: ArrayLike, *, module: float, root_thickness: float,
             tooth_height: float, rim: float, teeth: int,
             pressure_angle: float) -> NDArray[np.float64]:
    """Features ``(..., len(FEATURES))`` of load points of one part (:data:`FEATURES`):
    ``1``, ``ln(y_F / m)`` and its square, ``ln(S_f / m)``, ``ln(H / m)``,
    ``exp(-d / y_F)``, ``exp(-d / m)``, ``ln(t / m)``, ``1 / N``, ``phi - 20°`` (rad).

    Parameters
    ----------
    y_F : (...) float
        Load height above the part's root circle (mm).
    to_face_end : (...) float
        Distance ``d`` from the load point to the part's nearer face end (mm, >= 0).
    module : float
    root_thickness : float
        The tooth's thickness ``S_f`` at its root circle (mm).
    tooth_height : float
        ``H``: from the root circle to the end of the active flank (mm).
    rim : float
        ``t``: radial thickness of the body under the teeth, hub root to bore (the root
        radius for a solid hub), sleeve root to outside (mm).
    teeth : int
    pressure_angle : float
        Radians.
    """
    m = module
    y = np.maximum(np.asarray(y_F, dtype=float), 1e-3 * m)
    d = np.maximum(np.asarray(to_face_end, dtype=float), 0.0)
    y, d = np.broadcast_arrays(y, d)
    h = np.log(y / m)

    def const(v: float) -> NDArray[np.float64]:
        return np.full(y.shape, v)

    return np.stack([const(1.0), h, h * h, const(math.log(root_thickness / m)),
                     const(math.log(tooth_height / m)), np.exp(-d / y), np.exp(-d / m),
                     const(math.log(rim / m)), const(1.0 / teeth),
                     const(pressure_angle - math.radians(20.0))], axis=-1)


def load_fit() -> dict[str, Any]:
    """The shipped coefficients and fitted ranges (``fitted.json`` beside this module)."""
    text = resources.files("gearcoupling.loading").joinpath("fitted.json").read_text()
    return json.loads(text)


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
        top = {"hub": self.r_table[-1], "sleeve": self.r_table[0]}  # active flank ends
        self.tooth_height = {p: float(self._heights(p, top[p])[1]) for p in PARTS}
        self.beam = {p: self.terms[p][0] for p in PARTS}

    def part_features(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """:func:`features` of ``part`` at hub flank points ``(z, r)``."""
        r = np.clip(np.asarray(r_mm, dtype=float), self.r_table[0], self.r_table[-1])
        root, _ = self._heights(part, 0.0)
        half = self.half_face_hub if part == "hub" else self.half_face_sleeve
        return features(np.abs(r - root), half - np.abs(np.asarray(z_mm, dtype=float)),
                        module=self.module, root_thickness=self.root_thickness[part],
                        tooth_height=self.tooth_height[part], rim=self.rim[part],
                        teeth=self.teeth, pressure_angle=self.phi)

    def part_compliance_mm_per_N(self, part: str, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """Normal far-field compliance of one part at hub flank points ``(z, r)`` (mm/N)."""
        r = np.clip(np.asarray(r_mm, dtype=float), self.r_table[0], self.r_table[-1])
        root, _ = self._heights(part, 0.0)
        y_F = np.maximum(np.abs(r - root), 1e-6 * self.module)
        f = self.part_features(part, z_mm, r)
        lo, hi = (np.asarray(self.fit["ranges"][part][k], dtype=float) for k in ("low", "high"))
        a = np.asarray(self.fit["coefficients"][part], dtype=float)
        return np.interp(r, self.r_table, self.beam[part]) / (2.0 * y_F) * np.exp(
            np.clip(f, lo, hi) @ a)

    def normal_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike):
        """Hub and sleeve normal far-field compliances at the load (mm/N), broadcast."""
        return tuple(self.part_compliance_mm_per_N(p, z_mm, r_mm) for p in PARTS)

    @property
    def mesh_stiffness_N_per_mm(self) -> float:
        """Renzo's C of one tooth pair, as the FE table defines it (the linear model's
        default): 1 / (the far field at mid-face and the pitch radius + the local
        deformation under the table's load patch, a uniform square of side module / 2 on
        an elastic half-space, each part)."""
        side = 0.5 * self.module
        near = sum((1.0 - m.poisson_ratio**2) / (math.pi * m.youngs_modulus_MPa)
                   * SQUARE_MEAN_INVERSE_DISTANCE / side
                   for m in (self.materials.hub, self.materials.sleeve))
        far = float(self.pair_compliance_mm_per_N(0.0, self.R))
        return 1.0 / (far + near / math.cos(self.phi) ** 2)

    @cached_property
    def outside(self) -> list[str]:
        """What of this spec lies outside the fitted ranges (empty: inside)."""
        notes = []
        spec_ranges = self.fit.get("spec_ranges", {})
        values = {"teeth": self.teeth, "module_mm": self.module,
                  "pressure_angle_deg": math.degrees(self.phi),
                  "face_over_module": 2.0 * self.half_face_hub / self.module,
                  "hub_rim_over_module": self.rim["hub"] / self.module,
                  "sleeve_ring_over_module": self.rim["sleeve"] / self.module}
        for key, v in values.items():
            if key in spec_ranges:
                lo, hi = spec_ranges[key]
                if not lo <= v <= hi:
                    notes.append(f"{key} = {v:.3g} outside the fitted {lo:.3g}-{hi:.3g}")
        return notes
