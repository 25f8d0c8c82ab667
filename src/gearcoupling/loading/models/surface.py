"""The ``surface`` load model: contact pressure on the exact gap field of every loaded tooth.

Per rotation, every tooth's loaded flank gets a grid over its patch on the developed
sleeve flank (:mod:`.gapfield`: the whole active depth, cut by the sleeve tip chamfer edge
and the hub tip; a window along the face). The teeth share one rigid wind-up ``dpsi``: the
normal gap of a cell is ``r_b (G - dpsi) + u(p) + v_k(p)`` with ``u`` the elastic
half-space displacement (:mod:`.halfspace`, both bodies, composite modulus) and ``v_k``
the tooth pair's compliance behind the surface (today the bending deflection ``c_k W_k``:
the compliance object at the tooth's load centre, turned to the normal direction:
``c_n = c (r_b / R)^2``). All teeth are solved together as one Polonsky-Keer problem whose
load constraint is the torque: ``r_b sum_k W_k = T``, so the wind-up is its multiplier and
equilibrium holds to rounding.

**Windows.** The fine grid (``grid``) of a tooth covers a window along the face: a run of
cells of one lattice per window level (:func:`.gapfield.lattice_windows`; level 0 is the
whole face range, each level :data:`~.gapfield.WINDOW_RATIO` shorter). A pose is solved at
the shortest level at least :data:`WINDOW_FACTOR` times the longest patch, with no
pressure on a window end that is not a flank end, and with every tooth whose gap angle is
below the wind-up: a rule on the answer, so the answer is that level's lattice solution
wherever the search started (the windows' placement does not change the discrete problem
as long as they hold the patch).

**Starts.** A pose solved cold starts from a coarse grid (:data:`COARSE_GRID`) over the
whole face of every tooth that can touch, which finds the loaded teeth and their patches.
A pose next to a solved one (:class:`SurfaceSolver`: the next rotation, the same rotation
at another torque) starts from it instead: its teeth (matched by turning angle), window
level and patch centres, pressure and wind-up; no coarse pass. The half-space operators
are kept per grid (:func:`.halfspace.half_space`), so the poses of a turn share them.
With ideal teeth (no per-tooth gap offsets) a rotation one tooth pitch on is the same pose
with the teeth renumbered: a turn solves each distinct pose once, in order of its phase
within the pitch, each warm-started from the last; the last pose of a sweep is kept (as
long as the sweep is), so another torque on the sweep starts warm too. None of this
changes an answer, only where its search starts.

**Tooth compliance.** The coupling between the pressure and the teeth behind it is one
object, ``tooth_compliance`` of :class:`SurfaceSolver` (default :class:`BendingSprings`):
``for_field(gf, p0, z_mm, r_mm) -> GridCompliance`` returns, for the grids of a gap field
``gf`` (teeth first) and a starting pressure ``p0`` (or None; ``z_mm, r_mm`` the sweep's
contact points of those teeth), the operator the contact solver adds to the half-space
displacement (:class:`.halfspace.GridCompliance`: ``displacement(q)``, linear and
symmetric for its state; ``update(p)`` to move its state with the pressure;
``deflection_mm(p)`` the reported bending deflection). A dense per-tooth compliance matrix
(finite-element influence coefficients over the cells) plugs in there; the warm starts,
windows and tooth selection do not depend on what it is.

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
import weakref
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentError, GearCouplingError
from ...geometry import FLANKS, developed_arc
from ...numeric import TINY
from ...spec import CouplingSpec
from ..inputs import loaded_gaps
from ..kernels.gapfield import (
    GapField,
    depth_range,
    gap_field,
    lattice_windows,
    touch_z,
    window_level,
    windows,
)
from ..kernels.halfspace import (
    GridCompliance,
    LocalCompliance,
    RigidSprings,
    composite_modulus,
    half_space,
    influence,
    load_split,
    solve_contact,
)
from ..springs import tooth_compliance

DEFAULT_GRID = (48, 32)  # cells (along the face, across the depth); see bench_surface.py
COARSE_GRID = (32, 12)
INTERIOR_FRACTION = 0.1  # interior = at least this share of the active depth from any edge
DEFAULT_TOLERANCE = 1e-6  # contact solver: relative pressure change per iteration
COARSE_TOLERANCE = 1e-5
WINDOW_FACTOR = 1.75  # windows: the shortest level at least this x the longest patch
TEETH_MARGIN = 0.1  # a solve takes the teeth within this share of the lift above the wind-up
MAX_ROUNDS = 40  # solves of one pose while its windows and teeth settle
FIELD_ROWS = 4096  # per-tooth gap field rows a solver keeps (SurfaceSolver._field)
_ROW_FIELDS = ("z_mm", "gap_rad", "mask", "face_cut", "hub_z_mm", "hub_r_mm")

#: the last solved pose of each sweep and flank: a later load on the sweep (another torque)
#: starts from it; held as long as the sweep is
_LAST_POSE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: every pose solved on a sweep of at most :data:`KEPT_POSES` distinct rotations, by flank
#: and rotation: a load on a sweep next to one of them starts from it (:func:`start_from`);
#: held as long as the sweep is
_POSES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
KEPT_POSES = 16

ARRAYS = ("gap_angle_rad", "deflection_mm", "bending_deflection_mm", "tangential_force_N",
          "normal_force_N", "contact_z_mm", "contact_r_mm", "max_pressure_MPa",
          "interior_pressure_MPa", "edge_load_share", "edge_intensity_MPa_sqrt_mm",
          "patch_length_mm", "patch_extent_mm", "patch_width_mm", "patches")


def contact_modulus(spec: CouplingSpec) -> float:
    """Composite modulus ``E*`` (MPa) of the hub and sleeve materials (``[material]``)."""
    m = spec.material
    return composite_modulus(m.hub.youngs_modulus_MPa, m.hub.poisson_ratio,
                             m.sleeve.youngs_modulus_MPa, m.sleeve.poisson_ratio)


def _check_grid(grid) -> tuple[int, int]:
    try:
        nf, nd = (int(v) for v in grid)
    except (TypeError, ValueError) as err:
        raise ArgumentError("grid", grid, "must be (cells along the face, cells across the "
                        "depth)") from err
    if nf < 4 or nd < 4 or nf * nd > 1_000_000:
        raise ArgumentError("grid", grid, "needs at least 4 cells each way, at most 1e6 in all")
    return nf, nd


def flank_offsets(gap_offset_rad, f: int, n: int) -> NDArray[np.float64]:
    """Per-tooth gap offsets of the loaded flank ``(n,)`` (validated as ``load`` does)."""
    if gap_offset_rad is None:
        return np.zeros(n)
    off = np.asarray(gap_offset_rad, dtype=float)
    if off.shape == (2, n):
        off = off[f]
    if off.shape != (n,) or not np.all(np.isfinite(off)):
        raise ArgumentError("gap_offset_rad", off.shape, f"must be finite, shaped ({n},) or "
                        f"(2, {n})")
    return off


def _centres(gf: GapField, p: NDArray[np.float64]):
    """Pressure-weighted hub-frame load centre ``(z, r)`` of each grid (0 load: nan)."""
    w = np.sum(p, axis=(-2, -1))
    with np.errstate(invalid="ignore", divide="ignore"):
        z = np.sum(p * gf.hub_z_mm, axis=(-2, -1)) / w
        r = np.sum(p * gf.hub_r_mm, axis=(-2, -1)) / w
    return z, r


def _located(gf: GapField, p, z0, r0):
    """Load centres of the loaded grids, ``(z0, r0)`` of the others."""
    zc, rc = _centres(gf, p)
    loaded = np.sum(p, axis=(-2, -1)) > 0
    return np.where(loaded, zc, z0), np.where(loaded, rc, r0)


class BendingSprings:
    """Tooth-pair bending as a rigid-body spring per tooth: normal compliance
    ``c (r_b/R)^2`` of the compliance object at the tooth's load centre (the default
    tooth compliance of :class:`SurfaceSolver`; ``compliance=None``: rigid teeth)."""

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
            raise ArgumentError("compliance", "pair_compliance_mm_per_N",
                            "must give finite compliances >= 0 mm/N")
        return c * self.factor

    def for_field(self, gf: GapField, p0, z_mm, r_mm, tolerance: float) -> GridCompliance:
        """The springs of the teeth of ``gf``, at the load centres of ``p0`` (else at
        ``(z_mm, r_mm)``), following the load centre during the solve until no
        compliance moves by more than ``tolerance`` (relative)."""
        def update(p):
            return self(*_located(gf, p, z_mm, r_mm))

        c0 = self(*_located(gf, p0, z_mm, r_mm)) if p0 is not None else self(z_mm, r_mm)
        return RigidSprings(c0, gf.dz * gf.ds, None if self.compliance is None else update,
                            tolerance)


def _edge_cells(pad: NDArray[np.bool_], axis: int) -> NDArray[np.bool_]:
    """Cells of a straight stretch of cut edge across ``axis`` (1: an edge across the
    depth, 0: along the face) of the padded contactable masks ``(n, nf + 2, nd + 2)``: a
    masked neighbour across the edge, unmasked neighbours along it that share that edge.
    Staircase corners (where a curved flank end crosses a grid line) are left out: their
    peaks are artefacts of the grid, not of the flank."""
    m = pad[:, 1:-1, 1:-1]
    if axis == 1:
        lo, hi = ~pad[:, 1:-1, :-2], ~pad[:, 1:-1, 2:]
        side = (pad[:, :-2, 1:-1], pad[:, 2:, 1:-1])
        along = 1
    else:
        lo, hi = ~pad[:, :-2, 1:-1], ~pad[:, 2:, 1:-1]
        side = (pad[:, 1:-1, :-2], pad[:, 1:-1, 2:])
        along = 2
    ok = m & (lo | hi) & side[0] & side[1]
    for a in (lo, hi):  # the neighbours along the edge share it (edge rows repeat)
        before = np.concatenate([np.take(a, [0], axis=along),
                                 np.take(a, range(a.shape[along] - 1), axis=along)], axis=along)
        after = np.concatenate([np.take(a, range(1, a.shape[along]), axis=along),
                                np.take(a, [a.shape[along] - 1], axis=along)], axis=along)
        ok &= (before == a) & (after == a)
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
    from scipy import ndimage  # at the call: `import gearcoupling` stays light
    A = gf.dz * gf.ds
    load = A * np.sum(p, axis=(1, 2))
    loaded = load > 0
    pmax = np.max(p, axis=(1, 2))
    on = p > 1e-9 * np.maximum(pmax, TINY)[:, None, None]
    # cut edges: masked cells, and the depth ends of the grid (the sleeve chamfer edge and
    # the hub tip bound the depth range); the window ends along the face are not
    pad = np.pad(np.pad(gf.mask, ((0, 0), (0, 0), (1, 1)), constant_values=False),
                 ((0, 0), (1, 1), (0, 0)), constant_values=True)
    # one transform for all grids: a spacing between them longer than any in-grid distance
    far = 1e6 * (pad.shape[1] * gf.dz + pad.shape[2] * gf.ds)
    dist = ndimage.distance_transform_edt(pad, sampling=(far, gf.dz, gf.ds))[:, 1:-1, 1:-1]
    inner = dist >= interior_mm
    interior = np.max(np.where(inner, p, 0.0), axis=(1, 2))
    inner_on = on & inner
    inner_on = np.where(np.any(inner_on, axis=(1, 2))[:, None, None], inner_on, on)
    with np.errstate(invalid="ignore", divide="ignore"):
        near_share = np.where(loaded, A * np.sum(np.where(inner, 0.0, p), axis=(1, 2))
                              / np.where(loaded, load, 1.0), 0.0)
    intensity = np.maximum(
        np.max(np.where(_edge_cells(pad, 1), p, 0.0), axis=(1, 2)) * math.sqrt(gf.ds),
        np.max(np.where(_edge_cells(pad, 0), p, 0.0), axis=(1, 2)) * math.sqrt(gf.dz))
    structure = np.zeros((3, 3, 3), dtype=bool)  # 4-connected within a grid, none across
    structure[1] = ndimage.generate_binary_structure(2, 1)
    labels, _ = ndimage.label(on, structure)
    top = np.max(labels, axis=(1, 2))
    first = np.min(np.where(labels > 0, labels, np.iinfo(labels.dtype).max), axis=(1, 2))
    patches = np.where(top > 0, top - first + 1, 0)  # labels run in order, grid by grid
    fc = np.pad(gf.face_cut, ((0, 0), (1, 1), (0, 0)), constant_values=False)
    edge = np.any(on & (fc[:, :-2] | fc[:, 2:]), axis=(1, 2))
    out: dict[str, NDArray] = {
        "max_pressure_MPa": pmax,
        "interior_pressure_MPa": np.where(loaded, interior, 0.0),
        "edge_load_share": near_share,
        "edge_intensity_MPa_sqrt_mm": np.where(loaded, intensity, 0.0),
        "patch_length_mm": _extent(inner_on, gf.z_mm, gf.dz, 1),
        "patch_extent_mm": _extent(on, gf.z_mm, gf.dz, 1),
        "patch_width_mm": _extent(on, gf.s_mm[None, :], gf.ds, 2),
        "patches": np.where(loaded, patches, 0).astype(int),
        "edge_contact": edge & loaded,
    }
    return out


def face_end_closure(gf: GapField, p: NDArray[np.float64], gap_mm: NDArray[np.float64],
                     e_star_MPa: float) -> float:
    """How far the patches are from a face end, continuous in the load: the largest over
    the cells next to a face cut (in the windows) of ``1 + (p c - g) / h``, with ``g`` the
    loaded gap, ``p`` the pressure, ``c`` a cell's own compliance (mm/MPa) and ``h`` the
    cell's unloaded gap above its tooth's smallest (mm). Below 1: every such cell open (1 -
    the share of its gap the load has closed); 1: one closes, where ``edge_contact`` turns
    on; above 1: pressed. ``nan`` where no window reaches a face end (every patch is then
    inside its window, off the face ends)."""
    fc = np.pad(gf.face_cut, ((0, 0), (1, 1), (0, 0)), constant_values=False)
    edge = gf.mask & (fc[:, :-2] | fc[:, 2:])
    if not np.any(edge):
        return math.nan
    g0 = gf.base_radius * gf.gap_rad
    h = g0 - np.min(np.where(gf.mask, g0, np.inf), axis=(1, 2))[:, None, None]
    c = float(influence(0.0, 0.0, gf.dz, gf.ds, e_star_MPa))
    rho = 1.0 + (p[edge] * c - gap_mm[edge]) / np.maximum(h[edge], TINY)
    return float(np.max(rho))


def _window_hit(gf: GapField, p) -> NDArray[np.bool_]:
    """Grids whose pressure reaches a window end that is not a flank end."""
    on = p > 0
    first = on[:, 0, :] & gf.mask[:, 0, :]
    last = on[:, -1, :] & gf.mask[:, -1, :]
    return np.any(first, axis=1) | np.any(last, axis=1)


def _spans(gf: GapField, p: NDArray[np.float64]):
    """Each grid's patch along the face: the centre of its loaded cells (nan where
    unloaded) and its span ``4 sigma`` (``sigma`` the standard deviation of the load along
    the face: the whole length of a Hertzian line contact, 1.15 x a uniform patch). The
    span moves by a small fraction of a cell between grids, where a count of cells would
    move by a whole cell: a window rule on it has one answer per pose."""
    on = p > 0
    hit = np.any(on, axis=2)  # (n, nf)
    lo = np.min(np.where(hit, gf.z_mm, np.inf), axis=1)
    hi = np.max(np.where(hit, gf.z_mm, -np.inf), axis=1)
    w = np.sum(p, axis=2)  # load per face row
    total = np.sum(w, axis=1)
    loaded = total > 0
    safe = np.where(loaded, total, 1.0)
    mean = np.sum(w * gf.z_mm, axis=1) / safe
    var = np.sum(w * (gf.z_mm - mean[:, None]) ** 2, axis=1) / safe
    with np.errstate(invalid="ignore"):
        return (np.where(loaded, 0.5 * (lo + hi), np.nan),
                np.where(loaded, np.maximum(4.0 * np.sqrt(np.maximum(var, 0.0)), 2.0 * gf.dz),
                         0.0))


@dataclass(frozen=True, eq=False)
class SolvedPose:
    """A solved pose, as the next solve starts from it.

    ``teeth (n,)`` the tooth indices of its grids, ``theta (n,)`` their turning angles
    (radians), ``level`` the window level (None: the coarse whole-face grid), ``field`` and
    ``pressure_MPa (n, nf, nd)`` its grids, ``centres_mm (n,)`` where each tooth's patch
    (or, unloaded, its window) lies along the face, ``extent_mm`` the longest patch span,
    ``windup_rad`` and ``lift_rad`` (wind-up above the smallest gap angle), ``law (3, n)``
    each tooth's load-approach law (:attr:`.halfspace.ContactSolution.law`),
    ``touch_mm (n,)`` where its first touch lies along the face (sleeve frame) and
    ``sampled_rad (n,)`` its smallest cell gap above the sweep's exact gap angle.
    """

    teeth: NDArray[np.intp]
    theta: NDArray[np.float64]
    level: int | None
    field: GapField
    pressure_MPa: NDArray[np.float64]
    centres_mm: NDArray[np.float64]
    extent_mm: float
    windup_rad: float
    lift_rad: float
    law: NDArray[np.float64]
    touch_mm: NDArray[np.float64]
    sampled_rad: NDArray[np.float64]


class SurfaceSolver:
    """The surface model on the poses of one sweep, keeping what neighbouring poses share.

    Parameters
    ----------
    spec : CouplingSpec
    sweep_result : SweepResult
    flank : {"cw", "ccw"}
        The loaded hub flank.
    tooth_compliance : object with ``for_field``
        The compliance behind the teeth (module docstring; :class:`BendingSprings`).
    grid : (int, int)
    offsets : (N,) float
        Gap offsets of the loaded flank.
    tolerance : float
    extra_gap : callable, optional
        ``extra_gap(j, teeth, gf) -> (n, nf, nd)`` gap (rad, >= 0) added to every gap field
        ``gf`` of ``teeth`` at rotation ``j`` as it is built (a worn depth ``h`` along the
        flank normal opens it by ``h / r_b``); called on every field, so it may change
        between solves (the cached rows hold the gap without it). Its attribute
        ``uniform`` (default False) says every tooth gets the same addition, which keeps
        the whole-pitch symmetry of :meth:`plan`; its optional method ``compliance(j,
        teeth, gf) -> (n, nf, nd)`` (mm/MPa, or None) adds a compliance of each cell of
        its own in series with the contact (:class:`.halfspace.LocalCompliance`).
    """

    def __init__(self, spec: CouplingSpec, sweep_result, flank: str, tooth_compliance, *,
                 grid=DEFAULT_GRID, offsets=None, tolerance: float = DEFAULT_TOLERANCE,
                 extra_gap=None):
        self.spec = spec
        self.grid = _check_grid(grid)
        f = FLANKS.index(flank)
        self.flank = flank
        sw = sweep_result
        N, _ = sw.theta_deg.shape
        gap0 = loaded_gaps(sw, f, None)
        self.offsets = np.zeros(N) if offsets is None else np.asarray(offsets, float)
        self.gap = np.where(np.isfinite(gap0), gap0 + self.offsets[:, None], np.inf)
        self.theta = np.radians(sw.theta_deg)
        self.contact_z = sw.contact_z_mm[f]
        self.contact_r = sw.contact_r_mm[f]
        with np.errstate(invalid="ignore"):
            self.touch = touch_z(spec, math.radians(sw.misalignment_deg), self.theta, flank,
                                 self.contact_z, self.contact_r)
        self.mis = math.radians(sw.misalignment_deg)
        self.r_b = spec.tooth.base_radius
        self.pitch = 2.0 * math.pi / N
        self.extra_gap = extra_gap
        self.uniform = bool(np.ptp(self.offsets) == 0.0) and (
            extra_gap is None or bool(getattr(extra_gap, "uniform", False)))
        self.tooth_compliance = tooth_compliance
        self.e_star = contact_modulus(spec)
        self.tolerance = tolerance
        self._rows: dict[tuple, tuple] = {}  # gap field rows (_field)
        self._depth: dict[int, GapField] = {}  # a field per depth count: its depth rows

    def plan(self):
        """The rotations to solve, in solving order, and how every rotation maps onto them:
        ``(order (K,), source (M,), shift (M,))`` with rotation ``j``'s tooth ``k`` the
        tooth ``(k + shift[j]) % N`` of rotation ``source[j]``. With ideal teeth a rotation
        one pitch on is the same pose renumbered: each distinct phase once, in phase order."""
        N, M = self.theta.shape
        t0 = self.theta[0]
        if self.uniform:
            frac = np.mod(t0 / self.pitch, 1.0)
            key = np.mod(np.round(frac * 1e9).astype(np.int64), 10**9)
            _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
            source = first[inverse.ravel()]
            shift = np.mod(np.round((t0 - t0[source]) / self.pitch).astype(np.intp), N)
            k = np.arange(N)[:, None]
            moved = self.theta[(k + shift[None, :]) % N, source[None, :]]
            d = np.angle(np.exp(1j * (moved - self.theta)))
            if np.all(np.abs(d) <= 1e-9):
                return first, source, shift  # first: sorted by key, the phase order
        order = np.argsort(np.mod(t0, 2.0 * math.pi), kind="stable")
        return order, np.arange(M), np.zeros(M, dtype=np.intp)

    def _solve(self, gf: GapField, load_N: float, p0, z0, r0, tolerance: float):
        hs = half_space(gf.gap_rad.shape[1:], gf.dz, gf.ds, self.e_star)
        comp = self.tooth_compliance.for_field(gf, p0, z0, r0, tolerance)
        if gf.local_compliance_mm_per_MPa is not None:
            comp = LocalCompliance(comp, gf.local_compliance_mm_per_MPa)
        sol = solve_contact(hs, self.r_b * gf.gap_rad, load_N=load_N, mask=gf.mask,
                            tolerance=tolerance, p0=p0, compliance=comp)
        z, r = _located(gf, sol.pressure_MPa, z0, r0)
        return sol, z, r

    def _field(self, j: int, teeth, z_mm, n_depth: int) -> GapField:
        """The gap field of ``teeth`` at rotation ``j`` on windows ``z_mm``: each tooth's
        rows computed once per window (a search solves one rotation at several torques,
        mostly on the same windows; :data:`FIELD_ROWS` kept)."""
        z = np.asarray(z_mm, dtype=float)
        keys = [(j, int(k), z[i].tobytes(), n_depth) for i, k in enumerate(teeth)]
        new = [i for i, key in enumerate(keys) if key not in self._rows]
        if new and len(self._rows) + len(new) > FIELD_ROWS:
            self._rows.clear()  # full: start again, with every row of this call
            new = list(range(len(keys)))
        if new:
            sel = np.asarray(new)
            gf = gap_field(self.spec, self.mis, self.theta[teeth[sel], j], self.flank, z[sel],
                           n_depth, gap_offset_rad=self.offsets[teeth[sel]])
            self._depth[n_depth] = gf
            for r, i in enumerate(new):
                self._rows[keys[i]] = tuple(getattr(gf, f)[r] for f in _ROW_FIELDS)
        rows = [self._rows[key] for key in keys]
        stacked: dict[str, Any] = {f: np.stack([row[k] for row in rows])
                                   for k, f in enumerate(_ROW_FIELDS)}
        gf = replace(self._depth[n_depth], dz=float(z[0, 1] - z[0, 0]), **stacked)
        if self.extra_gap is None:
            return gf
        local = getattr(self.extra_gap, "compliance", None)
        return replace(gf, gap_rad=gf.gap_rad + self.extra_gap(j, teeth, gf),
                       local_compliance_mm_per_MPa=None if local is None else
                       local(j, teeth, gf))

    def _state(self, j, teeth, level, gf, sol, lift_from, centres) -> SolvedPose:
        c, e = _spans(gf, sol.pressure_MPa)
        windup = sol.approach_mm / self.r_b
        return SolvedPose(teeth, self.theta[teeth, j], level, gf, sol.pressure_MPa,
                          np.where(np.isfinite(c), c, centres), float(np.max(e)), windup,
                          windup - lift_from, sol.law, self.touch[teeth, j],
                          _smallest(gf) - self.gap[teeth, j])

    def _coarse(self, j: int, cand, load_N: float) -> SolvedPose:
        """Cold start: the coarse grid over the whole face of every tooth that can touch."""
        cf, cd = COARSE_GRID
        gf = self._field(j, cand, windows(self.spec, self.mis, np.zeros(cand.size), math.inf,
                                          cf), cd)
        sol, _, _ = self._solve(gf, load_N, None, self.contact_z[cand, j],
                                self.contact_r[cand, j], max(self.tolerance, COARSE_TOLERANCE))
        return self._state(j, cand, None, gf, sol, float(np.min(self.gap[cand, j])),
                           np.zeros(cand.size))

    def _match(self, start: SolvedPose, theta, alike: bool) -> NDArray[np.intp]:
        """Index into ``start``'s teeth of the tooth nearest each turning angle (within
        half a pitch; -1: none)."""
        if alike:
            return np.zeros(theta.size, dtype=np.intp)
        d = np.abs(np.angle(np.exp(1j * (theta[:, None] - start.theta[None, :]))))
        idx = np.argmin(d, axis=1)
        return np.where(d[np.arange(theta.size), idx] <= 0.5 * self.pitch, idx, -1)

    def solve_pose(self, j: int, load_N: float, start: SolvedPose | None = None,
                   keep: bool = False):
        """Rotation ``j`` under ``load_N`` (normal, summed over the teeth), from ``start``
        (a neighbouring solved pose; None: cold). Returns the per-tooth arrays ``(N,)``,
        the extras (wind-up, iterations, cells; with ``keep`` the fine field) and the
        :class:`SolvedPose` the next solve may start from."""
        nf, nd = self.grid
        gap = self.gap[:, j]
        cand = np.flatnonzero(np.isfinite(gap))
        if cand.size == 0:
            raise ArgumentError("torque_Nm", load_N * self.r_b / 1e3, "no tooth of the loaded "
                            "flank can touch at this pose")
        # aligned with equal offsets every tooth has the same gap field: solve one, share out
        alike = cand if self.mis == 0.0 and self.uniform else None
        if alike is not None:
            cand, load_N = cand[:1], load_N / alike.size
        g_min = float(np.min(gap[cand]))
        seed = start if start is not None else self._coarse(j, cand, load_N)
        # the seed's wind-up, or above the smallest gap its lift grown with the load (about
        # linearly: springs and line contacts), so that a start at a smaller load has no
        # teeth missing; a tooth that stays unloaded leaves the answer as it is
        lift = max(seed.lift_rad, 0.0)
        windup = max(seed.windup_rad, g_min + lift * _load_ratio(seed, load_N))
        teeth = cand[gap[cand] <= windup + TEETH_MARGIN * lift]
        teeth = np.union1d(teeth, cand[np.argmin(gap[cand])])
        if seed.level is None:  # from the coarse grid: its patches, less a coarse cell
            level = window_level(self.spec, self.mis, WINDOW_FACTOR * max(
                seed.extent_mm - seed.field.dz, seed.field.dz), nf)
        else:
            level = seed.level
        centres = self._centres(j, teeth, seed, alike is not None)
        solved: dict[int, tuple] = {}
        hits: set[int] = set()
        done = None
        for _ in range(MAX_ROUNDS):
            zw = self._windows(j, teeth, level, centres)
            gf = self._field(j, teeth, zw, nd)
            idx = self._match(seed, self.theta[teeth, j], alike is not None)
            sol, z0, r0 = self._solve(gf, load_N, self._start(j, teeth, seed, idx, gf, load_N),
                                      self.contact_z[teeth, j], self.contact_r[teeth, j],
                                      self.tolerance)
            seed = self._state(j, teeth, level, gf, sol, g_min, centres)
            missing = np.setdiff1d(cand[gap[cand] < seed.windup_rad + 1e-3 * seed.lift_rad],
                                   teeth)
            if missing.size:
                teeth = np.union1d(teeth, missing)
                centres = self._centres(j, teeth, seed, alike is not None)
                continue
            want = window_level(self.spec, self.mis, WINDOW_FACTOR * seed.extent_mm, nf)
            if np.any(_window_hit(gf, sol.pressure_MPa)):
                nxt = min(want, level)
                if nxt == level and level in hits:
                    nxt = level - 1
                hits.add(level)
                level, centres = max(nxt, 0), seed.centres_mm
                continue
            solved[level] = (seed, gf, sol, z0, r0)
            if want == level or want in solved:
                done = solved[min(want, level)]
                break
            level, centres = want, seed.centres_mm
        else:
            if not solved:
                raise GearCouplingError(f"surface model: the windows of rotation {j} did not "
                                        f"settle in {MAX_ROUNDS} solves")
            done = solved[min(solved)]
        seed, gf, sol, z0, r0 = done
        return (*self._output(j, seed, gf, sol, z0, r0, alike, keep), seed)

    def _start(self, j, teeth, seed: SolvedPose, idx, gf: GapField, load_N: float):
        """The warm start on ``gf``: ``seed``'s pressure of the matched teeth ``idx``, moved
        with their first touch, each tooth's load predicted from its law in ``seed`` (the
        law's first touch carried by the sweep's exact gap angle, which moves smoothly
        with the pose where the smallest cell gap jumps from cell to cell)."""
        known = idx >= 0
        m = np.maximum(idx, 0)
        moved = np.where(known, np.nan_to_num(self.touch[teeth, j] - seed.touch_mm[m]), 0.0)
        p0 = _transfer(seed, idx, gf, moved)
        law = np.where(known, seed.law[:, m], np.nan)
        if not np.any(np.isfinite(law[0])):
            return p0
        touch = self.gap[teeth, j] + np.where(known, seed.sampled_rad[m], 0.0)
        touch = np.where(np.isfinite(touch), touch, _smallest(gf))
        W = load_split(self.r_b * touch, law, load_N)
        A = gf.dz * gf.ds
        carried = A * np.sum(p0, axis=(1, 2))
        scale = np.where(carried > 0, W / np.where(carried > 0, carried, 1.0), 0.0)
        return p0 * scale[:, None, None]

    def _centres(self, j, teeth, seed: SolvedPose, alike: bool):
        """Window centres: the matched tooth's patch in ``seed``, else the first touch."""
        idx = self._match(seed, self.theta[teeth, j], alike)
        own = np.nan_to_num(self.touch[teeth, j])
        return np.where(idx >= 0, seed.centres_mm[np.maximum(idx, 0)], own)

    def _windows(self, j, teeth, level: int, centres):
        """Windows of ``level`` on ``centres``, moved onto each tooth's first touch where
        it would lie in a window's end cells: every window holds its tooth's smallest gap."""
        nf = self.grid[0]
        zw, _ = lattice_windows(self.spec, self.mis, level, centres, nf)
        dz = zw[0, 1] - zw[0, 0]
        touch = self.touch[teeth, j]
        off = np.isfinite(touch) & ((touch < zw[:, 0] + dz) | (touch > zw[:, -1] - dz))
        if np.any(off):
            zw, _ = lattice_windows(self.spec, self.mis, level,
                                    np.where(off, touch, centres), nf)
        return zw

    def _output(self, j, seed: SolvedPose, gf, sol, z0, r0, alike, keep):
        N = self.theta.shape[0]
        r_b, R = self.r_b, self.spec.tooth.pitch_radius
        teeth = seed.teeth
        windup = seed.windup_rad
        meas = patch_measures(gf, sol.pressure_MPa, INTERIOR_FRACTION * (
            gf.s_mm[-1] - gf.s_mm[0] + gf.ds))
        out = {name: np.zeros(N) for name in ARRAYS}
        out["edge_contact"] = np.zeros(N, dtype=bool)
        out["patches"] = np.zeros(N, dtype=int)
        cz, cr = self.contact_z[:, j], self.contact_r[:, j]
        out["contact_z_mm"] = np.where(np.isfinite(cz), cz, 0.0)
        out["contact_r_mm"] = np.where(np.isfinite(cr), cr, 0.0)
        out["gap_angle_rad"] = self.gap[:, j].copy()
        W = sol.load_N
        out["normal_force_N"][teeth] = W
        out["tangential_force_N"][teeth] = W * r_b / R
        loaded = W > 0
        out["contact_z_mm"][teeth[loaded]] = z0[loaded]
        out["contact_r_mm"][teeth[loaded]] = r0[loaded]
        out["bending_deflection_mm"][teeth] = sol.spring_mm * R / r_b  # circumferential
        with np.errstate(invalid="ignore"):
            out["deflection_mm"] = np.where(np.isfinite(out["gap_angle_rad"]),
                                            R * np.maximum(windup - out["gap_angle_rad"], 0.0),
                                            0.0)
        out["deflection_mm"] = np.where(out["normal_force_N"] > 0, out["deflection_mm"], 0.0)
        for name, v in meas.items():
            out[name][teeth] = v
        if alike is not None:
            for v in out.values():
                v[alike] = v[alike[0]]
        nf = gf.z_mm.shape[1]
        extra = {"windup_rad": windup, "iterations": sol.iterations,
                 "cell_mm": (gf.dz, gf.ds), "window_mm": gf.dz * nf, "level": seed.level,
                 "face_end_closure": face_end_closure(gf, sol.pressure_MPa, sol.gap_mm,
                                                      self.e_star)}
        if keep:
            extra.update({"field": gf, "pressure_MPa": sol.pressure_MPa, "teeth": teeth})
        return out, extra


def _load_ratio(seed: SolvedPose, load_N: float) -> float:
    """``load_N`` over the load of ``seed`` (its pressure summed)."""
    carried = float(np.sum(seed.pressure_MPa)) * seed.field.dz * seed.field.ds
    return load_N / carried if carried > 0 else 1.0


def _smallest(gf: GapField) -> NDArray[np.float64]:
    """Each grid's smallest contactable cell gap (rad)."""
    return np.min(np.where(gf.mask, gf.gap_rad, np.inf), axis=(1, 2))


def _transfer(seed: SolvedPose, idx: NDArray[np.intp], gf: GapField, moved_mm=0.0
              ) -> NDArray[np.float64]:
    """The pressure of ``seed``'s teeth ``idx`` (-1: none) on the grids of ``gf``, moved
    along the face by ``moved_mm`` (each tooth's first touch moved so much): bilinear in
    the developed flank co-ordinates, zero beyond the seed's windows (a warm start)."""
    from scipy import ndimage  # at the call: `import gearcoupling` stays light
    n, nf, nd = gf.gap_rad.shape
    out = np.zeros((n, nf, nd))
    sel = np.flatnonzero(idx >= 0)
    if sel.size == 0:
        return out
    src = seed.field
    shift = np.broadcast_to(np.asarray(moved_mm, float), (n,))[sel, None]
    iz = (gf.z_mm[sel] - shift - src.z_mm[idx[sel], :1]) / src.dz  # (ns, nf)
    js = (gf.s_mm - src.s_mm[0]) / src.ds  # (nd,)
    k = np.broadcast_to(np.arange(sel.size)[:, None, None], (sel.size, nf, nd))
    coords = np.stack([k, np.broadcast_to(iz[:, :, None], k.shape),
                       np.broadcast_to(js[None, None, :], k.shape)])
    p = ndimage.map_coordinates(seed.pressure_MPa[idx[sel]], coords.reshape(3, -1), order=1,
                                mode="nearest").reshape(sel.size, nf, nd)
    sn = src.s_mm.size
    inside = ((iz[:, :, None] > -0.5) & (iz[:, :, None] < src.z_mm.shape[1] - 0.5)
              & (js[None, None, :] > -0.5) & (js[None, None, :] < sn - 0.5))
    out[sel] = np.where(inside, np.maximum(p, 0.0), 0.0)
    return np.where(gf.mask, out, 0.0)


def solve_surface(spec: CouplingSpec,
                  sweep_result, *, torque_Nm: float, loaded_flank: str | None = None,
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
    T, flank = _torque_and_flank(torque_Nm, loaded_flank)
    _check_grid(grid)
    sw = sweep_result
    N, M = sw.theta_deg.shape
    r_b, R = spec.tooth.base_radius, spec.tooth.pitch_radius
    solver = SurfaceSolver(spec, sw, flank, BendingSprings(compliance, r_b, R), grid=grid,
                           offsets=flank_offsets(gap_offset_rad, FLANKS.index(flank), N),
                           tolerance=tolerance)
    load_N = abs(T) * 1e3 / r_b
    res: dict[str, Any] = {name: np.zeros((N, M)) for name in ARRAYS}
    res["edge_contact"] = np.zeros((N, M), dtype=bool)
    res["patches"] = np.zeros((N, M), dtype=int)
    if load_N == 0:
        windup = _unloaded_poses(solver, res, progress)
        cell: tuple[float, float] = (0.0, 0.0)
        fields: list[dict[str, Any]] = [{} for _ in range(M)]
    else:
        windup, cell, fields = _loaded_poses(solver, sw, flank, load_N, res, keep_fields,
                                             progress)
    res["gap_angle_rad"] = np.where(np.isfinite(res["gap_angle_rad"]), res["gap_angle_rad"],
                                    0.0)
    s_lo, s_hi = (developed_arc(v, r_b) for v in depth_range(spec, solver.mis))
    res.update({
        "windup_rad": windup, "torque_Nm": T, "loaded_flank": flank, "model": "surface",
        "grid": tuple(int(v) for v in grid), "cell_mm": cell,
        "interior_distance_mm": INTERIOR_FRACTION * (s_hi - s_lo),
        "contact_modulus_MPa": solver.e_star,
    })
    if keep_fields:
        res["fields"] = fields
    return res


def surface_solver(sweep_result, *, torque_Nm: float, grid=DEFAULT_GRID, gap_offset_rad=None,
                   tolerance: float = DEFAULT_TOLERANCE, extra_gap=None) -> SurfaceSolver:
    """The :class:`SurfaceSolver` :func:`solve_surface` solves a sweep with at a torque: the
    flank its sign loads, the tooth springs of the spec's ``[load] stiffness``, the gap
    offsets of that flank; ``extra_gap`` as :class:`SurfaceSolver` takes it. Its
    ``solve_pose(j, load_N, start, keep)`` solves one rotation (``load_N = |T| / r_b``)."""
    spec = sweep_result.spec
    _, flank = _torque_and_flank(torque_Nm, None)
    N = sweep_result.theta_deg.shape[0]
    r_b, R = spec.tooth.base_radius, spec.tooth.pitch_radius
    return SurfaceSolver(spec, sweep_result, flank,
                         BendingSprings(tooth_compliance(spec), r_b, R), grid=grid,
                         offsets=flank_offsets(gap_offset_rad, FLANKS.index(flank), N),
                         tolerance=tolerance, extra_gap=extra_gap)


def start_from(sweep_result, solved, rotation: int, flank: str) -> bool:
    """Start the next load on ``sweep_result`` from the pose of rotation ``rotation`` last
    solved on the sweep ``solved`` on ``flank`` (a pose next to it: shifted or tilted by a
    difference step) instead of the last pose solved on ``sweep_result`` or a cold start;
    False where ``solved`` kept no such pose (:data:`KEPT_POSES`). Only where the search
    starts moves: the answer is the same within the solver's tolerance."""
    pose = _POSES.get(solved, {}).get(flank, {}).get(int(rotation))
    if pose is None:
        return False
    _LAST_POSE.setdefault(sweep_result, {})[flank] = pose
    return True


def _torque_and_flank(torque_Nm: Any, loaded_flank: str | None) -> tuple[float, str]:
    """The torque as a finite float and the loaded flank (by default the one its sign
    loads: ccw for >= 0)."""
    try:
        T = float(torque_Nm)
    except (TypeError, ValueError) as err:
        raise ArgumentError("torque_Nm", torque_Nm, "must be a number") from err
    if not math.isfinite(T):
        raise ArgumentError("torque_Nm", torque_Nm, "must be finite")
    flank = loaded_flank if loaded_flank is not None else ("ccw" if T >= 0 else "cw")
    if flank not in FLANKS:
        raise ArgumentError("loaded_flank", loaded_flank, f"must be one of {FLANKS}")
    return T, flank


def _unloaded_poses(solver: SurfaceSolver, res: dict[str, Any], progress) -> NDArray:
    """Zero torque: the unloaded gap angles and contact points into ``res``; the wind-up
    ``(M,)`` is the smallest gap angle of each pose."""
    g = solver.gap
    M = g.shape[1]
    windup = np.min(g, axis=0)
    res["gap_angle_rad"] = g
    res["contact_z_mm"] = np.nan_to_num(solver.contact_z)
    res["contact_r_mm"] = np.nan_to_num(solver.contact_r)
    if progress is not None:
        progress(M, M)
    return windup


def _loaded_poses(solver: SurfaceSolver, sw, flank: str, load_N: float, res: dict[str, Any],
                  keep_fields: bool, progress
                  ) -> tuple[NDArray, tuple[float, float], list[dict[str, Any]]]:
    """Solve the planned poses (each warm-started from the last; the others are the solved
    ones rolled by whole teeth) into ``res``; the wind-up ``(M,)``, the cell size and, with
    ``keep_fields``, the fields of every pose."""
    N, M = sw.theta_deg.shape
    windup = np.zeros(M)
    fields: list[dict[str, Any]] = [{} for _ in range(M)]
    cell = (0.0, 0.0)
    order, source, shift = solver.plan()
    solved: dict[int, tuple] = {}
    # another load on this sweep starts where the last one ended (phases wrap around
    # the pitch, so the last pose neighbours the first)
    last = _LAST_POSE.get(sw, {}).get(flank)
    poses = {}
    for i, j in enumerate(order):
        out, extra, last = solver.solve_pose(int(j), load_N, last, keep_fields)
        solved[int(j)] = (out, extra)
        if order.size <= KEPT_POSES:
            poses[int(j)] = last
        if progress is not None:
            progress(i + 1, order.size)
    _LAST_POSE.setdefault(sw, {})[flank] = last
    if poses:
        _POSES.setdefault(sw, {})[flank] = poses
    for j in range(M):
        out, extra = solved[int(source[j])]
        s = int(shift[j])
        for name in (*ARRAYS, "edge_contact"):
            res[name][:, j] = np.roll(out[name], -s)
        res["gap_angle_rad"][:, j] = solver.gap[:, j]
        windup[j] = extra["windup_rad"]
        cell = extra["cell_mm"]
        if keep_fields:
            fields[j] = {**extra, "teeth": np.mod(extra["teeth"] - s, N)}
    return windup, cell, fields
