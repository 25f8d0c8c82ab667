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
# stays free of mesh, CAD and viewer libraries (the sweep is ``gearcoupling.sweep.sweep``)
_LAZY = {
    "build_part": "gearcoupling.parts",
    "export_part": "gearcoupling.export",
    "check_interference": "gearcoupling.interference",
    # loaded contact (issue 10); gearcoupling.load is also callable as load()
    "load": "gearcoupling.load",
    "load_from_sweep": "gearcoupling.load",
    "LoadResult": "gearcoupling.load",
    # manufacturing and inspection (issue 13)
    "hob_program": "gearcoupling.hob",
    "measuring_charts": "gearcoupling.hob",
    "compare_part": "gearcoupling.inspection",
    "capacity": "gearcoupling.load",
    "capacity_curve": "gearcoupling.load",
    # design studies on dask (issue 12)
    "load_study": "gearcoupling.study",
    "run_study": "gearcoupling.study",
}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'gearcoupling' has no attribute {name!r}")


__all__ = [
    "ArgumentError",
    "BackendError",
    "CouplingSpec",
    "FeedPath",
    "GearCouplingError",
    "GeometryError",
    "LoadResult",
    "SpecError",
    "build_part",
    "capacity",
    "capacity_curve",
    "check_interference",
    "compare_part",
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
    "run_study",
    "sleeve_flank",
    "spec_from_dict",
    "template_names",
    "transverse_section",
]
