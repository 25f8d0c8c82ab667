"""What the geometry reads of a coupling spec, as a protocol: the spec is built above the
geometry (its defaults come from geometry functions), so the geometry names no spec class.
"""

from __future__ import annotations

from collections.abc import Hashable
from typing import Any, Protocol


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
