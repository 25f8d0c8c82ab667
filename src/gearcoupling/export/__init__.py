"""Part export by file extension: meshes through trimesh, meshio and the project's own
writers, STEP files of the parts' OpenCASCADE solids (see ``docs/export.md``).

>>> import gearcoupling as gc
>>> spec = gc.load_spec("renzo-1967")
>>> gc.export_part(spec, "hub", "hub.stl", tolerance_mm=0.05).name
'hub.stl'
"""

from .job import PartJob
from .registry import WRITERS, Writer, export_part, formats, writer_for
from .step import read_step_volume, write_step, write_step_assembly
from .volume import inp_mesh_lines, region_ids, write_inp_text

__all__ = [
    "WRITERS",
    "PartJob",
    "Writer",
    "export_part",
    "formats",
    "inp_mesh_lines",
    "read_step_volume",
    "region_ids",
    "write_inp_text",
    "write_step",
    "write_step_assembly",
    "writer_for",
]
