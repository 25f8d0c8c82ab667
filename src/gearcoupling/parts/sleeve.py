"""Sleeve solid: ring with straight internal teeth, root fillets, tip chamfers, face ends.

The toothed bore is the exact transverse outline (the same in every plane), extruded over
the sleeve face width ``|z| <= B/2``; the ring is closed by the outer cylinder and two
annular end faces.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from ..geometry import sleeve_model
from ..spec import CouplingSpec
from . import builder as mb
from .grid import arc_count, sleeve_pitch


@dataclass(frozen=True, eq=False)
class SleeveLayout:
    """Everything the sleeve mesh needs, computed once per (spec, tolerance)."""

    pitch: NDArray[np.float64]  # (M, 2) space outline of one pitch
    kinds: NDArray[np.int16]
    half_face: float
    r_outer: float
    ring: int
    cap: NDArray[np.intp]


@lru_cache(maxsize=16)
def sleeve_layout(spec: CouplingSpec, tol: float) -> SleeveLayout:
    sm = sleeve_model(spec)
    pitch, kinds = sleeve_pitch(sm, tol)
    r_outer = 0.5 * spec.sleeve.outer_diameter
    ring = max(arc_count(r_outer, 2 * math.pi / sm.teeth, 0.9 * tol), mb.MIN_RING)
    cap = mb.zipper(mb.ring_pitch(r_outer, sm.teeth, ring), pitch)
    codes = np.array([mb.KIND_CODE[k] for k in kinds], dtype=np.int16)
    return SleeveLayout(pitch, codes, sm.half_face, r_outer, ring, cap)


def build_sleeve_run(b: mb.MeshBuilder, lay: SleeveLayout, run: mb.Run) -> None:
    """Add the sleeve solid of one run of teeth (closed ring or a sector with side walls)."""
    hf = lay.half_face
    nseg = len(lay.pitch) - 1
    band = mb.tile(lay.pitch[None], run)[0]
    i_bot, i_top = b.vertices(mb.with_z(band, -hf)), b.vertices(mb.with_z(band, hf))
    n_quads = len(band) if run.closed else len(band) - 1
    tooth = np.array([run.tooth(q // nseg) for q in range(n_quads)])
    b.strip(i_bot, i_top, np.resize(lay.kinds, n_quads), tooth, closed=run.closed, flip=True)
    ring = mb.tile(mb.ring_pitch(lay.r_outer, run.teeth, lay.ring)[None], run)[0]
    o_bot, o_top = b.vertices(mb.with_z(ring, -hf)), b.vertices(mb.with_z(ring, hf))
    b.strip(o_bot, o_top, "body", -1, closed=run.closed)
    mb.add_cap(b, lay.cap, o_top, i_top, run, lay.ring, nseg, flip=False)
    mb.add_cap(b, lay.cap, o_bot, i_bot, run, lay.ring, nseg, flip=True)
    if run.closed:
        return
    for col in (0, -1):
        b.wall(np.array([o_bot[col], o_top[col]]), np.array([i_bot[col], i_top[col]]),
               start=col == 0)



def sleeve_triangles(lay: SleeveLayout, run: mb.Run) -> int:
    """Triangles :func:`build_sleeve_run` adds for ``run``, from the layout's sizes alone:
    the toothed bore, the outer cylinder, two end faces and, for a sector, two side walls
    of two triangles each."""
    k = run.count
    total = 2 * k * (len(lay.pitch) - 1) + 2 * k * lay.ring + 2 * k * len(lay.cap)
    return total if run.closed else total + 4
