"""Finite elements: quadratic tetrahedral meshes of hub and sleeve sectors (gmsh) and tooth
stiffness from the CalculiX solver ``ccx``.

gmsh (``fea`` extra) and ``ccx`` (Debian ``calculix-ccx``) are imported or looked up only
when called; a missing one raises :class:`gearcoupling.errors.BackendError` naming it.
"""

from .backends import ccx_path, gmsh_module
from .bodies import (
    BodyInfluenceTable,
    RingSolution,
    body_influence_table,
    compute_body_influence,
    ring_deflections,
    sector_self,
)
from .mesh import (
    DEFAULT_SECTOR_TEETH,
    check_size,
    default_size,
    fillet_notes,
    mesh_part,
    sector_teeth,
)
from .reference import FEContactResult, fe_contact
from .sector import FESectorResult, fe_contact_sector
from .stiffness import (
    TABLE_FACE_SHARE,
    ComplianceTable,
    compute_compliance_table,
    default_patch_mm,
    fe_cache_folder,
    load_rows_mm,
    pitch_point_compliance,
    rectangle_halfspace_work_mm_per_N,
    table_entry,
    tooth_compliance_table,
)
from .validation import CUT_DISTANCE_PITCHES, check_sector, fe_sector_at_loads
from .volume import VolumeMesh
from .write import region_ids, write_inp, write_mesh

__all__ = [
    "CUT_DISTANCE_PITCHES",
    "DEFAULT_SECTOR_TEETH",
    "TABLE_FACE_SHARE",
    "BodyInfluenceTable",
    "ComplianceTable",
    "FEContactResult",
    "FESectorResult",
    "RingSolution",
    "VolumeMesh",
    "body_influence_table",
    "ccx_path",
    "check_sector",
    "check_size",
    "compute_body_influence",
    "compute_compliance_table",
    "default_patch_mm",
    "default_size",
    "fe_cache_folder",
    "fe_contact",
    "fe_contact_sector",
    "fe_sector_at_loads",
    "fillet_notes",
    "gmsh_module",
    "load_rows_mm",
    "mesh_part",
    "pitch_point_compliance",
    "rectangle_halfspace_work_mm_per_N",
    "region_ids",
    "ring_deflections",
    "sector_self",
    "sector_teeth",
    "table_entry",
    "tooth_compliance_table",
    "write_inp",
    "write_mesh",
]
