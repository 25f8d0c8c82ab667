"""``check_interference``: overlap and minimum gap of the posed part meshes over rotation.

For every rotation ``psi`` the hub mesh is posed in the sleeve frame (DESIGN.md §2) and
compared with the sleeve mesh:

- ``method="boolean"``: the overlap is the manifold3d intersection of the two solids,
  split into connected pieces; each piece gives its tooth, hub flank, volume, centroid and
  depth (the largest distance of the piece's points to the sleeve surface, i.e. how far the
  hub surface reaches into the sleeve).
- ``method="distance"``: no booleans; python-fcl tests the shells for collision and, where
  they collide, the hub vertices inside the sleeve (libigl signed distance) give depth,
  centroid and an *estimated* volume ``sum(vertex area * depth)`` (the lens volume to first
  order; ``volume_exact`` is False).

Both report the signed minimum gap: the closest distance of the shells (python-fcl, with
the point pair, tooth and surfaces) where they are apart, minus the depth where they
overlap. Compare it with the sweep's ``normal_clearance_mm``: for the straight involute
sleeve flank the distance to the flank *is* the normal clearance.

``teeth`` picks the model (:mod:`.submodel`): ``"sweep"`` (default) poses single tooth
pairs at the teeth the semi-analytic sweep finds near the smallest clearance, an integer
``k`` windows of ``2k + 1`` teeth there, ``"all"`` the full parts.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SpecError
from . import distance as dist
from .posed import hub_pose, window_pose, window_to_sleeve
from .submodel import Model, build_model, flank_clearance, hot_teeth, windows

METHODS = ("boolean", "distance")
MIN_VOLUME_MM3 = 1e-9  # overlap pieces below this are numerical dust of the intersection
FLANKS = ("cw", "ccw")


@dataclass(frozen=True)
class Overlap:
    """One connected overlap of a hub tooth with the sleeve at one rotation.

    Attributes
    ----------
    angle_index : int
        Index into the result's ``angles_deg``.
    tooth : int
        Hub tooth (= sleeve space) index.
    flank : str
        Hub flank ``"cw"`` or ``"ccw"`` (DESIGN.md §2).
    volume_mm3 : float
        Overlap volume (an estimate with ``method="distance"``).
    depth_mm : float
        Largest distance of a hub surface point inside the sleeve to the sleeve surface.
    centroid_mm : tuple of 3 float
        Centroid of the overlap in the sleeve frame.
    """

    angle_index: int
    angle_deg: float
    tooth: int
    flank: str
    volume_mm3: float
    depth_mm: float
    centroid_mm: tuple[float, float, float]


@dataclass(frozen=True, eq=False)
class InterferenceResult:
    """Overlap and signed minimum gap of posed hub and sleeve meshes per rotation.

    Arrays are indexed by angle ``(M,)``; points are in the sleeve frame (mm).

    Attributes
    ----------
    overlap_volume_mm3 : (M,) float
        Total overlap volume (exact on the meshes with ``method="boolean"``).
    overlap_depth_mm : (M,) float
        Largest penetration depth, 0 where the parts are apart.
    min_gap_mm : (M,) float
        Closest distance of the surfaces where apart, ``-overlap_depth_mm`` where they
        overlap (compare with the sweep's normal clearance).
    hub_point_mm, sleeve_point_mm : (M, 3) float
        The closest pair (apart) or the deepest hub point and its foot on the sleeve.
    gap_tooth : (M,) int
        Hub tooth of that pair; ``gap_hub_surface`` / ``gap_sleeve_surface`` its surface
        kinds (:data:`gearcoupling.parts.SURFACE_KINDS`).
    overlaps : tuple of Overlap
        Every overlapping piece.
    windows : (M,) int
        Windows (sector poses) evaluated per angle (1 for the full parts).
    seconds_per_pose : float
        Mean wall time of one rotation, model building excluded (``setup_seconds``).
    """

    spec_name: str
    misalignment_deg: float
    hub_rotation_deg: float
    method: str
    model: str
    tolerance_mm: float
    teeth: int
    angles_deg: NDArray[np.float64]
    overlap_volume_mm3: NDArray[np.float64]
    overlap_depth_mm: NDArray[np.float64]
    min_gap_mm: NDArray[np.float64]
    hub_point_mm: NDArray[np.float64]
    sleeve_point_mm: NDArray[np.float64]
    gap_tooth: NDArray[np.int64]
    gap_hub_surface: tuple[str, ...]
    gap_sleeve_surface: tuple[str, ...]
    overlaps: tuple[Overlap, ...]
    windows: NDArray[np.int64]
    triangles: tuple[int, int]
    volume_exact: bool
    setup_seconds: float
    seconds_per_pose: float
    prepared: Model | None = field(default=None, repr=False)
    poses: tuple = field(default=(), repr=False)

    @property
    def interferes(self) -> bool:
        """Whether any pose overlaps."""
        return len(self.overlaps) > 0

    def teeth_involved(self, index: int) -> list[int]:
        """Sorted hub teeth overlapping at angle ``index``."""
        return sorted({o.tooth for o in self.overlaps if o.angle_index == index})

    def overlaps_at(self, index: int) -> list[Overlap]:
        return [o for o in self.overlaps if o.angle_index == index]

    def worst(self, count: int = 10) -> NDArray[np.int64]:
        """Indices of the ``count`` angles with the smallest signed gap (largest overlap)."""
        order = np.lexsort((-self.overlap_volume_mm3, self.min_gap_mm))
        return order[:count]

    def rows(self) -> list[dict[str, Any]]:
        """One plain row per angle (for CSV/JSON)."""
        out = []
        for j, a in enumerate(self.angles_deg):
            out.append({
                "angle_deg": float(a),
                "overlap_volume_mm3": float(self.overlap_volume_mm3[j]),
                "overlap_depth_mm": float(self.overlap_depth_mm[j]),
                "min_gap_mm": float(self.min_gap_mm[j]),
                "teeth": " ".join(str(t) for t in self.teeth_involved(j)),
                "gap_tooth": int(self.gap_tooth[j]),
                "gap_hub_surface": self.gap_hub_surface[j],
                "gap_sleeve_surface": self.gap_sleeve_surface[j],
                "hub_point_mm": [float(v) for v in self.hub_point_mm[j]],
                "sleeve_point_mm": [float(v) for v in self.sleeve_point_mm[j]],
                "windows": int(self.windows[j]),
            })
        return out

    def summary(self) -> dict[str, Any]:
        """Settings, model size, timings and the worst pose, as plain data."""
        w = int(self.worst(1)[0])
        return {
            "spec": self.spec_name, "misalignment_deg": self.misalignment_deg,
            "hub_rotation_deg": self.hub_rotation_deg, "method": self.method,
            "model": self.model, "tolerance_mm": self.tolerance_mm,
            "angles": len(self.angles_deg), "interferes": self.interferes,
            "volume_exact": self.volume_exact,
            "triangles_hub": self.triangles[0], "triangles_sleeve": self.triangles[1],
            "setup_seconds": self.setup_seconds, "seconds_per_pose": self.seconds_per_pose,
            "max_overlap_volume_mm3": float(np.max(self.overlap_volume_mm3)),
            "max_overlap_depth_mm": float(np.max(self.overlap_depth_mm)),
            "min_gap_mm": float(self.min_gap_mm[w]), "worst_angle_deg": float(self.angles_deg[w]),
            "overlaps": [
                {"angle_deg": o.angle_deg, "tooth": o.tooth, "flank": o.flank,
                 "volume_mm3": o.volume_mm3, "depth_mm": o.depth_mm,
                 "centroid_mm": list(o.centroid_mm)} for o in self.overlaps],
        }


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise ValueError(f"method = {method!r}: must be one of {METHODS}")
    return method


def _check_teeth(teeth, N: int) -> int | str | None:
    """``"sweep"`` -> 0 windows at the sweep's teeth; int k; ``"all"`` -> None."""
    if teeth == "all":
        return None
    if teeth == "sweep":
        return 0
    if isinstance(teeth, int | np.integer) and not isinstance(teeth, bool) \
            and 0 <= teeth and 2 * teeth + 1 < N:
        return int(teeth)
    raise ValueError(f"teeth = {teeth!r}: must be 'sweep', 'all' or a half window k from 0 "
                     f"to {(N - 2) // 2} (sectors of 2k + 1 teeth)")


def _tooth_of(points: NDArray, N: int) -> NDArray[np.int64]:
    """Relative tooth (space) index nearest to the polar angle of window-frame points."""
    ang = np.arctan2(points[..., 1], points[..., 0])
    return np.rint(ang / (2.0 * math.pi / N)).astype(np.int64)


def _flank_of(points_hub: NDArray, rel: NDArray, N: int) -> list[str]:
    """Hub flank from polar angle offsets of hub-frame points to their tooth centre."""
    ang = np.arctan2(points_hub[..., 1], points_hub[..., 0]) - 2.0 * math.pi * rel / N
    ang = np.remainder(ang + math.pi, 2.0 * math.pi) - math.pi
    return [FLANKS[int(a > 0)] for a in np.atleast_1d(ang)]


@dataclass
class _PoseAcc:
    """What one rotation gathers over its windows."""

    gap: float = math.inf
    pair: tuple = ()
    depth: float = 0.0
    deep: tuple = ()
    pieces: list = field(default_factory=list)


def _boolean_pieces(model: Model, A: NDArray, N: int):
    """Overlap pieces of one window: (rel tooth, flank, volume, depth, centroid, deep pair)."""
    import trimesh

    inter = model.hub.posed_manifold(A) ^ model.sleeve.manifold
    if not inter.volume() > MIN_VOLUME_MM3:
        return []
    out = []
    for piece in inter.decompose():
        vol = piece.volume()
        if not vol > MIN_VOLUME_MM3:
            continue
        mesh = piece.to_mesh()
        v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
        tm = trimesh.Trimesh(v, np.asarray(mesh.tri_verts, dtype=np.int64), process=False)
        centroid = np.asarray(tm.center_mass, dtype=float)
        d, foot = dist.surface_distance(v, model.sleeve)
        k = int(np.argmax(d))
        rel = int(_tooth_of(centroid, N))
        flank = _flank_of(centroid @ A, np.array(rel), N)[0]
        out.append((rel, flank, float(vol), float(d[k]), centroid, (v[k], foot[k])))
    return _merge(out)


def _distance_pieces(model: Model, A: NDArray, N: int):
    """Overlap pieces of one window from signed distances of the posed hub shell."""
    if not dist.collide(model.hub, A, model.sleeve):
        return []
    hub = model.hub
    faces = hub.faces[hub.shell]
    used, local = np.unique(faces, return_inverse=True)
    local = local.reshape(faces.shape)
    pts = hub.vertices[used] @ A.T
    depth, foot = dist.penetration(pts, model.sleeve)
    if not np.any(depth > 0):
        return []
    vol = dist.positive_integral(pts, local, depth)  # per face
    hot = vol > 0
    centres = pts[local[hot]].mean(axis=1)
    rel = _tooth_of(centres, N)
    flank = np.array(_flank_of(hub.vertices[used][local[hot]].mean(axis=1), rel, N))
    out = []
    for r in np.unique(rel):
        for f in FLANKS:
            sel = (rel == r) & (flank == f)
            if not np.any(sel):
                continue
            w = vol[hot][sel]
            ids = np.unique(local[hot][sel])
            k = ids[int(np.argmax(depth[ids]))]
            mid = centres[sel] + 0.5 * (foot[local[hot][sel]].mean(axis=1) - centres[sel])
            out.append((int(r), f, float(np.sum(w)), float(depth[k]),
                        (w @ mid) / np.sum(w), (pts[k], foot[k])))
    return out


def _merge(pieces):
    """One piece per (tooth, flank): volumes add, depth is the largest, centroid weighted."""
    groups: dict[tuple[int, str], list] = {}
    for p in pieces:
        groups.setdefault((p[0], p[1]), []).append(p)
    out = []
    for (rel, flank), ps in groups.items():
        vol = sum(p[2] for p in ps)
        deepest = max(ps, key=lambda p: p[3])
        centroid = sum(p[2] * np.asarray(p[4]) for p in ps) / vol
        out.append((rel, flank, vol, deepest[3], centroid, deepest[5]))
    return out


_PIECES = {"boolean": _boolean_pieces, "distance": _distance_pieces}


def check_interference(spec, misalignment_deg: float, angles_deg: ArrayLike, *,
                       method: str = "boolean", tolerance_mm: float | None = None,
                       teeth: int | str = "sweep", margin_mm: float | None = None,
                       hub_rotation_deg: float = 0.0, model: Model | None = None,
                       progress: Callable[[int], None] | None = None) -> InterferenceResult:
    """Overlap volume, teeth, centroid, depth and minimum gap of the posed meshes per angle.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
        Misalignment ``i`` (degrees, 0-6).
    angles_deg : (M,) float
        Rotations ``psi`` of the coupling (degrees).
    method : {"boolean", "distance"}
        Overlap by manifold3d intersection (exact volumes) or by signed distances (fast,
        estimated volumes). The gap is measured the same way by both.
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (default module / 200). Mesh gaps differ from the
        exact clearance by less than this; finer costs triangles (see the README table).
    teeth : "sweep", int or "all"
        ``"sweep"``: single tooth pairs at the teeth the sweep finds within ``margin_mm``
        of each pose's smallest clearance (or below ``2 * tolerance_mm``); ``k``: windows
        of ``2k + 1`` teeth there; ``"all"``: the full parts at every pose.
    margin_mm : float, optional
        Selection margin of the sector submodels (default ``tolerance_mm``: the mesh gap
        differs from the exact clearance by less than the tolerance, measured, so a tooth
        further than that above the smallest cannot hold the mesh minimum).
    hub_rotation_deg : float
        Extra turn of the hub about its own axis (degrees, positive toward increasing
        polar angle: it closes the ccw flanks).
    model : Model, optional
        A prepared model from :func:`~.submodel.build_model` to reuse (it must match
        ``tolerance_mm`` and ``teeth``).
    progress : callable, optional
        Called with the angle index after each pose.

    Returns
    -------
    InterferenceResult
    """
    from ..parts import SURFACE_KINDS, check_tolerance
    from ..sweep import sweep
    from ..sweep.tooth_map import check_angles, check_misalignment

    method = _check_method(method)
    mis = check_misalignment(misalignment_deg)
    psi = np.radians(check_angles(angles_deg))
    tol = check_tolerance(spec, tolerance_mm)
    try:
        delta_deg = float(hub_rotation_deg)
    except (TypeError, ValueError) as err:
        raise SpecError("hub_rotation_deg", hub_rotation_deg, "must be a number") from err
    pitch_deg = 360.0 / spec.tooth.teeth
    if not (math.isfinite(delta_deg) and abs(delta_deg) < 0.5 * pitch_deg):
        raise SpecError("hub_rotation_deg", hub_rotation_deg,
                        f"must be finite and below half a pitch ({0.5 * pitch_deg:.4g}°)")
    delta = math.radians(delta_deg)
    N = spec.tooth.teeth
    k = _check_teeth(teeth, N)
    margin = tol if margin_mm is None else float(margin_mm)
    if not (math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin_mm = {margin_mm!r}: must be a length >= 0 (mm)")

    t0 = time.perf_counter()
    if model is None:
        model = build_model(spec, tol, k)
    elif model.half_window != k or abs(model.hub.tolerance_mm - tol) > 1e-12 * tol:
        raise ValueError(f"the given model ({model.label}, tolerance {model.hub.tolerance_mm}"
                         f" mm) does not match teeth = {teeth!r}, tolerance_mm = {tol}")
    if model.full:
        everything = frozenset(range(N))
        plan = [[(0, everything, everything, everything)] for _ in psi]
    else:
        swept = sweep(spec, misalignment_deg, np.degrees(psi), tolerance_mm=min(1e-4, tol / 10))
        gap_teeth, over_teeth = hot_teeth(flank_clearance(swept, delta), margin, 2.0 * tol)
        plan = []
        for g, o in zip(gap_teeth, over_teeth, strict=True):
            g, o = frozenset(g.tolist()), frozenset(o.tolist())
            plan.append([(c, owned, owned & o, owned & g)
                         for c, owned in windows(sorted(g | o), N, k)])
    _ = model.hub.shell_bvh, model.sleeve.shell_bvh  # built once, before the timing
    if method == "boolean":
        _ = model.hub.manifold, model.sleeve.manifold
    setup = time.perf_counter() - t0

    M = psi.size
    gap = np.zeros(M)
    depth = np.zeros(M)
    volume = np.zeros(M)
    hub_pt, sl_pt = np.zeros((M, 3)), np.zeros((M, 3))
    gap_tooth = np.zeros(M, dtype=np.int64)
    hub_kind, sl_kind = [""] * M, [""] * M
    overlaps: list[Overlap] = []
    poses = []
    pieces_of = _PIECES[method]
    t1 = time.perf_counter()
    for j, p in enumerate(psi):
        acc = _PoseAcc()
        seen: dict[bytes, tuple] = {}  # equal window poses (e.g. at i = 0) evaluated once
        for centre, _, owned, wants_gap in plan[j]:
            A = (hub_pose(mis, p, delta) if model.full
                 else window_pose(mis, p, centre, N, delta))
            key = np.round(A, 13).tobytes() + bytes([bool(owned), bool(wants_gap)])
            if key not in seen:
                pieces = pieces_of(model, A, N) if owned else []
                seen[key] = (pieces, dist.closest_pair(model.hub, A, model.sleeve)
                             if wants_gap and not pieces else None)
            pieces, c = seen[key]
            for rel, flank, vol, dep, cen, deep in pieces:
                tooth = (rel + centre) % N
                if tooth not in owned:
                    continue
                acc.pieces.append(Overlap(j, float(np.degrees(p)), tooth, flank, vol, dep,
                                          tuple(float(x) for x in
                                                window_to_sleeve(cen, centre, N))))
                if dep > acc.depth:
                    acc.depth = dep
                    acc.deep = (window_to_sleeve(deep[0], centre, N),
                                window_to_sleeve(deep[1], centre, N), tooth,
                                f"flank_{flank}", "overlap")
            if c is not None and c.distance_mm < acc.gap:
                t_rel = int(model.hub.tooth[c.hub_face])
                t_rel = t_rel - N if t_rel > N // 2 else t_rel
                acc.gap = c.distance_mm
                acc.pair = (window_to_sleeve(c.hub_point, centre, N),
                            window_to_sleeve(c.sleeve_point, centre, N),
                            (t_rel + centre) % N,
                            SURFACE_KINDS[model.hub.kind[c.hub_face]],
                            SURFACE_KINDS[model.sleeve.kind[c.sleeve_face]])
        if acc.pieces:
            overlaps.extend(acc.pieces)
            volume[j] = sum(o.volume_mm3 for o in acc.pieces)
            depth[j] = acc.depth
            gap[j] = -acc.depth
            pair = acc.deep
        else:
            gap[j] = acc.gap
            pair = acc.pair
        hub_pt[j], sl_pt[j], gap_tooth[j], hub_kind[j], sl_kind[j] = pair
        poses.append(tuple(plan[j]))
        if progress is not None:
            progress(j)
    per_pose = (time.perf_counter() - t1) / M
    return InterferenceResult(
        spec_name=spec.name, misalignment_deg=float(misalignment_deg),
        hub_rotation_deg=delta_deg, method=method, model=model.label, tolerance_mm=tol,
        teeth=N, angles_deg=np.degrees(psi), overlap_volume_mm3=volume,
        overlap_depth_mm=depth, min_gap_mm=gap, hub_point_mm=hub_pt, sleeve_point_mm=sl_pt,
        gap_tooth=gap_tooth, gap_hub_surface=tuple(hub_kind),
        gap_sleeve_surface=tuple(sl_kind), overlaps=tuple(overlaps),
        windows=np.array([len(w) for w in plan], dtype=np.int64), triangles=model.triangles,
        volume_exact=method == "boolean", setup_seconds=setup, seconds_per_pose=per_pose,
        prepared=model, poses=tuple(poses))


def posed_meshes(result: InterferenceResult, index: int) -> dict[str, Any]:
    """The posed hub and sleeve meshes of angle ``index`` in the sleeve frame (trimesh).

    For a sector model these are the windows that pose evaluated, each moved to its teeth.
    Returns ``{"hub": Trimesh, "sleeve": Trimesh}`` and ``"overlap"`` when it overlaps
    (``method="boolean"``).
    """
    import trimesh

    model = result.prepared
    if model is None:
        raise ValueError("the result holds no prepared model to pose")
    N = result.teeth
    mis = math.radians(result.misalignment_deg)
    p = math.radians(float(result.angles_deg[index]))
    delta = math.radians(result.hub_rotation_deg)
    hubs, sleeves, pieces = [], [], []
    for centre, *_ in result.poses[index]:
        A = hub_pose(mis, p, delta) if model.full else window_pose(mis, p, centre, N, delta)
        hubs.append(trimesh.Trimesh(window_to_sleeve(model.hub.vertices @ A.T, centre, N),
                                    model.hub.faces, process=False))
        sleeves.append(trimesh.Trimesh(window_to_sleeve(model.sleeve.vertices, centre, N),
                                       model.sleeve.faces, process=False))
        if result.method == "boolean" and result.overlap_volume_mm3[index] > 0:
            mesh = (model.hub.posed_manifold(A) ^ model.sleeve.manifold).to_mesh()
            v = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
            if len(v):
                pieces.append(trimesh.Trimesh(window_to_sleeve(v, centre, N),
                                              np.asarray(mesh.tri_verts, dtype=np.int64),
                                              process=False))
    out = {"hub": trimesh.util.concatenate(hubs), "sleeve": trimesh.util.concatenate(sleeves)}
    if pieces:
        out["overlap"] = trimesh.util.concatenate(pieces)
    return out
