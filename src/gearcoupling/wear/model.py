"""The surface model on worn flanks: one turn of every operating point solved on the current
depth maps, and the wear each turn removes (docs/wear.md, The model).

Per rotation of a turn the surface model solves the pressure on every loaded tooth's grid
(:class:`~gearcoupling.loading.SurfaceSolver`); the worn depths enter its gap field through
the solver's ``extra_gap``: a cell's gap opens by the hub flank's depth at the hub point
facing it plus the sleeve flank's depth at the cell, over ``r_b`` (the solver's gap is the
hub rotation that closes a cell, ``r_b G`` the normal gap; the hub flank's normal is
within the crown slope and the tilt, a few degrees, of the sleeve's, so its depth is taken
as a normal gap, an error below 1 %). Each cell wears both flanks by Archard's law, depth
``k p |v| dt`` with ``v`` the sliding velocity there; summed over the turn this is the
depth per revolution of every point of the hub flank (at the hub point facing the cell)
and of the sleeve flank (at the cell), per unit coefficient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..clearance import sweep
from ..errors import GearCouplingError
from ..geometry import FLANKS, developed_arc, hub_model, hub_to_sleeve, sleeve_model
from ..loading import (
    GapField,
    depth_range,
    face_range,
    gap_field,
    lattice_windows,
    surface_solver,
    turn_phases,
)
from ..spec import CouplingSpec
from .kernels import FlankGrid, deposit_many, sample, sleeve_rows, slip_runs, slip_velocity
from .settings import FLOAT_PHASES, Accuracy, DutyPoint

MAP_CELLS_PER_GRID_CELL = 4  # depth-map cells along the face per pressure-grid cell


@dataclass
class WearMaps:
    """Worn depth (mm along the flank normal) of the flanks: ``hub`` and ``sleeve`` are
    ``(2, T, nz, ns)``, per loaded flank ``(cw, ccw)`` and tooth (``T = 1``: every tooth
    alike), on ``hub_grid`` (hub frame ``z``, the hub point's ``s``) and ``sleeve_grid``
    (sleeve frame)."""

    hub: NDArray[np.float64]
    sleeve: NDArray[np.float64]
    hub_grid: FlankGrid
    sleeve_grid: FlankGrid

    @property
    def teeth(self) -> int:
        return int(self.hub.shape[1])

    def advanced(self, hub_rate: NDArray, sleeve_rate: NDArray, amount: float) -> WearMaps:
        """These maps worn further by ``amount`` times the rates (same shapes)."""
        return WearMaps(self.hub + amount * hub_rate, self.sleeve + amount * sleeve_rate,
                        self.hub_grid, self.sleeve_grid)


class WornGap:
    """The solver's ``extra_gap`` of one loaded flank: the worn depths facing each cell over
    ``r_b`` (rad), and the wear a step will add per MPa on each cell (``local``, mm/MPa
    maps like the depths; None: none) as the cell's own compliance. ``maps``, ``local``
    and ``shift_mm`` (an axial float's position of the hub in the sleeve) are set before
    each solve."""

    def __init__(self, maps: WearMaps, flank: int, r_b: float):
        self.maps, self.flank, self.r_b, self.shift_mm = maps, flank, r_b, 0.0
        self.local: WearMaps | None = None
        self.uniform = maps.teeth == 1

    def __call__(self, j: int, teeth: NDArray[np.intp], gf: GapField) -> NDArray[np.float64]:
        return facing_depth(self.maps, self.flank, teeth, gf, self.r_b, self.shift_mm) / self.r_b

    def compliance(self, j: int, teeth: NDArray[np.intp], gf: GapField) -> NDArray | None:
        if self.local is None:
            return None
        return facing_depth(self.local, self.flank, teeth, gf, self.r_b, self.shift_mm)


def facing_depth(maps: WearMaps, flank: int, teeth: NDArray[np.intp], gf: GapField,
                 r_b: float, shift_mm: float = 0.0) -> NDArray[np.float64]:
    """The worn depth (mm) of hub and sleeve flank facing each cell of ``gf`` ``(n, nf,
    nd)``: the hub's at the hub point facing it, the sleeve's at the cell (moved by an
    axial float's ``shift_mm``)."""
    t = teeth if maps.teeth > 1 else np.zeros(len(teeth), dtype=np.intp)
    hub = sample(maps.hub[flank], maps.hub_grid, t, gf.hub_z_mm,
                 developed_arc(gf.hub_r_mm, r_b), gf.dz, gf.ds)
    sleeve = sample(maps.sleeve[flank], maps.sleeve_grid, t, gf.z_mm[:, :, None] + shift_mm,
                    gf.s_mm[None, None, :], gf.dz, gf.ds)
    return hub + sleeve


def flank_grids(spec: CouplingSpec, duty: tuple[DutyPoint, ...], grid: tuple[int, int]
                ) -> tuple[FlankGrid, FlankGrid]:
    """The depth maps' grids: every active depth and face position any point of the duty
    loads (the widest misalignment's), ``grid``'s rows and four times its cells along the
    face; the sleeve's face also as far as an axial float moves the hub."""
    nf, nd = grid
    mis = math.radians(max(p.misalignment_deg for p in duty))
    r_b = spec.tooth.base_radius
    s_lo, s_hi = (float(developed_arc(r, r_b)) for r in depth_range(spec, mis))
    nz = MAP_CELLS_PER_GRID_CELL * nf
    hz = hub_model(spec).half_face
    Z = face_range(spec, mis) + max(p.axial_float_mm for p in duty)
    return (FlankGrid(-hz, 2 * hz / nz, nz, s_lo, (s_hi - s_lo) / nd, nd),
            FlankGrid(-Z, 2 * Z / nz, nz, s_lo, (s_hi - s_lo) / nd, nd))


@dataclass
class Turn:
    """What one turn of one operating point on the current flanks gives.

    ``hub_rate``, ``sleeve_rate`` ``(T, nz, ns)``: depth per revolution per unit
    coefficient (mm per mm³/(N·m)) of the loaded flank; ``hub_slide``, ``sleeve_slide``
    the same per MPa of pressure where a cell is loaded (mm/MPa: a step's wear per MPa of
    a cell's own pressure, its implicit part); ``bearing_MPa``: the largest pressure each
    hub map cell saw (the tooth bearing picture); ``stats``: the loads (numbers, units in
    the keys); ``solves``: poses solved; ``fields``: with ``keep``, every pose's ``(j,
    teeth, field, pressure, axial float velocity, weight)``."""

    flank: int
    hub_rate: NDArray[np.float64]
    sleeve_rate: NDArray[np.float64]
    hub_slide: NDArray[np.float64]
    sleeve_slide: NDArray[np.float64]
    bearing_MPa: NDArray[np.float64]
    stats: dict[str, float] = field(default_factory=dict)
    solves: int = 0
    fields: list = field(default_factory=list)


class PointSolver:
    """One operating point: its sweep and surface solver, kept between turns (each turn
    starts from the last solved pose)."""

    def __init__(self, spec: CouplingSpec, point: DutyPoint, accuracy: Accuracy,
                 maps: WearMaps, gap_offset_rad: Any = None):
        self.spec, self.point = spec, point
        self.flank = 1 if point.torque_Nm > 0 else 0
        self.r_b = spec.tooth.base_radius
        self.sweep = sweep(spec, point.misalignment_deg, turn_phases(spec, accuracy.phases))
        self.worn = WornGap(maps, self.flank, self.r_b)
        self.solver = surface_solver(self.sweep, torque_Nm=point.torque_Nm,
                                     grid=accuracy.grid, gap_offset_rad=gap_offset_rad,
                                     extra_gap=self.worn)
        self.offsets = flank_offsets(gap_offset_rad, spec.tooth.teeth)
        self.order = self.solver.plan()[0]
        theta = np.radians(self.sweep.theta_deg)
        self.theta = np.mod(theta, 2 * math.pi)
        pose_theta = math.pi - theta if self.flank == 1 else theta  # the ccw flank mirrored
        self.axis = hub_to_sleeve(math.radians(point.misalignment_deg), pose_theta)[..., :, 2]
        _N, M = theta.shape
        self.dpsi = 2 * math.pi / M
        self.load_N = abs(point.torque_Nm) * 1e3 / self.r_b
        self.last = None
        self.rows: tuple | None = None
        a, c = point.axial_float_mm, point.float_cycles_per_rev
        phases = (np.arange(FLOAT_PHASES) + 0.5) * 2 * math.pi / FLOAT_PHASES if a > 0 \
            else np.zeros(1)
        # (hub position in the sleeve, its axial velocity per radian of rotation)
        self.floats = [(a * math.sin(f), a * c * math.cos(f)) for f in phases]

    def _rows(self, gf: GapField):
        if self.rows is None:
            half = sleeve_model(self.spec).half_angle(gf.r_mm)
            polar, tangent, _ = sleeve_rows(gf.r_mm, half, self.r_b)
            self.rows = (polar, tangent)
        return self.rows

    def turn(self, maps: WearMaps, local: WearMaps | None = None, keep: bool = False) -> Turn:
        """Solve a turn on ``maps`` (with ``local``, mm/MPa maps: the wear of a step per
        MPa of a cell's own pressure in series with the contact) and what it wears."""
        self.worn.maps, self.worn.local = maps, local
        acc = _Stats(self, maps.teeth)
        worn = _Wear(maps, self.r_b)
        kept: list = []
        for shift, axial in self.floats:
            self.worn.shift_mm = shift
            acc.new_float(axial)
            for j in self.order:
                out, extra, self.last = self._solve(int(j))
                gf, p, teeth = extra["field"], extra["pressure_MPa"], extra["teeth"]
                polar, tangent = self._rows(gf)
                vz, vs = slip_velocity(self.axis[teeth, j], gf.z_mm, gf.r_mm, polar, tangent,
                                       axial)
                # aligned with ideal teeth the solver solves one tooth for all: each of the
                # loaded teeth is one more sample of the turn
                n_on = int(np.count_nonzero(out["normal_force_N"]))
                samples = n_on if teeth.size == 1 and n_on > 1 else 1
                weight = gf.dz * gf.ds * self.dpsi / len(self.floats) * samples
                slide = np.where(p > 0, np.hypot(vz, vs) * weight, 0.0)  # mm³ per rev
                work = p * slide  # N·mm per rev
                worn.add(gf, p, teeth, work, slide, shift)
                if keep:
                    kept.append((int(j), teeth, gf, p, axial, weight))
                acc.pose(j, out, extra, gf, p, teeth, vz, vs, work / samples)
        return worn.turn(self.flank, acc.done(), acc.solves, kept)

    def _solve(self, j: int):
        """Rotation ``j`` from the last solved pose; where its search does not settle from
        there (a worn flank's load split can cycle at the solver's tolerance), cold."""
        try:
            return self.solver.solve_pose(j, self.load_N, self.last, True)
        except GearCouplingError:
            if self.last is None:
                raise
            return self.solver.solve_pose(j, self.load_N, None, True)

    def backlash_mm(self, maps: WearMaps, fields: dict) -> float:
        """The backlash at the sweep's first rotation on the worn flanks (arc at the pitch
        radius): each flank's smallest gap angle over the teeth, the sweep's exact one
        moved by what the wear adds to the smallest cell gap of each tooth's whole-face
        grid (:func:`worn_gap_shift`)."""
        g = 0.0
        for f in (0, 1):
            if f not in fields:
                fields[f] = self._face_field(f)
            shift = worn_gap_shift(maps, f, fields[f], self.r_b)
            g += float(np.min(self.sweep.gap_angle_rad[f][:, 0] + self.offsets[f] + shift))
        return self.spec.tooth.pitch_radius * g

    def _face_field(self, f: int) -> GapField:
        """The whole-face gap field of flank ``f`` of every tooth at the first rotation."""
        N = self.theta.shape[0]
        nf, nd = self.solver.grid
        mis = math.radians(self.point.misalignment_deg)
        z, _ = lattice_windows(self.spec, mis, 0, np.zeros(N), nf)
        return gap_field(self.spec, mis, np.radians(self.sweep.theta_deg[:, 0]), FLANKS[f], z,
                         nd)


def flank_offsets(gap_offset_rad: Any, teeth: int) -> NDArray[np.float64]:
    """Per-tooth gap offsets ``(2, N)`` of the flanks ``(cw, ccw)`` from ``None``, ``(N,)``
    (both flanks) or ``(2, N)`` (already checked by the surface solver)."""
    if gap_offset_rad is None:
        return np.zeros((2, teeth))
    return np.broadcast_to(np.asarray(gap_offset_rad, float), (2, teeth))


def worn_gap_shift(maps: WearMaps, flank: int, gf: GapField, r_b: float) -> NDArray:
    """What the worn depths add to each tooth's smallest contactable cell gap (rad) of
    ``gf`` ``(N,)`` (a whole-face field of every tooth, teeth in order)."""
    teeth = np.arange(gf.gap_rad.shape[0])
    worn = gf.gap_rad + facing_depth(maps, flank, teeth, gf, r_b) / r_b
    far = np.inf
    return (np.min(np.where(gf.mask, worn, far), axis=(1, 2))
            - np.min(np.where(gf.mask, gf.gap_rad, far), axis=(1, 2)))


class _Wear:
    """What the poses of a turn wear, summed on the depth maps' grids (per unit
    coefficient: the work in N·mm, ``k`` in mm³/(N·m)), and the tooth bearing picture."""

    def __init__(self, maps: WearMaps, r_b: float):
        T, hg, sg = maps.teeth, maps.hub_grid, maps.sleeve_grid
        self.T, self.hg, self.sg, self.r_b = T, hg, sg, r_b
        self.hub, self.hub_slide, self.bearing = (np.zeros((T, hg.nz, hg.ns)) for _ in range(3))
        self.sleeve, self.sleeve_slide = (np.zeros((T, sg.nz, sg.ns)) for _ in range(2))

    def add(self, gf: GapField, p, teeth, work, slide, shift: float) -> None:
        """A pose's ``work`` and ``slide`` (per cell, per revolution) on the hub at the
        hub points facing the cells and on the sleeve at the cells (moved by ``shift``)."""
        hg, sg, T = self.hg, self.sg, self.T
        t = teeth if T > 1 else np.zeros(teeth.size, dtype=np.intp)
        s_hub = developed_arc(gf.hub_r_mm, self.r_b)
        share = gf.dz * gf.ds / hg.area_mm2
        w_hub, s_hub_, cover, seen = deposit_many(
            [work, slide, np.where(gf.mask, share, 0.0), p * share], hg, t, gf.hub_z_mm,
            s_hub, gf.dz, gf.ds, T)
        w_sl, s_sl = deposit_many([work, slide], sg, t, gf.z_mm[:, :, None] + shift,
                                  gf.s_mm[None, None, :], gf.dz, gf.ds, T)
        self.hub += w_hub
        self.hub_slide += s_hub_
        self.sleeve += w_sl
        self.sleeve_slide += s_sl
        # the tooth bearing picture: the mean pressure over each hub map cell's covered
        # part, where a pose's grid covers at least half of it
        np.maximum(self.bearing, np.where(cover > 0.5, seen / np.maximum(cover, 0.5), 0.0),
                   out=self.bearing)

    def turn(self, flank: int, stats, solves: int, kept: list) -> Turn:
        hk, sk = 1e-3 / self.hg.area_mm2, 1e-3 / self.sg.area_mm2
        return Turn(flank, self.hub * hk, self.sleeve * sk, self.hub_slide * hk,
                    self.sleeve_slide * sk, self.bearing, stats, solves, kept)


class _Stats:
    """The loads of a turn's poses, and its passes for the partial-slip test."""

    def __init__(self, ps: PointSolver, T: int):
        self.ps, self.T = ps, T
        _N, M = ps.theta.shape
        self.lattice = M  # samples of a tooth over the turn (every dpsi of turning angle)
        self.peak_N = self.peak_MPa = self.interior_MPa = 0.0
        self.edge = 0
        self.contact: list[int] = []
        self.approach = math.inf
        self.work = 0.0
        self.solves = 0
        self.partial = 0.0
        self.ratio = math.inf
        self.slip: tuple | None = None
        self.axial = 0.0

    def new_float(self, axial: float = 0.0):
        self._flush()
        self.axial = axial
        shape = (self.T, self.lattice)
        self.slip = (np.zeros(shape, bool), np.zeros(shape), np.zeros(shape), np.zeros(shape),
                     np.zeros(shape))

    def pose(self, j, out, extra, gf, p, teeth, vz, vs, work):
        self.solves += 1
        W = out["normal_force_N"]
        self.peak_N = max(self.peak_N, float(np.max(out["tangential_force_N"])))
        self.peak_MPa = max(self.peak_MPa, float(np.max(out["max_pressure_MPa"])))
        self.interior_MPa = max(self.interior_MPa, float(np.max(out["interior_pressure_MPa"])))
        self.edge = max(self.edge, int(np.sum(out["edge_contact"])))
        self.contact.append(int(np.sum(W > 0)))
        if np.any(p > 0):
            # the elastic approach: the largest elastic displacement (half-space and
            # bending) over the cells in contact, a step's own wear there left out
            r_b = self.ps.r_b
            local = gf.local_compliance_mm_per_MPa
            g = r_b * gf.gap_rad + (0.0 if local is None else local * p)
            elastic = r_b * extra["windup_rad"] - np.min(np.where(p > 0, g, np.inf))
            self.approach = min(self.approach, float(elastic))
        alike = teeth.size == 1 and np.sum(W > 0) > 1  # aligned: one tooth stands for all
        self.work += float(np.sum(work)) * (int(np.sum(W > 0)) if alike else 1)
        self._passes(j, np.flatnonzero(W > 0) if alike else teeth, alike, gf, p, vz, vs,
                     work)

    def _passes(self, j, teeth, alike, gf, p, vz, vs, work):
        """Each loaded tooth's sliding velocity at its load centre (less an axial float's)
        and half-width of its patch along the sliding direction, on the turn's lattice."""
        on, slip_z, slip_s, width, wk = self.slip
        P = np.sum(p, axis=(1, 2))
        axial = self.axial
        for n, tooth in enumerate(teeth):
            i = 0 if alike else n
            if not P[i] > 0:
                continue
            w = p[i] / P[i]
            uz, us = float(np.sum(w * vz[i])), float(np.sum(w * vs[i]))
            speed = math.hypot(uz, us)
            zz, ss = np.broadcast_arrays(gf.z_mm[i][:, None], gf.s_mm[None, :])
            cells = p[i] > 0
            if speed > 0:
                proj = (zz[cells] * uz + ss[cells] * us) / speed
                cell = (abs(uz) * gf.dz + abs(us) * gf.ds) / speed
                half = 0.5 * (float(np.ptp(proj)) + cell)
            else:
                half = 0.0
            if self.T == 1:
                t, k = 0, round(self.ps.theta[tooth, j] / self.ps.dpsi) % self.lattice
            else:
                t, k = int(tooth), int(j)
            on[t, k], slip_z[t, k], slip_s[t, k], width[t, k] = True, uz - axial, us, half
            wk[t, k] += float(np.sum(work[i]))

    def _flush(self):
        if self.slip is None:
            return
        share, ratio = slip_runs(*self.slip, self.ps.dpsi, self.ps.point.axial_float_mm)
        total = float(np.sum(self.slip[4]))
        self.partial += share * total
        self.ratio = min(self.ratio, ratio)

    def done(self) -> dict[str, float]:
        self._flush()
        self.slip = None
        spec = self.ps.spec
        R, N = spec.tooth.pitch_radius, spec.tooth.teeth
        T = abs(self.ps.point.torque_Nm)
        return {"max_tooth_load_N": self.peak_N,
                "q": T * 1e3 / (R * N * self.peak_N) if self.peak_N > 0 else 0.0,
                "max_pressure_MPa": self.peak_MPa,
                "max_interior_pressure_MPa": self.interior_MPa,
                "teeth_in_contact": float(np.mean(self.contact)) if self.contact else 0.0,
                "edge_contact_teeth": float(self.edge),
                "approach_mm": self.approach if math.isfinite(self.approach) else 0.0,
                "archard_work_N_mm_per_rev": self.work,
                "partial_slip_share": self.partial / self.work if self.work > 0 else 0.0,
                "slip_to_half_width": self.ratio}


__all__ = ["PointSolver", "Turn", "WearMaps", "WornGap", "facing_depth", "flank_grids",
           "flank_offsets", "worn_gap_shift"]
