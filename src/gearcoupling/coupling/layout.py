"""What the whole coupling is and how its shafts sit: :class:`CouplingLayout` (engagements,
span, sleeve arrangement, flanges, spacer, hub B) and :class:`ShaftAlignment` (parallel
offset and angle of shaft B against shaft A, with their directions), docs/coupling.md.

Both are the spec's (:mod:`gearcoupling.spec`: a spec file's ``[coupling]`` and
``[alignment]`` tables); each checks its own fields on construction. What needs the hubs'
specs (a span that the hubs fill, a spacer that does not fit the flanges) is checked by
:func:`~.geometry.coupling_geometry`, which every calculation calls first. Every refusal is
an :class:`~gearcoupling.errors.ArgumentError` naming the field, the value and what is
allowed.
"""

from __future__ import annotations

import math

from ..spec import MAX_SHAFT_ANGLE_DEG, SLEEVES, CouplingLayout, ShaftAlignment

#: how far a given span may differ from the one the flanges and spacer make (mm)
SPAN_SLACK_MM = 1e-6


def is_close(a: float, b: float) -> bool:
    """Whether two lengths agree to :data:`SPAN_SLACK_MM` (mm)."""
    return math.isclose(a, b, rel_tol=0.0, abs_tol=SPAN_SLACK_MM)


__all__ = ["MAX_SHAFT_ANGLE_DEG", "SLEEVES", "CouplingLayout", "ShaftAlignment"]
