"""Interference and minimum gap of the posed hub and sleeve meshes across rotation angles.

Sits after the part meshes and the sweep in the data flow: :func:`check_interference`
poses :func:`gearcoupling.parts.build_part` meshes (docs/conventions.md, Frames), measures overlap
by
manifold3d booleans or signed distances and the minimum gap by python-fcl, on sector
submodels chosen from :func:`gearcoupling.clearance.sweep` or on the full parts.
"""

from .attribution import flank_index, nearest_tooth
from .check import METHODS, InterferenceResult, Overlap, check_interference, posed_meshes
from .plot import plot_interference
from .posed import PreparedPart, affine
from .submodel import Model, build_model

__all__ = [
    "METHODS",
    "InterferenceResult",
    "Model",
    "Overlap",
    "PreparedPart",
    "affine",
    "build_model",
    "check_interference",
    "flank_index",
    "nearest_tooth",
    "plot_interference",
    "posed_meshes",
]
