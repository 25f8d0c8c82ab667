"""Part export by file extension: meshes through trimesh, meshio and the project's own
writers, STEP files of the parts' OpenCASCADE solids (see ``docs/export.md``).

>>> export_part(spec, "hub", "outputs/hub.step", tolerance_mm=0.01)  # doctest: +SKIP
"""

from .job import PartJob
from .registry import EXPORTERS, export_part, formats
from .step import read_step_volume, write_step

__all__ = [
    "EXPORTERS",
    "PartJob",
    "export_part",
    "formats",
    "read_step_volume",
    "write_step",
]
