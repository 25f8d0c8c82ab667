"""The posed pair: hub and sleeve meshes in one, the hub placed in the sleeve frame.

The contact decks (:mod:`.reference`, aligned; :mod:`.sector`, misaligned) solve this
merged mesh. Regions and faces keep their names with ``H_`` (hub) or ``S_`` (sleeve) in
front.
"""

from __future__ import annotations

import numpy as np

from .volume import VolumeMesh


def merge(hub: VolumeMesh, sleeve: VolumeMesh, hub_rotation: np.ndarray) -> VolumeMesh:
    """One mesh of the posed hub (regions ``H_...``) and the sleeve (``S_...``)."""
    off_n, off_e = len(hub.nodes), len(hub.tets)
    nodes = np.vstack([hub.nodes @ hub_rotation.T, sleeve.nodes])
    tets = np.vstack([hub.tets, sleeve.tets + off_n])
    regions = {f"H_{k}": v for k, v in hub.regions.items()}
    regions |= {f"S_{k}": v + off_n for k, v in sleeve.regions.items()}
    faces = {f"H_{k}": v for k, v in hub.faces.items()}
    faces |= {f"S_{k}": v + np.array([off_e, 0]) for k, v in sleeve.faces.items()}
    quality = {"hub": hub.quality, "sleeve": sleeve.quality}
    return VolumeMesh("pair", nodes, tets, regions, faces, hub.teeth, hub.size_mm, quality)
