"""Flank tolerances of ISO 1328-1:2013 for a tolerance class, as inspection limits.

ISO 1328-1:2013 (Cylindrical gears - ISO system of flank tolerance classification -
Part 1) gives each tolerance as its class-5 value times ``sqrt(2)^(A - 5)`` for the
flank tolerance class ``A = 1 .. 11`` (clause 5.2.2), in micrometres, from the reference
diameter ``d``, the normal module ``m_n`` and the face width ``b`` (mm):

- single pitch, eq. (5): ``f_pT = (0.001 d + 0.4 m_n + 5)``
- total cumulative pitch, eq. (6): ``F_pT = (0.002 d + 0.55 sqrt(d) + 0.7 m_n + 12)``
- profile slope, eq. (7): ``f_HaT = (0.4 m_n + 0.001 d + 4)``
- helix (lead) slope, eq. (10): ``f_HbT = (0.05 sqrt(d) + 0.35 sqrt(b) + 4)``
- runout (the standard's informative annex): ``F_rT = 0.9 F_pT``

each rounded by clause 5.2.3 (above 10 um to 1 um, 5 to 10 um to 0.5 um, below 5 um to
0.1 um). The formulas hold for 5 <= z <= 1000, 5 <= d <= 15 000 mm, 0.5 <= m_n <= 70 mm
and 4 <= b <= 1200 mm and are not to be extrapolated: outside, a class is refused and
the limits must be agreed and set by hand (``[inspection]`` or ``--limit``). A crowned hub
is a spur gear here (helix angle 0); its lead slope is measured against the nominal
crowned lead. The crown height and the tooth thickness have no ISO 1328 tolerance:
a class leaves them unset.
"""

from __future__ import annotations

import math

from ..errors import ArgumentError
from ..spec import CouplingSpec

GRADES = tuple(range(1, 12))
SCOPE = {"teeth": (5, 1000), "reference diameter d (mm)": (5.0, 15_000.0),
         "module m_n (mm)": (0.5, 70.0), "face width b (mm)": (4.0, 1200.0)}
SOURCE = "ISO 1328-1:2013 flank tolerance class {grade} (eqs. 5, 6, 7, 10; F_rT = 0.9 F_pT)"


def iso_round_um(value_um: float) -> float:
    """Clause 5.2.3: above 10 um to the micrometre, 5-10 um to 0.5 um, below to 0.1 um."""
    if value_um > 10.0:
        step = 1.0
    elif value_um >= 5.0:
        step = 0.5
    else:
        step = 0.1
    return round(math.floor(value_um / step + 0.5) * step, 1)


def tolerances_um(d_mm: float, module_mm: float, face_mm: float, grade: int
                  ) -> dict[str, float]:
    """Rounded tolerances (um) of class ``grade``: ``f_pT``, ``F_pT``, ``F_rT``,
    ``f_HaT``, ``f_HbT``."""
    step = math.sqrt(2.0) ** (grade - 5)
    F_pT = (0.002 * d_mm + 0.55 * math.sqrt(d_mm) + 0.7 * module_mm + 12.0) * step
    raw = {"f_pT": (0.001 * d_mm + 0.4 * module_mm + 5.0) * step, "F_pT": F_pT,
           "F_rT": 0.9 * F_pT, "f_HaT": (0.4 * module_mm + 0.001 * d_mm + 4.0) * step,
           "f_HbT": (0.05 * math.sqrt(d_mm) + 0.35 * math.sqrt(face_mm) + 4.0) * step}
    return {k: iso_round_um(v) for k, v in raw.items()}


def grade_limits(spec: CouplingSpec, grade: int, field: str = "grade") -> dict[str, float]:
    """Inspection limits (mm, keys of :data:`~gearcoupling.inspection.LIMITS`) of the
    ISO 1328-1:2013 flank tolerance class ``grade`` for the spec's hub: ``fpt``, ``Fp``,
    ``Fr``, ``f_Halpha``, ``f_Hbeta``. A class outside 1-11, or a hub outside the
    standard's range, is an :class:`ArgumentError` naming ``field``."""
    if isinstance(grade, bool) or grade not in GRADES:
        raise ArgumentError(field, grade, "an ISO 1328-1:2013 flank tolerance class, a whole "
                        "number from 1 (finest) to 11")
    t = spec.tooth
    sizes = {"teeth": t.teeth, "reference diameter d (mm)": 2.0 * t.pitch_radius,
             "module m_n (mm)": t.module, "face width b (mm)": spec.hub.face_width}
    for name, (lo, hi) in SCOPE.items():
        if not lo <= sizes[name] <= hi:
            raise ArgumentError(field, grade, f"{spec.name}'s {name} = {sizes[name]:.4g} is "
                            f"outside ISO 1328-1:2013's range {lo:g}-{hi:g}, where its "
                            "formulas are not extrapolated: set the limits by hand "
                            "([inspection] or --limit)")
    um = tolerances_um(sizes["reference diameter d (mm)"], t.module, spec.hub.face_width,
                       grade)
    keys = {"fpt": "f_pT", "Fp": "F_pT", "Fr": "F_rT", "f_Halpha": "f_HaT", "f_Hbeta": "f_HbT"}
    return {ours: um[iso] * 1e-3 for ours, iso in keys.items()}
