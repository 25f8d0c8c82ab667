"""The ``[load]`` and ``[material]`` spec sections (docs/conventions.md, Loaded analysis).

SI keys and their inch-pound alternatives (``torque_Nm`` | ``torque_lbf_in`` ...): give at
most one of each pair; inch-pound values are converted at loading, so the dataclasses hold
N, N·m, N/mm, MPa and kg/m³ only. ``[material]`` keys apply to both parts;
``[material.hub]`` and ``[material.sleeve]`` override them per part. Defaults:
through-hardened alloy steel (E = 206 000 MPa, nu = 0.3, allowable contact stress 700 MPa,
allowable root bending stress 280 MPa: ISO 6336-5 MQ limits of a ~300 HB
quenched-and-tempered steel; density 7850 kg/m³, taken only while E is a steel's,
190 000-220 000 MPa: another material must give its density).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from .arguments import torque_Nm as check_torque_Nm
from .errors import SpecError
from .io import Table

N_PER_LBF = 4.4482216152605
NM_PER_LBF_IN = N_PER_LBF * 0.0254
N_PER_MM_PER_LBF_PER_IN = N_PER_LBF / 25.4
MPA_PER_PSI = N_PER_LBF / 25.4**2
KG_PER_M3_PER_LB_PER_IN3 = 0.45359237 / 0.0254**3

# the load models a spec file may name (gearcoupling.loading.MODELS holds what each is;
# tests/test_load_models.py holds the two equal)
LOAD_MODELS = ("linear", "compliance", "surface")
# the tooth springs (gearcoupling.loading.springs.SPRINGS holds what each is)
STIFFNESS_SOURCES = ("fe-fit", "fe", "cantilever")
STEEL = {"youngs_modulus_MPa": 206_000.0, "poisson_ratio": 0.3,
         "allowable_contact_stress_MPa": 700.0, "allowable_bending_stress_MPa": 280.0,
         "density_kg_per_m3": 7850.0}
STEEL_MODULUS_RANGE_MPA = (190_000.0, 220_000.0)  # E of the steels the default density fits


def _finite_positive(path: str, value: float | None, *, optional: bool = False) -> None:
    if value is None and optional:
        return
    ok = isinstance(value, int | float) and math.isfinite(value) and value > 0
    if not ok:
        raise SpecError(path, value, "must be a positive finite number"
                        + (" (or omitted)" if optional else ""))


@dataclass(frozen=True)
class LoadSpec:
    """Loaded-contact settings (SI units).

    Attributes
    ----------
    torque_Nm : float or None
        Transmitted torque; the sign picks the loaded flank (positive loads ccw).
    model : str
        ``surface`` (default: the validated one), ``compliance`` (a fast estimate) or
        ``linear`` (Renzo).
    mesh_stiffness_N_per_mm : float or None
        Renzo's ``C`` for the linear model; ``None`` takes the cantilever pair stiffness at
        the pitch point in the midplane.
    allowable_tooth_load_N : float or None
        Renzo's ``P_i`` (tangential at the pitch radius); ``None`` drops that criterion.
    friction : float
        Coulomb coefficient at the flanks (0-1).
    accuracy_factor : float
        Renzo's ``K`` (0-1], 1 = perfect teeth.
    stiffness : str
        Tooth springs of the compliance and surface models: ``fe-fit`` (default: the FE
        far field by the shipped fit), ``fe`` (the FE table itself) or ``cantilever``
        (gearcoupling.loading.springs).
    """

    torque_Nm: float | None = None
    model: str = "surface"
    mesh_stiffness_N_per_mm: float | None = None
    allowable_tooth_load_N: float | None = None
    friction: float = 0.1
    accuracy_factor: float = 1.0
    stiffness: str = "fe-fit"

    def __post_init__(self):
        if self.torque_Nm is not None:  # the range of every entry point
            check_torque_Nm(self.torque_Nm, "load.torque_Nm", error=SpecError)
        if self.model not in LOAD_MODELS:
            raise SpecError("load.model", self.model, f"one of {LOAD_MODELS}")
        if self.stiffness not in STIFFNESS_SOURCES:
            raise SpecError("load.stiffness", self.stiffness, f"one of {STIFFNESS_SOURCES}")
        _finite_positive("load.mesh_stiffness_N_per_mm", self.mesh_stiffness_N_per_mm,
                         optional=True)
        _finite_positive("load.allowable_tooth_load_N", self.allowable_tooth_load_N,
                         optional=True)
        f = self.friction
        if not (isinstance(f, int | float) and 0 <= f <= 1):
            raise SpecError("load.friction", f, "must be a coefficient from 0 to 1")
        k = self.accuracy_factor
        if not (isinstance(k, int | float) and 0 < k <= 1):
            raise SpecError("load.accuracy_factor", k, "must be in (0, 1] (1 = perfect teeth)")


@dataclass(frozen=True)
class Material:
    """Elastic constants and allowable stresses (MPa) and density (kg/m³) of one part.

    ``density_kg_per_m3`` left out is steel's while ``E`` is a steel's (module docstring)
    and ``None`` otherwise (:meth:`mass_density_kg_per_m3` then refuses).
    """

    youngs_modulus_MPa: float = STEEL["youngs_modulus_MPa"]
    poisson_ratio: float = STEEL["poisson_ratio"]
    allowable_contact_stress_MPa: float = STEEL["allowable_contact_stress_MPa"]
    allowable_bending_stress_MPa: float = STEEL["allowable_bending_stress_MPa"]
    density_kg_per_m3: float | None = None
    part: str = field(default="hub", compare=False, repr=False)

    def __post_init__(self):
        p = f"material.{self.part}"
        _finite_positive(f"{p}.youngs_modulus_MPa", self.youngs_modulus_MPa)
        _finite_positive(f"{p}.density_kg_per_m3", self.density_kg_per_m3, optional=True)
        lo, hi = STEEL_MODULUS_RANGE_MPA
        if self.density_kg_per_m3 is None and lo <= self.youngs_modulus_MPa <= hi:
            object.__setattr__(self, "density_kg_per_m3", STEEL["density_kg_per_m3"])
        _finite_positive(f"{p}.allowable_contact_stress_MPa", self.allowable_contact_stress_MPa)
        _finite_positive(f"{p}.allowable_bending_stress_MPa", self.allowable_bending_stress_MPa)
        nu = self.poisson_ratio
        if not (isinstance(nu, int | float) and 0 <= nu < 0.5):
            raise SpecError(f"{p}.poisson_ratio", nu, "must be in [0, 0.5)")

    def mass_density_kg_per_m3(self) -> float:
        """The density; a :class:`SpecError` naming the key where it is missing."""
        if self.density_kg_per_m3 is None:
            lo, hi = STEEL_MODULUS_RANGE_MPA
            raise SpecError(f"material.{self.part}.density_kg_per_m3", None,
                            f"is required (kg/m³, or density_lb_per_in3): E = "
                            f"{self.youngs_modulus_MPa:g} MPa is not a steel's ({lo:g}-{hi:g} "
                            "MPa), so steel's 7850 kg/m³ is not assumed")
        return self.density_kg_per_m3

    @property
    def shear_modulus_MPa(self) -> float:
        """``G = E / (2 (1 + nu))``."""
        return self.youngs_modulus_MPa / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class Materials:
    """Materials of the two parts."""

    hub: Material = field(default_factory=lambda: Material(part="hub"))
    sleeve: Material = field(default_factory=lambda: Material(part="sleeve"))

    @property
    def contact_modulus_MPa(self) -> float:
        """``E* = 1 / ((1 - nu1²)/E1 + (1 - nu2²)/E2)`` (Hertz)."""
        return 1.0 / sum((1 - m.poisson_ratio**2) / m.youngs_modulus_MPa
                         for m in (self.hub, self.sleeve))


# --------------------------------------------------------------------------- loading

_LOAD_KEYS = {  # SI key -> (inch-pound key, factor to SI)
    "torque_Nm": ("torque_lbf_in", NM_PER_LBF_IN),
    "mesh_stiffness_N_per_mm": ("mesh_stiffness_lbf_per_in", N_PER_MM_PER_LBF_PER_IN),
    "allowable_tooth_load_N": ("allowable_tooth_load_lbf", N_PER_LBF),
}
_MATERIAL_KEYS = {
    "youngs_modulus_MPa": ("youngs_modulus_psi", MPA_PER_PSI),
    "allowable_contact_stress_MPa": ("allowable_contact_stress_psi", MPA_PER_PSI),
    "allowable_bending_stress_MPa": ("allowable_bending_stress_psi", MPA_PER_PSI),
    "density_kg_per_m3": ("density_lb_per_in3", KG_PER_M3_PER_LB_PER_IN3),
}


# every key of a pair names the other: setting one (an override) removes its sibling
UNIT_SIBLINGS = {k: v for si, (imp, _) in (_LOAD_KEYS | _MATERIAL_KEYS).items()
                 for k, v in ((si, imp), (imp, si))}
LOAD_TABLE_KEYS = (*(k for pair in _LOAD_KEYS.items() for k in (pair[0], pair[1][0])), "model",
                   "stiffness", "friction", "accuracy_factor")
MATERIAL_TABLE_KEYS = (*(k for pair in _MATERIAL_KEYS.items() for k in (pair[0], pair[1][0])),
                       "poisson_ratio")


def _pairs(t: Table, pairs: dict[str, tuple[str, float]]) -> dict[str, float]:
    found = {si: t.pair(si, imp, factor) for si, (imp, factor) in pairs.items()}
    return {k: v for k, v in found.items() if v is not None}


def parse_load(data: Any) -> LoadSpec:
    """A :class:`LoadSpec` from the ``[load]`` table (SI or inch-pound keys)."""
    t = data if isinstance(data, Table) else Table(data, "load")
    kw: dict[str, Any] = _pairs(t, _LOAD_KEYS)
    for key in ("model", "stiffness"):
        if t.has(key):
            kw[key] = t.get(key, str)
    for key in ("friction", "accuracy_factor"):
        if t.has(key):
            kw[key] = t.number(key)
    t.done(LOAD_TABLE_KEYS)
    return LoadSpec(**kw)


def _material_keys(t: Table) -> dict[str, float]:
    kw = _pairs(t, _MATERIAL_KEYS)
    if t.has("poisson_ratio"):
        kw["poisson_ratio"] = t.number("poisson_ratio")
    return kw


def parse_material(data: Any) -> Materials:
    """:class:`Materials` from ``[material]`` (shared keys, ``hub`` / ``sleeve`` sub-tables)."""
    t = data if isinstance(data, Table) else Table(data, "material")
    parts = {p: t.table(p) for p in ("hub", "sleeve")}
    shared = _material_keys(t)
    t.done((*MATERIAL_TABLE_KEYS, "hub", "sleeve"))
    out = {}
    for p, sub in parts.items():
        own = _material_keys(sub)
        sub.done(MATERIAL_TABLE_KEYS)
        out[p] = Material(**{**shared, **own}, part=p)
    return Materials(**out)


# --------------------------------------------------------------------------- wear

#: the keys of ``[wear]``: read here as text and numbers, judged by ``gearcoupling.wear``
#: (its ``WearSettings``, which knows the regimes and the ranges)
WEAR_TABLE_KEYS = ("regime", "coefficient_mm3_per_Nm", "coefficient_band_mm3_per_Nm",
                   "sleeve_factor", "limit_fraction", "required_life_h")


def parse_wear(data: Any) -> tuple[tuple[str, Any], ...]:
    """The ``[wear]`` table as ``(key, value)`` pairs in :data:`WEAR_TABLE_KEYS` order:
    ``regime`` a string, the band an array of numbers, the others numbers; unknown keys
    refused. What each value may be is ``gearcoupling.wear``'s to say."""
    t = data if isinstance(data, Table) else Table(data, "wear")
    out: list[tuple[str, Any]] = []
    for key in WEAR_TABLE_KEYS:
        if not t.has(key):
            continue
        if key == "regime":
            out.append((key, t.get(key, str)))
        elif key == "coefficient_band_mm3_per_Nm":
            out.append((key, t.array(key)))
        else:
            out.append((key, t.number(key)))
    t.done(WEAR_TABLE_KEYS)
    return tuple(out)


__all__ = ["LOAD_MODELS", "UNIT_SIBLINGS", "WEAR_TABLE_KEYS", "LoadSpec", "Material",
           "Materials", "parse_load", "parse_material", "parse_wear"]
