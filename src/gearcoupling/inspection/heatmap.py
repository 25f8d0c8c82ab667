"""Deviation heat map on the part: coloured points for a PLY file or a viser scene.

Kept apart from :mod:`gearcoupling.viewer` (another package owns it): the viewer, or a
user's own viser server, adds the cloud with :func:`add_deviation_heatmap`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..io import atomic_path
from ..numeric import divide
from .report import InspectionReport

# diverging blue - white - red (ColorBrewer RdBu end points), minus material blue
_LOW = np.array([33.0, 102.0, 172.0])
_MID = np.array([247.0, 247.0, 247.0])
_HIGH = np.array([178.0, 24.0, 43.0])


def deviation_colours(d_mm: NDArray[np.float64], limit_mm: float) -> NDArray[np.uint8]:
    """RGB colours of deviations: blue (-limit, missing material) - white - red (+limit).

    Parameters
    ----------
    d_mm : (n,) float
    limit_mm : float
        Deviation of full colour; larger values saturate.

    Returns
    -------
    (n, 3) uint8
    """
    t = np.clip(divide(np.asarray(d_mm, dtype=float), float(limit_mm)), -1.0, 1.0)
    a = np.abs(t)[:, None]
    end = np.where(t[:, None] < 0, _LOW, _HIGH)
    return np.rint(_MID + a * (end - _MID)).astype(np.uint8)


def heatmap_points(report: InspectionReport, limit_mm: float | None = None):
    """Hub-frame points of the report sample with their colours and the colour limit.

    The limit defaults to the 99.5th percentile of ``|d|``.
    """
    s = report.sample
    d = s["d"]
    if limit_mm is None:
        limit_mm = float(np.percentile(np.abs(d), 99.5)) if len(d) else 1.0
        limit_mm = limit_mm if limit_mm > 0 else 1e-3
    return s["points"], deviation_colours(d, limit_mm), limit_mm


def write_deviation_ply(report: InspectionReport, path: str | Path,
                        limit_mm: float | None = None) -> Path:
    """Write the coloured deviation cloud as a PLY point cloud (hub frame, mm)."""
    import trimesh


    pts, rgb, _ = heatmap_points(report, limit_mm)
    cloud = trimesh.PointCloud(pts, colors=np.concatenate(
        [rgb, np.full((len(rgb), 1), 255, np.uint8)], axis=1))
    with atomic_path(path) as tmp:
        cloud.export(tmp, file_type="ply")
    return Path(path)


def add_deviation_heatmap(server, report: InspectionReport, name: str = "/hub/deviation",
                          limit_mm: float | None = None, point_size: float | None = None):
    """Add the deviation cloud to a viser server's scene (``server.scene.add_point_cloud``).

    Under ``/hub`` it follows the posed hub of :class:`gearcoupling.viewer.nodes.CouplingScene`.
    Returns the point-cloud handle.
    """
    pts, rgb, _ = heatmap_points(report, limit_mm)
    size = point_size or 0.002 * float(np.ptp(pts[:, 0]) if len(pts) else 1.0)
    return server.scene.add_point_cloud(name, pts.astype(np.float32), rgb, point_size=size,
                                        point_shape="circle", precision="float32")
