"""The report's verdict table: each check against its limit, and the limits not set.

A check is ``pass`` or ``fail`` only against a limit; where the spec sets none (no
allowable tooth load, no inspection tolerance, no scan) it is ``not judged`` and says
which key would set it. Limits that come from a default rather than the spec (the steel
allowable stresses of ``[material]``) are judged and say so.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..loading import TOOTH_LOAD_RATIO, springs_name
from ..spec import STEEL, CouplingSpec

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
    band_crosses: bool = False  # the model's measured error band crosses the limit

    def row(self) -> tuple[str, ...]:
        text = self.verdict if not self.reason else f"{self.verdict}: {self.reason}"
        return (self.check, self.value, self.limit, self.source, text)


COLUMNS = ("check", "found", "limit", "limit from", "verdict")


def judge(value: float, limit: float, *, at_most: bool = True) -> str:
    ok = value <= limit if at_most else value >= limit
    return PASS if ok else FAIL


def load_band(model: str, springs: str) -> tuple[float, float] | None:
    """What a tooth load of ``model`` with ``springs`` may be in truth, as factors on it:
    the accuracy ladder's CalculiX-sector / model load on the most loaded teeth (None:
    not measured)."""
    return TOOTH_LOAD_RATIO.get((model, springs))


def judged(check: str, value: float, limit: float, shown: tuple[str, str, str],
           band: tuple[float, float] | None, *, scales_with_load: bool = True) -> Verdict:
    """A check of ``value`` at most ``limit``, with its margin and whether the model's
    error band crosses the limit (``band``: factors on the load; a capacity scales
    inversely, ``scales_with_load`` False); ``shown``: the value, limit and source texts."""
    text, crosses = margin(value, limit, band, scales_with_load=scales_with_load)
    return Verdict(check, *shown, judge(value, limit), text, crosses)


def margin(value: float, limit: float, band: tuple[float, float] | None, *,
           scales_with_load: bool = True) -> tuple[str, bool]:
    """The margin of ``value`` to ``limit`` as text, and whether the model's error band
    reaches the other side of the limit from the verdict's (arguments as :func:`judged`).
    With ``scales_with_load`` the model made ``value`` (a load, a stress: in truth ``value
    x band``); else it made ``limit`` (a capacity, which scales inversely: in truth
    ``limit / band``)."""
    text = f"margin {100.0 * (limit - value) / limit:+.1f} %"
    if band is None:
        return text + "; no measured error band for this model and springs", False
    passes = value <= limit
    if scales_with_load:
        lo, hi = band
        low, high = value * lo, value * hi
        crosses = high > limit if passes else low <= limit
        what = f"{lo:.2f}–{hi:.2f} × the value: {low:.4g}–{high:.4g}"
    else:
        lo, hi = 1.0 / band[1], 1.0 / band[0]
        low, high = limit * lo, limit * hi
        crosses = low < value if passes else high >= value
        what = f"{lo:.2f}–{hi:.2f} × the capacity: {low:.4g}–{high:.4g}"
    where = ("crosses the limit: the check could go the other way" if crosses else
             "stays on the same side of the limit")
    return f"{text}; the model's measured error band ({what}, docs/load.md) {where}", crosses


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


def load_verdicts(spec: CouplingSpec, res) -> list[Verdict]:
    """Tooth load, contact pressure, root stress and edge contact at the reported load
    (``res`` None: no torque, nothing judged)."""
    if res is None:
        why = "no torque: set [load] torque_Nm or --torque"
        return [Verdict(c, "–", "–", "–", OPEN, why) for c in
                ("tooth load ≤ allowable tooth load", "contact pressure ≤ allowable",
                 "root bending stress ≤ allowable")]
    mat = spec.material
    out = []
    band = load_band(res.model, springs_name(spec, res.model))
    P_max = float(np.max(res.tangential_force_N))
    P_i = spec.load.allowable_tooth_load_N
    if P_i is None:
        out.append(Verdict("tooth load ≤ allowable tooth load P_i", f"{P_max:.4g} N", "–",
                           "–", OPEN, "no limit set ([load] allowable_tooth_load_N)"))
    else:
        out.append(judged("tooth load ≤ allowable tooth load P_i", P_max, P_i,
                          (f"{P_max:.4g} N", f"{P_i:.4g} N", "[load] allowable_tooth_load"),
                          band))
    p = float(np.max(res.interior_pressure_MPa))
    p_allow = min(mat.hub.allowable_contact_stress_MPa, mat.sleeve.allowable_contact_stress_MPa)
    root = None if band is None else (band[0] ** 0.5, band[1] ** 0.5)  # p ~ sqrt(W)
    out.append(judged(f"contact pressure ≤ allowable ({res.model} model, interior)", p,
                      p_allow, (f"{p:.4g} MPa", f"{p_allow:.4g} MPa",
                                _material_source(spec, "allowable_contact_stress_MPa")), root))
    s = float(np.max(res.root_stress_MPa))
    s_allow = min(mat.hub.allowable_bending_stress_MPa, mat.sleeve.allowable_bending_stress_MPa)
    out.append(judged("root bending stress ≤ allowable", s, s_allow,
                      (f"{s:.4g} MPa", f"{s_allow:.4g} MPa",
                       _material_source(spec, "allowable_bending_stress_MPa")), band))
    edge = int(np.max(np.sum(res.edge_contact, axis=0)))
    out.append(Verdict("no contact patch reaches a face end at this torque",
                       f"{edge} teeth at worst", "0 teeth", "geometry (edge contact)",
                       PASS if edge == 0 else FAIL))
    return out


def capacity_verdict(spec: CouplingSpec, res, at) -> Verdict:
    """The torque of ``res`` against the capacity at its misalignment (``at``: a
    :class:`~gearcoupling.Capacity`; None: not computed)."""
    check = "torque ≤ capacity at the misalignment"
    if res is None:
        return Verdict(check, "–", "–", "–", OPEN, "no torque: set [load] torque_Nm or "
                       "--torque")
    T = abs(res.torque_Nm)
    if at is None or at.capacity_Nm is None:
        return Verdict(check, f"{T:.4g} N·m", "–", "–", OPEN,
                       "no criterion reaches its limit" if at is not None else
                       "the capacity was not computed")
    gov = at.governing.replace("_", " ")
    K = spec.load.accuracy_factor
    band = load_band(res.model, springs_name(spec, res.model))
    return judged(check, T, at.capacity_Nm,
                  (f"{T:.4g} N·m", f"{at.capacity_Nm:.4g} N·m = K × {at.capacity_Nm / K:.4g} "
                   f"N·m ({gov} governs, K = {K:g})", f"capacity × K = {K:g}"), band,
                  scales_with_load=False)


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
    judged and the count of checks not judged; either naming the checks whose limit lies
    within the model's measured error band."""
    failed = [r.check for r in rows if r.verdict == FAIL]
    open_ = [r for r in rows if r.verdict == OPEN]
    n_judged = len(rows) - len(open_)
    tail = f"; {len(open_)} not judged (no limit or no input): see the verdict table" \
        if open_ else ""
    close = [r.check for r in rows if r.band_crosses]
    if close:
        tail += ("; the model's measured error band crosses the limit of: "
                 + "; ".join(close))
    if failed:
        return "fail", (f"FAIL: {len(failed)} of {n_judged} judged checks fail "
                        f"({'; '.join(failed)})" + tail)
    if n_judged == 0:
        return "open", "NOT JUDGED: no check had a limit" + tail
    return ("open" if open_ else "pass"), f"PASS on all {n_judged} judged checks" + tail
