"""OpenCASCADE solids of hub and sleeve built from the exact geometry.

Not from triangles: every transverse outline is split into its edges; sleeve roots, tips,
fillets and chamfers are exact circles and lines, every other edge is a cubic B-spline
fitted to exact kernel points with the fewest control points that keep it within
``FIT_SHARE`` of the tolerance (:mod:`.fit`), on one knot vector for all sections. The
sleeve is that outline extruded; the hub is a loft (``BRepOffsetAPI_ThruSections``)
through outlines at the planes :mod:`.loft` chooses, fused with the shoulder and cut by
the bore. OpenCASCADE comes from the ``step`` extra (``cadquery-ocp-novtk``) and is
imported at the call. The STEP file output is
:func:`gearcoupling.export.write_step`; method and measurements: ``docs/export.md``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..errors import BackendError, GeometryError
from ..geometry import hub_model, sleeve_model
from ..interrupts import reraise as reraise_interrupt
from ..spec import CouplingSpec
from .builder import SURFACE_KINDS, Run, tile, tooth_runs
from .fit import DEGREE, fit_sections
from .hub import hub_layout
from .loft import Z_SHARE, curvature_breaks, loft_sections, sampling_tolerance
from .sleeve import sleeve_layout

FIT_SHARE = 0.5
"""Share of the tolerance the fitted profile B-splines may deviate from the exact points."""
DENSE_SHARE = 0.25
"""Chord tolerance (share of the tolerance) of the exact points the profiles are fitted to."""
_CIRCLES = {"root", "tip", "fillet_cw", "fillet_ccw"}  # exact arcs (hub fillets excepted)
_LINES = {"chamfer_cw", "chamfer_ccw"}


def _occ():
    try:
        import OCP  # noqa: F401
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("CAD solids need OpenCASCADE: pip install 'gearcoupling[step]' "
                           "(cadquery-ocp-novtk)") from err
    from OCP import (
        GC,
        BRepAlgoAPI,
        BRepBuilderAPI,
        BRepGProp,
        BRepOffsetAPI,
        BRepPrimAPI,
        GeomAPI,
        GProp,
        gp,
    )
    from OCP import collections as occ_collections

    return dict(algo=BRepAlgoAPI, build=BRepBuilderAPI, gprop=BRepGProp, offset=BRepOffsetAPI,
                prim=BRepPrimAPI, gc=GC, geomapi=GeomAPI, props=GProp, gp=gp,
                col=occ_collections)


def _groups(kinds: NDArray) -> list[tuple[int, int, int]]:
    """Cyclic runs ``(start, stop, kind)`` of equal segment kinds of a closed outline."""
    n = len(kinds)
    change = np.flatnonzero(kinds != np.roll(kinds, 1))
    if change.size == 0:
        raise GeometryError("outline has a single surface kind")
    out = []
    for a, b in zip(change, np.roll(change, -1), strict=True):
        out.append((int(a), int(b) if b > a else int(b) + n, int(kinds[a])))
    return out


def _edge(o, pts: NDArray, kind: str, centre: NDArray | None, tol: float, spline=None):
    """One exact edge through the 3-D points ``pts`` (first and last are its ends): a line,
    an arc, the fitted cubic ``spline = (poles (K, 3), knots, mults)`` when given, else a
    cubic interpolating ``pts``."""
    gp, build = o["gp"], o["build"]
    if spline is not None:
        return build.BRepBuilderAPI_MakeEdge(_bspline(o, *spline)).Edge()
    ends = [gp.gp_Pnt(*pts[i].tolist()) for i in (0, -1)]
    if kind in _LINES or (len(pts) == 2 and kind not in _CIRCLES):
        return build.BRepBuilderAPI_MakeEdge(*ends).Edge()
    if kind in _CIRCLES and centre is not None:
        c = np.asarray(centre, dtype=float)
        rad = np.linalg.norm(pts[0, :2] - c[:2])
        half = 0.5 * (pts[0, :2] + pts[-1, :2]) - c[:2]
        mid = np.append(c[:2] + rad * half / np.linalg.norm(half), pts[0, 2])
        arc = o["gc"].GC_MakeArcOfCircle(ends[0], gp.gp_Pnt(*mid.tolist()), ends[1]).Value()
        return build.BRepBuilderAPI_MakeEdge(arc).Edge()
    arr = o["col"].HArray1_gp_Pnt(1, len(pts))
    for i, q in enumerate(np.asarray(pts, dtype=float).tolist(), start=1):
        arr.SetValue(i, gp.gp_Pnt(*q))
    interp = o["geomapi"].GeomAPI_Interpolate(arr, False, 1e-3 * tol)
    interp.Perform()
    if not interp.IsDone():
        raise GeometryError(f"B-spline interpolation of a {kind} edge failed")
    return build.BRepBuilderAPI_MakeEdge(interp.Curve()).Edge()


def _bspline(o, poles: NDArray, knots: NDArray, mults: NDArray):
    from OCP.Geom import Geom_BSplineCurve

    col, gp = o["col"], o["gp"]
    p = col.Array1_gp_Pnt(1, len(poles))
    for i, q in enumerate(np.asarray(poles, dtype=float).tolist(), start=1):
        p.SetValue(i, gp.gp_Pnt(*q))
    k = col.Array1_double(1, len(knots))
    m = col.Array1_int(1, len(knots))
    for i, (kv, mv) in enumerate(zip(np.asarray(knots, dtype=float).tolist(),
                                     np.asarray(mults).tolist(), strict=True), start=1):
        k.SetValue(i, kv)
        m.SetValue(i, int(mv))
    return Geom_BSplineCurve(p, k, m, DEGREE)


def _wire(o, ring: NDArray, kinds: NDArray, z: float, centres, tol: float,
          splines: dict | None = None):
    """Closed wire of a whole transverse outline ``ring (n, 2)`` (counter-clockwise) whose
    segment ``i`` (``ring[i] -> ring[i + 1]``) has kind code ``kinds[i]``; built clockwise.
    ``splines[start]`` is the fitted ``(poles (K, 2), knots, mults)`` of the group of
    segments from ``start`` (in the wire's direction)."""
    n = len(ring)
    pts3 = np.concatenate([ring, np.full((n, 1), z)], axis=1)
    wire = o["build"].BRepBuilderAPI_MakeWire()
    for start, stop, code in reversed(_groups(kinds)):
        idx = np.arange(start, stop + 1) % n
        kind = SURFACE_KINDS[code]
        spline = None if splines is None else splines.get(start)
        if spline is not None:
            poles, knots, mults = spline
            spline = (np.column_stack([poles, np.full(len(poles), z)]), knots, mults)
        edge = _edge(o, pts3[idx][::-1], kind, centres(kind, ring[idx[len(idx) // 2]]), tol,
                     spline)
        wire.Add(edge)
        if not wire.IsDone():
            raise GeometryError("outline edges do not join into a wire")
    return wire.Wire()


def _volume(o, shape) -> float:
    props = o["props"].GProp_GProps()
    o["gprop"].BRepGProp.VolumeProperties_s(shape, props, 1e-6)
    return abs(props.Mass())


def _tile_ring(pitch: NDArray, teeth: int) -> NDArray:
    return tile(pitch[None], Run(0, teeth, teeth))[0]


def hub_solid(spec: CouplingSpec, tol: float):
    """OpenCASCADE solid of the whole hub (B-spline loft of the fitted tooth outlines).

    The loft is split at the planes where the feed-path curvature jumps (``end_round``)
    so that no B-spline surface spans a curvature break; the pieces are fused.
    """
    o = _occ()
    lay = hub_layout(spec, sampling_tolerance(spec, tol))  # section planes
    dense = hub_layout(spec, DENSE_SHARE * tol)  # exact points the profiles are fitted to
    n = spec.tooth.teeth
    dense_kinds = np.resize(dense.kinds, n * len(dense.kinds))
    cuts = curvature_breaks(hub_model(spec))
    edges = np.concatenate([[-lay.half_face], -cuts[::-1], cuts, [lay.half_face]])
    rows = loft_sections(lay.grid.z, edges, dense, Z_SHARE * tol)
    # one fit over every section of every piece: the pieces share their cut sections exactly
    z_fit = np.unique(np.concatenate(rows))
    rings = np.stack([_tile_ring(pitch, n) for pitch in dense.grid.points(z_fit)])
    splines = fit_outlines(rings, dense_kinds, FIT_SHARE * tol)
    pieces = []
    for z_rows in rows:
        loft = o["offset"].BRepOffsetAPI_ThruSections(True, False, 1e-6)
        loft.CheckCompatibility(False)
        loft.SetMaxDegree(3)
        for z in z_rows:
            i = int(np.argmin(np.abs(z_fit - z)))
            loft.AddWire(_wire(o, rings[i], dense_kinds, float(z),
                               lambda kind, p: _origin(kind), tol, splines[i]))
        loft.Build()
        if not loft.IsDone():
            raise GeometryError("hub loft failed")
        _drop_unit_weights(loft.Shape())
        pieces.append(loft.Shape())
    shape = pieces[0] if len(pieces) == 1 else _sew(o, pieces, np.concatenate([-cuts, cuts]))
    gp, prim, algo = o["gp"], o["prim"], o["algo"]
    hl = lay.half_length
    ax = gp.gp_Ax2(gp.gp_Pnt(0, 0, -hl), gp.gp_Dir(0, 0, 1))
    if lay.shoulder:
        body = prim.BRepPrimAPI_MakeCylinder(ax, lay.r_inner, 2 * hl).Shape()
        shape = algo.BRepAlgoAPI_Fuse(shape, body).Shape()
    if lay.r_bore > 0:
        ax = gp.gp_Ax2(gp.gp_Pnt(0, 0, -hl - 1.0), gp.gp_Dir(0, 0, 1))
        bore = prim.BRepPrimAPI_MakeCylinder(ax, lay.r_bore, 2 * hl + 2.0).Shape()
        shape = algo.BRepAlgoAPI_Cut(shape, bore).Shape()
    return shape


def _drop_unit_weights(shape) -> None:
    """Make the loft's B-spline faces and edges polynomial where all their weights are 1
    (to rounding): the same geometry, written without a weight per control point."""
    from OCP.BRep import BRep_Tool
    from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    exp = TopExp_Explorer(shape, TopAbs_FACE)
    while exp.More():
        surf = BRep_Tool.Surface_s(TopoDS.Face(exp.Current()))
        if isinstance(surf, Geom_BSplineSurface) and (surf.IsURational() or surf.IsVRational()):
            nu, nv = surf.NbUPoles(), surf.NbVPoles()
            w = np.array([[surf.Weight(i, j) for j in range(1, nv + 1)]
                          for i in range(1, nu + 1)])
            if np.abs(w - 1.0).max() < 1e-12:
                for i in range(1, nu + 1):
                    for j in range(1, nv + 1):
                        surf.SetWeight(i, j, 1.0)
        exp.Next()
    exp = TopExp_Explorer(shape, TopAbs_EDGE)
    while exp.More():
        curve = BRep_Tool.Curve_s(TopoDS.Edge(exp.Current()), 0.0, 1.0)
        if isinstance(curve, Geom_BSplineCurve) and curve.IsRational():
            w = np.array([curve.Weight(i) for i in range(1, curve.NbPoles() + 1)])
            if np.abs(w - 1.0).max() < 1e-12:
                for i in range(1, curve.NbPoles() + 1):
                    curve.SetWeight(i, 1.0)
        exp.Next()


def fit_outlines(rings: NDArray, kinds: NDArray, tol: float, skip=()) -> list:
    """Fitted cubic B-splines of every edge of the sections ``rings (s, n, 2)``: per section
    a dict ``{group start: (poles (K, 2), knots, mults)}`` in the wire's (clockwise)
    direction, one knot vector per edge for all sections, the fewest poles whose fit
    deviates by at most ``tol`` (:func:`~gearcoupling.parts.fit.fit_sections`); edges of
    the ``skip`` kinds (exact arcs) and of fewer than 4 points are left out."""
    n = rings.shape[1]
    out: list[dict] = [{} for _ in rings]
    for start, stop, code in _groups(kinds):
        if SURFACE_KINDS[code] in skip or stop - start + 1 < DEGREE + 1:
            continue
        idx = (np.arange(start, stop + 1) % n)[::-1]
        fit = fit_sections(rings[:, idx], tol)
        for section, poles in zip(out, fit.poles, strict=True):
            section[start] = (poles, fit.knots, fit.mults)
    return out


def _sew(o, pieces, cut_z: NDArray):
    """One solid from lofts that meet at the planes ``cut_z``: their faces, less the caps
    in those planes, sewn into a closed shell (much faster than boolean fusion)."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    from OCP.BRepLib import BRepLib
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    sew = o["build"].BRepBuilderAPI_Sewing(1e-6)
    for piece in pieces:
        exp = TopExp_Explorer(piece, TopAbs_FACE)
        while exp.More():
            face = exp.Current()
            box = Bnd_Box()
            BRepBndLib.Add_s(face, box)
            z0, z1 = box.GetZMin(), box.GetZMax()
            inner_cap = z1 - z0 < 1e-4 and np.any(np.abs(cut_z - 0.5 * (z0 + z1)) < 1e-4)
            if not inner_cap:
                sew.Add(face)
            exp.Next()
    sew.Perform()
    shell = TopoDS.Shell(sew.SewedShape())
    solid = o["build"].BRepBuilderAPI_MakeSolid(shell).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def _origin(kind: str):
    return np.zeros(2) if kind in ("root", "tip") else None


def sleeve_solid(spec: CouplingSpec, tol: float):
    """OpenCASCADE solid of the whole sleeve (the exact outline extruded)."""
    o = _occ()
    lay = sleeve_layout(spec, DENSE_SHARE * tol)  # exact points the flanks are fitted to
    sm = sleeve_model(spec)
    n = spec.tooth.teeth
    ring = _tile_ring(lay.pitch, n)
    kinds = np.resize(lay.kinds, n * len(lay.kinds))
    exact = tuple(_CIRCLES | _LINES)  # root, tip, fillets and chamfers stay exact
    fc = np.array(sm.fillet_centre)

    def centres(kind, p):
        if kind in ("root", "tip"):
            return np.zeros(2)
        if kind.startswith("fillet"):
            k = round(math.atan2(p[1], p[0]) / (2 * math.pi / n))
            a = 2 * math.pi * k / n
            c = fc if kind == "fillet_cw" else fc * np.array([1.0, -1.0])
            return np.array([math.cos(a) * c[0] - math.sin(a) * c[1],
                             math.sin(a) * c[0] + math.cos(a) * c[1]])
        return None

    gp, build, prim = o["gp"], o["build"], o["prim"]
    hf = lay.half_face
    fitted = fit_outlines(ring[None], kinds, FIT_SHARE * tol, skip=exact)[0]
    inner = _wire(o, ring, kinds, -hf, centres, tol, fitted)
    circ = gp.gp_Circ(gp.gp_Ax2(gp.gp_Pnt(0, 0, -hf), gp.gp_Dir(0, 0, 1)), lay.r_outer)
    outer = build.BRepBuilderAPI_MakeWire(build.BRepBuilderAPI_MakeEdge(circ).Edge()).Wire()
    face = build.BRepBuilderAPI_MakeFace(outer)
    face.Add(inner)
    if not face.IsDone():
        raise GeometryError("sleeve end face failed")
    shape = prim.BRepPrimAPI_MakePrism(face.Face(), gp.gp_Vec(0, 0, 2 * hf)).Shape()
    if _volume(o, shape) <= 0:
        raise GeometryError("sleeve solid has no volume")
    return shape


_SOLIDS = {"hub": hub_solid, "sleeve": sleeve_solid}


def part_solid(spec: CouplingSpec, part: str, tol: float, teeth=None):
    """OpenCASCADE solid of a part; a tooth selection keeps the sectors of its runs."""
    shape = _SOLIDS[part](spec, tol)
    if teeth is None:
        return shape
    runs = tooth_runs(spec.tooth.teeth, teeth)
    if len(runs) == 1 and runs[0].closed:
        return shape
    o = _occ()
    keep = None
    for run in runs:
        wedge = _wedge(o, spec, run)
        piece = o["algo"].BRepAlgoAPI_Common(shape, wedge).Shape()
        keep = piece if keep is None else o["algo"].BRepAlgoAPI_Fuse(keep, piece).Shape()
    return keep


def _wedge(o, spec: CouplingSpec, run: Run):
    """A prism over the run's polar sector, larger than the part."""
    gp, build, prim = o["gp"], o["build"], o["prim"]
    big = 4.0 * max(spec.sleeve.outer_diameter, spec.hub.tip.diameter)
    h = 2.0 * max(spec.sleeve.face_width, spec.hub.body.length)
    a0 = 2 * math.pi * (run.start - 0.5) / run.teeth
    span = 2 * math.pi * run.count / run.teeth
    steps = max(2, math.ceil(span / (math.pi / 4)))
    poly = build.BRepBuilderAPI_MakePolygon()
    poly.Add(gp.gp_Pnt(0, 0, -h / 2))
    for a in a0 + span * np.arange(steps + 1) / steps:
        r = big / math.cos(span / steps / 2)
        poly.Add(gp.gp_Pnt(r * math.cos(a), r * math.sin(a), -h / 2))
    poly.Close()
    face = build.BRepBuilderAPI_MakeFace(poly.Wire()).Face()
    return prim.BRepPrimAPI_MakePrism(face, gp.gp_Vec(0, 0, h)).Shape()


def shape_volume(shape) -> float:
    """Volume (mm³) of an OpenCASCADE shape (adaptive integration, relative error 1e-6)."""
    return _volume(_occ(), shape)
