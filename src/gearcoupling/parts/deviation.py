"""Measured deviation of a part mesh from the exact surfaces of the geometry kernels.

Exact points are sampled from the kernels (hub flanks from ``hub_flank_model`` up to the
crown ends and the tip, fillets from ``envelope`` of the hob tip round, tip and root
surfaces, sleeve flanks from ``flank_point``, fillet and chamfer, circles), rotated to
teeth of the mesh, and their distance to the mesh is the exact point-to-triangle
distance minimised over the triangles around the nearest mesh vertices. A minimum over a
subset of triangles can only overestimate the true distance, so the figure is an honest
upper bound.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..geometry import (
    envelope,
    flank_point,
    form_radius,
    hub_flank_model,
    hub_model,
    root_radius,
    round_point,
    sleeve_model,
    tip_radius,
)
from ..numeric import TINY, divide
from ..spec import CouplingSpec
from .grid import tip_corner


def _dot(a: NDArray, b: NDArray) -> NDArray:
    return np.einsum("...k,...k->...", a, b)


def point_triangle_distance(p: NDArray, a: NDArray, b: NDArray, c: NDArray) -> NDArray:
    """Exact distances ``(...)`` from points ``p`` to triangles ``(a, b, c)`` (all ``(..., 3)``)."""
    p, a, b, c = np.broadcast_arrays(p, a, b, c)
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    nn = _dot(n, n)
    ap = p - a
    # barycentric coordinates of the projection
    d00, d01, d11 = _dot(ab, ab), _dot(ab, ac), _dot(ac, ac)
    d20, d21 = _dot(ap, ab), _dot(ap, ac)
    den = np.maximum(d00 * d11 - d01 * d01, TINY)
    v = (d11 * d20 - d01 * d21) / den
    w = (d00 * d21 - d01 * d20) / den
    inside = (v >= 0) & (w >= 0) & (v + w <= 1) & (nn > 0)
    plane = np.abs(_dot(ap, n)) / np.sqrt(np.maximum(nn, TINY))

    def seg(p0, p1):
        d = p1 - p0
        q = p - p0
        t = np.clip(divide(_dot(q, d), _dot(d, d)), 0, 1)
        r = q - t[..., None] * d
        return np.sqrt(_dot(r, r))

    edge = np.minimum(np.minimum(seg(a, b), seg(b, c)), seg(c, a))
    return np.where(inside, np.minimum(plane, edge), edge)


def distance_to_mesh(points: NDArray, vertices: NDArray, faces: NDArray, *, k: int = 8,
                     chunk: int = 4000) -> NDArray[np.float64]:
    """Upper bound of the distance ``(n,)`` from ``points (n, 3)`` to a triangle mesh.

    Minimum exact point-to-triangle distance over the triangles incident to the ``k``
    mesh vertices nearest to each point (a minimum over a subset of the triangles can only
    overestimate the distance). The (point, triangle) pairs are listed flat, so a vertex of
    high valence (an end-cap fan) costs only its own triangles.
    """
    from scipy.spatial import cKDTree

    vertices = np.asarray(vertices, dtype=float)
    faces = np.asarray(faces, dtype=np.int64)
    points = np.asarray(points, dtype=float)
    order = np.argsort(faces.ravel(), kind="stable")
    owner = order // 3  # faces around each vertex, vertex by vertex
    starts = np.searchsorted(faces.ravel()[order], np.arange(len(vertices) + 1))
    tree = cKDTree(vertices)
    out = np.empty(len(points))
    for lo in range(0, len(points), chunk):
        p = points[lo:lo + chunk]
        _, near = tree.query(p, k=min(k, len(vertices)))
        near = near.reshape(len(p), -1).ravel()
        count = starts[near + 1] - starts[near]
        total = int(count.sum())
        # flat positions into ``owner``: starts[near] + 0..count-1 for every near vertex
        offset = np.arange(total) - np.repeat(np.cumsum(count) - count, count)
        tri_idx = owner[np.repeat(starts[near], count) + offset]
        point_idx = np.repeat(np.repeat(np.arange(len(p)), near.size // len(p)), count)
        tri = vertices[faces[tri_idx]]
        d = point_triangle_distance(p[point_idx], tri[:, 0], tri[:, 1], tri[:, 2])
        best = np.full(len(p), np.inf)
        np.minimum.at(best, point_idx, d)
        out[lo:lo + chunk] = best
    return out


def _rotate(points: NDArray, angle: NDArray) -> NDArray:
    c, s = np.cos(angle), np.sin(angle)
    x, y = points[..., 0], points[..., 1]
    return np.stack([c * x - s * y, s * x + c * y, points[..., 2]], axis=-1)


def _mirror(points: NDArray) -> NDArray:
    return points * np.array([1.0, -1.0, 1.0])


def hub_samples(spec: CouplingSpec,
                n: int, rng: np.random.Generator) -> dict[str, NDArray[np.float64]]:
    """Exact points on hub tooth 0 by surface kind, ``(n, 3)`` each (crown ends included)."""
    m = hub_model(spec)
    hf = m.half_face
    z = rng.uniform(-hf, hf, n)
    z[: n // 8] = hf * np.sign(rng.uniform(-1, 1, n // 8))  # crown ends
    out = {}
    r_lo, r_hi = form_radius(m, z), tip_radius(m, z)
    r = r_lo + rng.uniform(0, 1, n) * (r_hi - r_lo)
    for flank in ("cw", "ccw"):
        out[f"flank_{flank}"] = hub_flank_model(m, flank, z, r, check=False)[0]
    g = rng.uniform(m.phi, math.pi / 2, n)
    u, h = round_point(m, g)
    fil = envelope(m, z, u, h, g)[0]
    out["fillet_cw"], out["fillet_ccw"] = fil, _mirror(fil)
    r_tip, _, a_top = tip_corner(m, z)
    a = a_top * rng.uniform(-1, 1, n)
    out["tip"] = np.stack([r_tip * np.cos(a), r_tip * np.sin(a), z], -1)
    u_c, _ = m.round_centre
    a = rng.uniform(-math.pi / m.teeth, -u_c / m.R, n) * np.sign(rng.uniform(-1, 1, n))
    rr = root_radius(m, z)
    out["root"] = np.stack([rr * np.cos(a), rr * np.sin(a), z], -1)
    return out


def sleeve_samples(spec: CouplingSpec,
                   n: int, rng: np.random.Generator) -> dict[str, NDArray[np.float64]]:
    """Exact points on sleeve space 0 by surface kind, ``(n, 3)`` each."""
    sm = sleeve_model(spec)
    z = rng.uniform(-sm.half_face, sm.half_face, n)

    def lift(p2):
        return np.concatenate([p2, z[:, None]], axis=-1)

    out = {}
    p, _ = flank_point(sm, rng.uniform(sm.r_form, sm.r_fillet, n))
    out["flank_cw"], out["flank_ccw"] = lift(p), _mirror(lift(p))
    if sm.fillet > 0:
        cx, cy = sm.fillet_centre
        p_end, _ = flank_point(sm, sm.r_fillet)
        a0 = math.atan2(p_end[1] - cy, p_end[0] - cx)
        a1 = a0 + math.remainder(math.atan2(cy, cx) - a0, 2 * math.pi)
        a = rng.uniform(min(a0, a1), max(a0, a1), n)
        f = lift(np.stack([cx + sm.fillet * np.cos(a), cy + sm.fillet * np.sin(a)], -1))
        out["fillet_cw"], out["fillet_ccw"] = f, _mirror(f)
    if sm.chamfer > 0:
        p0 = sm.r_minor * np.array([math.cos(sm.chamfer_tip_angle),
                                     math.sin(sm.chamfer_tip_angle)])
        p1, _ = flank_point(sm, sm.r_form)
        t = rng.uniform(0, 1, n)[:, None]
        c = lift(p0 + t * (p1 - p0))
        out["chamfer_cw"], out["chamfer_ccw"] = c, _mirror(c)
    a = rng.uniform(sm.major_angle, -sm.major_angle, n)
    out["root"] = lift(sm.r_major * np.stack([np.cos(a), np.sin(a)], -1))
    half = math.pi / sm.teeth
    a = rng.uniform(-half, sm.chamfer_tip_angle, n) * np.sign(rng.uniform(-1, 1, n))
    out["tip"] = lift(sm.r_minor * np.stack([np.cos(a), np.sin(a)], -1))
    return out


def circle_samples(radius: float, z0: float, z1: float, n: int, rng) -> NDArray[np.float64]:
    """Points on a cylinder of ``radius`` between ``z0`` and ``z1``."""
    a = rng.uniform(0, 2 * math.pi, n)
    return np.stack([radius * np.cos(a), radius * np.sin(a), rng.uniform(z0, z1, n)], -1)


def exact_samples(spec: CouplingSpec, part: str, samples: int, teeth=None, *,
                  seed: int = 0) -> dict[str, NDArray[np.float64]]:
    """Exact surface points ``{kind: (samples, 3)}`` of a part, each tooth-surface point on
    a random tooth of ``teeth`` (all by default); the bore and the sleeve's outer cylinder
    are included for whole parts. Hub flank samples include the crown ends (1/8 of them).
    """
    rng = np.random.default_rng(seed)
    n_teeth = spec.tooth.teeth
    chosen = np.array(range(n_teeth) if teeth is None else list(teeth))
    pts = hub_samples(spec, samples, rng) if part == "hub" else sleeve_samples(spec, samples, rng)
    for kind in pts:
        pts[kind] = _rotate(pts[kind], 2 * math.pi * rng.choice(chosen, samples) / n_teeth)
    if teeth is None:
        if part == "hub":
            hl = 0.5 * spec.hub.body.length
            if spec.hub.body.bore_diameter > 0:
                pts["bore"] = circle_samples(0.5 * spec.hub.body.bore_diameter, -hl, hl,
                                             samples, rng)
        else:
            hf = 0.5 * spec.sleeve.face_width
            pts["body"] = circle_samples(0.5 * spec.sleeve.outer_diameter, -hf, hf, samples, rng)
    return pts


def measure_deviation(spec: CouplingSpec,
                      mesh, *, samples: int = 2000, seed: int = 0) -> dict[str, float]:
    """Largest distance (mm) from exact surface points to the mesh, per surface kind.

    Parameters
    ----------
    spec : CouplingSpec
    mesh : trimesh.Trimesh
        From :func:`~gearcoupling.parts.build_part` (its metadata give part and teeth).
    samples : int
        Exact points per surface kind (:func:`exact_samples`).

    Returns
    -------
    dict
        ``{kind: max distance}`` plus ``"max"`` over all kinds.
    """
    pts = exact_samples(spec, mesh.metadata["part"], samples, mesh.metadata.get("teeth"),
                        seed=seed)
    dist = distance_to_mesh(np.concatenate(list(pts.values())), mesh.vertices, mesh.faces)
    ends = np.cumsum([len(p) for p in pts.values()])
    out = {kind: float(d.max()) for kind, d in zip(pts, np.split(dist, ends[:-1]), strict=True)}
    out["max"] = max(out.values())
    return out
