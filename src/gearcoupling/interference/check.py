"""``check_interference``: overlap and minimum gap of the posed part meshes over rotation.

For every rotation ``psi`` the hub mesh is posed in the sleeve frame (docs/conventions.md, Frames)
and
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
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import MAXIMA, angle_list, flag, real
from ..clearance import check_misalignment, sweep
from ..errors import ArgumentError
from ..io import write_text
from ..parts import SURFACE_KINDS, check_tolerance
from ..spec import CouplingSpec, as_spec
from . import distance as dist
from .attribution import FLANKS, flank_index, nearest_tooth
from .posed import hub_pose, window_pose, window_to_sleeve
from .submodel import (
    Model,
    Window,
    build_model,
    hot_teeth,
    plan_pose,
    side_clearance,
    side_teeth,
)

METHODS = ("boolean", "distance")
MIN_VOLUME_MM3 = 1e-9  # overlap pieces below this are numerical dust of the intersection


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
        Hub flank ``"cw"`` or ``"ccw"`` (docs/conventions.md, Frames).
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
    backlash_rad, backlash_mm : (M,) float or None
        With ``backlash=True``: free turn of the hub (cw side + ccw side), as an angle and
        as arc length at the pitch radius; negative where a side binds.
    side_gap_rad : (2, M) float or None
        The free turn toward each side ``(cw, ccw)``.
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
    backlash_rad: NDArray[np.float64] | None = None
    backlash_mm: NDArray[np.float64] | None = None
    side_gap_rad: NDArray[np.float64] | None = None
    prepared: Model | None = field(default=None, repr=False)
    poses: tuple = field(default=(), repr=False)

    def __getstate__(self) -> dict[str, Any]:
        """Pickled without the prepared model (its manifold3d solids do not pickle): an
        unpickled result has every array but cannot be posed again (:func:`posed_meshes`)."""
        state = {f.name: getattr(self, f.name) for f in fields(self)}
        state["prepared"], state["poses"] = None, ()
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        for key, value in state.items():
            object.__setattr__(self, key, value)

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

    def write_csv(self, path):
        """Write :meth:`rows` as CSV atomically (points split into x/y/z columns)."""
        import csv
        import io


        rows = self.rows()
        buf = io.StringIO()
        fields = [k for k in rows[0] if not k.endswith("point_mm")] + [
            "hub_x_mm", "hub_y_mm", "hub_z_mm", "sleeve_x_mm", "sleeve_y_mm", "sleeve_z_mm"]
        w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
        w.writeheader()
        for row in rows:
            hub, sl = row.pop("hub_point_mm"), row.pop("sleeve_point_mm")
            row.update(zip(fields[-6:], [*hub, *sl], strict=True))
            w.writerow({k: (f"{v:.9g}" if isinstance(v, float) else v) for k, v in row.items()})
        return write_text(path, buf.getvalue())

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
            if self.backlash_mm is not None:
                out[-1]["backlash_mm"] = float(self.backlash_mm[j])
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
            "min_backlash_mm": (None if self.backlash_mm is None
                                else float(np.min(self.backlash_mm))),
            "overlaps": [
                {"angle_deg": o.angle_deg, "tooth": o.tooth, "flank": o.flank,
                 "volume_mm3": o.volume_mm3, "depth_mm": o.depth_mm,
                 "centroid_mm": list(o.centroid_mm)} for o in self.overlaps],
        }


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise ArgumentError("method", method, f"one of {METHODS}")
    return method


def _check_teeth(teeth, N: int) -> int | None:
    """``"sweep"`` -> 0 windows at the sweep's teeth; int k; ``"all"`` -> None."""
    if teeth == "all":
        return None
    if teeth == "sweep":
        return 0
    if isinstance(teeth, int | np.integer) and not isinstance(teeth, bool) \
            and 0 <= teeth and 2 * teeth + 1 < N:
        return int(teeth)
    raise ArgumentError("teeth", teeth, f"'sweep', 'all' or a half window k from 0 to "
                        f"{(N - 2) // 2} (sectors of 2k + 1 teeth)")


@dataclass
class _PoseAcc:
    """What one rotation gathers over its windows."""

    gap: float = math.inf
    pair: tuple = ()
    depth: float = 0.0
    deep: tuple = ()
    pieces: list = field(default_factory=list)
    side: list = field(default_factory=lambda: [math.inf, math.inf])  # -depth angles
    side_free: list = field(default_factory=lambda: [math.inf, math.inf])  # gap angles
    side_hit: list = field(default_factory=lambda: [False, False])
    side_cands: list = field(default_factory=lambda: [[], []])  # (estimate, id, A, rate)


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
        rel = int(nearest_tooth(centroid, N))
        flank = FLANKS[int(flank_index(centroid @ A, rel, N))]
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
    rel = nearest_tooth(centres, N)
    flank = np.array(FLANKS)[flank_index(hub.vertices[used][local[hot]].mean(axis=1), rel, N)]
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


def check_interference(spec: CouplingSpec, misalignment_deg: float, angles_deg: ArrayLike, *,
                       method: str = "boolean", tolerance_mm: float | None = None,
                       teeth: int | str = "sweep", margin_mm: float | None = None,
                       hub_rotation_deg: float = 0.0, backlash: bool = False,
                       model: Model | None = None,
                       progress: Callable[[int, int], None] | None = None) -> InterferenceResult:
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
        exact clearance by less than this; finer costs triangles (docs/interference.md).
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
    backlash : bool
        Also measure the free turn of the hub toward each flank side on the meshes: turn
        the posed hub about its own axis until that side's flank, fillet and chamfer
        surfaces touch the sleeve (Newton steps on the closest distance, bisection on
        overshoot, to 1e-3 tolerance at the pitch radius; where a side already overlaps,
        minus its depth over ``r_b`` times the turning rate), summed over the
        sides:
        ``backlash_rad`` / ``backlash_mm`` at the pitch radius (docs/conventions.md, Frames).
        Costs two
        distance queries per window plus a few per side for the refinement.
    model : Model, optional
        A prepared model from :func:`~.submodel.build_model` to reuse (it must match
        ``tolerance_mm`` and ``teeth``).
    progress : callable, optional
        ``progress(done, total)`` after each pose.

    Returns
    -------
    InterferenceResult
    """
    spec = as_spec(spec)
    method = _check_method(method)
    mis = check_misalignment(misalignment_deg)
    psi = np.radians(angle_list(angles_deg, "angles_deg", most=MAXIMA["poses"]))
    tol = check_tolerance(spec, tolerance_mm)
    delta_deg = real(hub_rotation_deg, "hub_rotation_deg", unit="degrees")
    flag(backlash, "backlash")
    pitch_deg = 360.0 / spec.tooth.teeth
    if not (math.isfinite(delta_deg) and abs(delta_deg) < 0.5 * pitch_deg):
        raise ArgumentError("hub_rotation_deg", hub_rotation_deg,
                        f"must be finite and below half a pitch ({0.5 * pitch_deg:.4g}°)")
    delta = math.radians(delta_deg)
    N = spec.tooth.teeth
    k = _check_teeth(teeth, N)
    margin = tol if margin_mm is None else real(margin_mm, "margin_mm", 0.0, unit="mm")

    t0 = time.perf_counter()
    model = _prepared_model(spec, model, tol, k, teeth)
    if k is None:  # model.full
        plan = _full_plan(N, psi.size, backlash)
    else:
        plan = _sector_plan(spec, misalignment_deg, psi, delta, tol, k, margin, backlash)
    _build_trees(model, method, backlash)
    setup = time.perf_counter() - t0

    M = psi.size
    t1 = time.perf_counter()
    out, overlaps = _run_poses(spec, model, plan, mis, psi, delta, method, backlash, tol,
                               progress)
    per_pose = (time.perf_counter() - t1) / M
    R = spec.tooth.pitch_radius
    return InterferenceResult(
        spec_name=spec.name, misalignment_deg=float(misalignment_deg),
        hub_rotation_deg=delta_deg, method=method, model=model.label, tolerance_mm=tol,
        teeth=N, angles_deg=np.degrees(psi), overlap_volume_mm3=out.volume,
        overlap_depth_mm=out.depth, min_gap_mm=out.gap, hub_point_mm=out.hub_pt,
        sleeve_point_mm=out.sl_pt, gap_tooth=out.gap_tooth,
        gap_hub_surface=tuple(out.hub_kind), gap_sleeve_surface=tuple(out.sl_kind),
        overlaps=tuple(overlaps),
        windows=np.array([len(w) for w in plan], dtype=np.int64), triangles=model.triangles,
        volume_exact=method == "boolean", setup_seconds=setup, seconds_per_pose=per_pose,
        backlash_rad=np.sum(out.side_angle, axis=0) if backlash else None,
        backlash_mm=R * np.sum(out.side_angle, axis=0) if backlash else None,
        side_gap_rad=out.side_angle if backlash else None,
        prepared=model, poses=tuple(tuple(windows) for windows in plan))


def _prepared_model(spec: CouplingSpec, model: Model | None, tol: float, k: int | None,
                    teeth: int | str) -> Model:
    """``model`` if it was built for ``k`` and ``tol`` (else an :class:`ArgumentError`
    quoting ``teeth``), or a new one."""
    if model is None:
        return build_model(spec, tol, k)
    if model.half_window != k or abs(model.hub.tolerance_mm - tol) > 1e-12 * tol:
        raise ArgumentError("model", f"{model.label}, tolerance {model.hub.tolerance_mm} mm",
                            f"does not match teeth = {teeth!r}, tolerance_mm = {tol}: give "
                            "a model built for them")
    return model


def _full_plan(N: int, M: int, backlash: bool) -> list[list[Window]]:
    """One window of all ``N`` teeth for each of the ``M`` poses (the full parts)."""
    every = frozenset(range(N))
    sides = (every, every) if backlash else (frozenset(), frozenset())
    return [[Window(0, every, every, sides)] for _ in range(M)]


def _sector_plan(spec: CouplingSpec, misalignment_deg: float, psi: NDArray, delta: float,
                 tol: float, k: int, margin: float, backlash: bool) -> list[list[Window]]:
    """Windows of ``2k + 1`` teeth per pose ``psi`` (radians) at the teeth the sweep finds
    within ``margin`` of the smallest clearance (or below ``2 tol``), and at each side's
    teeth with ``backlash``."""
    N = spec.tooth.teeth
    swept = sweep(spec, misalignment_deg, np.degrees(psi), tolerance_mm=min(1e-4, tol / 10))
    per_side = side_clearance(swept, delta)
    gap_teeth, over_teeth = hot_teeth(np.min(per_side, axis=0), margin, 2.0 * tol)
    side_sets = side_teeth(per_side, margin) if backlash else [((), ())] * psi.size
    return [plan_pose(N, k, o, g, sd)
            for g, o, sd in zip(gap_teeth, over_teeth, side_sets, strict=True)]


def _build_trees(model: Model, method: str, backlash: bool) -> None:
    """Build the model's bounding-volume trees (and manifolds for ``"boolean"``) once,
    before the per-pose timing."""
    _ = model.hub.shell_bvh, model.sleeve.shell_bvh
    if backlash:
        _ = [part.side_bvh(f) for part in (model.hub, model.sleeve) for f in FLANKS]
    if method == "boolean":
        _ = model.hub.manifold, model.sleeve.manifold


def _run_poses(spec: CouplingSpec, model: Model, plan: list[list[Window]], mis: float,
               psi: NDArray, delta: float, method: str, backlash: bool, tol: float,
               progress: Callable[[int, int], None] | None) -> tuple[_Arrays, list[Overlap]]:
    """Evaluate every pose ``psi`` (radians) over its windows of ``plan``: the per-angle
    arrays and every overlap piece (the backlash refined to ``1e-3 tol`` at the pitch
    radius)."""
    N, r_b = spec.tooth.teeth, spec.tooth.base_radius
    pieces_of = _PIECES[method]
    M = psi.size
    out = _Arrays(M)
    overlaps: list[Overlap] = []
    seen: dict[bytes, _WindowResult] = {}  # every pose's windows, by their exact pose
    for j, p in enumerate(psi):
        acc = _pose(model, plan[j], mis, p, delta, j, N, r_b, pieces_of, seen)
        if backlash:
            _refine_sides(acc, model, 1e-3 * tol / spec.tooth.pitch_radius)
        overlaps.extend(acc.pieces)
        out.store(j, acc)
        if progress is not None:
            progress(j + 1, M)
    return out, overlaps


def _pose(model: Model, windows: list[Window], mis: float, p: float, delta: float, j: int,
          N: int, r_b: float, pieces_of: Callable,
          seen: dict[bytes, _WindowResult]) -> _PoseAcc:
    """Gather one rotation ``p`` (radians, index ``j``) over its windows; windows with the
    same pose (to 1e-13) and the same queries are evaluated once (e.g. all teeth at i = 0).
    ``seen`` holds the windows of earlier rotations by their exact pose and queries: a
    tooth at the turning angle another tooth had before (renzo-1967 at 72 rotations: one
    window in six) takes that result, the one it would compute."""
    acc = _PoseAcc()
    here: dict[bytes, _WindowResult] = {}
    for w in windows:
        A = hub_pose(mis, p, delta) if model.full else window_pose(mis, p, w.centre, N,
                                                                     delta)
        queries = bytes([bool(w.overlap), bool(w.gap), bool(w.sides[0]), bool(w.sides[1])])
        key = np.round(A, 13).tobytes() + queries
        if key not in here:
            exact = A.tobytes() + queries
            if exact not in seen:
                seen[exact] = _evaluate(model, A, N, w, pieces_of)
            here[key] = seen[exact]
        _collect(acc, here[key], w, A, j, float(np.degrees(p)), N, r_b, model)
    return acc


@dataclass
class _WindowResult:
    pieces: list
    closest: dist.Closest | None
    sides: list  # per flank: Closest or None


def _evaluate(model: Model, A: NDArray, N: int, w: Window, pieces_of) -> _WindowResult:
    pieces = pieces_of(model, A, N) if w.overlap else []
    closest = dist.closest_pair(model.hub, A, model.sleeve) if w.gap and not pieces else None
    hit = {f for _, f, *_ in pieces}
    sides = [dist.closest_pair(model.hub, A, model.sleeve, f)
             if w.sides[i] and f not in hit else None for i, f in enumerate(FLANKS)]
    return _WindowResult(pieces, closest, sides)


def _collect(acc: _PoseAcc, ev: _WindowResult, w: Window, A: NDArray, j: int, angle: float,
             N: int, r_b: float, model: Model) -> None:
    """Add one window's findings to the pose, in sleeve-frame coordinates and real teeth."""
    c = w.centre
    for rel, flank, vol, dep, cen, deep in ev.pieces:
        tooth = (rel + c) % N
        if tooth not in w.overlap:
            continue
        x, y, z = window_to_sleeve(cen, c, N)
        acc.pieces.append(Overlap(j, angle, tooth, flank, vol, dep,
                                  (float(x), float(y), float(z))))
        f = FLANKS.index(flank)
        acc.side[f] = min(acc.side[f], -dep / (r_b * abs(dist.turning_rate(A, deep[0]))))
        if dep > acc.depth:
            acc.depth = dep
            acc.deep = (window_to_sleeve(deep[0], c, N), window_to_sleeve(deep[1], c, N),
                        tooth, f"flank_{flank}", "overlap")
    if ev.closest is not None and ev.closest.distance_mm < acc.gap:
        cl = ev.closest
        t_rel = int(model.hub.tooth[cl.hub_face])
        t_rel = t_rel - N if t_rel > N // 2 else t_rel
        acc.gap = cl.distance_mm
        acc.pair = (window_to_sleeve(cl.hub_point, c, N), window_to_sleeve(cl.sleeve_point, c, N),
                    (t_rel + c) % N, SURFACE_KINDS[model.hub.kind[cl.hub_face]],
                    SURFACE_KINDS[model.sleeve.kind[cl.sleeve_face]])
    for f, cl in enumerate(ev.sides):
        if cl is not None:
            sign = 1.0 if FLANKS[f] == "ccw" else -1.0
            fallback = r_b * abs(dist.turning_rate(A, cl.hub_point))
            acc.side_cands[f].append((cl.distance_mm / dist.closing_speed(A, cl, sign, fallback),
                                      id(A), A, fallback))
    for p in acc.pieces:
        acc.side_hit[FLANKS.index(p.flank)] = True


def _refine_sides(acc: _PoseAcc, model: Model, tol_angle: float) -> None:
    """Free turn per side: refine the window with the smallest first-order estimate by
    distance queries, then any other whose estimate is still below the refined value."""
    for f, flank in enumerate(FLANKS):
        if acc.side_hit[f]:
            continue
        best = math.inf
        for estimate, _, A, fallback in sorted(acc.side_cands[f], key=lambda c: c[0]):
            if estimate >= best:
                break
            best = min(best, dist.free_turn(model.hub, A, model.sleeve, flank, fallback,
                                            tol_angle))
        acc.side_free[f] = best


class _Arrays:
    """Per-angle output arrays."""

    def __init__(self, M: int):
        self.gap, self.depth, self.volume = np.zeros(M), np.zeros(M), np.zeros(M)
        self.hub_pt, self.sl_pt = np.zeros((M, 3)), np.zeros((M, 3))
        self.gap_tooth = np.zeros(M, dtype=np.int64)
        self.hub_kind, self.sl_kind = [""] * M, [""] * M
        self.side_angle = np.zeros((2, M))

    def store(self, j: int, acc: _PoseAcc) -> None:
        if acc.pieces:
            self.volume[j] = sum(o.volume_mm3 for o in acc.pieces)
            self.depth[j] = acc.depth
            self.gap[j] = -acc.depth
            pair = acc.deep
        else:
            self.gap[j] = acc.gap
            pair = acc.pair
        self.hub_pt[j], self.sl_pt[j], self.gap_tooth[j], self.hub_kind[j], self.sl_kind[j] = pair
        for f in range(2):  # an overlapping side binds: its (negative) depth angle counts
            self.side_angle[f, j] = acc.side[f] if acc.side_hit[f] else acc.side_free[f]


def posed_meshes(result: InterferenceResult, index: int) -> dict[str, Any]:
    """The posed hub and sleeve meshes of angle ``index`` in the sleeve frame (trimesh).

    For a sector model these are the windows that pose evaluated, each moved to its teeth.
    Returns ``{"hub": Trimesh, "sleeve": Trimesh}`` and ``"overlap"`` when it overlaps
    (``method="boolean"``).
    """
    import trimesh

    model = result.prepared
    if model is None:
        raise ArgumentError("result", "no prepared model", "a result of check_interference "
                            "that holds its prepared model to pose")
    N = result.teeth
    mis = math.radians(result.misalignment_deg)
    p = math.radians(float(result.angles_deg[index]))
    delta = math.radians(result.hub_rotation_deg)
    hubs, sleeves, pieces = [], [], []
    for centre in (w.centre for w in result.poses[index]):
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
