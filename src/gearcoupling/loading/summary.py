"""``load_summary.json``: sharing, pressures, machine loads and wear of a LoadResult.

Machine loads (docs/conventions.md, Loaded analysis, Wei's additional moment): every loaded tooth
pushes the hub
with ``-W n`` (``n`` the exact hub flank normal at the contact point) plus Coulomb friction
``-mu W t`` against the hub's sliding velocity ``t`` at that point. Hub and sleeve turn at
the same speed about their own axes, so the sliding velocity per unit speed is
``(a_hub - a_sleeve) x p`` (mm/rad), projected onto the flank. Summed over the teeth and
taken about O in the hub frame: the net radial force, the axial thrust along the hub axis
and the tilting (additional) moment perpendicular to the axis, per rotation.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..geometry import form_radius, hub_flank_model, hub_model, tip_radius
from .accuracy import springs_name, tooth_load_error, windup_error
from .contact import REGIMES
from .springs import tooth_compliance


def contact_frames(res) -> tuple[NDArray, NDArray]:
    """Contact points and outward unit flank normals ``(N, M, 3)`` of every tooth in the hub
    frame at each rotation, with x along the tilt axis."""
    m = hub_model(res.spec)
    z = np.clip(res.contact_z_mm, -m.half_face, m.half_face)
    r = np.clip(res.contact_r_mm, form_radius(m, z), tip_radius(m, z))
    p, n, _ = hub_flank_model(m, res.loaded_flank, z, r, check=False)
    th = np.radians(res.theta_deg)
    c, s = np.cos(th), np.sin(th)

    def rot(v):
        return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1],
                         v[..., 2]], axis=-1)

    return rot(p), rot(n)


def sliding(res, p: NDArray, n: NDArray) -> NDArray:
    """Sliding velocity of the hub on the sleeve per unit speed, in the flank plane (mm/rad)."""
    i = math.radians(res.misalignment_deg)
    axis_diff = np.array([0.0, 0.0, 1.0]) - np.array([0.0, math.sin(i), math.cos(i)])
    v = np.cross(axis_diff, p)
    return v - np.sum(v * n, axis=-1, keepdims=True) * n


def machine_loads(res) -> dict[str, NDArray]:
    """Per rotation ``(M,)``: radial force (N), axial thrust (N), tilting moment (N·m) and the
    torque carried about the hub axis (N·m, a check on equilibrium with friction)."""
    p, n = contact_frames(res)
    v = sliding(res, p, n)
    speed = np.linalg.norm(v, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(speed[..., None] > 1e-12, v / speed[..., None], 0.0)
    mu = res.spec.load.friction
    W = res.normal_force_N[..., None]
    f = -W * (n + mu * t)  # on the hub
    F = np.sum(f, axis=0)  # (M, 3)
    M = np.sum(np.cross(p, f), axis=0) * 1e-3
    return {"radial_force_N": np.hypot(F[:, 0], F[:, 1]), "axial_force_N": F[:, 2],
            "tilting_moment_Nm": np.hypot(M[:, 0], M[:, 1]), "torque_about_axis_Nm": M[:, 2],
            "sliding_mm_per_rad": speed}


def rotation_table(res) -> dict[str, NDArray]:
    """Per rotation ``(M,)``: the rotation, teeth in contact, the largest tooth load,
    pressures and root stress, wind-up, mesh stiffness and the machine loads (units in the
    keys)."""
    loads = machine_loads(res)
    return {"psi_deg": np.asarray(res.angles_deg, float),
            "teeth_in_contact": np.sum(res.in_contact, axis=0),
            "max_tooth_load_N": np.max(res.tangential_force_N, axis=0),
            "max_interior_pressure_MPa": np.max(res.interior_pressure_MPa, axis=0),
            "max_pressure_MPa": np.max(res.max_pressure_MPa, axis=0),
            "max_root_stress_MPa": np.max(res.root_stress_MPa, axis=0),
            "windup_deg": np.degrees(res.windup_rad),
            "mesh_stiffness_Nm_per_rad": res.mesh_stiffness_Nm_per_rad,
            "radial_force_N": loads["radial_force_N"], "axial_force_N": loads["axial_force_N"],
            "tilting_moment_Nm": loads["tilting_moment_Nm"]}


def _range(a: NDArray) -> dict[str, float]:
    return {"min": float(np.min(a)), "mean": float(np.mean(a)), "max": float(np.max(a))}


def summarise(res) -> dict[str, Any]:
    """The ``load_summary.json`` keys."""
    P = res.tangential_force_N
    n_contact = np.sum(res.in_contact, axis=0)
    loads = machine_loads(res)
    v = loads.pop("sliding_mm_per_rad")
    # wear per tooth over the rotations given (a full turn with the CLI default): Archard
    # index sum W |v| dpsi (N·mm per rad of speed ... per revolution when the angles span one)
    dpsi = 2 * math.pi / res.angles_deg.size
    archard = np.sum(res.normal_force_N * v, axis=1) * dpsi
    pv = np.max(res.interior_pressure_MPa * v, axis=1)
    regimes = {name: int(np.sum(res.contact_regime == k)) for k, name in enumerate(REGIMES)
               if k > 0}
    out = {
        "spec": res.spec.name, "model": res.model, "stiffness": res.spec.load.stiffness,
        "accuracy": accuracy_notes(res.spec, res.model),
        "torque_Nm": res.torque_Nm,
        "loaded_flank": res.loaded_flank, "misalignment_deg": res.misalignment_deg,
        "angles": int(res.angles_deg.size), "teeth": res.teeth,
        "max_tooth_load_N": float(np.max(P)), "max_normal_force_N":
        float(np.max(res.normal_force_N)), "q": res.q(), "load_sharing_factor": 1.0 / res.q(),
        "teeth_in_contact": _range(n_contact),
        "max_pressure_MPa": float(np.max(res.max_pressure_MPa)),
        "max_interior_pressure_MPa": float(np.max(res.interior_pressure_MPa)),
        "max_root_stress_MPa": float(np.max(res.root_stress_MPa)),
        "edge_contact_teeth_max": int(np.max(np.sum(res.edge_contact, axis=0))),
        "contact_regimes": regimes,
        "mesh_torsional_stiffness_Nm_per_rad": _range(res.mesh_stiffness_Nm_per_rad),
        "windup_deg": _range(np.degrees(res.windup_rad)),
        "radial_force_N": _range(loads["radial_force_N"]),
        "axial_force_N": _range(loads["axial_force_N"]),
        "tilting_moment_Nm": _range(loads["tilting_moment_Nm"]),
        "torque_about_axis_Nm": _range(loads["torque_about_axis_Nm"]),
        "max_sliding_velocity_mm_per_rad": float(np.max(v * res.in_contact)),
        "pv_max_MPa_mm_per_rad_per_tooth": pv.tolist(),
        "archard_index_N_mm_per_rev_per_tooth": archard.tolist(),
        "limits": _limits(res),
    }
    return out


def accuracy_notes(spec, model: str) -> dict[str, Any]:
    """What the accuracy ladder measured for this model and its springs (docs/load.md), and
    what of the spec lies outside the range the springs were fitted on."""
    springs = springs_name(spec, model)
    outside = getattr(tooth_compliance(spec), "outside", []) if springs == "fe-fit" else []
    return {"springs": springs, "windup": windup_error(model, springs),
            "tooth_load": tooth_load_error(model, springs), "outside_fitted_range": outside}


def _limits(res) -> list[str]:
    """Plain-language notes where the loads leave what the estimates cover."""
    notes = []
    if np.any(res.edge_contact):
        notes.append("a contact patch reaches a face end (edge contact): max_pressure_MPa is a "
                     "truncated-Hertz estimate there, see edge_load_share")
    mat = res.spec.material
    if np.max(res.root_stress_MPa) > min(mat.hub.allowable_bending_stress_MPa,
                                         mat.sleeve.allowable_bending_stress_MPa):
        notes.append("root bending stress exceeds the allowable")
    if np.max(res.interior_pressure_MPa) > min(mat.hub.allowable_contact_stress_MPa,
                                               mat.sleeve.allowable_contact_stress_MPa):
        notes.append("contact pressure exceeds the allowable")
    P_i = res.spec.load.allowable_tooth_load_N
    if P_i is not None and np.max(res.tangential_force_N) > P_i:
        notes.append("tooth load exceeds the allowable tooth load")
    return notes
