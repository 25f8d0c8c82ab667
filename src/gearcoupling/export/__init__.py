"""Part export by file extension: meshes through trimesh, meshio and the project's own
writers, STEP files of the parts' OpenCASCADE solids (see ``docs/export.md``).

>>> import gearcoupling as gc
>>> spec = gc.load_spec("renzo-1967")
>>> gc.export_part(spec, "hub", "hub.stl", tolerance_mm=0.05).name
'hub.stl'
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
