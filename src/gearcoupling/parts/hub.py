"""Hub solid: crowned teeth with generated root fillets, trimmed tip, end faces, body, bore.

Layout (hub frame, mm): the toothed band spans ``|z| <= b/2``; its end faces reach down to
the body. When the body is longer than the face width it continues beyond the teeth as a
shoulder cylinder a quarter module below the smallest root radius (so the root and the
shoulder never touch), closed by annular body end faces at ``z = +-L/2``. The bore runs
through the whole length (``bore_diameter = 0``: a solid hub).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from ..geometry import hub_model, root_radius
from ..spec import CouplingSpec
from .builder import (
    KIND_CODE,
    MIN_RING,
    MeshBuilder,
    Run,
    add_cap,
    ring_pitch,
    tile,
    with_z,
    zipper,
)
from .grid import HubToothGrid, arc_count, hub_tooth_grid


@dataclass(frozen=True, eq=False)
class HubLayout:
    """Everything the hub mesh needs, computed once per (spec, tolerance)."""

    grid: HubToothGrid
    pitch: NDArray[np.float64]  # (nz, M, 2) tooth outline rows
    kinds: NDArray[np.int16]  # (M - 1,) kind codes of the outline segments
    half_face: float
    half_length: float
    r_bore: float
    r_inner: float  # radius of the circle the tooth end faces reach down to
    shoulder: bool  # body longer than the face: shoulder cylinder at r_inner
    ring: int  # circle segments per pitch
    cap: NDArray[np.intp]  # zipper triangles of one pitch of end face
    module: float


@lru_cache(maxsize=16)
def hub_layout(spec: CouplingSpec, tol: float) -> HubLayout:
    m = hub_model(spec)
    grid = hub_tooth_grid(m, tol)
    pitch = grid.points()
    body = spec.hub.body
    half_length = 0.5 * body.length
    r_bore = 0.5 * body.bore_diameter
    r_root = float(np.min(root_radius(m, grid.z)))
    shoulder = half_length > m.half_face * (1 + 1e-9)
    module = spec.tooth.module
    if shoulder:
        r_inner = r_root - 0.25 * module
    elif r_bore > 0:
        r_inner = r_bore
    else:
        r_inner = 0.5 * r_root
    ring = max(arc_count(r_inner, 2 * math.pi / m.teeth, 0.9 * tol), MIN_RING)
    inner = ring_pitch(r_inner, m.teeth, ring)
    cap = zipper(pitch[-1], inner)
    kinds = np.array([KIND_CODE[k] for k in grid.kinds()], dtype=np.int16)
    return HubLayout(grid, pitch, kinds, m.half_face, half_length, r_bore, r_inner, shoulder,
                     ring, cap, module)


def build_hub_run(b: MeshBuilder, lay: HubLayout, run: Run) -> None:
    """Add the hub solid of one run of teeth (closed ring or a sector with side walls)."""
    z = lay.grid.z
    nseg = lay.pitch.shape[1] - 1
    band = tile(lay.pitch, run)
    iT = b.vertices(with_z(band, z[:, None]))
    ncol = iT.shape[1]
    n_quads = ncol if run.closed else ncol - 1
    kinds = np.resize(lay.kinds, n_quads)
    tooth = np.array([run.tooth(q // nseg) for q in range(n_quads)])
    for j in range(len(z) - 1):
        b.strip(iT[j], iT[j + 1], kinds, tooth, closed=run.closed)

    def ring(radius: float, zz: float) -> NDArray[np.intp]:
        pts = tile(ring_pitch(radius, run.teeth, lay.ring)[None], run)[0]
        return b.vertices(with_z(pts, zz))

    hf, hl = lay.half_face, lay.half_length
    q_top, q_bot = ring(lay.r_inner, hf), ring(lay.r_inner, -hf)
    add_cap(b, lay.cap, iT[-1], q_top, run, nseg, lay.ring, flip=False)
    add_cap(b, lay.cap, iT[0], q_bot, run, nseg, lay.ring, flip=True)
    closed = run.closed
    if lay.shoulder:
        s_top, s_bot = ring(lay.r_inner, hl), ring(lay.r_inner, -hl)
        b.strip(q_top, s_top, "body", -1, closed=closed)
        b.strip(s_bot, q_bot, "body", -1, closed=closed)
        end_top, end_bot = s_top, s_bot
    else:
        end_top, end_bot = q_top, q_bot
    has_bore = lay.r_bore > 0
    if has_bore:
        if lay.shoulder:
            z_top, z_bot = ring(lay.r_bore, hl), ring(lay.r_bore, -hl)
            b.strip(end_top, z_top, "end", -1, closed=closed)
            b.strip(z_bot, end_bot, "end", -1, closed=closed)
            # a midplane row lets the sector walls reach both shoulder steps
            z_mid = ring(lay.r_bore, 0.0)
            b.strip(z_top, z_mid, "bore", -1, closed=closed)
            b.strip(z_mid, z_bot, "bore", -1, closed=closed)
            axis = [z_bot, z_mid, z_top]
        else:
            z_top, z_bot = end_top, end_bot
            b.strip(z_top, z_bot, "bore", -1, closed=closed)
            axis = [z_bot, z_top]
    else:
        hz = hl if lay.shoulder else hf
        c_top, c_bot = b.vertices(np.array([[0.0, 0.0, hz], [0.0, 0.0, -hz]]))
        _fan(b, c_top, end_top, closed, flip=False)
        _fan(b, c_bot, end_bot, closed, flip=True)
        n = len(end_top)
        axis = [np.full(n, c_bot), np.full(n, c_top)]
        if lay.shoulder and not closed:
            axis.insert(1, np.full(n, b.vertices(np.zeros((1, 3)))[0]))
    if closed:
        return
    for col in (0, -1):
        top = list(iT[:, col])
        bottom = [a[col] for a in axis]
        if lay.shoulder:
            top = [end_bot[col], q_bot[col], *top, q_top[col], end_top[col]]
        elif not has_bore:
            bottom = [q_bot[col], *bottom, q_top[col]]
        b.wall(np.array(top), np.array(bottom), start=col == 0)


def _fan(b: MeshBuilder, centre: int, chain: NDArray, closed: bool, *, flip: bool) -> None:
    nxt = np.roll(chain, -1) if closed else chain[1:]
    cur = chain if closed else chain[:-1]
    tris = np.stack([np.full(len(cur), centre), cur, nxt], axis=1)
    b.faces(tris[:, ::-1] if flip else tris, "end", -1)



def hub_triangles(lay: HubLayout, run: Run) -> int:
    """Triangles :func:`build_hub_run` adds for ``run``, from the layout's grid sizes alone
    (nothing is built): the tooth band, its end faces, the rings of body, shoulder and bore
    and, for a sector, its two side walls."""
    nz, nseg, k, ring = len(lay.grid.z), lay.pitch.shape[1] - 1, run.count, lay.ring
    bore = lay.r_bore > 0
    strips = (2 if lay.shoulder else 0) + ((4 if lay.shoulder else 1) if bore else 0)
    fans = 0 if bore else 2
    total = 2 * (nz - 1) * k * nseg + 2 * k * len(lay.cap) + (2 * strips + fans) * k * ring
    if run.closed:
        return total
    top = nz + (4 if lay.shoulder else 0)
    bottom = (3 if lay.shoulder else 2) + (0 if bore or lay.shoulder else 2)
    return total + 2 * (top + bottom - 2)
