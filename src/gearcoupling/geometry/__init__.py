"""Pure numpy/scipy geometry kernels: involutes, feed paths, hub and sleeve surfaces, sections.

Nothing here imports a mesh, CAD or viewer library.
"""

from .feedpath import FeedPath, feed_path
from .hub import hub_flank, hub_model
from .involute import inv, inv_inverse
from .section import transverse_section
from .sleeve import sleeve_flank, sleeve_model

__all__ = [
    "FeedPath",
    "feed_path",
    "hub_flank",
    "hub_model",
    "inv",
    "inv_inverse",
    "sleeve_flank",
    "sleeve_model",
    "transverse_section",
]
