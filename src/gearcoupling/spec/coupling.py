"""The complete coupling spec, :class:`CouplingSpec`, and where one comes from: file data
(:func:`spec_from_dict`), a template or TOML file with dotted overrides
(:func:`load_spec`), or any of these where a function takes a spec (:func:`as_spec`).

The parts are :mod:`.model` (and :mod:`.load`), read from their tables by :mod:`.file`.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import os
from dataclasses import asdict, dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from ..errors import ArgumentError, SpecError
from ..io import Table, as_path, read_toml, set_dotted
from .arrangement import SINGLE, CouplingLayout, ShaftAlignment
from .checks import check_spec, derived_values
from .file import TABLES, check_keys, explained, read_parts, resolve_spec_path
from .kinds import CROWN_FIELDS
from .load import UNIT_SIBLINGS, LoadSpec, Materials
from .model import Hub, InspectionLimits, Sleeve, ToothSystem
from .values import check_misalignment_deg


@dataclass(frozen=True)
class CouplingSpec:
    """A complete coupling: tooth system, hub, sleeve and design misalignment (radians)."""

    tooth: ToothSystem
    hub: Hub
    sleeve: Sleeve
    design_misalignment: float = 0.0
    name: str = field(default="custom", compare=False)
    load: LoadSpec = field(default_factory=LoadSpec)  # [load] (load.py)
    material: Materials = field(default_factory=Materials)  # [material] (load.py)
    units: str = field(default="mm", compare=False)
    inspection: InspectionLimits = field(default_factory=InspectionLimits, compare=False)
    wear: tuple[tuple[str, Any], ...] = ()  # [wear] as read (wear.py)
    #: [coupling]: one engagement (the default) or two, with hub B (``hub_b``) and the
    #: floating member; [alignment]: the shafts (docs/coupling.md). An engagement is
    #: compared by its hub and sleeve: these are left out of ``==``.
    coupling: CouplingLayout = field(default=SINGLE, compare=False)
    alignment: ShaftAlignment | None = field(default=None, compare=False)

    def __post_init__(self):
        check_misalignment_deg(math.degrees(self.design_misalignment), "design_misalignment_deg")
        if self.alignment is not None and self.coupling.engagements == 1:
            raise SpecError("alignment", self.alignment.summary(), "only for a double-"
                            "engagement coupling ([coupling] engagements = 2): a single "
                            "engagement's mesh takes design_misalignment_deg")
        check_spec(self)  # the checks that need the geometry kernels (spec -> geometry)

    @property
    def engagements(self) -> int:
        """1 (one hub in a sleeve) or 2 (two hubs in a floating member)."""
        return self.coupling.engagements

    @property
    def design_misalignment_deg(self) -> float:
        """The design misalignment in degrees to 12 digits (as the file gave it: no
        round-trip excess through radians), inside 0-6°."""
        return check_misalignment_deg(float(f"{math.degrees(self.design_misalignment):.12g}"),
                                      "design_misalignment_deg")

    def replace(self, **changes: Any) -> CouplingSpec:
        """A copy with dotted file keys changed, re-read and re-validated.

        Overrides follow one rule everywhere: they are keys of the spec file, in the units
        of the file they change. The file of a resolved spec is :meth:`to_dict`, in mm and
        degrees, so here ``{"hub.crowning.radius": 80.0}`` is 80 mm and
        ``{"tooth.pressure_angle_deg": 25}`` 25°; ``None`` removes a key (its default
        applies); one key of an SI/inch-pound pair replaces the other.
        """
        data = self.to_dict()
        for key, value in changes.items():
            set_dotted(data, key, value, UNIT_SIBLINGS)
        return spec_from_dict(data, self.name)

    @cached_property
    def derived(self) -> dict[str, float]:
        """Derived values in mm and degrees (see :func:`derived_values`)."""
        return derived_values(self)

    def to_dict(self) -> dict[str, Any]:
        """The resolved spec as plain data in mm and degrees (keys say their unit)."""
        out: dict[str, Any] = {"name": self.name, "units": "mm",
                               "design_misalignment_deg": self.design_misalignment_deg}
        d = asdict(self)
        tooth = d["tooth"]
        tooth["pressure_angle_deg"] = math.degrees(tooth.pop("pressure_angle"))
        out.update(tooth=tooth, hub=d["hub"], sleeve=d["sleeve"])
        out.update({t.key: table for t in TABLES
                    if (table := t.write(getattr(self, t.key))) or not t.optional})
        if self.coupling.hub_b is not None:
            out["hub_b"] = self.coupling.hub_b.to_dict()["hub"]
        cr = out["hub"]["crowning"]
        for key, (attr, _, _) in CROWN_FIELDS.items():
            if attr != key:  # the file's keys of a tabulated path
                samples = list(cr.pop(attr))
                if samples:
                    cr[key] = samples
        return out


def spec_from_dict(data: dict[str, Any], name: str = "custom") -> CouplingSpec:
    """Build a :class:`CouplingSpec` from parsed TOML data (file units, angles in degrees).

    Keys left out get the defaults of :data:`DEFAULT_RULES`, chosen so that they always
    fit; if a derived value is refused anyway, the error says so and names the key to set.
    """
    if not isinstance(data, dict):
        raise ArgumentError("data", data, "a dict of spec tables, as read from a TOML "
                            "spec file")
    if not isinstance(name, str):
        raise ArgumentError("name", name, "a str")
    check_keys(data)
    data = copy.deepcopy(data)
    hub_b = data.pop("hub_b", None)
    root = Table(data)
    try:
        parts = read_parts(root, name)
        spec = CouplingSpec(**parts)
    except SpecError as err:
        better = explained(err, root)
        if better is err:
            raise
        raise better from None
    if hub_b is None:
        return spec
    return dataclasses.replace(spec, coupling=_with_hub_b(data, hub_b, parts, name))


def _with_hub_b(data: dict[str, Any], hub_b: Any, parts: dict[str, Any],
                name: str) -> CouplingLayout:
    """The layout of ``parts`` with hub B: the file ``data`` with each key of ``[hub_b]``
    (a sub-table counts as one key) in place of that of ``[hub]``; its refusals name
    ``hub_b``."""
    layout = parts["coupling"]
    if layout.engagements == 1:
        raise SpecError("hub_b", "[hub_b]", "only for a double-engagement coupling "
                        "([coupling] engagements = 2)")
    if not isinstance(hub_b, dict):
        raise SpecError("hub_b", hub_b, "must be a TOML table (keys of [hub])")
    hub = dict(data.get("hub") or {}) if isinstance(data.get("hub"), dict) else {}
    for one, other in (("backlash", "tooth_thickness"), ("tooth_thickness", "backlash")):
        if one in hub_b:
            hub.pop(other, None)  # one of the pair says the other
    merged = {k: v for k, v in data.items() if k not in ("coupling", "alignment")}
    merged["hub"] = {**hub, **copy.deepcopy(hub_b)}
    try:
        spec_b = spec_from_dict(merged, name)
    except SpecError as err:
        field_ = err.field.replace("hub.", "hub_b.", 1) if err.field.startswith("hub.") \
            else err.field
        raise SpecError(field_, err.value, err.allowed, err.shown) from None
    return CouplingLayout(**{**{f: getattr(layout, f) for f in layout.__dataclass_fields__},
                             "hub_b": spec_b})


def load_spec(name_or_path: str | Path, **overrides: Any) -> CouplingSpec:
    """Load a template (by name) or a TOML spec file, with dotted overrides in file units.

    >>> spec = load_spec("renzo-1967", **{"hub.crowning.radius": 2.0})  # doctest: +SKIP
    """
    as_path(name_or_path, "name_or_path")
    path = resolve_spec_path(name_or_path)
    data, _ = read_toml(path)
    for key, value in overrides.items():
        set_dotted(data, key, value, UNIT_SIBLINGS)
    return spec_from_dict(data, name=path.stem)


def as_spec(spec: Any, field: str = "spec") -> CouplingSpec:
    """``spec`` when it is a :class:`CouplingSpec`; a template name or the path of a TOML
    spec is loaded (:func:`load_spec`); anything else is an :class:`ArgumentError` naming
    ``field``. Every public function that takes a spec starts with this."""
    if isinstance(spec, CouplingSpec):
        return spec
    if isinstance(spec, str | os.PathLike):
        return load_spec(as_path(spec, field))
    raise ArgumentError(field, spec, "a CouplingSpec (gearcoupling.load_spec), a "
                        "template name or the path of a TOML spec")
