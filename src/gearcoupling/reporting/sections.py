"""The report's sections, one :class:`~.view.ReportSection` each in :data:`SECTIONS`: the
stages it shows, a renderer that lays out their results (tables, notes and the stages'
own figures and data files) and the verdicts it judges. A section computes nothing and
writes nothing: the stages did (:mod:`gearcoupling.outputs`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ..clearance import SweepResult
from ..geometry import renzo_z0_mm
from ..hob import MeasuringCharts
from ..inspection import InspectionReport
from ..loading import LoadResult, load_model, springs_name, tooth_load_error, windup_error
from ..outputs import (
    BacklashCurve,
    CapacityAgainstMisalignment,
    Check,
    CrownProfile,
    DesignPoint,
    Hob,
    QGraph,
    Rating,
    StaticViewer,
)
from ..spec import CouplingSpec
from ..wear import WearResult
from .datasheet import datasheet
from .document import Block, Note, Row, Table, Viewer
from .verdict import (
    FAIL,
    OPEN,
    PASS,
    Verdict,
    capacity_verdict,
    geometry_verdicts,
    inspection_verdicts,
    interference_verdict,
    load_verdicts,
)
from .view import ReportSection, View
from .whole import whole, whole_datasheet, whole_verdicts


def _sweep_settings(sw: SweepResult) -> str:
    return (f"Sweep of the exact flanks: {sw.angles_deg.size} rotations, flank-table "
            f"tolerance {sw.tolerance_mm:.3g} mm (table error {sw.table_error_mm:.2g} mm), "
            f"i = {sw.misalignment_deg:g}°.")


def _load_settings(spec: CouplingSpec, res: LoadResult) -> str:
    springs = springs_name(spec, res.model)
    return (f"{res.model} model, {springs} tooth springs ({windup_error(res.model, springs)}; "
            f"{tooth_load_error(res.model, springs)}), T = {res.torque_Nm:.4g} N·m on the "
            f"{res.loaded_flank} flanks, friction {spec.load.friction:g}, "
            f"{res.angles_deg.size} rotations, i = {res.misalignment_deg:g}°.")


# --------------------------------------------------------------------------- coupling


def _flatten(data: dict, prefix: str = "") -> list[tuple[str, Any]]:
    rows: list[tuple[str, Any]] = []
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            rows += _flatten(value, f"{name}.")
        elif isinstance(value, list):
            if value:
                rows.append((name, ", ".join(f"{v:g}" if isinstance(v, float) else str(v)
                                             for v in value)))
        else:
            rows.append((name, value))
    return rows


def coupling(v: View) -> list[Block]:
    spec = v.spec
    data = spec.to_dict()
    prof = v.get("sections", CrownProfile)
    blocks: list[Block] = [
        Note(f"{spec.name}: {spec.tooth.teeth} teeth, module {spec.tooth.module:.4g} mm, "
             f"pressure angle {math.degrees(spec.tooth.pressure_angle):g}°, face width "
             f"{spec.hub.face_width:.4g} mm, {spec.hub.crowning.kind} crown (R_c "
             f"{spec.derived['crowning_radius_midplane_mm']:.4g} mm at the midplane), design "
             f"misalignment {spec.design_misalignment_deg:g}°. Lengths in mm, angles in "
             f"degrees, as resolved from the spec file (written in {spec.units})."),
        Row([Table(("spec key", "value"),
                   _flatten({k: data[k] for k in ("tooth", "hub", "sleeve", "load",
                                                  "material", "coupling", "alignment",
                                                  "hub_b") if k in data}),
                   "The resolved spec."),
             Table(("derived value", "value"), list(spec.derived.items()),
                   "Derived values (renzo_z0 at the design angle: Renzo eq. 4).")])]
    if prof is not None:
        blocks.append(v.figure("sections", "Transverse sections and the crown along the face",
                               "sections.png", f"Exact tooth sections at chordal tolerance "
                               f"{prof.tolerance_mm:.3g} mm; crown profile at "
                               f"{prof.z_mm.size} planes.", "crown_profile.csv"))
    return blocks


# --------------------------------------------------------------------------- clearance


def clearance(v: View) -> list[Block]:
    sw = v.get("sweep", SweepResult)
    if sw is None:
        return [Note(f"Not computed: {v.why('sweep')}", "skip")]
    summ = sw.summary()
    rows = [("aligned backlash", summ["aligned_backlash_mm"] * 1e3, "µm"),
            ("smallest backlash over the turn", summ["min_backlash_mm"] * 1e3, "µm"),
            ("largest backlash over the turn", summ["max_backlash_mm"] * 1e3, "µm"),
            *((f"smallest circumferential clearance, {f} flank",
               summ["min_clearance_mm"][f] * 1e3, "µm") for f in ("cw", "ccw")),
            *((f"separation peak to peak on the pitch line (normal), {f}",
               summ["pitch_line_peak_to_peak_normal_mm"][f] * 1e3, "µm") for f in ("cw", "ccw")),
            ("largest |z| of first touch", summ["max_contact_z_mm"], "mm"),
            ("half face width", summ["half_face_mm"], "mm")]
    how = _sweep_settings(sw)
    return [Table(("quantity", "value", "unit"), rows,
                  f"At i = {sw.misalignment_deg:g}°, over {sw.angles_deg.size} rotations."),
            v.figure("clearance", "Clearance of every tooth against the rotation (Renzo "
                     "Fig. 10)", "sweep_clearance.png", how, "sweep.csv"),
            v.figure("backlash", "Backlash over the turn", "sweep_backlash_over_turn.png", how,
                     "backlash_over_turn.csv"),
            v.figure("contact-path", "Where each tooth touches first (Wei Fig. 9)",
                     "sweep_contact_path.png", how, "sweep.csv")]


def design_angles(v: View) -> list[Block]:
    """Critical and binding misalignment, contact travel and z0 with Renzo's estimates."""
    spec, mis = v.spec, v.point.misalignment_deg
    dq, sw = v.get("design", DesignPoint), v.get("sweep", SweepResult)
    curve = v.get("backlash", BacklashCurve)
    if dq is None or sw is None or curve is None:
        return [Note(f"Not computed: {v.why('sweep')}", "skip")]
    rc = spec.derived["crowning_radius_midplane_mm"]
    phi = spec.tooth.pressure_angle
    half = 0.5 * spec.hub.face_width
    B = spec.derived["aligned_backlash_mm"]
    finite = math.isfinite(rc)
    est_crit = math.degrees(half / (rc / math.tan(phi))) if finite else None
    est_bind = math.degrees(math.atan(math.sqrt(B * math.sin(phi) / rc))) if finite else None
    z0 = renzo_z0_mm(rc, math.radians(mis), phi) if finite else None
    sep = max(sw.summary()["pitch_line_peak_to_peak_normal_mm"].values())
    travel = dq.quantities["pivot_contact_z_mm"]
    uniform = "" if spec.hub.crowning.kind == "circular" else \
        " (uniform-crown estimate with the midplane R_c)"
    rows = [
        ("critical misalignment (contact reaches a face end)", dq.critical_deg, est_crit, "deg",
         f"b/2 = R_c cot φ · i{uniform}"),
        ("binding angle (smallest backlash over a turn = 0)", dq.binding_deg, est_bind, "deg",
         f"Δb = 2 z0 / cos φ = aligned backlash (eqs. 4, 6){uniform}"),
        (f"contact travel on the pivot teeth at {mis:g}° (pitch line)",
         travel["pitch_line_z_mm"], travel["renzo_mm"], "mm", f"R_c cot φ · i{uniform}"),
        (f"largest separation z0 at {mis:g}° (pitch line, normal)", sep, z0, "mm",
         f"z0 = ½ R_c cot φ tan² i (eq. 4){uniform}"),
    ]
    table = [(q, c, e, None if (c is None or e is None or e == 0) else (c - e) / e * 100, u, f)
             for q, c, e, u, f in rows]
    return [Table(("quantity", "computed", "Renzo's estimate", "difference %", "unit",
                   "estimate"), table,
                  "Computed by root finding on the exact geometry to "
                  f"{dq.quantities['design_angle_tolerance_deg']:g}° "
                  f"({dq.quantities['design_rotations_per_pitch']} rotations per tooth "
                  "pitch); – where the coupling does not reach it by 6° or the crown is "
                  "straight."),
            v.figure("backlash-vs-misalignment", "Smallest backlash over a turn against "
                     "misalignment", "sweep_backlash.png", f"{curve.misalignments_deg.size} "
                     "misalignments, 8 rotations per tooth pitch each.",
                     "backlash_vs_misalignment.csv")]


def design_verdicts(v: View) -> list[Verdict]:
    dq, sw = v.get("design", DesignPoint), v.get("sweep", SweepResult)
    if dq is None or sw is None:
        return []
    return geometry_verdicts(v.point.misalignment_deg, sw.summary()["min_backlash_mm"],
                             dq.critical_deg, dq.binding_deg)


# --------------------------------------------------------------------------- loads


def loads(v: View) -> list[Block]:
    spec = v.spec
    res = v.get("load", LoadResult)
    if res is None:
        return [Note(f"Not computed: {v.why('load')}; the loads and the capacity verdict "
                     "are not judged.", "skip")]
    summ = res.summary()
    P = summ["max_normal_force_N"]
    tc = summ["teeth_in_contact"]
    rows = [("largest tangential tooth load P", summ["max_tooth_load_N"], "N"),
            ("Renzo's load proportion q = T / (R N P_max)", summ["q"], ""),
            ("load sharing factor 1/q", summ["load_sharing_factor"], ""),
            ("teeth in contact (min / mean / max)", f"{tc['min']:.0f} / {tc['mean']:.1f} / "
             f"{tc['max']:.0f}", f"of {res.teeth}"),
            ("largest contact pressure (interior, grid independent)",
             summ["max_interior_pressure_MPa"], "MPa"),
            ("largest contact pressure (peak)", summ["max_pressure_MPa"], "MPa"),
            ("largest root bending stress", summ["max_root_stress_MPa"], "MPa"),
            ("wind-up (mean)", summ["windup_deg"]["mean"], "deg"),
            ("mesh torsional stiffness (mean)", summ["mesh_torsional_stiffness_Nm_per_rad"]
             ["mean"], "N·m/rad"),
            ("tilting moment on the machine (mean / max)",
             f"{summ['tilting_moment_Nm']['mean']:.4g} / {summ['tilting_moment_Nm']['max']:.4g}",
             "N·m"),
            ("axial thrust (mean)", _noise_free(summ["axial_force_N"]["mean"], P), "N"),
            ("radial force (mean)", _noise_free(summ["radial_force_N"]["mean"], P), "N")]
    how = _load_settings(spec, res)
    blocks: list[Block] = [Table(("quantity", "value", "unit"), rows, how)]
    blocks += [Note(text, "warn") for text in summ["limits"]]
    outside = summ["accuracy"]["outside_fitted_range"]
    if outside:
        blocks.append(Note("The fe-fit tooth springs are evaluated outside the range they "
                           f"were fitted on ({'; '.join(outside)}): their error there is not "
                           "measured; --set load.stiffness=fe computes this spec's own FE "
                           "table.", "warn"))
    j = int(np.argmax(np.max(res.tangential_force_N, axis=0)))
    grid = load_model(res.model).pressure_grid
    blocks += [
        v.figure("tooth-load", "Tooth load against the turning angle (Renzo Fig. 11)",
                 "load_tooth_load.png", how, "load.csv"),
        v.figure("loads-over-turn", "Teeth in contact, stresses and machine loads over the "
                 "rotations", "load_over_turn.png", how, "loads_over_turn.csv"),
        v.figure("patches", "Contact pressure on the developed flanks, the most loaded teeth "
                 "and every tooth", "load_patches.png",
                 how + f" Rotation ψ = {res.angles_deg[j]:.3g}°"
                 + (", its solved pressure grid." if grid else
                    " (the largest tooth load); analytic maps on a 481 × 61 grid"),
                 "contact_patches.csv")]
    return blocks + q_graph(v)


def _noise_free(value: float, scale: float) -> float:
    """``value`` or 0 where it is rounding noise of sums of forces of size ``scale``."""
    return 0.0 if abs(value) < 1e-9 * max(scale, 1.0) else value


def q_graph(v: View) -> list[Block]:
    """Renzo's q graph with the linear model's points (needs the allowable tooth load and
    Renzo's mesh stiffness C)."""
    graph = v.get("q_graph", QGraph)
    if graph is None:
        return [Note(f"Not drawn: {v.why('q_graph')}.", "skip")]
    ld = v.spec.load
    return [v.figure("q-graph", "Renzo's load proportion q against z_c / z0",
                     "load_q_graph.png", f"Linear model (C = {ld.mesh_stiffness_N_per_mm:.4g} "
                     f"N/mm, P_i = {ld.allowable_tooth_load_N:.4g} N) at {len(graph.points)} "
                     f"misalignments to {graph.top_deg:g}°, 25 rotations per tooth pitch.",
                     "q_graph.csv")]


def loads_verdicts(v: View) -> list[Verdict]:
    return load_verdicts(v.spec, v.get("load", LoadResult))


# --------------------------------------------------------------------------- capacity


def capacity(v: View) -> list[Block]:
    cap = v.get("capacity", CapacityAgainstMisalignment)
    if cap is None:
        return [Note(f"Not computed: {v.why('capacity')}", "skip")]
    at, flank = cap.at_point, v.point.flank
    rows = [(f"{k.replace('_', ' ')}", val, "N·m") for k, val in at.criteria_Nm.items()]
    rows += [("governing capacity K·T", at.capacity_Nm, f"N·m ({at.governing.replace('_', ' ')}"
              f", K = {at.accuracy_factor:g})"),
             ("torque at which a patch reaches a face end", at.face_end_torque_Nm, "N·m"),
             ("aligned capacity K N P_i R (Renzo)", at.aligned_capacity_Nm, "N·m"),
             ("q at the governing torque", at.q, ""),
             ("largest tooth load at the governing torque", at.max_tooth_load_N, "N")]
    mis = cap.misalignments_deg
    return [Table(("criterion / quantity", "value", "unit"), rows,
                  f"At i = {v.point.misalignment_deg:g}° ({at.model} model, {flank} flanks, "
                  f"K = {at.accuracy_factor:g}); a criterion without its limit is left out."),
            v.figure("capacity", "Capacity per criterion against misalignment, design point "
                     "starred", "capacity.png",
                     f"{at.model} model, {mis.size} misalignments 0–{cap.top_deg:.3g}° (to the "
                     "critical misalignment)"
                     f"{', the operating point among them' if flank == 'ccw' else ''}, "
                     f"{load_model(at.model).rotations} rotations over one tooth pitch each, "
                     "loaded flank ccw.", "capacity.csv")]


def capacity_verdicts(v: View) -> list[Verdict]:
    rating = v.get("rating", Rating)
    return [capacity_verdict(v.spec, v.get("load", LoadResult),
                             None if rating is None else rating.capacity)]


# --------------------------------------------------------------------------- wear


def wear(v: View) -> list[Block]:
    """The wear history at the operating point: the life with its band, the flanks'
    depth maps and tooth bearing pictures over time, backlash, q and pressure against
    hours, and what the numbers rest on (partial slip)."""
    res = v.get("wear", WearResult)
    if res is None:
        return [Note(f"Not computed: {v.why('wear')}", "skip")]
    summ = res.summary()
    s, p = res.settings, res.duty[0]
    lo, hi = res.life_band_h
    start, end = summ["loads_start"], summ["loads_end"]
    flank = "ccw" if p.torque_Nm > 0 else "cw"
    rows = [("life to the wear limit", res.life_h, f"h ({res.life_basis})"),
            (f"life across the {s.regime} band", f"{lo:.4g} – {hi:.4g}", "h"),
            ("required life", s.required_life_h, "h ([wear] required_life_h)"),
            ("hours run", summ["hours"], f"h in {res.steps} steps"),
            ("wear limit: tooth thinning", summ["limit_thickness_loss_mm"]["hub"],
             f"mm ({s.limit_fraction:g} of the hub tooth's thickness)"),
            ("largest worn depth, hub / sleeve",
             f"{summ['max_depth_mm']['hub'] * 1e3:.4g} / "
             f"{summ['max_depth_mm']['sleeve'] * 1e3:.4g}", "µm"),
            ("backlash, start → end", f"{res.backlash_mm[0, 0] * 1e3:.4g} → "
             f"{res.backlash_mm[-1, 0] * 1e3:.4g}", "µm"),
            ("q, start → end", f"{start['q'][0]:.3g} → {end['q'][0]:.3g}", ""),
            ("peak pressure, start → end", f"{start['max_pressure_MPa'][0]:.4g} → "
             f"{end['max_pressure_MPa'][0]:.4g}", "MPa"),
            ("teeth with edge contact, start → end",
             f"{start['edge_contact_teeth'][0]:.0f} → {end['edge_contact_teeth'][0]:.0f}", "")]
    how = (f"Archard wear at i = {p.misalignment_deg:g}°, T = {p.torque_Nm:.4g} N·m on the "
           f"{flank} flanks, {p.speed_rpm:.4g} rpm; k = {s.coefficient_mm3_per_Nm:.3g} "
           f"mm³/(N·m) ({s.regime}), sleeve factor {s.sleeve_factor:g}; surface model on "
           f"{res.accuracy.grid[0]} × {res.accuracy.grid[1]} cells, {res.accuracy.phases} "
           f"rotations per tooth pitch, a step at most {res.accuracy.step_fraction:g} of the "
           "elastic approach (docs/wear.md).")
    return [Table(("quantity", "value", "unit"), rows, how),
            *(Note(text, "warn") for text in res.notes()),
            Note(f"The coefficient's source: {s.source}."),
            v.figure("wear-maps", "Worn depth on the developed flanks over time, beside the "
                     "tooth bearing pictures", "wear_maps.png", how, "wear_depth.csv"),
            v.figure("wear-history", "Depth, backlash, q and pressure against hours",
                     "wear_history.png", how, "wear.csv")]


def wear_verdicts(v: View) -> list[Verdict]:
    """The life against ``[wear] required_life_h``, judged only where the spec sets it
    (nothing where no wear was computed)."""
    res = v.get("wear", WearResult)
    if res is None:
        return []
    check = "wear life ≥ required life"
    found = f"{res.life_h:.4g} h ({res.life_basis})"
    need = res.settings.required_life_h
    if need is None:
        return [Verdict(check, found, "–", "–", OPEN, "no limit set ([wear] required_life_h)")]
    lo, hi = res.life_band_h
    crosses = lo < need <= hi
    where = ("crosses the limit: the check could go the other way" if crosses else
             "stays on the same side of the limit")
    return [Verdict(check, found, f"≥ {need:.4g} h", "[wear] required_life_h",
                    PASS if res.life_h >= need else FAIL,
                    f"across the {res.settings.regime} band {lo:.4g}–{hi:.4g} h: {where}",
                    crosses)]


# --------------------------------------------------------------------------- checks


def interference(v: View) -> list[Block]:
    found = v.get("check", Check)
    if found is None:
        return [Note(f"Not run: {v.why('check')}", "skip")]
    result = found.result
    summ = result.summary()
    rows = [("poses over the turn", summ["angles"], ""),
            ("overlap volume (largest)", summ["max_overlap_volume_mm3"], "mm³"),
            ("overlap depth (largest)", summ["max_overlap_depth_mm"], "mm"),
            ("smallest mesh gap", summ["min_gap_mm"], "mm"),
            ("smallest exact normal clearance (sweep)",
             None if found.reference_mm is None else float(np.min(found.reference_mm)), "mm"),
            ("mesh chordal tolerance", summ["tolerance_mm"], "mm"),
            ("triangles hub / sleeve", f"{summ['triangles_hub']} / {summ['triangles_sleeve']}",
             "")]
    return [Table(("quantity", "value", "unit"), rows),
            v.figure("interference", "Overlap volume and minimum gap of the posed meshes",
                     "interference.png", f"{result.method} method on {result.model}, "
                     f"{result.angles_deg.size} poses, meshes at {result.tolerance_mm:.3g} mm;"
                     " dashed: the sweep's exact clearance.", "interference.csv")]


def interference_verdicts(v: View) -> list[Verdict]:
    found = v.get("check", Check)
    return [interference_verdict(None if found is None else found.result,
                                 "" if found is not None else f"not run: {v.why('check')}")]


def manufacturing(v: View) -> list[Block]:
    blocks: list[Block] = []
    hob = v.get("hob", Hob)
    if hob is None:
        blocks.append(Note(f"Hob program not made: {v.why('hob')}", "skip"))
    else:
        prog = hob.program
        summ = prog.summary()
        if hob.illustrative:
            blocks.append(Note(f"Hob outside diameter {prog.hob_diameter_mm:g} mm is an "
                               "illustrative size (max(50, 20 module)); give --hob-diameter "
                               "for your hob.", "warn"))
        blocks.append(Table(("hob program", "value"),
                            [(k, val) for k, val in summ.items() if k not in ("spec", "notes")],
                            "Lengths in mm; X = hob centre distance, Z = axial position."))
        blocks += [Note(note, "warn") for note in summ["notes"]]
        blocks.append(v.figure("hob-path", "Hob centre path over the face", "hob_path.png",
                               f"{summ['arc_moves']} arcs and {summ['line_moves']} lines, "
                               f"chordal tolerance {prog.tolerance_mm:.3g} mm (largest "
                               f"deviation {prog.max_deviation_mm:.2g} mm). Program: "
                               "hob_program.nc.", "hob_path.csv"))
    charts = v.get("charts", MeasuringCharts)
    if charts is not None:
        blocks.append(v.figure("measuring-charts", "Nominal profile and lead measuring charts",
                               "charts.png", "Exact flank traces, 101 points each, tip "
                               "exclusion 8 %.", "nominal_traces.csv"))
    return blocks


def measured(v: View) -> list[Block]:
    rep = v.get("inspection", InspectionReport)
    if rep is None:
        return [Note(f"Not inspected: {v.why('inspection')}", "skip")]
    s = v.settings
    part = rep.part
    source = (f"{len(s.scan)} points" if isinstance(s.scan, np.ndarray)
              else Path(str(s.scan)).name)
    rows = [("source", source), ("points", rep.points),
            ("teeth measured", part["teeth_measured"]),
            ("registration rms", f"{rep.registration.rms_mm * 1e3:.2f} µm"),
            ("runout datum", part["runout_datum"])]
    how = (f"Registration on {s.fit_points} points, flank table 61 × 41; "
           + (f"ISO 1328-1:2013 class {s.grade} limits. " if s.grade else ""))
    return [Table(("inspection", "value"), rows),
            Table(("limit", "what", "worst measured (mm)", "limit (mm)", "verdict"),
                  [(x["limit"], x["what"], x["measured_mm"], x["limit_mm"],
                    x["verdict"] + (f" ({x['reason']})" if x["reason"] else ""))
                   for x in part["verdicts"]], "Not judged: no limit set for it "
                  "([inspection], --limit or --grade).", verdict_column=4),
            v.figure("inspection", "Per tooth pitch, runout, thickness and crown",
                     "inspection.png", how, "inspection.csv"),
            v.figure("deviation-map", "Flank deviation map", "deviation_map.png", how,
                     "inspection.csv")]


def measured_verdicts(v: View) -> list[Verdict]:
    return inspection_verdicts(v.get("inspection", InspectionReport))


def view3d(v: View) -> list[Block]:
    scene = v.get("viewer", StaticViewer)
    if scene is None:
        return [Note(f"Not included: {v.why('viewer')}", "skip")]
    if v.point.coupling is not None:
        return [Viewer(scene.html, "The whole coupling at the shaft alignment, rotation 0, "
                       "every part placed, each mesh's hub flanks coloured by its clearance "
                       "at its angle; the sleeve rings in quarter cutaway, the floating "
                       "member's plain parts translucent (drag to turn, scroll to zoom; "
                       "gearcoupling view SPEC has sliders for the offset and angle).")]
    return [Viewer(scene.html, f"Hub and sleeve at i = {scene.misalignment_deg:g}°, rotation "
                   "0, quarter cutaway, coloured by clearance (drag to turn, scroll to zoom).")]


#: the report's sections in their order
SECTIONS: tuple[ReportSection, ...] = (
    ReportSection("coupling", "The coupling: spec and derived values", ("sections",),
                  coupling, level="spec"),
    ReportSection("whole", "The whole coupling: meshes, capacity against offset, loads on "
                  "the machines", ("alignment", "whole_capacity", "allowable_offset",
                                   "whole_loads", "assembly"), whole, whole_verdicts,
                  level="whole"),
    ReportSection("whole-datasheet", "The whole coupling's data sheet (AGMA 9009 halves, "
                  "torsion, lateral frequency)", ("whole_datasheet",), whole_datasheet,
                  shown=lambda s: s.datasheet, level="whole"),
    ReportSection("clearance", "Clearance, backlash and contact over the turn", ("sweep",),
                  clearance),
    ReportSection("design-angles", "Critical and binding angles",
                  ("design", "backlash", "sweep"), design_angles, design_verdicts),
    ReportSection("loads", "Loads: tooth load, q, pressure, root stress, machine loads",
                  ("load", "q_graph"), loads, loads_verdicts),
    ReportSection("capacity", "Capacity per criterion against misalignment",
                  ("rating", "capacity"), capacity, capacity_verdicts),
    ReportSection("wear", "Wear over life: worn flanks, backlash and the life to the wear "
                  "limit", ("wear",), wear, wear_verdicts,
                  asked=lambda s, spec: s.wear_asked(spec)),
    ReportSection("datasheet", "Coupling data sheet for rotordynamics, after API 671",
                  ("datasheet",), datasheet, shown=lambda s: s.datasheet, level="single"),
    ReportSection("interference", "Interference check of the meshes", ("check",),
                  interference, interference_verdicts),
    ReportSection("manufacturing", "Hob program and measuring charts", ("hob", "charts"),
                  manufacturing, level="spec"),
    ReportSection("measured", "Measured part against the nominal", ("inspection",),
                  measured, measured_verdicts, shown=lambda s: s.scan is not None,
                  level="spec"),
    ReportSection("view", "3D view", ("viewer",), view3d, shown=lambda s: s.viewer,
                  level="spec"),
)
