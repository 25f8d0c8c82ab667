"""The misaligned contact reference: a sector of teeth at one pose, turned by a wind-up.

At a misalignment every tooth meets its space at its own gap, so the teeth share the
torque unequally and one pitch no longer stands for the coupling. A sector of ``sector``
hub and sleeve teeth, meshed by gmsh with periodic cuts, is posed as the coupling's teeth
``first_tooth ..`` at the turning angle ``rotation_deg`` (the hub in the sleeve frame by
``Rz(-psi) Rx(i) Rz(psi)``, ``psi`` the turning angle of the sector's first tooth;
docs/conventions.md, Frames). The hub bore, a rigid body, turns by the wind-up about the
hub axis: displacement control, since the share of the torque a sector carries is what is
sought. The sleeve outside diameter is fixed. The cuts carry cyclic equations, each about
its own part's axis, so the body beneath the teeth continues as an annulus would instead
of ending clamped or free; the sector's size is the accuracy knob whose effect the
benchmark measures by growing it. The hub is meshed turned beyond the sector's first
touch (the sweep's exact gap angles; exact, as a rotation of the nodes, and from teeth
that touch before the nominal pose as well) by :data:`START_SHARE` of the way to the
wind-up, and the solver turns it on the rest: frictionless and elastic, the answer does
not depend on where the turn starts, but ccx's first contact set is then the flanks'
overlap at that turn, nearer the converged one than none at all, and its contact
iterations fewer. Every hub ccw flank (slave) meets the sleeve ccw flank of its space
(master) through the reference's stiff linear penalty law.

Per tooth: the tangential load (the contact moment about the hub axis / pitch radius),
the peak contact pressure and where the patch lies across the face (load-weighted ``z``,
sleeve frame).
"""

from __future__ import annotations

import math
import resource
from dataclasses import asdict, dataclass, field

import numpy as np

from ..clearance import sweep
from ..errors import ArgumentError
from ..geometry import hub_to_sleeve, rot_z
from ..io import inp_id_lines, inp_number
from ..spec import CouplingSpec, as_spec
from .ccx import run_ccx, solver_dir
from .contact import merge
from .mesh import check_size, mesh_part
from .reference import (
    CONTACT_CHANGE_TOLERANCE,
    CONTACT_SOLVER,
    PENALTY_FACTOR,
    TOLERANCE_MODULES,
    cyclic_equations,
    frd_nodal,
)
from .stiffness import material
from .volume import VolumeMesh
from .write import inp_mesh_lines

#: the hub is meshed turned this share of the way from the sector's first touch to the
#: wind-up (module docstring; before issue 42, -0.01: just short of first touch)
START_SHARE = 0.25
MAX_MISALIGNMENT_DEG = 6.0


@dataclass(frozen=True)
class FESectorResult:
    """One misaligned contact reference pose (module docstring). Per-tooth lists follow
    ``teeth`` (the coupling's tooth numbers); angles rad unless named ``_deg``; the
    ``gap_angle_rad`` is each tooth's exact first touch (the sweep's), ``windup_rad`` the
    imposed turn from the unloaded pose, measured like :attr:`LoadResult.windup_rad`."""

    spec: str
    misalignment_deg: float
    rotation_deg: float
    windup_rad: float
    teeth: list[int]
    theta_deg: list[float]
    gap_angle_rad: list[float]
    tangential_force_N: list[float]
    peak_pressure_MPa: list[float]
    patch_z_mm: list[float | None]
    sector_torque_Nm: float
    size_mm: float
    nodes: int
    solve_seconds: float
    max_rss_MB: float
    settings: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """Plain values, for a JSON file."""
        return asdict(self)


def fe_contact_sector(spec: CouplingSpec, *, misalignment_deg: float, rotation_deg: float,
                      windup_rad: float, first_tooth: int = 0, sector: int = 5,
                      size_mm: float | None = None, tolerance_mm: float | None = None,
                      workdir=None) -> FESectorResult:
    """Solve one pose of a tooth sector turned by ``windup_rad`` (module docstring).

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
        From 0 to 6.
    rotation_deg : float
        Turning angle of the coupling (of its tooth 0), as in :func:`gearcoupling.load`.
    windup_rad : float
        The hub's turn from the unloaded pose; beyond the sector's first touch.
    first_tooth : int
        The coupling's tooth that is the sector's first; the sector holds ``sector`` teeth
        on from it. The teeth two pitches or more from a cut are the ones to compare.
    sector : int
        Teeth in the sector (the cut conditions' accuracy knob), 1 to N - 1.
    size_mm : float, optional
        Element size on the teeth (default module / 4).
    tolerance_mm : float, optional
        Chordal tolerance of the solids (default module x 2e-4).
    workdir : path, optional
        Keep the deck, log and printout here (default: a temporary folder, kept on failure).
    """
    spec = as_spec(spec)
    i, rot, teeth, gaps = _pose(spec, misalignment_deg, rotation_deg, first_tooth, sector)
    touch = float(np.min(gaps))
    if not (isinstance(windup_rad, int | float) and math.isfinite(windup_rad)
            and windup_rad > touch):
        raise ArgumentError("windup_rad", windup_rad, f"a turn (rad) beyond the sector's first "
                            f"touch, {touch:.6g}: below it no tooth carries load")
    size = min(check_size(spec, "hub", size_mm), check_size(spec, "sleeve", size_mm))
    tol = TOLERANCE_MODULES * spec.tooth.module if tolerance_mm is None else tolerance_mm
    hub, sleeve = (mesh_part(spec, part, sector=sector, size_mm=size, periodic=True,
                             tolerance_mm=tol) for part in ("hub", "sleeve"))
    psi = math.radians(rot) + 2 * math.pi * first_tooth / spec.tooth.teeth
    M = hub_to_sleeve(math.radians(i), psi)
    start = touch + START_SHARE * (windup_rad - touch)
    pair = merge(hub, sleeve, M @ rot_z(start))
    E, _ = material(spec, "hub")
    deck = sector_deck(pair, spec, hub_axis=M[:, 2],
                       hub_cut_rotation=M @ rot_z(2 * math.pi * sector / spec.tooth.teeth) @ M.T,
                       turn_rad=windup_rad - start, penalty=PENALTY_FACTOR * E / size)
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, "fe_sector")
        pressure = frd_nodal(res.job.with_suffix(".frd").read_text(), "CONTACT")
    R = spec.tooth.pitch_radius
    peaks, centres = zip(*(_patch(pair, pressure, k) for k in range(sector)), strict=True)
    moment = res.get("forces", "ROTN")[-1][0, 1:4]
    return FESectorResult(
        spec=spec.name, misalignment_deg=i, rotation_deg=rot, windup_rad=float(windup_rad),
        teeth=teeth, theta_deg=[float(np.degrees(psi)) + 360.0 * k / spec.tooth.teeth
                                for k in range(sector)],
        gap_angle_rad=[float(g) for g in gaps],
        tangential_force_N=[_tooth_load(res, k, M[:, 2], R) for k in range(sector)],
        peak_pressure_MPa=list(peaks), patch_z_mm=list(centres),
        sector_torque_Nm=abs(float(moment @ M[:, 2])) * 1e-3, size_mm=size,
        nodes=len(pair.nodes), solve_seconds=res.seconds,
        max_rss_MB=resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,
        settings={"penalty_factor": PENALTY_FACTOR, "sector": sector, "element": "C3D10",
                  "solver": CONTACT_SOLVER,
                  "tolerance_mm": tol, "cuts": "cyclic equations about each part's axis",
                  "start_share": START_SHARE,
                  "contact_change_tolerance": CONTACT_CHANGE_TOLERANCE,
                  "loading": "hub bore turned by the wind-up, sleeve outside fixed"})


def _pose(spec: CouplingSpec, misalignment_deg, rotation_deg, first_tooth, sector):
    """The checked pose: misalignment and rotation (degrees), the sector's coupling teeth
    and their exact gap angles (rad, the loaded ccw flank), or :class:`ArgumentError`."""
    N = spec.tooth.teeth
    i = _angle(misalignment_deg, "misalignment_deg", 0.0, MAX_MISALIGNMENT_DEG)
    rot = _angle(rotation_deg, "rotation_deg", -360.0, 360.0)
    if isinstance(sector, bool) or not (isinstance(sector, int) and 1 <= sector < N):
        raise ArgumentError("sector", sector, f"a whole number of teeth from 1 to {N - 1}")
    if isinstance(first_tooth, bool) or not (isinstance(first_tooth, int)
                                             and 0 <= first_tooth < N):
        raise ArgumentError("first_tooth", first_tooth, f"a tooth number from 0 to {N - 1}")
    teeth = [(first_tooth + k) % N for k in range(sector)]
    return i, rot, teeth, sweep(spec, i, [rot]).gap_angle_rad[1][teeth, 0]


def _angle(value, name: str, lo: float, hi: float) -> float:
    """``value`` as a finite float in ``[lo, hi]`` (degrees), or :class:`ArgumentError`."""
    if not (isinstance(value, int | float) and math.isfinite(value) and lo <= value <= hi):
        raise ArgumentError(name, value, f"an angle from {lo:g} to {hi:g} degrees")
    return float(value)


def sector_deck(pair: VolumeMesh, spec: CouplingSpec, *, hub_axis: np.ndarray,
                hub_cut_rotation: np.ndarray, turn_rad: float, penalty: float,
                increment: float = 1.0) -> str:
    """The deck (module docstring) of a merged sector pair: the rigid hub bore turns by
    ``turn_rad`` about ``hub_axis (3,)``, the hub's cuts tied by ``hub_cut_rotation (3, 3)``
    (the sector angle about the hub axis), the sleeve's by the same angle about z; the
    step starts with ``increment`` of the turn (the solver cuts it where contact does not
    converge; ccx's equation solver :data:`.reference.CONTACT_SOLVER`, its contact-change
    tolerance :data:`.reference.CONTACT_CHANGE_TOLERANCE`). Frictionless and
    elastic, the answer does not depend on the path: on renzo-1967's one-tooth sector at 0°
    one increment gave the load of four quarter increments within 5e-5, in less time."""
    E, nu = material(spec, "hub")
    ref, rot = len(pair.nodes) + 1, len(pair.nodes) + 2
    bore, outer = pair.node_set("H_BORE"), pair.node_set("S_OUTER")
    teeth = pair.teeth or [0]
    lines = inp_mesh_lines(pair)
    lines += ["*NODE", f"{ref}, 0.0, 0.0, 0.0", f"{rot}, 0.0, 0.0, 0.0",
              "*NSET, NSET=ROTN", f"{rot}", "*NSET, NSET=HRIGID", *inp_id_lines(bore + 1),
              "*NSET, NSET=SFIX", *inp_id_lines(outer + 1)]
    lines += cyclic_equations(pair, "H_CUT_CW", "H_CUT_CCW", hub_cut_rotation, bore)
    lines += cyclic_equations(pair, "S_CUT_CW", "S_CUT_CCW",
                              rot_z(2 * math.pi * len(teeth) / spec.tooth.teeth), outer)
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{inp_number(E)}, {inp_number(nu)}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              f"*RIGID BODY, NSET=HRIGID, REF NODE={ref}, ROT NODE={rot}",
              "*SURFACE INTERACTION, NAME=SI",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{inp_number(penalty)}"]
    for k in teeth:
        lines += ["*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE",
                  f"S_H_T{k}_FLANK_CCW, S_S_T{k}_FLANK_CCW"]
    lines += ["*BOUNDARY", "SFIX, 1, 3, 0.0", f"{ref}, 1, 3, 0.0",
              "*STEP, INC=200", f"*STATIC, SOLVER={CONTACT_SOLVER}",
              f"{increment}, 1.0, 1e-4, {increment}",
              "*CONTROLS, PARAMETERS=CONTACT", inp_number(CONTACT_CHANGE_TOLERANCE), "*BOUNDARY"]
    lines += [f"{rot}, {d + 1}, {d + 1}, {inp_number(turn_rad * hub_axis[d])}"
              for d in range(3)]
    lines += ["*NODE PRINT, NSET=ROTN", "U, RF"]
    for k in teeth:
        lines += [f"*CONTACT PRINT, SLAVE=S_H_T{k}_FLANK_CCW, MASTER=S_S_T{k}_FLANK_CCW", "CF"]
    lines += ["*CONTACT FILE", "CSTR", "*END STEP"]
    return "\n".join(lines) + "\n"


def _tooth_load(res, k: int, axis: np.ndarray, R: float) -> float:
    """Tangential load (N) of sector tooth ``k``: its contact moment about ``axis`` / R."""
    stats = res.get("statistics", f"S_H_T{k}_FLANK_CCW")
    fm = stats[-1][0, :6] if stats and stats[-1].shape[1] >= 6 else np.zeros(6)
    return abs(float(np.nan_to_num(fm[3:6]) @ axis)) / R


def _patch(pair: VolumeMesh, pressure: dict, k: int) -> tuple[float, float | None]:
    """Peak pressure (MPa) and load-weighted ``z`` (mm; None: unloaded) of sector tooth
    ``k``'s hub flank."""
    nodes = pair.node_set(f"H_T{k}_FLANK_CCW")
    p = np.array([pressure.get(int(n) + 1, np.zeros(4))[3] for n in nodes])
    if not np.any(p > 0):
        return 0.0, None
    return float(p.max()), float(np.sum(p * pair.nodes[nodes, 2]) / np.sum(p))
