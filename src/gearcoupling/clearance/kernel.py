"""The clearance kernel: smallest gap of a hub flank to the sleeve, over the whole flank.

For a hub flank point in the sleeve frame at radius ``rq``, polar angle ``aq`` (about the
centre of the sleeve space it sits in) and axial position ``zq``, the sleeve surface at
that radius is the straight involute flank (``sm.r_form <= rq <= sm.r_fillet``), the root
fillet above it or the tip chamfer below it. Against the involute the gaps are exact:

- circumferential ``rq * (aq + sigma(rq)/2)`` (docs/conventions.md, Frames, Wei eq. 9),
- normal ``r_b * (aq + sigma(rq)/2)``: involutes of one base circle are parallel curves.

The hub flank (tooth 0, cw) is parametrised by ``(z, t)`` (see :mod:`.flank_table`); at
turning angle ``theta`` the point maps by ``P(theta)`` (:mod:`.pose`). The search is
compiled (:mod:`._compiled`, numba; docs/sweep-speed.md): the minimum over ``t`` of each
plane ``z`` is solved exactly (the ends of the active interval - sleeve tip edge, sleeve
face ends, root-fillet start - and an interior minimum), the minimum over ``z`` from a
coarse grid of planes refined to the tolerance, and from one turning angle to the next
each minimum is followed by Newton steps from the neighbouring angle's. The slow exact
reference it is tested against is :mod:`.reference`.

``contact_kind`` codes (:data:`KINDS`) name where the minimum lies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..arguments import GAP_TOLERANCE_MM, SWEEP_GRID
from ..errors import ArgumentError
from ..geometry import SleeveModel, inv
from .fast import kernels
from .flank_table import FlankTable

KINDS = ("interior", "face end", "tip edge", "form edge", "sleeve tip edge",
         "sleeve root fillet", "sleeve face end", "no contact")
INTERIOR, FACE_END, TIP_EDGE, FORM_EDGE, SLEEVE_TIP, SLEEVE_FILLET, SLEEVE_FACE, NONE = range(8)
MEASURES = ("circumferential", "normal", "pitch_circumferential", "pitch_normal")


@dataclass(frozen=True)
class Minimum:
    """Minima of one measure for a batch of poses (all arrays ``(n,)``).

    ``value_mm`` is ``inf`` where no point of the flank faces the sleeve flank (``kind``
    is ``"no contact"``); ``z_mm`` and ``r_mm`` are hub-frame flank coordinates of the
    minimum and ``rate`` the turning rate of the sleeve polar angle per unit hub turn there.
    """

    value_mm: NDArray[np.float64]
    z_mm: NDArray[np.float64]
    r_mm: NDArray[np.float64]
    t: NDArray[np.float64]
    kind: NDArray[np.int8]
    rate: NDArray[np.float64]


def minimise(table: FlankTable, sm: SleeveModel, misalignment: float, theta, *,
             pitch_radius: float, tolerance_mm: float = GAP_TOLERANCE_MM,
             grid: int = SWEEP_GRID, max_levels: int = 40,
             measures: tuple[str, ...] = MEASURES) -> dict[str, Minimum]:
    """Minimum gaps of tooth 0's cw flank to space 0 at turning angles ``theta``.

    The compiled search (:func:`._compiled.minimise_rows`) in the order of ``theta``:
    the coarse planes and the refinement over ``z`` where no neighbouring minimum is known,
    else each minimum followed from the previous turning angle's (docs/sweep-speed.md);
    each measure's minimum over its branches.

    Parameters
    ----------
    table : FlankTable
        The hub flank.
    sm : SleeveModel
    misalignment : float
        Tilt ``i`` (radians).
    theta : (n,) float
        Turning angles (radians).
    pitch_radius : float
        Radius of the pitch line (``R``).
    tolerance_mm : float
        Stop refining a minimum when it cannot lie lower by more than this (and the flank
        table error is below it).
    grid : int
        Coarse planes over the face width (>= 3); more finds narrow minima more surely.
    max_levels : int
        Nested grids of the refinement where a bracket does not close by steps.
    measures : tuple of str
        Which of :data:`MEASURES` to find (the others are not computed: the design
        searches want only ``normal``, a third of the rows).

    Returns
    -------
    dict of measure name -> Minimum
        For each of ``measures``.
    """
    if grid < 3:
        raise ArgumentError("grid", grid, "at least 3 planes")
    if not tolerance_mm > 0:
        raise ArgumentError("tolerance_mm", tolerance_mm, "must be > 0 mm")
    unknown = set(measures) - set(MEASURES)
    if unknown or not measures:
        raise ArgumentError("measures", measures, f"must be among {MEASURES}")
    compiled = kernels()
    if table.y.shape[1] > compiled.MAX_NZ:
        raise ArgumentError("table", table.y.shape[1],
                            f"at most {compiled.MAX_NZ} Chebyshev terms in z")
    theta = np.asarray(theta, dtype=float).ravel()
    n = theta.size
    # the virtual measures (branches) the requested measures fold from
    wanted = sorted({vm for m in measures for vm in compiled.FOLD[MEASURES.index(m)] if vm >= 0})
    tab, ws = _compiled_arrays(compiled, table, sm, misalignment, pitch_radius, tolerance_mm,
                               grid)
    order = np.argsort(theta, kind="stable")  # neighbours in turn: each follows the last
    out = np.empty((6, len(measures), n))
    compiled.minimise_rows(tab, ws, np.linspace(-table.half_face, table.half_face, grid),
                           theta[order], np.array(wanted, np.int64),
                           np.array([MEASURES.index(m) for m in measures], np.int64),
                           max_levels, out)
    res = np.empty_like(out)
    res[:, :, order] = out
    v, z, r, t, k, rate = res
    return {m: Minimum(v[j], z[j], r[j], t[j], k[j].astype(np.int8), rate[j])
            for j, m in enumerate(measures)}


def _sleeve_constants(sm: SleeveModel) -> list[float]:
    """The sleeve's constants in the order of the compiled kernel's indices ``RB ... SHF``."""
    cx, cy = sm.fillet_centre
    c0 = 0.5 * sm.space_width / sm.R + float(inv(sm.phi))
    return [sm.r_base, c0, sm.r_fillet, float(sm.fillet), math.hypot(cx, cy),
            math.atan2(cy, cx), cx, cy, sm.r_form, sm.half_face]


def _compiled_arrays(compiled, table: FlankTable, sm: SleeveModel, misalignment: float,
                     pitch_radius: float, tolerance_mm: float, grid: int):
    """``tab`` and ``ws`` of the compiled kernel (:mod:`._compiled`): the constants in the
    order of its indices (``CI, SI, RB, ...``), the table's edges and plane matrices; the
    work space."""
    mats = table._plane_matrices  # (pieces, nt + 1, nz)
    pieces, rows, nz = mats.shape
    consts = [math.cos(misalignment), math.sin(misalignment), *_sleeve_constants(sm),
              table.half_face, pitch_radius, tolerance_mm, table.tip_radius,
              float(table.tip_kind != "cylinder"), float(table._power is not None),
              rows - 1, nz, pieces]
    tab = np.concatenate([consts, table.edges, mats.ravel()])
    return tab, np.full(compiled.workspace_size(grid, rows - 1), np.nan)


def sleeve_gaps(sm: SleeveModel, rq, aq) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(circumferential, normal)`` gaps (mm) of points at sleeve radius ``rq``, polar
    angle ``aq`` (broadcast): to the involute, above ``r_fillet`` to the root fillet."""
    compiled = kernels()
    rq, aq = np.broadcast_arrays(np.asarray(rq, dtype=float), np.asarray(aq, dtype=float))
    tab = np.zeros(compiled.EDGES)
    tab[compiled.RB:compiled.SHF + 1] = _sleeve_constants(sm)
    circ, normal = np.empty(rq.size), np.empty(rq.size)
    compiled.gap_field(tab, np.ascontiguousarray(rq).ravel(),
                       np.ascontiguousarray(aq).ravel(), circ, normal)
    return circ.reshape(rq.shape), normal.reshape(rq.shape)
