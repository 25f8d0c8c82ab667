"""The report's sections of the whole coupling (a double-engagement spec, docs/coupling.md):
the meshes at the shaft alignment, the capacity and the allowable parallel offset, the
loads on the machines and the floating member's balance, the assembly; and the whole
coupling's data sheet (each half's AGMA 9009 lumps, the torsional chain, the lateral
frequency of the floating member)."""

from __future__ import annotations

import numpy as np

from ..coupling import (
    AllowableOffset,
    CouplingGeometry,
    WholeCapacity,
    WholeCouplingData,
    WholeLoads,
)
from ..outputs import Assembly, datasheet_rows
from .document import Block, Note, Row, Table
from .verdict import FAIL, OPEN, PASS, Verdict
from .view import View


def _geometry_table(geom: CouplingGeometry) -> Table:
    a = geom.alignment
    rows = [("span between the hubs' tooth midplanes", geom.span_mm, "mm"),
            ("sleeve", geom.layout.sleeve, ""),
            ("parallel offset at the coupling's centre", a.offset_mm, "mm"),
            ("offset azimuth", a.offset_azimuth_deg, "deg"),
            ("shaft angle", a.angle_deg, "deg"),
            ("angle azimuth", a.angle_azimuth_deg, "deg"),
            ("floating axis tilt against shaft A", geom.angles.sleeve_tilt_deg, "deg")]
    for m in geom.meshes:
        rows += [(f"mesh {m} angle", geom.misalignment_deg(m), "deg"),
                 (f"mesh {m} tilt axis azimuth (its rotation phase)", geom.tilt_axis_deg(m),
                  "deg")]
    return Table(("alignment", "value", "unit"), rows, "Shaft B against shaft A; azimuths "
                 "about shaft A from its x (docs/coupling.md, Conventions). Each mesh is "
                 "analysed as one engagement at its angle, its rotations the coupling's "
                 "less its tilt axis azimuth: its sections below, its files in mesh-a/ and "
                 "mesh-b/.")


def _capacity_tables(v: View) -> list[Block]:
    blocks: list[Block] = []
    cap = v.get("whole_capacity", WholeCapacity)
    if cap is None:
        blocks.append(Note(f"Capacity not computed: {v.why('whole_capacity')}.", "skip"))
    else:
        rows: list[tuple] = [(f"mesh {m}", c.misalignment_deg, c.loaded_flank, c.capacity_Nm,
                              c.governing.replace("_", " ")) for m, c in cap.meshes.items()]
        rows.append(("whole coupling", None, f"mesh {cap.governing_mesh} governs",
                     cap.capacity_Nm, cap.criterion.replace("_", " ")))
        blocks.append(Table(("capacity", "angle (deg)", "loaded flank", "capacity K·T (N·m)",
                             "governing criterion"), rows, "Each mesh's capacity at its "
                            "angle on the flank the torque loads there (hub B's cw: the "
                            "sleeve drives it); the whole coupling's is the smaller."))
    off = v.get("allowable_offset", AllowableOffset)
    if off is None:
        blocks.append(Note(f"Allowable offset not computed: {v.why('allowable_offset')}.",
                           "skip"))
        return blocks
    crit = off.criterion + (f" ({off.capacity_criterion.replace('_', ' ')})"
                            if off.capacity_criterion else "")
    rows2: list[tuple] = [("allowable parallel offset at the span", off.offset_mm, "mm"),
                          ("the alignment's offset", off.alignment.offset_mm, "mm"),
                          ("governing mesh", off.governing_mesh, ""),
                          ("what limits it", crit, "")]
    rows2 += [(f"mesh {m} allowable angle at the torque", off.allowable_deg[m], "deg")
              for m in off.allowable_deg]
    rows2 += [(f"mesh {m} angle at the allowable offset", off.mesh_angles_deg[m], "deg")
              for m in off.mesh_angles_deg]
    blocks.append(Table(("allowable offset", "value", "unit"), rows2,
                        f"At T = {off.torque_Nm:.4g} N·m over the span {off.span_mm:.4g} mm, "
                        "in the alignment's offset direction with its shaft angle held: the "
                        "offset at which the first mesh reaches its allowable misalignment "
                        "(the smaller of its critical angle and the largest angle whose "
                        "capacity carries the torque), solved to 1e-6 mm."))
    return blocks


def _loads_blocks(v: View) -> list[Block]:
    loads = v.get("whole_loads", WholeLoads)
    if loads is None:
        return [Note(f"Loads on the machines not computed: {v.why('whole_loads')}.", "skip")]
    rows = []
    for m in loads.meshes:
        ml = loads.machine_loads(m)
        rows += [(f"mesh {m} on shaft {m}", "bending moment (max)",
                  float(np.max(ml["bending_moment_Nm"])), "N·m"),
                 ("", "radial force (max)", float(np.max(ml["radial_force_N"])), "N"),
                 ("", "axial force (min / max)",
                  f"{float(np.min(ml['axial_force_N'])):.4g} / "
                  f"{float(np.max(ml['axial_force_N'])):.4g}", "N"),
                 ("", "torque carried (mean)", float(np.mean(ml["torque_Nm"])), "N·m")]
    eq = loads.equilibrium()
    balance = [("largest residual force / largest tooth normal force", eq["relative_force"],
                ""),
               ("largest residual moment / largest mesh moment", eq["relative_moment"], ""),
               ("largest shear the hubs give it", eq["shear_max_N"], "N"),
               ("largest thrust share", eq["thrust_share_max_N"], "N"),
               ("torque lost between the shafts (friction, mean)",
                eq["torque_share_mean_Nm"], "N·m")]
    how = (f"{loads.results['A'].model} model, T = {loads.torque_Nm:.4g} N·m through both "
           f"meshes, {loads.angles_deg.size} rotations over the turn.")
    return [Row([Table(("shaft", "load", "value", "unit"), rows, "What each mesh puts on "
                       "its machine at the mesh centre over the turn (tooth friction's "
                       "locking moment and thrust included): API 671's moments and forces "
                       "at the misalignment. " + how),
                 Table(("floating member", "value", "unit"), balance, "Sum of the forces "
                       "and moments on the floating member over the turn: zero up to "
                       "rounding.")]),
            v.figure("machine-loads", "Loads on the machines over the turn",
                     "machine_loads.png", how, "machine_loads.csv")]


def whole(v: View) -> list[Block]:
    """The whole coupling at the alignment: meshes, capacity and allowable offset, loads on
    the machines, the assembly."""
    geom = v.get("alignment", CouplingGeometry)
    if geom is None:
        return [Note(f"Not computed: {v.why('alignment')}", "skip")]
    blocks: list[Block] = [_geometry_table(geom), *_capacity_tables(v), *_loads_blocks(v)]
    asm = v.get("assembly", Assembly)
    if asm is not None:
        blocks.append(Note("The placed assembly (every part named, at this alignment, "
                           "rotation 0) is coupling.glb; its placed hubs and sleeve rings "
                           "share " + ", ".join(f"{vol:.3g} mm³ (mesh {m})" for m, vol in
                                                asm.overlap_mm3.items()) + "."))
    return blocks


def whole_verdicts(v: View) -> list[Verdict]:
    """The alignment's offset within the allowable parallel offset at the span."""
    check = "parallel offset ≤ allowable offset at the span"
    off = v.get("allowable_offset", AllowableOffset)
    if off is None:
        return [Verdict(check, "–", "–", "–", OPEN, f"not computed: "
                        f"{v.why('allowable_offset')}")]
    given = off.alignment.offset_mm
    crit = off.criterion + (f", {off.capacity_criterion.replace('_', ' ')}"
                            if off.capacity_criterion else "")
    return [Verdict(check, f"{given:.4g} mm", f"{off.offset_mm:.4g} mm (mesh "
                    f"{off.governing_mesh}: {crit})", f"allowable misalignment at "
                    f"{off.torque_Nm:.4g} N·m", PASS if given <= off.offset_mm else FAIL,
                    f"margin {100.0 * (off.offset_mm - given) / off.offset_mm:+.1f} %"
                    if off.offset_mm > 0 else "")]


def whole_datasheet(v: View) -> list[Block]:
    """The whole coupling's data sheet: the AGMA 9009 halves, the torsional chain, the
    floating member's lateral frequency."""
    data = v.get("whole_datasheet", WholeCouplingData)
    if data is None:
        return [Note(f"Not made: {v.why('whole_datasheet')}.", "skip")]
    rows = [(item, what, value, unit) for item, what, value, unit in datasheet_rows(data)]
    t = data.torsion
    chain = [(part, t.secant_rad_per_Nm[part], t.tangent_rad_per_Nm[part])
             for part in t.secant_rad_per_Nm]
    chain.append(("whole coupling (stiffness, N·m/rad)", t.secant_Nm_per_rad,
                  t.tangent_Nm_per_rad))
    return [Table(("item", "quantity", "value", "unit"), rows,
                  f"At T = {data.torque_Nm:.4g} N·m, {data.model} model. Each half as "
                  "AGMA 9009 lumps it at its shaft end (its hub and the floating parts on "
                  "its side of the coupling's centre); the centre of gravity from the hub's "
                  "outboard face. The lateral frequency: the floating member pinned at the "
                  "mesh centres (API 671)."),
            Table(("torsion, shaft A to shaft B", "secant compliance (rad/N·m)",
                   "tangent compliance (rad/N·m)"), chain, "The parts in series: meshes "
                  "from the load model, bodies, flanges and spacer in closed form."),
            Note("Each mesh's 6 x 6 stiffness under load is in whole_datasheet.json "
                 "(its own mesh frame); datasheet --ross writes the ROSS pieces.")]
