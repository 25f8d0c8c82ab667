"""The hub ∩ sleeve volume at a pose (manifold3d), less the pieces that are chord error."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ...interference import affine, flank_index, nearest_tooth
from ...numeric import divide
from .meshes import Patch, SceneMeshes, patch_from_manifold


def interference_mesh(meshes: SceneMeshes, rotation: ArrayLike,
                      interfering: ArrayLike | None = None) -> tuple[Patch, float]:
    """Hub ∩ sleeve at a pose: the overlap solid in the sleeve frame and its volume (mm³).

    Parameters
    ----------
    meshes : SceneMeshes
    rotation : (3, 3) float
        Hub pose (:func:`hub_rotation`).
    interfering : (2, N) bool, optional
        The (flank, tooth) pairs the exact sweep finds interfering
        (:attr:`PoseState.interfering`). The meshes' chords lie inside the convex hub
        flanks but outside the concave flanks of the internal sleeve teeth, so a coarse
        mesh shows overlap up to about its chordal tolerance deep where the exact
        surfaces are still apart. Given this mask, a piece is kept when the sweep finds
        its tooth and flank (nearest its centroid) interfering, or when it is thicker on
        average (``2 V / A``) than the chordal tolerance, which no chord error makes: an
        overlap outside the flank pairs the sweep models (e.g. a sleeve chamfer corner in
        a hub root fillet).
    """
    rot = np.asarray(rotation, dtype=float)
    overlap = meshes.hub_manifold.transform(affine(rot)) ^ meshes.sleeve_manifold
    if interfering is not None:
        mask = np.asarray(interfering, dtype=bool)
        teeth = mask.shape[1]
        keep = []
        for piece in overlap.decompose():
            verts = np.asarray(piece.to_mesh().vert_properties, dtype=float)[:, :3]
            if verts.size == 0:
                continue
            c = rot.T @ verts.mean(axis=0)  # hub frame
            k = int(nearest_tooth(c, teeth)) % teeth
            flank = int(flank_index(c, k, teeth))
            thick = divide(2.0 * piece.volume(), piece.surface_area())
            if mask[flank, k] or thick > meshes.tolerance_mm:
                keep.append(piece)
        overlap = type(overlap).compose(keep) if keep else type(overlap)()
    volume = float(overlap.volume())
    return patch_from_manifold(overlap), max(volume, 0.0)
