"""Torsion of the bodies that carry the teeth: the hub from its bore to the tooth root and
the sleeve from its tooth root to the outside diameter.

The load models work at the teeth: their wind-up is the rotation that closes the tooth
gaps. Between the bore and the sleeve's outside diameter the bodies twist as well. Each
is an annulus of radii ``a < b`` and length ``L`` in circumferential shear under the
torque: the shear stress ``T / (2 pi r² L)`` gives ``dtheta/dr = T / (2 pi G L r³)``, so

    theta = T / (4 pi G L) (1 / a² - 1 / b²)

(hub: ``a`` the bore radius, ``b`` the root radius, ``L`` the body length; sleeve: ``a``
the root radius, ``b`` the outside radius, ``L`` the sleeve face width). A hub without a
bore is held by its shaft or end faces: its body torsion depends on them and is not
counted (0). The FE contact reference, whose bore is fixed and whose sleeve outside
diameter is a rigid body, holds both parts in its wind-up.
"""

from __future__ import annotations

import math

from ..arguments import torque_Nm as check_torque_Nm
from ..spec import CouplingSpec, as_spec


def annulus_twist_rad(torque_Nmm: float, inner_mm: float, outer_mm: float, length_mm: float,
                      shear_modulus_MPa: float) -> float:
    """Twist of an annulus of radii ``inner_mm < outer_mm`` in circumferential shear."""
    return (torque_Nmm / (4.0 * math.pi * shear_modulus_MPa * length_mm)
            * (1.0 / inner_mm**2 - 1.0 / outer_mm**2))


def body_windup_rad(spec: CouplingSpec, torque_Nm: float) -> dict[str, float]:
    """Body torsion of hub and sleeve at ``torque_Nm`` (module docstring).

    Returns
    -------
    dict
        ``hub_rad``, ``sleeve_rad`` and their sum ``body_rad`` (signed like the torque).
    """
    spec = as_spec(spec)
    T = check_torque_Nm(torque_Nm) * 1e3
    hub, sleeve = spec.hub, spec.sleeve
    root = spec.tooth.pitch_radius - hub.root.dedendum
    bore = 0.5 * hub.body.bore_diameter
    length = max(hub.body.length, hub.face_width)
    hub_rad = (annulus_twist_rad(T, bore, root, length, spec.material.hub.shear_modulus_MPa)
               if bore > 0 else 0.0)
    sleeve_rad = annulus_twist_rad(T, 0.5 * sleeve.major_diameter, 0.5 * sleeve.outer_diameter,
                                   sleeve.face_width, spec.material.sleeve.shear_modulus_MPa)
    return {"hub_rad": hub_rad, "sleeve_rad": sleeve_rad, "body_rad": hub_rad + sleeve_rad}
