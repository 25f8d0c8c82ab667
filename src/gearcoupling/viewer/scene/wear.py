"""The worn depth of a wear history (:class:`gearcoupling.WearResult`) on the hub flank
meshes, and its heat-map colours: plain arrays, no viser."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .colors import NO_CONTACT_RGB
from .meshes import HubPieces

#: heat-map stops from a trace of wear (0) to the largest depth (1): pale yellow, orange,
#: dark red; unworn points are grey
_WEAR_STOPS = np.array([[0.0, 250, 240, 170], [0.5, 245, 145, 30], [1.0, 170, 20, 20]])
UNWORN_RGB = NO_CONTACT_RGB


def grid_depth_mm(grid: Any, depth_map: ArrayLike, z_mm: ArrayLike, s_mm: ArrayLike
                  ) -> NDArray[np.float64]:
    """The depth ``(n,)`` at the flank points ``(z_mm, s_mm)`` (axial position, involute arc
    from the base circle), bilinear between the cell centres of ``grid``
    (:class:`~gearcoupling.wear.kernels.FlankGrid`) of ``depth_map (nz, ns)``, the edge
    cells' values held beyond the outer centres."""
    d = np.asarray(depth_map, dtype=float)
    iz, tz = _cell(np.asarray(z_mm, dtype=float), grid.z0, grid.dz, grid.nz)
    js, ts = _cell(np.asarray(s_mm, dtype=float), grid.s0, grid.ds, grid.ns)
    return ((1 - tz) * ((1 - ts) * d[iz, js] + ts * d[iz, js + 1])
            + tz * ((1 - ts) * d[iz + 1, js] + ts * d[iz + 1, js + 1]))


def _cell(x: NDArray, lo: float, step: float, n: int) -> tuple[NDArray[np.intp], NDArray]:
    """The lower centre index ``i`` (``0 <= i <= n - 2``) and the weight of ``i + 1``."""
    u = np.clip((x - lo) / step - 0.5, 0.0, n - 1.0)
    i = np.minimum(np.floor(u).astype(np.intp), n - 2)
    return i, u - i


def hub_flank_depths(result: Any, pieces: HubPieces) -> list[list[NDArray[np.float64]]]:
    """The worn depth at every vertex of every hub flank patch, ``[flank][tooth]`` of
    ``(n,)`` (mm along the flank normal): the result's final map of that tooth (every
    tooth's where they wear alike) at the vertex's axial position and involute arc length
    ``s = (r² − r_b²) / (2 r_b)``."""
    r_b = result.spec.tooth.base_radius
    maps = result.hub_depth_mm  # (2, T, nz, ns)
    out: list[list[NDArray[np.float64]]] = [[], []]
    for f in range(2):
        for k, patch in enumerate(pieces.flanks[f]):
            v = patch.vertices.astype(float)
            r2 = v[:, 0] ** 2 + v[:, 1] ** 2
            depth = maps[f, k if maps.shape[1] > 1 else 0]
            out[f].append(grid_depth_mm(result.hub_grid, depth, v[:, 2],
                                        (r2 - r_b * r_b) / (2 * r_b)))
    return out


def wear_colors(depth_mm: ArrayLike, top_mm: float) -> NDArray[np.uint8]:
    """RGB ``(..., 3) uint8`` of worn depths: grey where unworn (0), then pale yellow
    through orange to dark red at ``top_mm`` and above."""
    d = np.asarray(depth_mm, dtype=float)
    t = np.clip(d / top_mm, 0.0, 1.0) if top_mm > 0 else np.zeros_like(d)
    rgb = np.stack([np.interp(t, _WEAR_STOPS[:, 0], _WEAR_STOPS[:, j]) for j in (1, 2, 3)],
                   axis=-1)
    rgb = np.where((d <= 0)[..., None], np.asarray(UNWORN_RGB, dtype=float), rgb)
    return np.rint(rgb).astype(np.uint8)


def wear_legend(top_mm: float, steps: int = 4) -> list[tuple[str, tuple[int, int, int]]]:
    """Legend entries ``(label, rgb)``: unworn, then ``steps`` depths up to ``top_mm``."""
    values = np.linspace(0.0, top_mm, steps + 1)[1:]
    cols = wear_colors(values, top_mm)
    return [("unworn", UNWORN_RGB)] + [
        (f"{1e3 * v:.3g} µm" + (" (deepest)" if j == steps - 1 else ""),
         (int(c[0]), int(c[1]), int(c[2]))) for j, (v, c) in enumerate(zip(values, cols,
                                                                          strict=True))]


__all__ = ["UNWORN_RGB", "grid_depth_mm", "hub_flank_depths", "wear_colors", "wear_legend"]
