"""Model only what a pose needs: sector submodels and the teeth each pose must look at.

Because the ideal coupling repeats every tooth, one hub sector of ``2k + 1`` teeth around
tooth 0 and the sleeve sector of the same spaces, built once, stand for *any* ``2k + 1``
consecutive teeth: posed by :func:`~.posed.window_pose` for a centre tooth ``c`` they are
exactly hub teeth ``c - k .. c + k`` in their sleeve spaces. A pose therefore costs a few
windows of a few hundred triangles each instead of the full parts.

Which teeth a pose needs comes from the semi-analytic sweep (:func:`gearcoupling.clearance.
sweep`): every tooth whose smallest normal clearance lies within ``margin_mm`` of the
pose's smallest, and every tooth whose clearance is below ``2 * tolerance_mm`` (a tooth
that could overlap on the meshes). The windows tile those teeth without overlapping, so
overlap volumes add up.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError
from ..parts import build_part
from ..spec import CouplingSpec
from .posed import PreparedPart

NOT_SHELL = ("body", "bore", "side")  # left out of the flank-only shells


@dataclass(frozen=True, eq=False)
class Model:
    """Prepared hub and sleeve meshes: the full parts or a sector of ``2k + 1`` teeth.

    Attributes
    ----------
    hub, sleeve : PreparedPart
        In their own frames; a sector is centred on tooth 0 / space 0.
    half_window : int or None
        ``k`` of a sector, ``None`` for the full parts.
    teeth : int
        Tooth count ``N`` of the coupling.
    """

    hub: PreparedPart
    sleeve: PreparedPart
    half_window: int | None
    teeth: int

    @property
    def full(self) -> bool:
        return self.half_window is None

    @property
    def window_teeth(self) -> int:
        """Teeth one window covers (``N`` for the full parts)."""
        return self.teeth if self.half_window is None else 2 * self.half_window + 1

    @property
    def triangles(self) -> tuple[int, int]:
        return self.hub.triangles, self.sleeve.triangles

    @property
    def label(self) -> str:
        return "full parts" if self.full else f"sector ±{self.half_window}"


def build_model(spec: CouplingSpec, tolerance_mm: float, half_window: int | None) -> Model:
    """Build (once) the meshes of the full parts (``half_window=None``) or of a sector.

    Parameters
    ----------
    spec : CouplingSpec
    tolerance_mm : float
        Chordal tolerance of both meshes (see :func:`gearcoupling.parts.build_part`).
    half_window : int or None
        ``k``: the sector holds teeth ``-k .. k`` around tooth 0 (``2k + 1 < N``).
    """
    N = spec.tooth.teeth
    if half_window is not None:
        k = int(half_window)
        if k != half_window or k < 0 or 2 * k + 1 >= N:
            raise ArgumentError("half_window", half_window, f"a whole number from 0 to "
                                f"{(N - 2) // 2} for {N} teeth (or None for the full parts)")
        teeth = [t % N for t in range(-k, k + 1)]
    else:
        k, teeth = None, None
    hub = build_part(spec, "hub", tolerance_mm=tolerance_mm, teeth=teeth)
    sleeve = build_part(spec, "sleeve", tolerance_mm=tolerance_mm, teeth=teeth)
    return Model(PreparedPart.from_trimesh(hub, NOT_SHELL),
                 PreparedPart.from_trimesh(sleeve, NOT_SHELL), k, N)


def side_clearance(sweep_result, hub_rotation: float = 0.0) -> NDArray[np.float64]:
    """Normal clearance of each flank and tooth, ``(flank, tooth, angle)`` in mm.

    An extra hub turn ``delta`` (radians, toward increasing polar angle) opens the cw
    flanks and closes the ccw flanks by ``r_b * delta`` (first order), which is all the
    tooth selection needs.
    """
    nc = np.asarray(sweep_result.normal_clearance_mm, dtype=float)
    shift = sweep_result.base_radius_mm * hub_rotation
    return np.stack([nc[0] + shift, nc[1] - shift])


def flank_clearance(sweep_result, hub_rotation: float = 0.0) -> NDArray[np.float64]:
    """Smallest normal clearance of each tooth over both flanks, ``(tooth, angle)`` in mm."""
    return np.min(side_clearance(sweep_result, hub_rotation), axis=0)


def hot_teeth(clearance: NDArray, margin_mm: float, floor_mm: float):
    """Per angle, the teeth a pose must model for its gap and for its overlap.

    Parameters
    ----------
    clearance : (N, M) float
        Smallest clearance of each tooth at each angle (mm), e.g. :func:`flank_clearance`.
    margin_mm : float
        Gap teeth: within this much of the angle's smallest clearance.
    floor_mm : float
        Overlap teeth: below this clearance (the ones that may overlap on the meshes), and
        always the tightest tooth, so every pose runs at least one overlap test.

    Returns
    -------
    gap, overlap : lists of (n_j,) int arrays, one per angle, sorted.
    """
    c = np.where(np.isfinite(clearance), clearance, np.inf)
    low = np.min(c, axis=0)
    gap = [np.flatnonzero(c[:, j] <= low[j] + margin_mm) for j in range(c.shape[1])]
    over = [np.union1d(np.flatnonzero(c[:, j] < floor_mm), [int(np.argmin(c[:, j]))])
            for j in range(c.shape[1])]
    return gap, over


@dataclass(frozen=True)
class Window:
    """One posed sector: its centre tooth and the teeth it owns for each purpose.

    Attributes
    ----------
    centre : int
        Tooth the sector around tooth 0 stands for.
    overlap, gap : frozenset of int
        Owned teeth whose overlap / minimum gap this window reports.
    sides : tuple of 2 frozensets
        Owned teeth whose cw / ccw flank-side gap (for the backlash) it reports.
    """

    centre: int
    overlap: frozenset
    gap: frozenset
    sides: tuple[frozenset, frozenset] = (frozenset(), frozenset())


def plan_pose(count: int, half_window: int, overlap, gap,
              sides=((), ())) -> list[Window]:
    """Windows of ``2k + 1`` teeth covering every tooth any purpose needs, each tooth owned
    by one window (see :func:`windows`)."""
    want = [frozenset(int(t) for t in x) for x in (overlap, gap, *sides)]
    union = frozenset().union(*want)
    return [Window(c, owned & want[0], owned & want[1], (owned & want[2], owned & want[3]))
            for c, owned in windows(sorted(union), count, half_window)]


def side_teeth(clearance: NDArray, margin_mm: float) -> list[tuple[NDArray, NDArray]]:
    """Per angle, the teeth within ``margin_mm`` of each flank side's smallest clearance.

    ``clearance`` is ``(flank, tooth, angle)`` (:func:`side_clearance`).
    """
    c = np.where(np.isfinite(clearance), clearance, np.inf)
    low = np.min(c, axis=1)  # (flank, angle)
    near = c <= low[:, None, :] + margin_mm  # (flank, tooth, angle)
    return [(np.flatnonzero(near[0, :, j]), np.flatnonzero(near[1, :, j]))
            for j in range(c.shape[2])]


def windows(teeth: Iterable[int], count: int, half_window: int) -> list[tuple[int, frozenset]]:
    """Windows of ``2k + 1`` teeth that cover ``teeth``, each owning a disjoint part of them.

    Each cyclic run of consecutive selected teeth is tiled from its first tooth; a window
    may reach past its run, but it only *owns* the selected teeth no earlier window owns, so
    overlap volumes attributed to owned teeth add up without double counting.

    Returns
    -------
    list of (centre tooth, owned teeth)
    """
    sel = sorted({int(t) % count for t in teeth})
    width = 2 * half_window + 1
    present = set(sel)
    if len(sel) == count:
        runs = [(0, count)]
    else:
        runs = []
        for start in (t for t in sel if (t - 1) % count not in present):
            n = 1
            while (start + n) % count in present:
                n += 1
            runs.append((start, n))
    out: list[tuple[int, frozenset]] = []
    taken: set[int] = set()
    for start, n in runs:
        for j in range(-(-n // width)):
            first = start + width * j
            covered = {(first + d) % count for d in range(min(width, count))}
            owned = frozenset((covered & present) - taken)
            taken |= owned
            if owned:
                out.append(((first + half_window) % count, owned))
    return out
