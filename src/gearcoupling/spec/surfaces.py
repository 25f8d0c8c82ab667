"""The geometry's public functions for a spec given as a :class:`CouplingSpec`, a template
name or the path of a TOML spec: the name is loaded here (:func:`as_spec`), the geometry
kernels take spec objects only."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..geometry import hub_flank as geometry_hub_flank
from ..geometry import sleeve_flank as geometry_sleeve_flank
from ..geometry import transverse_section as geometry_transverse_section
from .coupling import as_spec


def hub_flank(spec: Any, flank: str, z_mm: ArrayLike, r_mm: ArrayLike
              ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Exact points ``(..., 3)`` and unit normals ``(..., 3)`` (out of the tooth) of tooth
    0's ``flank`` (``cw``, ``ccw``) at axial positions ``z_mm`` and radii ``r_mm`` in the
    hub frame: :func:`gearcoupling.geometry.hub_flank` of ``spec`` (a spec, template name
    or TOML path)."""
    return geometry_hub_flank(as_spec(spec), flank, z_mm, r_mm)


def sleeve_flank(spec: Any, flank: str, z_mm: ArrayLike, r_mm: ArrayLike
                 ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Points ``(..., 3)`` and unit normals ``(..., 3)`` (into the space) of sleeve space
    0's flank facing hub tooth 0's ``flank``, at ``z_mm`` and ``r_mm`` in the sleeve frame:
    :func:`gearcoupling.geometry.sleeve_flank` of ``spec`` (a spec, template name or TOML
    path)."""
    return geometry_sleeve_flank(as_spec(spec), flank, z_mm, r_mm)


def transverse_section(spec: Any, part: str, z_mm: float, tolerance_mm: float
                       ) -> NDArray[np.float64]:
    """Closed section polygon ``(n, 2)`` (counter-clockwise) of all teeth of ``part``
    (``hub``, ``sleeve``) at ``z_mm`` within ``tolerance_mm`` of the exact curves:
    :func:`gearcoupling.geometry.transverse_section` of ``spec`` (a spec, template name or
    TOML path)."""
    return geometry_transverse_section(as_spec(spec), part, z_mm, tolerance_mm)
