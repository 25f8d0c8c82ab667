"""The ``surface`` load model: contact pressure on the exact gap field of every loaded tooth.

Per rotation, every tooth's loaded flank gets a grid over its patch on the developed
sleeve flank (:mod:`.gapfield`: the whole active depth, cut by the sleeve tip chamfer edge
and the hub tip; a window along the face). The teeth share one rigid wind-up ``dpsi``: the
normal gap of a cell is ``r_b (G - dpsi) + u(p) + c_k W_k`` with ``u`` the elastic
half-space displacement (:mod:`.halfspace`, both bodies, composite modulus) and
``c_k W_k`` the tooth pair's bending deflection (the compliance object at the tooth's load
centre, turned to the normal direction: ``c_n = c (r_b / R)^2``). All teeth are solved
together as one Polonsky-Keer problem whose load constraint is the torque:
``r_b sum_k W_k = T``, so the wind-up is its multiplier and equilibrium holds to rounding.

Two passes: a coarse grid over the whole face of every tooth finds which teeth carry load
and where; a fine grid (``grid``) over a window around each patch then solves the pressure.
The window grows until no pressure reaches a window end that is not a flank end. The
compliance, evaluated at each tooth's load centre, is iterated to a fixed point.

Reported measures beside the grid-dependent peak ``max_pressure_MPa`` (it grows like
1/sqrt(cell) where the patch is cut by a flank end):

- ``interior_pressure_MPa``: the peak over cells at least ``interior_distance_mm`` (a tenth
  of the active depth, :data:`INTERIOR_FRACTION`) from every cut edge;
- ``edge_load_share``: the share of the tooth load carried within that distance of an edge;
- ``edge_intensity_MPa_sqrt_mm``: ``p sqrt(h)`` of the cell next to a cut edge (``h`` the
  cell size across the edge), which converges as the grid is refined;
- ``patch_length_mm``: the patch length along the face in the interior (cells at least the
  interior distance from every cut edge; the whole patch where none is interior),
  ``patch_extent_mm`` the whole patch's (longer where the edge peaks spread it), and
  ``patch_width_mm`` along the developed profile;
- ``edge_contact``: the patch reaches a face end.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

from ..errors import SpecError
from ..geometry import FLANKS
from .gapfield import GapField, depth_range, developed_s, face_range, gap_field, windows
from .halfspace import composite_modulus, half_space, solve_contact
from .inputs import loaded_gaps

DEFAULT_GRID = (48, 32)  # cells (along the face, across the depth); see bench_surface.py
COARSE_GRID = (32, 12)
INTERIOR_FRACTION = 0.1  # interior = at least this share of the active depth from any edge
DEFAULT_TOLERANCE = 1e-6  # contact solver: relative pressure change per iteration
COARSE_TOLERANCE = 1e-5
COMPLIANCE_TOLERANCE = 1e-3  # relative change of a tooth's compliance between rounds
WINDOW_MARGIN = 1.5  # fine window = coarse patch length x this + 2 coarse cells

ARRAYS = ("gap_angle_rad", "deflection_mm", "bending_deflection_mm", "tangential_force_N",
          "normal_force_N", "contact_z_mm", "contact_r_mm", "max_pressure_MPa",
          "interior_pressure_MPa", "edge_load_share", "edge_intensity_MPa_sqrt_mm",
          "patch_length_mm", "patch_extent_mm", "patch_width_mm", "patches")


def contact_modulus(spec) -> float:
    """Composite modulus ``E*`` (MPa) of the hub and sleeve materials (``[material]``)."""
    m = spec.material
    return composite_modulus(m.hub.youngs_modulus_MPa, m.hub.poisson_ratio,
                             m.sleeve.youngs_modulus_MPa, m.sleeve.poisson_ratio)


def _check_grid(grid) -> tuple[int, int]:
    try:
        nf, nd = (int(v) for v in grid)
    except (TypeError, ValueError) as err:
        raise SpecError("grid", grid, "must be (cells along the face, cells across the "
                        "depth)") from err
    if nf < 4 or nd < 4 or nf * nd > 1_000_000:
        raise SpecError("grid", grid, "needs at least 4 cells each way, at most 1e6 in all")
    return nf, nd


def _offsets(gap_offset_rad, f: int, n: int) -> NDArray[np.float64]:
    """Per-tooth gap offsets of the loaded flank ``(n,)`` (validated as ``load`` does)."""
    if gap_offset_rad is None:
        return np.zeros(n)
    off = np.asarray(gap_offset_rad, dtype=float)
    if off.shape == (2, n):
        off = off[f]
    if off.shape != (n,) or not np.all(np.isfinite(off)):
        raise SpecError("gap_offset_rad", off.shape, f"must be finite, shaped ({n},) or "
                        f"(2, {n})")
    return off


class _Springs:
    """Normal-direction compliance ``c (r_b/R)^2`` of each tooth pair at a load point."""

    def __init__(self, compliance, r_b: float, R: float):
        self.compliance = compliance
        self.factor = (r_b / R) ** 2

    def __call__(self, z, r) -> NDArray[np.float64]:
        if self.compliance is None:
            return np.zeros(np.shape(z))
        c = np.asarray(self.compliance.pair_compliance_mm_per_N(np.asarray(z, float),
                                                                np.asarray(r, float)), float)
        c = np.broadcast_to(c, np.shape(z))
        if not np.all(np.isfinite(c)) or np.any(c < 0):
            raise SpecError("compliance", "pair_compliance_mm_per_N",
                            "must give finite compliances >= 0 mm/N")
        return c * self.factor


def _centres(gf: GapField, p: NDArray[np.float64]):
    """Pressure-weighted hub-frame load centre ``(z, r)`` of each grid (0 load: nan)."""
    w = np.sum(p, axis=(-2, -1))
    with np.errstate(invalid="ignore", divide="ignore"):
        z = np.sum(p * gf.hub_z_mm, axis=(-2, -1)) / w
        r = np.sum(p * gf.hub_r_mm, axis=(-2, -1)) / w
    return z, r


def _solve(gf: GapField, hs, load_N: float, springs: _Springs, z0, r0, tolerance: float,
           p0=None):
    """Contact of all grids of ``gf`` under ``load_N``, each tooth's compliance taken at
    its load centre (updated inside the solve; the sweep's contact point ``(z0, r0)`` where
    a tooth carries nothing)."""
    gap0 = gf.base_radius * gf.gap_rad

    def locate(p):
        zc, rc = _centres(gf, p)
        loaded = np.sum(p, axis=(-2, -1)) > 0
        return np.where(loaded, zc, z0), np.where(loaded, rc, r0)

    update = None if springs.compliance is None else (lambda p: springs(*locate(p)))
    c0 = springs(*locate(p0)) if p0 is not None else springs(z0, r0)
    sol = solve_contact(hs, gap0, load_N=load_N, mask=gf.mask, spring_mm_per_N=c0,
                        tolerance=tolerance, p0=p0, spring_update=update,
                        spring_tolerance=COMPLIANCE_TOLERANCE)
    z, r = locate(sol.pressure_MPa)
    return sol, z, r


def _edge_cells(pad: NDArray[np.bool_], axis: int) -> NDArray[np.bool_]:
    """Cells of a straight stretch of cut edge across ``axis`` (1: an edge across the
    depth, 0: along the face) of the padded contactable mask: a masked neighbour across
    the edge, unmasked neighbours along it that share that edge. Staircase corners (where a
    curved flank end crosses a grid line) are left out: their peaks are artefacts of the
    grid, not of the flank."""
    m = pad[1:-1, 1:-1]
    if axis == 1:
        lo, hi = ~pad[1:-1, :-2], ~pad[1:-1, 2:]
        side = (pad[:-2, 1:-1], pad[2:, 1:-1])
        shift = (lambda a: np.pad(a, ((1, 0), (0, 0)), mode="edge")[:-1],
                 lambda a: np.pad(a, ((0, 1), (0, 0)), mode="edge")[1:])
    else:
        lo, hi = ~pad[:-2, 1:-1], ~pad[2:, 1:-1]
        side = (pad[1:-1, :-2], pad[1:-1, 2:])
        shift = (lambda a: np.pad(a, ((0, 0), (1, 0)), mode="edge")[:, :-1],
                 lambda a: np.pad(a, ((0, 0), (0, 1)), mode="edge")[:, 1:])
    ok = m & (lo | hi) & side[0] & side[1]
    for sh in shift:
        ok &= (sh(lo) == lo) & (sh(hi) == hi)
    return ok


def _extent(on: NDArray[np.bool_], axis_coord: NDArray[np.float64], cell: float, axis: int):
    """Extent (mm) of the cells ``on`` along ``axis`` of ``(n, nf, nd)`` arrays."""
    hit = np.any(on, axis=2 if axis == 1 else 1)  # (n, n_axis)
    coord = np.broadcast_to(axis_coord, hit.shape)
    lo = np.min(np.where(hit, coord, np.inf), axis=1)
    hi = np.max(np.where(hit, coord, -np.inf), axis=1)
    return np.where(np.any(hit, axis=1), hi - lo + cell, 0.0)


def patch_measures(gf: GapField, p: NDArray[np.float64], interior_mm: float
                   ) -> dict[str, NDArray]:
    """Grid-independent measures of each grid's pressure ``p`` ``(n, nf, nd)``."""
    n = p.shape[0]
    A = gf.dz * gf.ds
    load = A * np.sum(p, axis=(1, 2))
    pmax = np.max(p, axis=(1, 2))
    on = p > 1e-9 * np.maximum(pmax, 1e-300)[:, None, None]
    out: dict[str, NDArray] = {"max_pressure_MPa": pmax}
    interior = np.zeros(n)
    inner_on = np.zeros(on.shape, dtype=bool)
    near_share = np.zeros(n)
    intensity = np.zeros(n)
    patches = np.zeros(n, dtype=int)
    edge = np.zeros(n, dtype=bool)
    for k in range(n):
        if load[k] <= 0:
            continue
        m = gf.mask[k]
        # cut edges: masked cells, and the depth ends of the grid (the sleeve chamfer edge
        # and the hub tip bound the depth range); the window ends along the face are not
        pad = np.pad(np.pad(m, ((0, 0), (1, 1)), constant_values=False), ((1, 1), (0, 0)),
                     constant_values=True)
        dist = ndimage.distance_transform_edt(pad, sampling=(gf.dz, gf.ds))[1:-1, 1:-1]
        inner = dist >= interior_mm
        interior[k] = float(np.max(p[k][inner], initial=0.0))
        inner_on[k] = on[k] & inner if np.any(on[k] & inner) else on[k]
        near_share[k] = A * float(np.sum(p[k][~inner])) / load[k]
        cand = [p[k][_edge_cells(pad, 1)] * math.sqrt(gf.ds),
                p[k][_edge_cells(pad, 0)] * math.sqrt(gf.dz)]
        intensity[k] = max(float(np.max(c, initial=0.0)) for c in cand)
        patches[k] = int(ndimage.label(on[k])[1])
        fc = np.pad(gf.face_cut[k], 1, constant_values=False)
        next_to_face = fc[:-2, 1:-1] | fc[2:, 1:-1]
        edge[k] = bool(np.any(on[k] & next_to_face))
    out.update({
        "interior_pressure_MPa": interior,
        "edge_load_share": near_share,
        "edge_intensity_MPa_sqrt_mm": intensity,
        "patch_length_mm": _extent(inner_on, gf.z_mm, gf.dz, 1),
        "patch_extent_mm": _extent(on, gf.z_mm, gf.dz, 1),
        "patch_width_mm": _extent(on, gf.s_mm[None, :], gf.ds, 2),
        "patches": patches,
        "edge_contact": edge,
    })
    return out


def _resample(coarse: GapField, p: NDArray[np.float64], fine: GapField) -> NDArray[np.float64]:
    """The coarse pressure ``p`` (of the kept teeth) interpolated onto the fine grids
    (bilinear; a warm start for the fine solve)."""
    n, nf, nd = fine.gap_rad.shape
    iz = (fine.z_mm - coarse.z_mm[0, 0]) / coarse.dz  # (n, nf); coarse windows all equal
    js = (fine.s_mm - coarse.s_mm[0]) / coarse.ds
    k = np.broadcast_to(np.arange(n)[:, None, None], (n, nf, nd))
    coords = np.stack([k, np.broadcast_to(iz[:, :, None], k.shape),
                       np.broadcast_to(js[None, None, :], k.shape)])
    out = ndimage.map_coordinates(p, coords.reshape(3, -1), order=1, mode="nearest")
    return np.where(fine.mask, out.reshape(n, nf, nd), 0.0)


def _window_hit(gf: GapField, p) -> NDArray[np.bool_]:
    """Grids whose pressure reaches a window end that is not a flank end."""
    on = p > 0
    first = on[:, 0, :] & gf.mask[:, 0, :]
    last = on[:, -1, :] & gf.mask[:, -1, :]
    return np.any(first, axis=1) | np.any(last, axis=1)


def solve_pose(spec, misalignment: float, theta: NDArray[np.float64], gap_angle: NDArray,
               contact_z: NDArray, contact_r: NDArray, load_N: float, flank: str, *,
               springs: _Springs, e_star: float, grid=DEFAULT_GRID,
               tolerance: float = DEFAULT_TOLERANCE, offsets=None, keep: bool = False):
    """One rotation: all teeth at turning angles ``theta (N,)`` carry ``load_N`` (normal,
    summed). Returns per-tooth arrays, the wind-up and (``keep``) the fine field."""
    nf, nd = _check_grid(grid)
    N = theta.size
    offsets = np.zeros(N) if offsets is None else offsets
    r_b = spec.tooth.base_radius
    cand = np.flatnonzero(np.isfinite(gap_angle))
    if cand.size == 0:
        raise SpecError("torque_Nm", load_N * r_b / 1e3, "no tooth of the loaded flank can "
                        "touch at this pose")
    # aligned with equal offsets every tooth has the same gap field: solve one, share out
    alike = cand if misalignment == 0.0 and np.ptp(offsets[cand]) == 0.0 else None
    if alike is not None:
        cand, load_N = cand[:1], load_N / alike.size
    # pass 1: coarse, whole face, every tooth that can touch
    cf, cd = COARSE_GRID
    zc = windows(spec, misalignment, np.zeros(cand.size), math.inf, cf)
    g1 = gap_field(spec, misalignment, theta[cand], flank, zc, cd, gap_offset_rad=offsets[cand])
    hs1 = half_space((cf, cd), g1.dz, g1.ds, e_star)
    s1, z1, r1 = _solve(g1, hs1, load_N, springs, contact_z[cand], contact_r[cand],
                        max(tolerance, COARSE_TOLERANCE))
    windup1 = s1.approach_mm / r_b
    gmin = np.min(np.where(g1.mask, g1.gap_rad, np.inf), axis=(1, 2))
    lift = windup1 - np.min(gmin)
    keep_t = (s1.load_N > 0) | (gmin <= windup1 + 0.1 * lift)
    teeth = cand[keep_t]
    p1 = s1.pressure_MPa[keep_t]
    on = p1 > 0
    zz = np.broadcast_to(g1.z_mm[keep_t][:, :, None], on.shape)
    has = np.any(on, axis=(1, 2))
    z_lo = np.where(has, np.min(np.where(on, zz, np.inf), axis=(1, 2)), z1[keep_t])
    z_hi = np.where(has, np.max(np.where(on, zz, -np.inf), axis=(1, 2)), z1[keep_t])
    centre = 0.5 * (z_lo + z_hi)
    length = float(np.max(z_hi - z_lo)) * WINDOW_MARGIN + 2.0 * g1.dz
    z0, r0 = z1[keep_t], r1[keep_t]
    while True:
        zw = windows(spec, misalignment, centre, length, nf)
        gf = gap_field(spec, misalignment, theta[teeth], flank, zw, nd,
                       gap_offset_rad=offsets[teeth])
        hs = half_space((nf, nd), gf.dz, gf.ds, e_star)
        p_start = _resample(g1, p1, gf)
        sol, z0, r0 = _solve(gf, hs, load_N, springs, z0, r0, tolerance, p_start)
        full = length >= 2.0 * face_range(spec, misalignment) * nf / (nf - 2)
        if full or not np.any(_window_hit(gf, sol.pressure_MPa)):
            break
        length *= 1.5
    windup = sol.approach_mm / r_b
    meas = patch_measures(gf, sol.pressure_MPa, INTERIOR_FRACTION * (gf.s_mm[-1] - gf.s_mm[0]
                                                                      + gf.ds))
    out = {name: np.zeros(N) for name in ARRAYS}
    out["edge_contact"] = np.zeros(N, dtype=bool)
    out["patches"] = np.zeros(N, dtype=int)
    out["contact_z_mm"] = np.where(np.isfinite(contact_z), contact_z, 0.0)
    out["contact_r_mm"] = np.where(np.isfinite(contact_r), contact_r, 0.0)
    out["gap_angle_rad"] = np.where(np.isfinite(gap_angle), gap_angle + offsets, np.inf)
    W = sol.load_N
    out["normal_force_N"][teeth] = W
    out["tangential_force_N"][teeth] = W * r_b / spec.tooth.pitch_radius
    loaded = W > 0
    out["contact_z_mm"][teeth[loaded]] = z0[loaded]
    out["contact_r_mm"][teeth[loaded]] = r0[loaded]
    R = spec.tooth.pitch_radius
    out["bending_deflection_mm"][teeth] = sol.spring_mm * R / r_b  # circumferential, pitch
    with np.errstate(invalid="ignore"):
        out["deflection_mm"] = np.where(np.isfinite(out["gap_angle_rad"]),
                                        R * np.maximum(windup - out["gap_angle_rad"], 0.0), 0.0)
    out["deflection_mm"] = np.where(out["normal_force_N"] > 0, out["deflection_mm"], 0.0)
    for name, v in meas.items():
        out[name][teeth] = v
    if alike is not None:
        for v in out.values():
            v[alike] = v[alike[0]]
    extra = {"windup_rad": windup, "iterations": sol.iterations,
             "cell_mm": (gf.dz, gf.ds), "window_mm": gf.dz * nf}
    if keep:
        extra.update({"field": gf, "pressure_MPa": sol.pressure_MPa, "teeth": teeth})
    return out, extra


def solve_surface(spec, sweep_result, *, torque_Nm: float, loaded_flank: str | None = None,
                  compliance=None, grid=DEFAULT_GRID, gap_offset_rad=None,
                  tolerance: float = DEFAULT_TOLERANCE, keep_fields: bool = False,
                  progress=None) -> dict[str, Any]:
    """Contact pressure of every tooth over the rotations of a sweep (the ``surface`` model).

    Parameters
    ----------
    spec : CouplingSpec
    sweep_result : SweepResult
        The sweep at the misalignment and rotations to load (its gap angles and contact
        points seed the solve).
    torque_Nm : float
        Torque; positive loads the ccw flanks (docs/conventions.md, Loaded analysis), negative the
        cw flanks.
    loaded_flank : {"cw", "ccw"}, optional
        Defaults to the flank the torque's sign loads.
    compliance : object with ``pair_compliance_mm_per_N(z_mm, r_mm)``, optional
        Tooth pair bending compliance (e.g. ``load.cantilever.CantileverCompliance``);
        ``None`` keeps the teeth rigid (contact compliance only).
    grid : (int, int)
        Fine grid cells (along the face, across the depth): the accuracy knob; see
        ``benchmarks/bench_surface.py`` for its cost and the p_max error.
    gap_offset_rad : (N,) or (2, N) float, optional
        Per-tooth additions to the gap angles (per flank cw, ccw).
    tolerance : float
        Relative convergence tolerance of the contact solver.
    keep_fields : bool
        Also return the fine gap fields and pressures of every rotation (``fields``).

    Returns
    -------
    dict
        ``(N, M)`` arrays named as in ``LoadResult`` (``gap_angle_rad``, ``deflection_mm``,
        ``tangential_force_N``, ``normal_force_N``, ``contact_z_mm``, ``contact_r_mm``,
        ``max_pressure_MPa``, ``interior_pressure_MPa``, ``edge_load_share``,
        ``patch_length_mm``, ``patch_width_mm``, ``edge_contact``) and
        ``bending_deflection_mm``, ``edge_intensity_MPa_sqrt_mm``, ``patches``;
        ``windup_rad (M,)``, ``loaded_flank``, ``torque_Nm``, ``grid``,
        ``interior_distance_mm`` and ``cell_mm``.
    """
    try:
        T = float(torque_Nm)
    except (TypeError, ValueError) as err:
        raise SpecError("torque_Nm", torque_Nm, "must be a number") from err
    if not math.isfinite(T):
        raise SpecError("torque_Nm", torque_Nm, "must be finite")
    flank = loaded_flank if loaded_flank is not None else ("ccw" if T >= 0 else "cw")
    if flank not in FLANKS:
        raise SpecError("loaded_flank", loaded_flank, f"must be one of {FLANKS}")
    _check_grid(grid)
    f = FLANKS.index(flank)
    sw = sweep_result
    N, M = sw.theta_deg.shape
    gap0 = loaded_gaps(sw, f, None)
    offsets = _offsets(gap_offset_rad, f, N)
    r_b, R = spec.tooth.base_radius, spec.tooth.pitch_radius
    gap = np.where(np.isfinite(gap0), gap0, np.inf)
    springs = _Springs(compliance, r_b, R)
    e_star = contact_modulus(spec)
    mis = math.radians(sw.misalignment_deg)
    load_N = abs(T) * 1e3 / r_b
    res: dict[str, Any] = {name: np.zeros((N, M)) for name in ARRAYS}
    res["edge_contact"] = np.zeros((N, M), dtype=bool)
    res["patches"] = np.zeros((N, M), dtype=int)
    windup = np.zeros(M)
    fields = []
    cell = (0.0, 0.0)
    theta = np.radians(sw.theta_deg)
    for j in range(M):
        if load_N == 0:
            g = gap[:, j] + offsets
            windup[j] = float(np.min(g))
            res["gap_angle_rad"][:, j] = g
            res["contact_z_mm"][:, j] = np.nan_to_num(sw.contact_z_mm[f, :, j])
            res["contact_r_mm"][:, j] = np.nan_to_num(sw.contact_r_mm[f, :, j])
        else:
            out, extra = solve_pose(spec, mis, theta[:, j], gap[:, j], sw.contact_z_mm[f, :, j],
                                    sw.contact_r_mm[f, :, j], load_N, flank, springs=springs,
                                    e_star=e_star, grid=grid, tolerance=tolerance,
                                    offsets=offsets, keep=keep_fields)
            for name in ARRAYS:
                res[name][:, j] = out[name]
            res["edge_contact"][:, j] = out["edge_contact"]
            windup[j] = extra["windup_rad"]
            cell = extra["cell_mm"]
            if keep_fields:
                fields.append(extra)
        if progress is not None:
            progress(j + 1, M)
    res["gap_angle_rad"] = np.where(np.isfinite(res["gap_angle_rad"]), res["gap_angle_rad"],
                                    0.0)
    s_lo, s_hi = (developed_s(v, r_b) for v in depth_range(spec, mis))
    res.update({
        "windup_rad": windup, "torque_Nm": T, "loaded_flank": flank, "model": "surface",
        "grid": tuple(int(v) for v in grid), "cell_mm": cell,
        "interior_distance_mm": INTERIOR_FRACTION * (s_hi - s_lo),
        "contact_modulus_MPa": e_star,
    })
    if keep_fields:
        res["fields"] = fields
    return res
