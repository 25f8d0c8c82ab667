"""gearcoupling: crowned-tooth gear couplings, from a parameter file to exact geometry.

The public kernels (pure numpy/scipy) and the spec loader are importable from here;
mesh, CAD and viewer back-ends are imported only where they are used.
"""

from .errors import BackendError, GearCouplingError, GeometryError, SpecError
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

__all__ = [
    "BackendError",
    "CouplingSpec",
    "FeedPath",
    "GearCouplingError",
    "GeometryError",
    "SpecError",
    "feed_path",
    "hub_flank",
    "inv",
    "inv_inverse",
    "load_spec",
    "sleeve_flank",
    "spec_from_dict",
    "template_names",
    "transverse_section",
]
