"""The tooth springs by name (``[load] stiffness``): what each is, how it is made and what the
accuracy ladder measured for it (docs/load.md). The one place that knows the names; the
spec's allowed values (:data:`gearcoupling.loadspec.STIFFNESS_SOURCES`) are these keys.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from ..fea import tooth_compliance_table
from ..spec import CouplingSpec
from .kernels.cantilever import CantileverCompliance
from .kernels.fitted import FittedCompliance


@dataclass(frozen=True)
class Springs:
    """One source of tooth-pair springs.

    Attributes
    ----------
    name : str
        The ``[load] stiffness`` value.
    make : callable
        ``make(spec)`` -> an object with ``pair_compliance_mm_per_N(z_mm, r_mm)``.
    far_field : bool
        The springs leave out the local deformation under the load (the FE far field and
        its fit): the compliance model's line contact then takes the half-space strip law,
        the surface model's half-space adds the local part once.
    what : str
        One line for settings tables (what the accuracy ladder measured for them:
        :mod:`.accuracy`).
    """

    name: str
    make: Callable[[CouplingSpec], Any]
    far_field: bool
    what: str


@lru_cache(maxsize=32)
def _cantilever(spec: CouplingSpec) -> CantileverCompliance:
    return CantileverCompliance(spec)


@lru_cache(maxsize=32)
def _fitted(spec: CouplingSpec) -> FittedCompliance:
    return FittedCompliance(spec)


SPRINGS: dict[str, Springs] = {s.name: s for s in (
    Springs("fe-fit", _fitted, True,
            "the FE tooth table's far field by the shipped fit (no solver at run time)"),
    Springs("fe", tooth_compliance_table, True,
            "the FE tooth table's far field (gmsh and CalculiX, once per spec, cached)"),
    Springs("cantilever", _cantilever, False,
            "tapered Timoshenko cantilevers with Weber's foundation (Wei)"),
)}


def springs_of(spec: CouplingSpec) -> Springs:
    """The :class:`Springs` of ``[load] stiffness``."""
    return SPRINGS[spec.load.stiffness]


def tooth_compliance(spec: CouplingSpec):
    """The tooth-pair compliance of ``[load] stiffness`` (cached per spec)."""
    return springs_of(spec).make(spec)


def cantilever(spec: CouplingSpec) -> CantileverCompliance:
    """The tapered cantilever of ``spec`` (cached): the nominal root stress's source."""
    return _cantilever(spec)
