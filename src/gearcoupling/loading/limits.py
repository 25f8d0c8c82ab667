"""The capacity criteria as per-tooth limit loads: the normal tooth load at which each
criterion is reached at each contact point (independent of the torque; the load models'
capacity searches find the torque that brings the first tooth there)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..spec import CouplingSpec
from .contact import contact_model
from .inputs import nominal_root_stress_MPa

CRITERIA = ("tooth_load", "contact_stress", "bending_stress")


def limit_loads(spec: CouplingSpec, z: NDArray, r: NDArray, compliance) -> dict[str, NDArray]:
    """Normal tooth loads (N) at which each criterion is reached at each contact point, and
    ``face_end``: the load at which the patch reaches the face end. ``inf`` = never."""
    cosphi = math.cos(spec.tooth.pressure_angle)
    cm = contact_model(spec)
    geo = cm.geometry(z, r)
    mat = spec.material
    out: dict[str, NDArray] = {}
    if spec.load.allowable_tooth_load_N is not None:
        out["tooth_load"] = np.full(z.shape, spec.load.allowable_tooth_load_N / cosphi)
    p_allow = min(mat.hub.allowable_contact_stress_MPa, mat.sleeve.allowable_contact_stress_MPa)
    out["contact_stress"] = cm.pressure_limit_load(p_allow, geo)
    s_allow = min(mat.hub.allowable_bending_stress_MPa, mat.sleeve.allowable_bending_stress_MPa)
    per_N = nominal_root_stress_MPa(spec, np.ones(z.shape), z, r)
    out["bending_stress"] = s_allow / per_N
    room = np.maximum(cm.half_face - np.abs(geo["z"]), 0.0)
    out["face_end"] = np.where(room > 0, cm.half_length_limit_load(room, geo), 0.0)
    return out
