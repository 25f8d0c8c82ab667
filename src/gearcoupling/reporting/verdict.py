"""The report's verdict table: each check against its limit, and the limits not set.

A check is ``pass`` or ``fail`` only against a limit; where the spec sets none (no
allowable tooth load, no inspection tolerance, no scan) it is ``not judged`` and says
which key would set it. Limits that come from a default rather than the spec (the steel
allowable stresses of ``[material]``) are judged and say so.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..loadspec import STEEL
from ..spec import CouplingSpec

PASS, FAIL, OPEN = "pass", "fail", "not judged"


@dataclass(frozen=True)
class Verdict:
    """One row: what is checked, the value found, the limit, where the limit comes from,
    the verdict and, when not judged, why."""

    check: str
    value: str
    limit: str
    source: str
    verdict: str
    reason: str = ""

    def row(self) -> tuple[str, ...]:
        text = self.verdict if not self.reason else f"{self.verdict}: {self.reason}"
        return (self.check, self.value, self.limit, self.source, text)


COLUMNS = ("check", "found", "limit", "limit from", "verdict")


def judge(value: float, limit: float, *, at_most: bool = True) -> str:
    ok = value <= limit if at_most else value >= limit
    return PASS if ok else FAIL


def geometry_verdicts(design_deg: float, min_backlash_mm: float, critical_deg: float | None,
                      binding_deg: float | None) -> list[Verdict]:
    """No binding and the contact kept off the face ends at the misalignment reported."""
    out = [Verdict("teeth do not bind: smallest backlash over a turn",
                   f"{min_backlash_mm * 1e3:.2f} µm at {design_deg:g}°", "> 0",
                   "geometry (binding angle " + (f"{binding_deg:.3f}°)" if binding_deg
                                                 else "beyond 6°)"),
                   PASS if min_backlash_mm > 0 else FAIL)]
    if critical_deg is None:
        out.append(Verdict("contact stays off the face ends (pivot teeth)", f"{design_deg:g}°",
                           "no face end reached up to 6°", "geometry", PASS))
    else:
        out.append(Verdict("contact stays off the face ends (pivot teeth)", f"{design_deg:g}°",
                           f"≤ critical misalignment {critical_deg:.3f}°", "geometry",
                           judge(design_deg, critical_deg)))
    return out


def _material_source(spec: CouplingSpec, key: str) -> str:
    mats = (spec.material.hub, spec.material.sleeve)
    if all(getattr(m, key) == STEEL[key] for m in mats):
        return "default steel value (not set in [material])"
    return "[material] (smaller of hub and sleeve)"


def load_verdicts(spec: CouplingSpec, res, capacity_at_design) -> list[Verdict]:
    """Tooth load, contact pressure, root stress and torque capacity at the reported load
    (``res`` None: no torque, nothing judged)."""
    if res is None:
        why = "no torque: set [load] torque_Nm or --torque"
        return [Verdict(c, "–", "–", "–", OPEN, why) for c in
                ("tooth load ≤ allowable tooth load", "contact pressure ≤ allowable",
                 "root bending stress ≤ allowable", "torque ≤ capacity at the misalignment")]
    mat = spec.material
    out = []
    P_max = float(np.max(res.tangential_force_N))
    P_i = spec.load.allowable_tooth_load_N
    if P_i is None:
        out.append(Verdict("tooth load ≤ allowable tooth load P_i", f"{P_max:.4g} N", "–",
                           "–", OPEN, "no limit set ([load] allowable_tooth_load_N)"))
    else:
        out.append(Verdict("tooth load ≤ allowable tooth load P_i", f"{P_max:.4g} N",
                           f"{P_i:.4g} N", "[load] allowable_tooth_load", judge(P_max, P_i)))
    p = float(np.max(res.interior_pressure_MPa))
    p_allow = min(mat.hub.allowable_contact_stress_MPa, mat.sleeve.allowable_contact_stress_MPa)
    out.append(Verdict(f"contact pressure ≤ allowable ({res.model} model, interior)",
                       f"{p:.4g} MPa", f"{p_allow:.4g} MPa",
                       _material_source(spec, "allowable_contact_stress_MPa"), judge(p, p_allow)))
    s = float(np.max(res.root_stress_MPa))
    s_allow = min(mat.hub.allowable_bending_stress_MPa, mat.sleeve.allowable_bending_stress_MPa)
    out.append(Verdict("root bending stress ≤ allowable", f"{s:.4g} MPa", f"{s_allow:.4g} MPa",
                       _material_source(spec, "allowable_bending_stress_MPa"),
                       judge(s, s_allow)))
    T = abs(res.torque_Nm)
    cap = None if capacity_at_design is None else capacity_at_design.capacity_Nm
    if cap is None:
        out.append(Verdict("torque ≤ capacity at the misalignment", f"{T:.4g} N·m", "–", "–",
                           OPEN, "no criterion reaches its limit"))
    else:
        out.append(Verdict("torque ≤ capacity at the misalignment", f"{T:.4g} N·m",
                           f"{cap:.4g} N·m ({capacity_at_design.governing.replace('_', ' ')}"
                           " governs)", f"capacity × K = {spec.load.accuracy_factor:g}",
                           judge(T, cap)))
    edge = int(np.max(np.sum(res.edge_contact, axis=0)))
    out.append(Verdict("no contact patch reaches a face end at this torque",
                       f"{edge} teeth at worst", "0 teeth", "geometry (edge contact)",
                       PASS if edge == 0 else FAIL))
    return out


def interference_verdict(result, reason: str = "") -> Verdict:
    """No overlap of the posed meshes (``result`` None: the check did not run)."""
    check = "no mesh interference at the misalignment"
    if result is None:
        return Verdict(check, "–", "0 mm³", "meshes", OPEN, reason)
    vol = float(np.max(result.overlap_volume_mm3))
    return Verdict(check, f"{vol:.3g} mm³ overlap at worst", "0 mm³",
                   f"meshes at {result.tolerance_mm:.3g} mm chordal tolerance",
                   FAIL if result.interferes else PASS)


def inspection_verdicts(report) -> list[Verdict]:
    """The measured part's limits (``report`` None: no scan given)."""
    if report is None:
        return [Verdict("measured part within its tolerances", "–", "–", "–", OPEN,
                        "no scan given (--scan FILE)")]
    out = []
    for v in report.part["verdicts"]:
        value = "–" if v["measured_mm"] is None else f"{v['measured_mm'] * 1e3:.2f} µm"
        if v["limit_mm"] is None:
            out.append(Verdict(f"measured {v['what']}", value, "–", "–", OPEN,
                               f"{v['reason']} ([inspection] {v['limit']}, --limit or --grade)"))
        else:
            out.append(Verdict(f"measured {v['what']}", value, f"{v['limit_mm'] * 1e3:.2f} µm",
                               "inspection limits", v["verdict"], "" if v["verdict"] != OPEN
                               else v["reason"]))
    return out


def overall(rows: list[Verdict]) -> tuple[str, str]:
    """``(css class, sentence)``: FAIL naming the failed checks, else PASS on what was
    judged and the count of checks not judged."""
    failed = [r.check for r in rows if r.verdict == FAIL]
    open_ = [r for r in rows if r.verdict == OPEN]
    judged = len(rows) - len(open_)
    tail = f"; {len(open_)} not judged (no limit or no input): see the verdict table" \
        if open_ else ""
    if failed:
        return "fail", f"FAIL: {len(failed)} of {judged} judged checks fail ({'; '.join(failed)})" \
            + tail
    if judged == 0:
        return "open", "NOT JUDGED: no check had a limit" + tail
    return ("open" if open_ else "pass"), f"PASS on all {judged} judged checks" + tail
