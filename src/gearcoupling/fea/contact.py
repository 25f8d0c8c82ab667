"""One loaded pose with CalculiX surface-to-surface contact between hub and sleeve teeth.

A hub sector and a sleeve sector of the same teeth (``0 .. k-1``) are meshed, the hub is
placed in the sleeve frame at the pose (misalignment ``i``, turning angle ``psi``,
docs/conventions.md, Frames: ``Rz(-psi) Rx(i) Rz(psi)``), and the hub bore and cut faces are tied
to a
rigid body that turns by the wind-up ``windup_rad`` about the hub axis (displacement
control, so the run needs no initial contact); the sleeve outside diameter and cut faces
are fixed. Every hub ccw flank (slave) meets the sleeve ccw flank of its space (master)
through a linear penalty contact (``*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR``,
stiffness ``penalty_factor * E / size``), frictionless. Reported per tooth: contact
normal force, its moment about the hub axis as a tangential load at the pitch radius,
peak contact pressure (at the slave nodes), and the torque of the sector.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import ArgumentError
from ..geometry import hub_to_sleeve
from ..io import inp_id_lines, inp_number
from ..spec import CouplingSpec
from .ccx import run_ccx, solver_dir
from .mesh import mesh_part
from .stiffness import material
from .volume import VolumeMesh
from .write import inp_mesh_lines


def merge(hub: VolumeMesh, sleeve: VolumeMesh, hub_rotation: np.ndarray) -> VolumeMesh:
    """One mesh of the posed hub (regions ``H_...``) and the sleeve (``S_...``)."""
    off_n, off_e = len(hub.nodes), len(hub.tets)
    nodes = np.vstack([hub.nodes @ hub_rotation.T, sleeve.nodes])
    tets = np.vstack([hub.tets, sleeve.tets + off_n])
    regions = {f"H_{k}": v for k, v in hub.regions.items()}
    regions |= {f"S_{k}": v + off_n for k, v in sleeve.regions.items()}
    faces = {f"H_{k}": v for k, v in hub.faces.items()}
    faces |= {f"S_{k}": v + np.array([off_e, 0]) for k, v in sleeve.faces.items()}
    quality = {"hub": hub.quality, "sleeve": sleeve.quality}
    return VolumeMesh("pair", nodes, tets, regions, faces, hub.teeth, hub.size_mm, quality)


def contact_deck(pair: VolumeMesh, spec: CouplingSpec, *, windup_rad: float, axis: np.ndarray,
                 penalty: float, teeth: list[int], increments: int = 10) -> str:
    """The contact deck of a merged pair: rigid hub bore + cuts turned by ``windup_rad``
    about ``axis`` (3,), sleeve fixed, one penalty contact pair per tooth in ``teeth``."""
    E, nu = material(spec, "hub")
    n = len(pair.nodes)
    ref, rot = n + 1, n + 2
    rigid = np.unique(np.concatenate([pair.node_set(r) for r in pair.regions
                                      if r in ("H_BORE", "H_CUT_CW", "H_CUT_CCW")]))
    lines = inp_mesh_lines(pair)
    lines += ["*NODE", f"{ref}, 0.0, 0.0, 0.0", f"{rot}, 0.0, 0.0, 0.0",
              "*NSET, NSET=ROTN", f"{rot}", "*NSET, NSET=HRIGID"]
    lines += inp_id_lines(rigid + 1)
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{inp_number(E)}, {inp_number(nu)}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              f"*RIGID BODY, NSET=HRIGID, REF NODE={ref}, ROT NODE={rot}",
              "*SURFACE INTERACTION, NAME=SI",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{inp_number(penalty)}"]
    for k in teeth:
        lines += ["*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE",
                  f"S_H_T{k}_FLANK_CCW, S_S_T{k}_FLANK_CCW"]
    lines += ["*BOUNDARY", "S_OUTER, 1, 3, 0.0", "S_CUT_CW, 1, 3, 0.0", "S_CUT_CCW, 1, 3, 0.0",
              f"{ref}, 1, 3, 0.0",
              "*STEP, INC=200", "*STATIC", f"{1.0 / increments}, 1.0", "*BOUNDARY"]
    lines += [f"{rot}, {d + 1}, {d + 1}, {inp_number(windup_rad * axis[d])}" for d in range(3)]
    lines += ["*NODE PRINT, NSET=ROTN", "RF"]
    for k in teeth:
        lines += [f"*CONTACT PRINT, SLAVE=S_H_T{k}_FLANK_CCW, MASTER=S_S_T{k}_FLANK_CCW",
                  "CF"]
    lines += ["*CONTACT PRINT", "CSTR", "*END STEP"]
    return "\n".join(lines) + "\n"


def contact_pose(spec: CouplingSpec, *, misalignment_deg: float, psi_deg: float, windup_rad: float,
                 sector: int = 3, size_mm: float | None = None, penalty_factor: float = 20.0,
                 workdir=None) -> dict:
    """Solve one loaded pose with contact (module docstring); returns the per-tooth table."""
    if not (math.isfinite(windup_rad) and windup_rad > 0):
        raise ArgumentError("windup_rad", windup_rad, "a positive wind-up angle (rad)")
    t0 = time.perf_counter()
    hub = mesh_part(spec, "hub", sector=sector, size_mm=size_mm)
    sleeve = mesh_part(spec, "sleeve", sector=sector, size_mm=size_mm)
    t_mesh = time.perf_counter() - t0
    i, psi = math.radians(misalignment_deg), math.radians(psi_deg)
    M = hub_to_sleeve(i, psi)
    pair = merge(hub, sleeve, M)
    teeth = list(range(sector))
    E, _ = material(spec, "hub")
    penalty = penalty_factor * E / hub.size_mm
    deck = contact_deck(pair, spec, windup_rad=windup_rad, axis=M[:, 2], penalty=penalty,
                        teeth=teeth)
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, "contact")
    R = spec.tooth.pitch_radius
    moment = res.get("forces", "ROTN")[-1][0, 1:4]
    torque = float(moment @ M[:, 2]) * 1e-3  # N mm -> N m: moment the rigid body applies
    rows = _tooth_rows(res, pair, teeth, M, R)
    total = sum(r["tangential_force_N"] for r in rows)
    for r in rows:
        r["load_share"] = r["tangential_force_N"] / total if total > 0 else 0.0
    return {"spec": spec.name, "misalignment_deg": misalignment_deg, "psi_deg": psi_deg,
            "windup_rad": windup_rad, "torque_Nm": torque, "teeth": rows,
            "penalty_MPa_per_mm": penalty, "size_mm": hub.size_mm,
            "elements": len(pair.tets), "mesh_seconds": t_mesh, "solve_seconds": res.seconds}


def _tooth_rows(res, pair, teeth, M, R) -> list[dict]:
    """Per tooth: slave-surface force and moment (contact statistics) and peak pressure."""
    rows = []
    stress = res.last("contact stress")
    axis = M[:, 2]
    for k in teeth:
        name = f"S_H_T{k}_FLANK_CCW"
        stats = res.get("statistics", name)
        fm = stats[-1][0, :6] if stats and stats[-1].shape[1] >= 6 else np.zeros(6)
        fm = np.nan_to_num(fm)
        elems = set((pair.faces[f"H_T{k}_FLANK_CCW"][:, 0] + 1).tolist())
        press = [] if stress is None else [r[-3] for r in stress if int(r[0]) in elems]
        rows.append({"tooth": k, "normal_force_N": float(np.linalg.norm(fm[:3])),
                     "tangential_force_N": abs(float(fm[3:6] @ axis)) / R,
                     "max_pressure_MPa": float(max(press)) if press else 0.0})
    return rows
