"""gearcoupling: crowned-tooth gear couplings, from a parameter file to exact geometry.

The public kernels (pure numpy/scipy) and the spec loader are importable from here;
mesh, CAD and viewer back-ends are imported only where they are used. Units, frames,
signs and names: ``docs/conventions.md``.
"""

from .errors import ArgumentError, BackendError, GearCouplingError, GeometryError, SpecError
from .geometry import (
    FeedPath,
    feed_path,
    hub_flank,
    inv,
    inv_inverse,
    sleeve_flank,
    transverse_section,
)
from .spec import CouplingSpec, load_spec, spec_from_dict, template_names

__version__ = "0.1.0"

# later stages of the data flow, imported on first use so that ``import gearcoupling``
# stays free of mesh, CAD, solver and viewer libraries
_LAZY = {
    # parts, export and checks
    "build_part": "gearcoupling.parts",
    "check_part": "gearcoupling.parts.validity",
    "export_part": "gearcoupling.export",
    "check_interference": "gearcoupling.interference",
    # sweeps and design angles (gearcoupling.sweep is also callable as sweep())
    "sweep": "gearcoupling.sweep",
    "SweepResult": "gearcoupling.sweep",
    "critical_misalignment_deg": "gearcoupling.sweep",
    "binding_angle_deg": "gearcoupling.sweep",
    "min_backlash_rad": "gearcoupling.sweep",
    "contact_travel": "gearcoupling.sweep",
    "double_engagement": "gearcoupling.sweep",
    "design_quantities": "gearcoupling.sweep",
    # loaded contact (gearcoupling.load is also callable as load())
    "load": "gearcoupling.load",
    "load_from_sweep": "gearcoupling.load",
    "LoadResult": "gearcoupling.load",
    "capacity": "gearcoupling.load",
    "capacity_curve": "gearcoupling.load",
    # finite elements (gmsh, CalculiX)
    "mesh_part": "gearcoupling.fea",
    "write_mesh": "gearcoupling.fea",
    "tooth_compliance_table": "gearcoupling.fea",
    # design studies on dask
    "load_study": "gearcoupling.study",
    "run_study": "gearcoupling.study",
    # manufacturing and inspection
    "hob_program": "gearcoupling.hob",
    "measuring_charts": "gearcoupling.hob",
    "compare_part": "gearcoupling.inspection",
    # viewer
    "pose_state": "gearcoupling.viewer",
    "write_html": "gearcoupling.viewer",
    "serve": "gearcoupling.viewer",
}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'gearcoupling' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


__all__ = [
    "ArgumentError",
    "BackendError",
    "CouplingSpec",
    "FeedPath",
    "GearCouplingError",
    "GeometryError",
    "LoadResult",
    "SpecError",
    "SweepResult",
    "binding_angle_deg",
    "build_part",
    "capacity",
    "capacity_curve",
    "check_interference",
    "check_part",
    "compare_part",
    "contact_travel",
    "critical_misalignment_deg",
    "design_quantities",
    "double_engagement",
    "export_part",
    "feed_path",
    "hob_program",
    "hub_flank",
    "inv",
    "inv_inverse",
    "load",
    "load_from_sweep",
    "load_spec",
    "load_study",
    "measuring_charts",
    "mesh_part",
    "min_backlash_rad",
    "pose_state",
    "run_study",
    "serve",
    "sleeve_flank",
    "spec_from_dict",
    "sweep",
    "template_names",
    "tooth_compliance_table",
    "transverse_section",
    "write_html",
    "write_mesh",
]
