"""What the geometry reads of a coupling spec, as a protocol: the spec is built above the
geometry (its defaults come from geometry functions), so the geometry names no spec class.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Hashable
from typing import Any, Protocol

from ..errors import ArgumentError


class SpecLike(Hashable, Protocol):
    """A coupling spec as the geometry sees it (:class:`gearcoupling.CouplingSpec` is one):
    lengths in mm, angles in radians; hashable, as the geometry caches per spec."""

    @property
    def name(self) -> str: ...

    @property
    def tooth(self) -> Any: ...

    @property
    def hub(self) -> Any: ...

    @property
    def sleeve(self) -> Any: ...

    @property
    def design_misalignment(self) -> float: ...


#: loads a template name or TOML path as a spec: set by :mod:`gearcoupling.spec` (the spec
#: is built above the geometry), so that the geometry's public functions take names too
load_named: Callable[[Any, str], Any] | None = None


def use_spec_loader(load: Callable[[Any, str], Any]) -> None:
    """Load template names and TOML paths given as a spec with ``load(name, field)``."""
    global load_named
    load_named = load


def as_spec_like(spec: Any, field: str = "spec") -> Any:
    """``spec`` when it is a spec; a template name or TOML path is loaded
    (:func:`gearcoupling.load_spec`); anything else is an :class:`ArgumentError`."""
    if isinstance(spec, str | os.PathLike) and load_named is not None:
        return load_named(spec, field)
    if not all(hasattr(spec, a) for a in ("tooth", "hub", "sleeve", "design_misalignment")):
        raise ArgumentError(field, spec, "a CouplingSpec (gearcoupling.load_spec), a "
                            "template name or the path of a TOML spec")
    return spec
