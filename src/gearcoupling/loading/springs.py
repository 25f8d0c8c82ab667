"""The tooth springs by name (``[load] stiffness``): what each is, how it is made and what the
accuracy ladder measured for it (docs/load.md). The one place that knows the names; the
spec's allowed values (:data:`gearcoupling.spec.STIFFNESS_SOURCES`) are these keys.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..fea import TABLE_FACE_SHARE, tooth_compliance_table
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


class _Delegate:
    """Every attribute but :meth:`pair_compliance_mm_per_N` from ``springs``."""

    def __init__(self, springs: Any):
        self.springs = springs

    def __getattr__(self, name: str) -> Any:
        if name == "springs":  # not set yet (a copy or an unpickled one): no recursion
            raise AttributeError(name)
        return getattr(self.springs, name)


class FitShapedTable(_Delegate):
    """The FE tooth table between its load points along the fit's shape: the fit times
    the bilinear interpolation of table / fit at the table's points (exact there). Read
    linearly between its rows, the table is too soft where the far field rises toward the
    face end; along the fit's shape it follows FE solved between the rows (docs/load.md
    has the errors of both)."""

    def __init__(self, table: Any, fit: FittedCompliance):
        super().__init__(table)
        self.fit = fit
        Z, R = np.meshgrid(table.z_mm, table.r_mm, indexing="ij")
        self.ratio = table.far_field_mm_per_N / fit.pair_compliance_mm_per_N(Z, R)

    def pair_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        return (self.fit.pair_compliance_mm_per_N(z_mm, r_mm)
                * self.springs.interpolate(self.ratio, z_mm, r_mm))


class HeldAlongFace(_Delegate):
    """A tooth spring read at ``|z|`` held at ``z_hold_mm``: the load models' one spring
    per tooth at its load centre. At the face end the tooth is much softer under a patch
    (the FE table's last row), but a rigid tooth on one spring cannot move its load inward
    as the tooth does there: read there, the default carries less than a CalculiX sector
    (the unsafe side); held at :data:`~gearcoupling.fea.TABLE_FACE_SHARE` of the half face,
    more (docs/load.md, "The face end", has the figures)."""

    def __init__(self, springs: Any, z_hold_mm: float):
        super().__init__(springs)
        self.z_hold_mm = z_hold_mm

    def pair_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        z = np.clip(np.asarray(z_mm, dtype=float), -self.z_hold_mm, self.z_hold_mm)
        return self.springs.pair_compliance_mm_per_N(z, r_mm)


@lru_cache(maxsize=32)
def _cantilever(spec: CouplingSpec) -> CantileverCompliance:
    return CantileverCompliance(spec)


@lru_cache(maxsize=32)
def _fitted(spec: CouplingSpec) -> FittedCompliance:
    return FittedCompliance(spec)


def _held(spec: CouplingSpec, springs: Any) -> HeldAlongFace:
    return HeldAlongFace(springs, TABLE_FACE_SHARE * 0.5 * spec.hub.face_width)


@lru_cache(maxsize=32)
def _fitted_held(spec: CouplingSpec) -> HeldAlongFace:
    return _held(spec, _fitted(spec))


def _table_held(spec: CouplingSpec) -> HeldAlongFace:
    return _held(spec, FitShapedTable(tooth_compliance_table(spec), _fitted(spec)))


SPRINGS: dict[str, Springs] = {s.name: s for s in (
    Springs("fe-fit", _fitted_held, True,
            "the FE tooth table's far field by the shipped fit (no solver at run time)"),
    Springs("fe", _table_held, True,
            "the FE tooth table's far field (gmsh and CalculiX, once per spec, cached), "
            "read along the fit's shape between its load points"),
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
