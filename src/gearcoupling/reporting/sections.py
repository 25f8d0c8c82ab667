"""The report's sections: each computes its results, draws its figures, writes each
figure's data file and leaves what the verdict table needs in ``ctx.found``.

A section whose optional extra or input is missing says so in place of its content; the
others still run.
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..clearance import (
    plot_backlash,
    plot_backlash_over_turn,
    plot_clearance,
    plot_contact_path,
    sweep,
)
from ..errors import ArgumentError, BackendError
from ..geometry import renzo_z0_mm
from ..hob import hob_program, measuring_charts, plot_measuring_charts, write_nominal_csv
from ..inspection import compare_part, plot_deviation_map, plot_inspection
from ..interference import check_interference, plot_interference
from ..io import plot_text, write_csv_records, write_csv_rows, write_text
from ..loading import (
    capacity,
    load_from_sweep,
    load_model,
    most_loaded,
    plot_capacity,
    plot_loads_over_turn,
    plot_patches,
    plot_q_graph,
    plot_tooth_load,
    resolve_torque_Nm,
    rotation_table,
    springs_name,
    tooth_load_error,
    windup_error,
    write_capacity_csv,
)
from ..outputs import backlash_grid, backlash_range_deg, design_point, q_points, turn_sweep
from ..plots import crown_profile, fixed_layout, new_figure, sections_figure
from ..spec import CouplingSpec, check_misalignment_deg
from ..viewer import ViewSettings, write_html
from .capacity import StartedComparison, comparison_range
from .document import Figure, Note, Row, Section, Table, Viewer, png_bytes
from .settings import ReportSettings

DATA_DIR = "report-data"


@dataclass
class Context:
    """What the sections share: the spec, the settings, where data files go, the resolved
    misalignment, torque and model, and the results the verdicts read (``found``)."""

    spec: CouplingSpec
    settings: ReportSettings
    out: Path
    misalignment_deg: float
    torque_Nm: float | None
    model: str
    files: list[Path] = field(default_factory=list)
    found: dict[str, Any] = field(default_factory=dict)
    scan_points: Any = None  # the scan's (n, 3) points in mm, read before any work
    capacity_curve: Any = None  # the capacity curve, started before the first section
    datasheet_run: Any = None  # the data sheet, started after the capacity section

    @property
    def data_dir(self) -> Path:
        return self.out / DATA_DIR

    @property
    def flank(self) -> str:
        """The loaded flank: ``cw`` under a negative torque, else ``ccw``."""
        return "cw" if (self.torque_Nm or 0.0) < 0 else "ccw"

    def data_path(self, name: str) -> Path:
        path = self.data_dir / name
        self.files.append(path)
        return path

    def figure(self, key: str, title: str, fig, settings: str, data_file: str | None,
               note: str = "") -> Figure:
        """A report figure from a matplotlib figure; ``data_file`` a name in the data folder
        (already written)."""
        rel = None if data_file is None else f"{DATA_DIR}/{data_file}"
        return Figure(key, title, png_bytes(fig, self.settings.dpi), settings, rel, note)

    def table_file(self, name: str, columns, rows) -> str:
        """Write rows under ``columns`` as CSV in the data folder; returns the name."""
        write_csv_rows(self.data_path(name), columns, rows)
        return name


def _sweep_settings(sw) -> str:
    return (f"Sweep of the exact flanks: {sw.angles_deg.size} rotations, flank-table "
            f"tolerance {sw.tolerance_mm:.3g} mm (table error {sw.table_error_mm:.2g} mm), "
            f"i = {sw.misalignment_deg:g}°.")


def _load_settings(ctx: Context, res) -> str:
    spec = ctx.spec
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


def coupling(ctx: Context) -> Section:
    spec = ctx.spec
    data = spec.to_dict()
    sec = Section("coupling", "The coupling: spec and derived values")
    sec.blocks.append(Note(f"{spec.name}: {spec.tooth.teeth} teeth, module "
                           f"{spec.tooth.module:.4g} mm, pressure angle "
                           f"{math.degrees(spec.tooth.pressure_angle):g}°, face width "
                           f"{spec.hub.face_width:.4g} mm, {spec.hub.crowning.kind} crown "
                           f"(R_c {spec.derived['crowning_radius_midplane_mm']:.4g} mm at the "
                           f"midplane), design misalignment {spec.design_misalignment_deg:g}°. "
                           "Lengths in mm, angles in degrees, as resolved from the spec file "
                           f"(written in {spec.units})."))
    rows = _flatten({k: data[k] for k in ("tooth", "hub", "sleeve", "load", "material")})
    sec.blocks.append(Row([
        Table(("spec key", "value"), rows, "The resolved spec."),
        Table(("derived value", "value"), list(spec.derived.items()),
              "Derived values (renzo_z0 at the design angle: Renzo eq. 4).")]))
    z = np.linspace(-0.5 * spec.hub.face_width, 0.5 * spec.hub.face_width, 81)
    prof = crown_profile(spec, z)
    cols = ("z_mm", "thickness_enveloped_mm", "thickness_revolved_mm",
            "pressure_angle_enveloped_deg", "pressure_angle_revolved_deg", "crown_drop_mm")
    name = ctx.table_file("crown_profile.csv", cols, zip(z, *(prof[c] for c in cols[1:]),
                                                          strict=True))
    tol = 1e-3 * spec.tooth.module
    sec.blocks.append(ctx.figure("sections", "Transverse sections and the crown along the face",
                                 sections_figure(spec, tol),
                                 f"Exact tooth sections at chordal tolerance {tol:.3g} mm; "
                                 "crown profile at 81 planes.", name))
    return sec


# --------------------------------------------------------------------------- clearance


def clearance(ctx: Context) -> Section:
    spec, s = ctx.spec, ctx.settings
    sec = Section("clearance", "Clearance, backlash and contact over the turn")
    sw = turn_sweep(spec, ctx.misalignment_deg, s.angles, s.tolerance_mm)
    ctx.found["sweep"] = sw
    summ = sw.summary()
    ctx.found["min_backlash_mm"] = summ["min_backlash_mm"]
    rows = [("aligned backlash", summ["aligned_backlash_mm"] * 1e3, "µm"),
            ("smallest backlash over the turn", summ["min_backlash_mm"] * 1e3, "µm"),
            ("largest backlash over the turn", summ["max_backlash_mm"] * 1e3, "µm"),
            *((f"smallest circumferential clearance, {f} flank",
               summ["min_clearance_mm"][f] * 1e3, "µm") for f in ("cw", "ccw")),
            *((f"separation peak to peak on the pitch line (normal), {f}",
               summ["pitch_line_peak_to_peak_normal_mm"][f] * 1e3, "µm") for f in ("cw", "ccw")),
            ("largest |z| of first touch", summ["max_contact_z_mm"], "mm"),
            ("half face width", summ["half_face_mm"], "mm")]
    sec.blocks.append(Table(("quantity", "value", "unit"), rows,
                            f"At i = {ctx.misalignment_deg:g}°, over {s.angles} rotations."))
    sw.write_csv(ctx.data_path("sweep.csv"))
    how = _sweep_settings(sw)
    sec.blocks.append(ctx.figure("clearance", "Clearance of every tooth against the rotation "
                                 "(Renzo Fig. 10)", plot_clearance(sw), how, "sweep.csv"))
    name = ctx.table_file("backlash_over_turn.csv", ("psi_deg", "backlash_mm", "backlash_deg"),
                          zip(sw.angles_deg, sw.backlash_mm, np.degrees(sw.backlash_rad),
                              strict=True))
    sec.blocks.append(ctx.figure("backlash", "Backlash over the turn", plot_backlash_over_turn(sw),
                                 how, name))
    sec.blocks.append(ctx.figure("contact-path", "Where each tooth touches first (Wei Fig. 9)",
                                 plot_contact_path(sw, spec), how, "sweep.csv"))
    return sec


def design_angles(ctx: Context) -> Section:
    """Critical and binding misalignment, contact travel and z0 with Renzo's estimates."""
    spec = ctx.spec
    sec = Section("design-angles", "Critical and binding angles")
    dq = design_point(spec, ctx.misalignment_deg)
    crit, bind = dq["critical_misalignment_deg"], dq["binding_angle_deg"]
    ctx.found.update(critical_deg=crit, binding_deg=bind)
    rc = spec.derived["crowning_radius_midplane_mm"]
    phi = spec.tooth.pressure_angle
    half = 0.5 * spec.hub.face_width
    B = spec.derived["aligned_backlash_mm"]
    i = math.radians(ctx.misalignment_deg)
    finite = math.isfinite(rc)
    est_crit = math.degrees(half / (rc / math.tan(phi))) if finite else None
    est_bind = math.degrees(math.atan(math.sqrt(B * math.sin(phi) / rc))) if finite else None
    z0 = renzo_z0_mm(rc, i, phi) if finite else None
    sw = ctx.found["sweep"]
    sep = max(sw.summary()["pitch_line_peak_to_peak_normal_mm"].values())
    travel = dq["pivot_contact_z_mm"]
    uniform = "" if spec.hub.crowning.kind == "circular" else \
        " (uniform-crown estimate with the midplane R_c)"
    rows = [
        ("critical misalignment (contact reaches a face end)", crit, est_crit, "deg",
         f"b/2 = R_c cot φ · i{uniform}"),
        ("binding angle (smallest backlash over a turn = 0)", bind, est_bind, "deg",
         f"Δb = 2 z0 / cos φ = aligned backlash (eqs. 4, 6){uniform}"),
        (f"contact travel on the pivot teeth at {ctx.misalignment_deg:g}° (pitch line)",
         travel["pitch_line_z_mm"], travel["renzo_mm"], "mm", f"R_c cot φ · i{uniform}"),
        (f"largest separation z0 at {ctx.misalignment_deg:g}° (pitch line, normal)", sep, z0,
         "mm", f"z0 = ½ R_c cot φ tan² i (eq. 4){uniform}"),
    ]
    table = [(q, c, e, None if (c is None or e is None or e == 0) else (c - e) / e * 100, u, f)
             for q, c, e, u, f in rows]
    sec.blocks.append(Table(("quantity", "computed", "Renzo's estimate", "difference %", "unit",
                             "estimate"), table,
                            "Computed by root finding on the exact geometry to "
                            f"{dq['design_angle_tolerance_deg']:g}° "
                            f"({dq['design_rotations_per_pitch']} rotations per tooth pitch); "
                            "– where the coupling does not reach it by 6° or the crown is "
                            "straight."))
    mis, curve = backlash_grid(spec, backlash_range_deg(spec, bind, ctx.misalignment_deg))
    name = ctx.table_file("backlash_vs_misalignment.csv",
                          ("misalignment_deg", "min_backlash_mm"), zip(mis, curve, strict=True))
    sec.blocks.append(ctx.figure("backlash-vs-misalignment",
                                 "Smallest backlash over a turn against misalignment",
                                 plot_backlash(spec, binding_deg=bind, curve=(mis, curve)),
                                 "25 misalignments, 8 rotations per tooth pitch each.", name))
    return sec


# --------------------------------------------------------------------------- loads


def loads(ctx: Context) -> Section:
    spec, s = ctx.spec, ctx.settings
    sec = Section("loads", "Loads: tooth load, q, pressure, root stress, machine loads")
    if ctx.torque_Nm is None:
        sec.blocks.append(Note("No torque: set [load] torque_Nm in the spec or --torque; the "
                               "loads and the capacity verdict are not judged.", "skip"))
        ctx.found["load"] = None
        return sec
    sw = ctx.found["sweep"]
    if load_model(ctx.model).cost == "slow":  # one tooth pitch covers all θ
        pitch = np.arange(s.surface_angles) * 360.0 / (spec.tooth.teeth * s.surface_angles)
        sw = sweep(spec, ctx.misalignment_deg, pitch, tolerance_mm=s.tolerance_mm)
    res = load_from_sweep(sw, torque_Nm=ctx.torque_Nm, model=ctx.model)
    ctx.found["load"] = res
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
    sec.blocks.append(Table(("quantity", "value", "unit"), rows, _load_settings(ctx, res)))
    for text in summ["limits"]:
        sec.blocks.append(Note(text, "warn"))
    outside = summ["accuracy"]["outside_fitted_range"]
    if outside:
        sec.blocks.append(Note("The fe-fit tooth springs are evaluated outside the range they "
                               f"were fitted on ({'; '.join(outside)}): their error there is "
                               "not measured; --set load.stiffness=fe computes this spec's "
                               "own FE table.", "warn"))
    res.write_csv(ctx.data_path("load.csv"))
    how = _load_settings(ctx, res)
    sec.blocks.append(ctx.figure("tooth-load", "Tooth load against the turning angle (Renzo "
                                 "Fig. 11)", plot_tooth_load(res), how, "load.csv"))
    table = rotation_table(res)
    name = ctx.table_file("loads_over_turn.csv", tuple(table), zip(*table.values(), strict=True))
    sec.blocks.append(ctx.figure("loads-over-turn", "Teeth in contact, stresses and machine "
                                 "loads over the rotations", plot_loads_over_turn(res), how,
                                 name))
    j = int(np.argmax(np.max(res.tangential_force_N, axis=0)))
    mapped = set(most_loaded(res, j, s.patch_teeth).tolist())  # the teeth plot_patches maps
    name = ctx.table_file(
        "contact_patches.csv", ("tooth", "theta_deg", "normal_force_N", "contact_z_mm",
                                "contact_r_mm", "patch_length_mm", "patch_width_mm",
                                "interior_pressure_MPa", "max_pressure_MPa", "edge_contact",
                                "mapped"),
        ((k, res.theta_deg[k, j], res.normal_force_N[k, j], res.contact_z_mm[k, j],
          res.contact_r_mm[k, j], res.patch_length_mm[k, j], res.patch_width_mm[k, j],
          res.interior_pressure_MPa[k, j], res.max_pressure_MPa[k, j],
          bool(res.edge_contact[k, j]), k in mapped)
         for k in range(res.teeth)))
    sec.blocks.append(ctx.figure(
        "patches", "Contact pressure on the developed flanks, the most loaded teeth and every "
        "tooth", plot_patches(res, j, count=s.patch_teeth),
        how + f" Rotation ψ = {res.angles_deg[j]:.3g}° (the largest tooth load); analytic "
        "maps on a 481 × 61 grid" if not load_model(ctx.model).pressure_grid else
        how + f" Rotation ψ = {res.angles_deg[j]:.3g}°, its solved pressure grid.",
        name))
    q_graph(ctx, sec)
    return sec


def _noise_free(value: float, scale: float) -> float:
    """``value`` or 0 where it is rounding noise of sums of forces of size ``scale``."""
    return 0.0 if abs(value) < 1e-9 * max(scale, 1.0) else value


def q_graph(ctx: Context, sec: Section) -> None:
    """Renzo's q graph with the linear model's points at 7 misalignments (needs the
    allowable tooth load and Renzo's mesh stiffness C)."""
    spec = ctx.spec
    ld = spec.load
    if ld.allowable_tooth_load_N is None or ld.mesh_stiffness_N_per_mm is None:
        sec.blocks.append(Note("Renzo's q graph needs [load] allowable_tooth_load and "
                               "mesh_stiffness (Renzo's C); not drawn.", "skip"))
        return
    top = max(ctx.misalignment_deg, 0.5)
    pts = q_points(spec, ctx.misalignment_deg)  # the stage gc.run's q graph draws
    name = ctx.table_file("q_graph.csv", ("misalignment_deg", "zc_over_z0", "q_linear_model",
                                          "q_renzo_eq8"),
                          [(p.misalignment_deg, p.zc_over_z0, p.q_linear, p.q_renzo)
                           for p in pts])
    fig = plot_q_graph({"linear model, exact geometry": [(p.zc_over_z0, p.q_linear)
                                                         for p in pts]},
                       title=f"{plot_text(spec.name)}: "
                             "load proportion q against z_c / z0 (Renzo Fig. 12)")
    sec.blocks.append(ctx.figure("q-graph", "Renzo's load proportion q against z_c / z0", fig,
                                 f"Linear model (C = {ld.mesh_stiffness_N_per_mm:.4g} N/mm, "
                                 f"P_i = {ld.allowable_tooth_load_N:.4g} N) at 7 misalignments "
                                 f"to {top:g}°, 25 rotations per tooth pitch.", name))


def start_capacity(ctx: Context) -> None:
    """Start the capacity curve's points (forked workers where the machine has two cores):
    they run while the sections before the capacity are built. The caller stops it in a
    ``finally`` (``ctx.capacity_curve.stop()``)."""
    known = comparison_range([ctx.spec], ctx.settings.capacity_count)
    flank = ctx.flank
    mis = _through(known[0], ctx.misalignment_deg) if flank == "ccw" else known[0]
    ctx.capacity_curve = StartedComparison([ctx.spec], mis, model=ctx.model,
                                           known_range=known)


def capacity_section(ctx: Context) -> Section:
    spec = ctx.spec
    sec = Section("capacity", "Capacity per criterion against misalignment")
    flank = ctx.flank
    if ctx.capacity_curve is None:
        start_capacity(ctx)
    comp = ctx.capacity_curve.result()
    mis, critical = comp.misalignments_deg, comp.critical_deg
    if flank == "ccw":
        at = comp.curves[spec.name][int(np.searchsorted(mis, ctx.misalignment_deg))]
    else:
        at = capacity(spec, ctx.misalignment_deg, model=ctx.model, loaded_flank=flank)
    ctx.found["capacity"] = at
    ctx.found["capacity_curve"] = comp.curves[spec.name]  # ccw flanks: the data sheet's too
    rows = [(f"{k.replace('_', ' ')}", v, "N·m") for k, v in at.criteria_Nm.items()]
    rows += [("governing capacity K·T", at.capacity_Nm, f"N·m ({at.governing.replace('_', ' ')})"),
             ("torque at which a patch reaches a face end", at.face_end_torque_Nm, "N·m"),
             ("aligned capacity K N P_i R (Renzo)", at.aligned_capacity_Nm, "N·m"),
             ("q at the governing torque", at.q, ""),
             ("largest tooth load at the governing torque", at.max_tooth_load_N, "N")]
    sec.blocks.append(Table(("criterion / quantity", "value", "unit"), rows,
                            f"At i = {ctx.misalignment_deg:g}° ({at.model} model, {flank} flanks,"
                            f" K = {at.accuracy_factor:g}); a criterion without its limit is "
                            "left out."))
    write_capacity_csv(comp.curves, ctx.data_path("capacity.csv"))
    sec.blocks.append(ctx.figure(
        "capacity", "Capacity per criterion against misalignment, design point starred",
        plot_capacity(comp.curves, critical_deg=critical),
        f"{at.model} model, {mis.size} misalignments 0–{ctx.capacity_curve.top_deg:.3g}° "
        f"(to the critical misalignment)"
        f"{', the design point among them' if flank == 'ccw' else ''}, "
        f"{load_model(at.model).rotations} rotations over one tooth pitch each, loaded flank ccw.",
        "capacity.csv"))
    return sec


def _through(grid: np.ndarray, design_deg: float) -> np.ndarray:
    """The capacity curve's misalignments through the design point, so that one search
    gives the verdict's capacity and the curve's point: it takes the place of the nearest
    interior point of ``grid`` (0 and the critical misalignment stay), else it is added."""
    inside = grid[1:-1]
    out = grid.copy()
    if inside.size and grid[0] < design_deg < grid[-1]:
        out[1 + int(np.argmin(np.abs(inside - design_deg)))] = design_deg
    else:
        out = np.append(out, design_deg)
    return np.unique(out)


# --------------------------------------------------------------------------- checks


def interference(ctx: Context) -> Section:
    spec, s = ctx.spec, ctx.settings
    sec = Section("interference", "Interference check of the meshes")
    angles = np.arange(s.check_angles) * 360.0 / s.check_angles
    try:
        result = check_interference(spec, ctx.misalignment_deg, angles)
    except BackendError as err:
        ctx.found["interference"] = (None, f"not run: {err}")
        sec.blocks.append(Note(f"Not run: {err}", "skip"))
        return sec
    ctx.found["interference"] = (result, "")
    ref = turn_sweep(spec, ctx.misalignment_deg, s.check_angles, s.tolerance_mm)
    reference = np.min(ref.normal_clearance_mm, axis=(0, 1))
    summ = result.summary()
    rows = [("poses over the turn", summ["angles"], ""),
            ("overlap volume (largest)", summ["max_overlap_volume_mm3"], "mm³"),
            ("overlap depth (largest)", summ["max_overlap_depth_mm"], "mm"),
            ("smallest mesh gap", summ["min_gap_mm"], "mm"),
            ("smallest exact normal clearance (sweep)", float(np.min(reference)), "mm"),
            ("mesh chordal tolerance", summ["tolerance_mm"], "mm"),
            ("triangles hub / sleeve", f"{summ['triangles_hub']} / {summ['triangles_sleeve']}",
             "")]
    sec.blocks.append(Table(("quantity", "value", "unit"), rows))
    result.write_csv(ctx.data_path("interference.csv"))
    sec.blocks.append(ctx.figure(
        "interference", "Overlap volume and minimum gap of the posed meshes",
        plot_interference(result, reference),
        f"{result.method} method on {result.model}, {s.check_angles} poses, meshes at "
        f"{result.tolerance_mm:.3g} mm; dashed: the sweep's exact clearance.",
        "interference.csv"))
    return sec


def manufacturing(ctx: Context) -> Section:
    spec, s = ctx.spec, ctx.settings
    sec = Section("manufacturing", "Hob program and measuring charts")
    D = s.hob_diameter_mm
    illustrative = D is None
    if D is None:
        D = float(round(max(50.0, 20.0 * spec.tooth.module)))
    prog = hob_program(spec, D)
    summ = prog.summary()
    if illustrative:
        sec.blocks.append(Note(f"Hob outside diameter {D:g} mm is an illustrative size "
                               "(max(50, 20 module)); give --hob-diameter for your hob.", "warn"))
    rows = [(k, v) for k, v in summ.items() if k not in ("spec", "notes")]
    sec.blocks.append(Table(("hob program", "value"), rows,
                            "Lengths in mm; X = hob centre distance, Z = axial position."))
    for note in summ["notes"]:
        sec.blocks.append(Note(note, "warn"))
    write_text(ctx.data_path("hob_program.nc"), prog.gcode())
    write_csv_records(ctx.data_path("hob_path.csv"), prog.rows(),
                      ["hob centre path, mm and degrees"])
    fig, ax = new_figure(figsize=(9, 3.6))
    fixed_layout(fig, 0.7, 0.05, 0.48, 0.24)
    ax.plot(prog.table["z_mm"], prog.table["infeed_mm"] * 1e3, "-")
    ax.set_xlabel("hob centre Z (mm)")
    ax.set_ylabel("infeed from the midplane (µm)")
    ax.invert_yaxis()
    ax.grid(alpha=0.3)
    ax.set_title(f"{plot_text(spec.name)}: "
                 f"hob centre path, {prog.crown_kind} crown, hob Ø {D:g} mm",
                 fontsize=10)
    sec.blocks.append(ctx.figure("hob-path", "Hob centre path over the face", fig,
                                 f"{summ['arc_moves']} arcs and {summ['line_moves']} lines, "
                                 f"chordal tolerance {prog.tolerance_mm:.3g} mm (largest "
                                 f"deviation {prog.max_deviation_mm:.2g} mm). Program: "
                                 "report-data/hob_program.nc.", "hob_path.csv"))
    charts = measuring_charts(spec)
    write_nominal_csv(charts, ctx.data_path("measuring_charts.csv"))
    sec.blocks.append(ctx.figure("measuring-charts", "Nominal profile and lead measuring charts",
                                 plot_measuring_charts(charts),
                                 "Exact flank traces, 101 points each, tip exclusion 8 %.",
                                 "measuring_charts.csv"))
    return sec


def measured(ctx: Context) -> Section:
    spec, s = ctx.spec, ctx.settings
    sec = Section("measured", "Measured part against the nominal")
    scan = s.scan if ctx.scan_points is None else ctx.scan_points
    rep = compare_part(spec, scan, units="mm" if ctx.scan_points is not None else s.scan_units,
                       limits=s.limits, grade=s.grade, fit_points=s.fit_points)
    ctx.found["inspection"] = rep
    part = rep.part
    rows = [("source", Path(str(s.scan)).name), ("points", rep.points),
            ("teeth measured", part["teeth_measured"]),
            ("registration rms", f"{rep.registration.rms_mm * 1e3:.2f} µm"),
            ("runout datum", part["runout_datum"])]
    sec.blocks.append(Table(("inspection", "value"), rows))
    sec.blocks.append(Table(("limit", "what", "worst measured (mm)", "limit (mm)", "verdict"),
                            [(v["limit"], v["what"], v["measured_mm"], v["limit_mm"],
                              v["verdict"] + (f" ({v['reason']})" if v["reason"] else ""))
                             for v in part["verdicts"]], "Not judged: no limit set for it "
                            "([inspection], --limit or --grade).", verdict_column=4))
    write_csv_records(ctx.data_path("inspection.csv"), rep.rows(),
              ["lengths in mm, + = material excess / toward increasing polar angle"])
    how = (f"Registration on {s.fit_points} points, flank table 61 × 41; "
           + (f"ISO 1328-1:2013 class {s.grade} limits. " if s.grade else ""))
    sec.blocks.append(ctx.figure("inspection", "Per tooth pitch, runout, thickness and crown",
                                 plot_inspection(rep), how, "inspection.csv"))
    sec.blocks.append(ctx.figure("deviation-map", "Flank deviation map", plot_deviation_map(rep),
                                 how, "inspection.csv"))
    return sec


def view3d(ctx: Context) -> Section:
    sec = Section("view", "3D view")
    with tempfile.TemporaryDirectory() as tmp:
        try:
            path = write_html(ctx.spec, Path(tmp) / "viewer.html",
                              settings=ViewSettings(misalignment_deg=ctx.misalignment_deg))
        except BackendError as err:
            sec.blocks.append(Note(f"Not included: {err}", "skip"))
            return sec
        scene = path.read_text(encoding="utf-8")
    sec.blocks.append(Viewer(scene, f"Hub and sleeve at i = {ctx.misalignment_deg:g}°, rotation "
                             "0, quarter cutaway, coloured by clearance (drag to turn, scroll "
                             "to zoom)."))
    return sec


def resolve(spec: CouplingSpec, s: ReportSettings) -> tuple[float, float | None, str]:
    """The misalignment (deg), torque (N·m or None) and model a report uses."""
    mis = spec.design_misalignment_deg if s.misalignment_deg is None else s.misalignment_deg
    mis = check_misalignment_deg(mis, "misalignment_deg", ArgumentError)
    torque = None
    if s.torque_Nm is not None or spec.load.torque_Nm is not None:
        torque = resolve_torque_Nm(spec, s.torque_Nm)
    return float(mis), torque, s.model or spec.load.model
