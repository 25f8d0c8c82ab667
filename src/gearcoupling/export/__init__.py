"""Part export by file extension: meshes through trimesh and meshio, STEP through OCP.

>>> export_part(spec, "hub", "outputs/hub.step", tolerance_mm=0.01)  # doctest: +SKIP
"""

from . import meshes, step  # noqa: F401  (registers the writers)
from .registry import EXPORTERS, PartJob, export_part, exporter, formats

__all__ = ["EXPORTERS", "PartJob", "export_part", "exporter", "formats"]
