"""Quadratic tetrahedral meshes of hub and sleeve sectors, by gmsh from the STEP solids.

The exact OpenCASCADE solid of a sector (:func:`gearcoupling.parts.part_solid`) is
written to a temporary STEP file and imported into gmsh. Every B-rep face is then named by
geometry: the nodes of a coarse surface mesh of the face vote for the surface kind and
tooth of the nearest point of the labelled triangle mesh of the same sector
(:func:`gearcoupling.parts.build_part`, its ``kind`` and ``tooth`` face attributes). The
teeth get the element size ``size_mm``; the size grows to ``body_size_mm`` away from them.
"""

from __future__ import annotations

import math
import numbers
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..arguments import choice, flag, is_real
from ..errors import ArgumentError, GeometryError
from ..export import write_step
from ..parts import SURFACE_KINDS, build_part, check_tolerance, part_solid
from ..spec import CouplingSpec, as_spec
from .backends import gmsh_session
from .volume import VolumeMesh, aspect_ratios, match_faces, tet_volumes

TOOTH_KINDS = ("flank_cw", "flank_ccw", "fillet_cw", "fillet_ccw", "root", "tip",
               "chamfer_cw", "chamfer_ccw")
DEFAULT_SECTOR_TEETH = 3
ALGORITHMS = {"delaunay": (1, 2), "hxt": (10, 1)}
"""gmsh ``Mesh.Algorithm3D`` and ``Mesh.HighOrderOptimize`` (untangling of the curved
quadratic elements: 2 elastic + optimisation, 1 optimisation of invalid ones) per name."""


@dataclass(frozen=True)
class LoadedTooth:
    """Element sizes for load cases on the middle tooth of a sector (:func:`loaded_faces`).

    Within ``zone_mm`` of that tooth's flanks and fillets the size is :func:`mesh_part`'s
    ``size_mm``; it grows to ``far_size_mm`` on the other teeth over as much again. The
    loaded flank (the first of :func:`loaded_faces`) gets ``flank_size_mm`` between
    ``z_mm[0]`` and ``z_mm[1]``, growing to ``size_mm`` over twice the difference, so a
    pressure patch of a few ``size_mm`` is resolved without a fine tooth.
    """

    far_size_mm: float
    flank_size_mm: float
    z_mm: tuple[float, float]
    zone_mm: float


def default_size(spec: CouplingSpec) -> float:
    """Default element size on the teeth: module / 4 (0.5 mm for industrial-m2), in mm."""
    return spec.tooth.module / 4.0


def fillet_radius(spec: CouplingSpec, part: str) -> float:
    """Root fillet radius of a part (mm)."""
    return spec.hub.root.fillet_radius if part == "hub" else spec.sleeve.root_fillet_radius


def size_range(spec: CouplingSpec) -> tuple[float, float]:
    """Smallest and largest element size on the teeth (mm): module / 40 and module / 2
    (two elements across the tooth at least)."""
    m = spec.tooth.module
    return m / 40.0, m / 2.0


def fillet_size(spec: CouplingSpec, part: str, size: float) -> float:
    """Element size on a part's root fillets: ``size``, or twice the fillet radius where
    that is smaller (a coarser mesh cannot follow the fillet, where the root stress is), but
    not below module / 40."""
    rho = fillet_radius(spec, part)
    return size if rho <= 0 else min(size, max(size_range(spec)[0], 2.0 * rho))


def fillet_notes(spec: CouplingSpec, size_mm: float | None,
                 parts=("hub", "sleeve")) -> list[str]:
    """One line per part whose root fillets are meshed finer than the teeth (for the
    commands to say so)."""
    size = check_size(spec, "hub", size_mm)
    notes = []
    for part in parts:
        fs = fillet_size(spec, part, size)
        if fs < size:
            notes.append(f"the {part} root fillets (radius {fillet_radius(spec, part):.3g} mm) "
                         f"are meshed at {fs:.3g} mm, the teeth at {size:.3g} mm")
    return notes


def check_size(spec: CouplingSpec, part: str, size_mm, field: str = "size_mm") -> float:
    """The element size on the teeth as a float, or :class:`ArgumentError` naming the
    allowed range, module / 40 to module / 2 (:func:`size_range`). The root fillets follow
    at :func:`fillet_size`."""
    size = default_size(spec) if size_mm is None else size_mm
    if not is_real(size):
        raise ArgumentError(field, size_mm, "must be a number (mm)")
    size = float(size)
    lo, hi = size_range(spec)
    if not (math.isfinite(size) and lo <= size <= hi):
        hint = "choose a larger size" if size < lo else "choose a smaller size"
        raise ArgumentError(field, size_mm, f"must be from {lo:.3g} to {hi:.3g} mm for the "
                            f"{part} of this spec (module / 40 to module / 2: two elements "
                            f"across the tooth at least); {hint}")
    return size


def sector_teeth(spec: CouplingSpec, count) -> list[int] | None:
    """Teeth ``0 .. count - 1`` of a sector, ``None`` for the whole part (count = N or None),
    or :class:`SpecError` when the count does not fit the teeth."""
    n = spec.tooth.teeth
    if count is None:
        return None
    if isinstance(count, bool) or not isinstance(count, numbers.Integral):
        raise ArgumentError("sector", count, f"an integer from 1 to {n}")
    k = int(count)
    if not 1 <= k <= n:
        raise ArgumentError("sector_teeth", count, f"an integer from 1 to {n} (the spec has {n} "
                        f"teeth; {n} meshes the whole part)")
    return None if k == n else list(range(k))


def mesh_part(spec: CouplingSpec, part: str, *, sector: int | None = DEFAULT_SECTOR_TEETH,
              size_mm: float | None = None, body_size_mm: float | None = None,
              tolerance_mm: float | None = None, order: int = 2,
              periodic: bool = False, contact: tuple[float, float] | None = None,
              loaded: LoadedTooth | None = None, algorithm: str = "delaunay",
              axial: tuple[float, float] | None = None) -> VolumeMesh:
    """Quadratic tetrahedral mesh of a sector of ``sector`` teeth (``None``: the whole part).

    Parameters
    ----------
    spec : CouplingSpec
    part : {"hub", "sleeve"}
    sector : int or None
        Teeth ``0 .. sector - 1``; the cut planes pass through the middle of the spaces
        (hub) or teeth (sleeve) beside them. ``None`` or N: the whole part.
    size_mm : float, optional
        Element size on the teeth (:func:`check_size`; default module / 4).
    body_size_mm : float, optional
        Element size far from the teeth (default ``max(3 size, module)``).
    tolerance_mm : float, optional
        Chordal tolerance of the STEP solid (default module / 200).
    order : {1, 2}
        Element order (2: C3D10; 1 only for tests of the pipeline).
    periodic : bool
        Mesh the ccw cut face as the cw cut face turned by the sector angle, node for
        node, so the cuts can be joined by cyclic-symmetry equations.
    contact : (size_mm, half_length_mm), optional
        A finer size on the ccw flanks within ``half_length_mm`` of mid-face, where an
        aligned coupling's contact patch lies (growing at half the distance beyond).
    loaded : LoadedTooth, optional
        Sizes for load cases on the middle tooth: fine at its loaded flank, coarser on the
        other teeth (default: ``size_mm`` on every tooth).
    axial : (half_length_mm, far_size_mm), optional
        ``size_mm`` only within ``half_length_mm`` of mid-face; beyond, the teeth grow to
        ``far_size_mm`` over the difference of the sizes (a contact patch near mid-face).
    algorithm : {"delaunay", "hxt"}
        gmsh's 3-D mesher: ``"delaunay"`` with elastic and optimising curving of the
        quadratic elements, or ``"hxt"`` with optimising curving of invalid elements only
        (less CPU on the 3-tooth sectors of the templates, similar quality).

    Returns
    -------
    VolumeMesh
    """
    spec = as_spec(spec)
    choice(part, "part", ("hub", "sleeve"))
    choice(algorithm, "algorithm", tuple(ALGORITHMS))
    flag(periodic, "periodic")
    teeth = sector_teeth(spec, sector)
    size = check_size(spec, part, size_mm)
    body = max(3.0 * size, spec.tooth.module) if body_size_mm is None else float(body_size_mm)
    if not (math.isfinite(body) and body >= size):
        raise ArgumentError("body_size_mm", body_size_mm, f"a size (mm) of at least {size:.3g}")
    if loaded is not None and not (0 < loaded.flank_size_mm <= size <= loaded.far_size_mm
                                   <= body):
        raise ArgumentError("loaded", loaded, f"flank size <= {size:.3g} mm <= far size <= "
                            f"body size {body:.3g} mm")
    tol = check_tolerance(spec, tolerance_mm)
    t0 = time.perf_counter()
    labelled = build_part(spec, part, tolerance_mm=tol, teeth=teeth)
    shape = part_solid(spec, part, tol, teeth)
    with tempfile.TemporaryDirectory(prefix="gearcoupling-fea-") as tmp:
        step = write_step(shape, Path(tmp) / f"{part}.step", name=f"{spec.name}-{part}")
        t_cad = time.perf_counter() - t0
        with gmsh_session() as gmsh:
            gmsh.option.setNumber("Mesh.Algorithm3D", ALGORITHMS[algorithm][0])
            gmsh.option.setNumber("Mesh.HighOrderOptimize", ALGORITHMS[algorithm][1])
            vm = _mesh_in_gmsh(gmsh, spec, part, step, labelled, teeth, size, body, order,
                               periodic, contact, loaded, axial)
    vm.quality["cad_seconds"] = t_cad
    vm.quality["algorithm"] = algorithm
    vm.quality["fillet_size_mm"] = fillet_size(spec, part, size)
    if loaded is not None:
        vm.quality["loaded_tooth"] = asdict(loaded)
    return vm


def _mesh_in_gmsh(gmsh, spec: CouplingSpec,
                  part, step, labelled, teeth, size, body, order, periodic,
                  contact, loaded=None, axial=None) -> VolumeMesh:
    occ = gmsh.model.occ
    vols = occ.importShapes(str(step))
    occ.synchronize()
    if [d for d, _ in vols] != [3]:
        raise GeometryError(f"the {part} STEP gave {len(vols)} entities, expected one solid")
    surfaces = [t for _, t in gmsh.model.getEntities(2)]
    gmsh.option.setNumber("Mesh.MeshSizeMax", body)
    gmsh.option.setNumber("Mesh.MeshSizeMin", size / 4.0)
    t0 = time.perf_counter()
    gmsh.model.mesh.generate(2)  # coarse surface mesh, only to sample every face
    names = classify_surfaces(gmsh, spec, part, labelled, surfaces)
    fillets = [s for s in surfaces if "_FILLET_" in names[s][0]]
    fillet_r = _radius_range(gmsh, fillets)
    gmsh.model.mesh.clear()
    teeth_faces = [s for s in surfaces if names[s][0].startswith("T")]
    flanks = [s for s in surfaces if names[s][0].endswith("_FLANK_CCW")]
    f = gmsh.model.mesh.field
    top = _size_field(f, teeth_faces, size, body, spec.tooth.module, flanks, contact)
    if loaded is not None:
        regions = loaded_faces(part, teeth)
        top = _loaded_size_field(f, top, [s for s in surfaces if names[s][0] in regions],
                                 [s for s in surfaces if names[s][0] == regions[0]], size,
                                 body, loaded)
    if axial is not None:
        top = _axial_size_field(f, top, size, *axial)
    coarsest = max(size, 0.0 if loaded is None else loaded.far_size_mm,
                   0.0 if axial is None else axial[1])  # on any tooth
    fs = fillet_size(spec, part, coarsest)
    if fs < coarsest and fillet_r is not None:  # follow a small fillet, last
        near = (_radial_band(f, fs, *fillet_r) if periodic and teeth is not None
                else _threshold(f, fillets, fs, body, 0.0, 2.0 * (body - fs)))
        top = _min_field(f, [top, near])
    f.setAsBackgroundMesh(top)
    for key in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{key}", 0)
    if periodic and teeth is not None:
        _periodic_cuts(gmsh, names, 2 * math.pi * len(teeth) / spec.tooth.teeth)
    gmsh.option.setNumber("Mesh.ElementOrder", order)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    gmsh.option.setNumber("Mesh.Optimize", 1)
    _generate_volume(gmsh)
    t_mesh = time.perf_counter() - t0
    return extract_mesh(gmsh, part, names, teeth, size, order, t_mesh)


HO_GAVE_UP = ("Failed to reach critical value", "Failed to reach target",
              "Optimization failed", "Optimization partially failed")
"""gmsh's high-order optimiser's errors when it cannot untangle a curved element: it then
keeps the elements it has, which :func:`extract_mesh` checks."""


def _generate_volume(gmsh) -> None:
    """``generate(3)`` with gmsh's errors reported, not thrown: the high-order optimiser
    throws from a parallel region, where the throw ends the process (std::terminate). Its
    own error is left to the element check; any other error is raised."""
    gmsh.option.setNumber("General.AbortOnError", 1)
    gmsh.logger.start()
    try:
        gmsh.model.mesh.generate(3)
        errors = [m for m in gmsh.logger.get()
                  if m.startswith("Error") and not any(h in m for h in HO_GAVE_UP)]
    finally:
        gmsh.logger.stop()
        gmsh.option.setNumber("General.AbortOnError", 2)
    if errors:
        raise GeometryError(f"gmsh could not mesh the volume: {errors[0]}")


def _size_field(f, faces, size, body, module, flanks=(), contact=None) -> int:
    """The teeth's size field: ``size`` within a quarter module of the tooth ``faces``,
    growing to ``body``; with ``contact = (size, half_length)`` finer on the ``flanks``
    near mid-face."""
    fields = [_threshold(f, faces, size, body, 0.25 * module, 2.0 * (body - size))]
    if contact is not None:
        c, half = contact
        near = _threshold(f, flanks, c, body, c, 4.0 * (body - c), sampling=200)
        box = f.add("MathEval")  # + half the distance beyond |z| = half
        f.setString(box, "F", f"F{near} + 0.25 * (abs(z) - {half} + abs(abs(z) - {half}))")
        fields.append(box)
    return _min_field(f, fields)


def _radius_range(gmsh, surfaces) -> tuple[float, float] | None:
    """Smallest and largest radius of the nodes of meshed ``surfaces`` (None if none)."""
    r = [np.hypot(*np.asarray(gmsh.model.mesh.getNodes(2, s, includeBoundary=True)[1])
                  .reshape(-1, 3)[:, :2].T) for s in surfaces]
    return (float(min(x.min() for x in r)), float(max(x.max() for x in r))) if r else None


def _radial_band(f, size: float, r_lo: float, r_hi: float) -> int:
    """``size`` between the radii ``r_lo`` and ``r_hi``, growing at half the distance
    beyond: the root fillets' band, the same at every polar angle, so periodic cuts stay
    periodic (a distance to the fillet faces differs between a sector's two cuts)."""
    c, h = 0.5 * (r_lo + r_hi), 0.5 * (r_hi - r_lo)
    band = f.add("MathEval")
    d = f"Fabs(Sqrt(x * x + y * y) - {c!r})"
    f.setString(band, "F", f"{size!r} + 0.25 * ({d} - {h!r} + Fabs({d} - {h!r}))")
    return band


def _min_field(f, fields, kind: str = "Min") -> int:
    top = f.add(kind)
    f.setNumbers(top, "FieldsList", fields)
    return top


def _box(f, inside: float, outside: float, z: tuple[float, float], ramp: float) -> int:
    """``inside`` between ``z[0]`` and ``z[1]``, ``outside`` beyond, linear over ``ramp``."""
    box = f.add("Box")
    for key, value in (("VIn", inside), ("VOut", outside), ("XMin", -1e9), ("XMax", 1e9),
                       ("YMin", -1e9), ("YMax", 1e9), ("ZMin", z[0]), ("ZMax", z[1]),
                       ("Thickness", max(ramp, 1e-9))):
        f.setNumber(box, key, value)
    return box


def _loaded_size_field(f, top: int, faces, flank_faces, size, body,
                       loaded: LoadedTooth) -> int:
    """``min(max(top, away), flank)``: ``away`` is ``size`` near the loaded tooth's
    ``faces`` and ``far_size_mm`` beyond, ``flank`` is ``flank_size_mm`` on the
    ``flank_faces`` within the axial window, growing to ``size`` over twice the difference
    (at its ends too)."""
    zone, fs = loaded.zone_mm, loaded.flank_size_mm
    away = _threshold(f, faces, size, loaded.far_size_mm, zone, zone)
    fine = _threshold(f, flank_faces, fs, body, 0.0, 2.0 * (body - fs), sampling=100)
    window = _box(f, fs, size, loaded.z_mm, 2.0 * (size - fs))
    return _min_field(f, [_min_field(f, [top, away], "Max"),
                          _min_field(f, [fine, window], "Max")])


def _axial_size_field(f, top: int, size, half, far) -> int:
    """``max(top, window)``: ``window`` is 0 within ``half`` of mid-face and grows to
    ``far`` over ``far - size`` beyond."""
    return _min_field(f, [top, _box(f, 0.0, far, (-half, half), far - size)], "Max")


def loaded_faces(part: str, teeth: list[int] | None) -> list[str]:
    """Regions of the tooth a compliance load case loads, the middle one of the sector,
    loaded flank first: hub tooth k's ccw flank, its cw flank and fillets; the sleeve
    tooth between spaces k and k + 1 (its flank on space k meets hub tooth k's ccw
    flank)."""
    k = 0 if teeth is None else teeth[len(teeth) // 2]
    if part == "hub":
        return [f"T{k}_FLANK_CCW", f"T{k}_FLANK_CW", f"T{k}_FILLET_CW", f"T{k}_FILLET_CCW"]
    return [f"T{k}_FLANK_CCW", f"T{k}_FILLET_CCW", f"T{k + 1}_FLANK_CW", f"T{k + 1}_FILLET_CW"]


def _threshold(f, faces, size, body, dist_min, ramp, sampling=20) -> int:
    """A size field: ``size`` within ``dist_min`` of ``faces``, growing to ``body`` over
    ``ramp``."""
    dist = f.add("Distance")
    f.setNumbers(dist, "SurfacesList", faces)
    f.setNumber(dist, "Sampling", sampling)
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", size)
    f.setNumber(thr, "SizeMax", body)
    f.setNumber(thr, "DistMin", dist_min)
    f.setNumber(thr, "DistMax", dist_min + ramp)
    return thr


def _periodic_cuts(gmsh, names, angle: float) -> None:
    """Make gmsh mesh the ccw cut faces as the cw ones turned by ``angle`` about z."""
    cw = [s for s, (n, _) in names.items() if n == "CUT_CW"]
    ccw = [s for s, (n, _) in names.items() if n == "CUT_CCW"]
    if len(cw) != 1 or len(ccw) != 1:
        raise GeometryError(f"a periodic sector needs one face per cut, got {len(cw)} cw and "
                            f"{len(ccw)} ccw faces")
    c, s = math.cos(angle), math.sin(angle)
    affine = [c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    gmsh.model.mesh.setPeriodic(2, ccw, cw, affine)


def classify_surfaces(gmsh, spec: CouplingSpec,
                      part, labelled, surfaces) -> dict[int, tuple[str, float]]:
    """Region name and vote share of every gmsh surface (see the module docstring)."""
    kind, tooth = labelled.face_attributes["kind"], labelled.face_attributes["tooth"]
    r_outer = 0.5 * spec.sleeve.outer_diameter
    ring = 0.05 * (r_outer - 0.5 * spec.sleeve.major_diameter)
    n = spec.tooth.teeth
    out = {}
    for s in surfaces:
        p = surface_samples(gmsh, s)
        tri = nearest_triangle(labelled, p)
        code, share = _majority(kind[tri])
        name = SURFACE_KINDS[code]
        if name in TOOTH_KINDS:
            region = f"T{_majority(tooth[tri][kind[tri] == code])[0]}_{name.upper()}"
        elif name == "side":
            region = "CUT_CW" if _cut_is_cw(p.mean(axis=0), labelled.metadata["teeth"], n) \
                else "CUT_CCW"
        elif name == "body" and part == "sleeve":
            # within a twentieth of the ring: the solid's outside cylinder is a fitted
            # surface whose points stray from the radius by its chordal tolerance (more
            # than 1e-3 of it on a sector of a few teeth)
            r = np.hypot(p[:, 0], p[:, 1])
            region = "OUTER" if np.all(np.abs(r - r_outer) <= ring) else "BODY"
        else:
            region = name.upper()
        out[s] = (region, float(share))
    return out


def _majority(values: NDArray) -> tuple[int, float]:
    """Most frequent value and its share."""
    vals, counts = np.unique(values, return_counts=True)
    return int(vals[np.argmax(counts)]), float(counts.max() / counts.sum())


def surface_samples(gmsh, surface: int) -> NDArray[np.float64]:
    """Points on a meshed gmsh surface ``(k, 3)``: the centroids of its triangles."""
    tags, xyz, _ = gmsh.model.mesh.getNodes(2, surface, includeBoundary=True)
    tags = np.asarray(tags, dtype=np.int64)
    coords = np.asarray(xyz).reshape(-1, 3)
    lookup = dict(zip(tags.tolist(), range(len(tags)), strict=True))
    types, _, enodes = gmsh.model.mesh.getElements(2, surface)
    if len(types) == 0:
        raise GeometryError(f"gmsh surface {surface} has no triangles to classify")
    tri = np.array([lookup[t] for t in enodes[0]]).reshape(-1, 3)
    return coords[tri].mean(axis=1)


def nearest_triangle(mesh, points: NDArray, candidates: int = 24) -> NDArray[np.int64]:
    """Index ``(k,)`` of the triangle of ``mesh`` nearest to each point (exact distance to
    the ``candidates`` triangles with the nearest centroids)."""
    from scipy.spatial import cKDTree
    from trimesh.triangles import closest_point

    k = min(candidates, len(mesh.faces))
    _, cand = cKDTree(mesh.triangles_center).query(points, k=k)
    cand = cand.reshape(len(points), k)
    tris = mesh.triangles[cand.ravel()]
    q = closest_point(tris, np.repeat(points, k, axis=0))
    d = np.linalg.norm(q - np.repeat(points, k, axis=0), axis=1).reshape(-1, k)
    return cand[np.arange(len(points)), np.argmin(d, axis=1)]


def _cut_is_cw(point, teeth, n: int) -> bool:
    """Is a point of a cut face on the cut plane at the smaller polar angle of the sector?"""
    a = math.atan2(point[1], point[0])
    a0 = 2 * math.pi * (min(teeth) - 0.5) / n
    return abs(math.remainder(a - a0, 2 * math.pi)) < math.pi / n


def extract_mesh(gmsh, part, names, teeth, size, order, t_mesh) -> VolumeMesh:
    """The :class:`VolumeMesh` of gmsh's current 3-D mesh; ``names`` maps each surface tag
    to ``(region name, vote share)``. Refuses inverted elements."""
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    tags = np.asarray(tags, dtype=np.int64)
    nodes = np.asarray(xyz).reshape(-1, 3)
    index = np.zeros(tags.max() + 1, dtype=np.int64)
    index[tags] = np.arange(len(tags))
    etype = 11 if order == 2 else 4
    types, etags, enodes = gmsh.model.mesh.getElements(3)
    if list(types) != [etype]:
        raise GeometryError(f"gmsh gave element types {list(types)}, expected [{etype}]")
    tets = index[np.asarray(enodes[0], dtype=np.int64)].reshape(-1, 10 if order == 2 else 4)
    if order == 2:
        tets[:, [8, 9]] = tets[:, [9, 8]]  # gmsh (.., 3-4, 2-4) -> C3D10 (.., 2-4, 3-4)
    qual = gmsh.model.mesh.getElementQualities(np.asarray(etags[0]), "minSJ")
    regions: dict[str, list] = {}
    for s, (name, _) in sorted(names.items()):
        _, _, tn = gmsh.model.mesh.getElements(2, s)
        tri = index[np.asarray(tn[0], dtype=np.int64)].reshape(-1, 6 if order == 2 else 3)
        regions.setdefault(name, []).append(tri)
    regions_arr = {k: np.concatenate(v) for k, v in sorted(regions.items(), key=_region_order)}
    faces = {k: match_faces(tets, v) for k, v in regions_arr.items()}
    vol = tet_volumes(nodes, tets)
    ar = aspect_ratios(nodes, tets)
    quality = {
        "nodes": len(nodes), "elements": len(tets),
        "min_scaled_jacobian": float(np.min(qual)), "p01_scaled_jacobian":
            float(np.percentile(qual, 1)), "inverted": int(np.sum((qual <= 0) | (vol <= 0))),
        "max_aspect_ratio": float(ar.max()), "p99_aspect_ratio": float(np.percentile(ar, 99)),
        "volume_mm3": float(vol.sum()), "mesh_seconds": t_mesh,
        "min_face_vote": min(share for _, share in names.values()),
    }
    if quality["inverted"]:
        raise GeometryError(f"{quality['inverted']} inverted {part} elements (minimum scaled "
                            f"Jacobian {quality['min_scaled_jacobian']:.3g}); choose a "
                            "smaller size_mm")
    return VolumeMesh(part, nodes, tets, regions_arr, faces, teeth, size, quality)


def _region_order(item) -> tuple:
    name = item[0]
    if name.startswith("T") and "_" in name and name[1:name.index("_")].isdigit():
        return (0, int(name[1:name.index("_")]), name)
    return (1, 0, name)
