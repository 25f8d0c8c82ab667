"""What the geometry reads of a coupling spec, as a protocol: the spec is built above the
geometry (its defaults and checks use geometry functions), so the geometry names no spec
class and loads no spec; callers resolve template names first (``gearcoupling.spec.as_spec``).
"""

from __future__ import annotations

from collections.abc import Hashable
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


def as_spec_like(spec: Any, field: str = "spec") -> Any:
    """``spec`` when it is a spec object; anything else (a template name too) is an
    :class:`ArgumentError` naming ``field``."""
    if not all(hasattr(spec, a) for a in ("tooth", "hub", "sleeve", "design_misalignment")):
        raise ArgumentError(field, spec, "a CouplingSpec (gearcoupling.load_spec; the "
                            "functions of gearcoupling itself take template names too)")
    return spec
