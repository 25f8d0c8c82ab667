"""The hub crown kinds: one :class:`CrownKind` each in :data:`CROWN_KINDS`, the one place
that knows them. An entry names the keys of ``[hub.crowning]`` its kind needs, checks its
values and builds its feed path (the builders are kernels of :mod:`gearcoupling.geometry`);
the reader, the dataclasses and the spec checks take everything kind-specific from here, so
a new kind is one entry plus its path function (docs/api.md, "A crown kind").
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from itertools import pairwise
from typing import Any, ClassVar, Protocol

import numpy as np

from ..errors import SpecError
from ..geometry import (
    FeedPath,
    arc_path,
    curvature_table_path,
    drop_table_path,
    end_round_path,
    vari_crown_path,
)
from .values import _check, _positive

#: steepest feed-path tangent allowed at the face ends (degrees)
MAX_END_TANGENT_DEG = 45.0
_PATH_SAMPLES = 401  # points of a table crown's splined path checked between its samples

#: the keys of ``[hub.crowning]`` after ``kind``, in reading order: key -> (the
#: :class:`~gearcoupling.spec.Crowning` attribute, its default, the power of length of its
#: unit: 1 for mm, -1 for 1/mm). A key a kind does not use keeps its default.
CROWN_FIELDS: dict[str, tuple[str, Any, int]] = {
    "radius": ("radius", math.inf, 1),
    "end_radius": ("end_radius", math.inf, 1),
    "start_z": ("start_z", 0.0, 1),
    "s": ("table_s", (), 1),
    "kappa": ("table_kappa", (), -1),
    "z": ("table_z", (), 1),
    "drop": ("table_drop", (), 1),
}


class CrownValues(Protocol):
    """The values of a ``[hub.crowning]`` table as its kind reads them (mm, 1/mm):
    :class:`gearcoupling.spec.Crowning` (which validates itself through this table)."""

    PATH: ClassVar[str]

    @property
    def kind(self) -> str: ...

    @property
    def radius(self) -> float: ...

    @property
    def end_radius(self) -> float: ...

    @property
    def start_z(self) -> float: ...

    @property
    def table_s(self) -> tuple[float, ...]: ...

    @property
    def table_kappa(self) -> tuple[float, ...]: ...

    @property
    def table_z(self) -> tuple[float, ...]: ...

    @property
    def table_drop(self) -> tuple[float, ...]: ...


def _nothing(*_: Any) -> None:
    """No check: the kind has nothing to check at this stage."""


def _radius_key(crowning: CrownValues, sharpest: bool) -> str:
    return "radius"


@dataclass(frozen=True)
class CrownKind:
    """One crown kind.

    Attributes
    ----------
    name : str
        The ``hub.crowning.kind`` value.
    path : callable
        ``path(crowning, pitch_radius, face_width) -> FeedPath`` (mm), labelled with
        ``crowning.kind``: the hob feed path the crown stands for.
    what : str
        One line for the docs.
    needs : tuple of str
        Keys of :data:`CROWN_FIELDS` a spec of this kind must give.
    check : callable
        ``check(crowning)``: the kind's values, on construction (a :class:`SpecError`).
    check_face : callable
        ``check_face(crowning, half_face)``: against the hub's half face width (mm).
    check_path : callable
        ``check_path(crowning, path, half_face)``: along its built feed path.
    curvature_key : callable
        ``curvature_key(crowning, sharpest)``: the key of :data:`CROWN_FIELDS` that sets the
        crown's curvature at the midplane (or where it is sharpest), named when the spec
        checks refuse the curvature.
    """

    name: str
    path: Callable[[CrownValues, float, float], FeedPath]
    what: str
    needs: tuple[str, ...] = ()
    check: Callable[[CrownValues], None] = _nothing
    check_face: Callable[[CrownValues, float], None] = _nothing
    check_path: Callable[[CrownValues, FeedPath, float], None] = _nothing
    curvature_key: Callable[[CrownValues, bool], str] = _radius_key


# ----------------------------------------------------------------------- vari_crown
def _vari_crown_path(c: CrownValues, R: float, face_width: float) -> FeedPath:
    return vari_crown_path(R, c.radius, c.end_radius, face_width, c.kind)


def _check_vari_crown(c: CrownValues) -> None:
    p = c.PATH
    _positive(f"{p}.radius", c.radius)
    _check(c.radius < c.end_radius, f"{p}.end_radius", c.end_radius,
           f"vari_crown is less curved toward the ends: end_radius must exceed "
           f"radius = {c.radius:.6g} mm (inf allowed)")


# ----------------------------------------------------------------------- end_round
def _end_round_path(c: CrownValues, R: float, face_width: float) -> FeedPath:
    return end_round_path(R, c.radius, c.end_radius, c.start_z, c.kind)


def _check_end_round(c: CrownValues) -> None:
    p = c.PATH
    _positive(f"{p}.end_radius", c.end_radius)
    _check(c.end_radius < c.radius, f"{p}.end_radius", c.end_radius,
           f"end_round turns sharper at the ends: end_radius must be below "
           f"radius = {c.radius:.6g} mm")
    limit = c.radius * math.sin(math.radians(MAX_END_TANGENT_DEG))
    _check(math.isfinite(c.start_z) and 0 <= c.start_z <= limit, f"{p}.start_z",
           c.start_z, f"must be a length from 0 to radius * sin 45° = {limit:.6g} mm")


def _check_end_round_face(c: CrownValues, half_face: float) -> None:
    _check(c.start_z < half_face, f"{c.PATH}.start_z", c.start_z,
           f"must lie inside the half face width {half_face:.6g} mm")


def _end_round_key(c: CrownValues, sharpest: bool) -> str:
    return "end_radius" if sharpest else "radius"


# ----------------------------------------------------------------------- table
def _table_path(c: CrownValues, R: float, face_width: float) -> FeedPath:
    if c.table_s:
        return curvature_table_path(R, c.table_s, c.table_kappa, c.kind)
    return drop_table_path(R, c.table_z, c.table_drop, c.kind)


def _check_table(c: CrownValues) -> None:
    p = c.PATH
    by_s = bool(c.table_s or c.table_kappa)
    by_z = bool(c.table_z or c.table_drop)
    _check(by_s != by_z, f"{p}.s|z", None,
           "give either s and kappa samples or z and drop samples, not both or neither")
    xs, ys, xn, yn = (
        (c.table_s, c.table_kappa, "s", "kappa") if by_s
        else (c.table_z, c.table_drop, "z", "drop")
    )
    _check(len(xs) == len(ys) and len(xs) >= 3, f"{p}.{yn}", len(ys),
           f"needs as many samples as {xn} ({len(xs)}), at least 3")
    _check(all(math.isfinite(x) for x in xs + ys), f"{p}.{xn}", xs, "samples must be finite")
    _check(xs[0] == 0 and all(b > a for a, b in pairwise(xs)), f"{p}.{xn}",
           xs, "must start at 0 (the midplane) and increase strictly")
    if by_z:
        _check(ys[0] == 0 and all(d >= 0 for d in ys), f"{p}.drop", ys,
               "crown drop must be 0 at z = 0 and >= 0 elsewhere")
    else:
        _check(all(k >= 0 for k in ys), f"{p}.kappa", ys, "curvatures must be >= 0 (1/mm)")


def _check_table_path(c: CrownValues, path: FeedPath, half_face: float) -> None:
    """A table crown is validated along its splined path, not only at its samples: the
    samples must reach the face end and the drop must stay >= 0 between them."""
    key = _table_key(c, True)
    reach = float(path.evaluate(c.table_s[-1])[3]) if c.table_s else c.table_z[-1]
    if reach < half_face * (1.0 - 1e-9):
        raise SpecError(f"{c.PATH}.{'s' if c.table_s else 'z'}", reach,
                        f"the samples must reach the face end z = {half_face:.6g} mm "
                        "(the path is not extrapolated)")
    z = np.linspace(0.0, half_face, _PATH_SAMPLES)
    drop = path.drop(z)
    if np.min(drop) < -1e-9 * path.R:
        zi = float(z[np.argmin(drop)])
        raise SpecError(f"{c.PATH}.{key}", getattr(c, CROWN_FIELDS[key][0]),
                        f"the splined crown rises above the midplane (drop "
                        f"{float(np.min(drop)):.3g} mm at z = {zi:.4g} mm): the tooth would "
                        "be thicker than at the midplane; add samples or smooth the table")


def _table_key(c: CrownValues, sharpest: bool) -> str:
    return "kappa" if c.table_s else "drop"


# ----------------------------------------------------------------------- the table
CROWN_KINDS: dict[str, CrownKind] = {k.name: k for k in (
    CrownKind("none", lambda c, R, b: arc_path(R, math.inf, c.kind), "straight teeth"),
    CrownKind("circular", lambda c, R, b: arc_path(R, c.radius, c.kind),
              "a circular path of radius R_c = radius", needs=("radius",)),
    CrownKind("vari_crown", _vari_crown_path,
              "radius at the midplane growing smoothly to end_radius at the face ends",
              needs=("radius",), check=_check_vari_crown),
    CrownKind("end_round", _end_round_path,
              "radius up to start_z from the midplane, then end_radius",
              needs=("radius",), check=_check_end_round, check_face=_check_end_round_face,
              curvature_key=_end_round_key),
    CrownKind("table", _table_path,
              "curvature samples s, kappa or crown-drop samples z, drop, splined",
              check=_check_table, check_path=_check_table_path, curvature_key=_table_key),
)}
"""Crown kind name -> :class:`CrownKind`: the one table of crown kinds."""

#: the built-in crown kinds
CROWNING_KINDS = tuple(CROWN_KINDS)
