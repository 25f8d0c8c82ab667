"""The names of the files the stages of :mod:`gearcoupling.outputs` write, without their
modules: what a command checks before any work (a light import; the stage records name
them, :data:`~gearcoupling.outputs.STAGES`, and each stage is tested to write no other
name)."""

from __future__ import annotations

from collections.abc import Sequence

PART_NAMES = ("hub", "sleeve")
SPEC = ("spec.json",)
SECTIONS = ("crown_profile.csv", "sections.png")
#: the stage ``sweep`` and :func:`~gearcoupling.outputs.write_sweep` (the plots with
#: ``plots``, the studies with the design point)
SWEEP = ("sweep.csv", "sweep_summary.json", "backlash_over_turn.csv",
         "backlash_vs_misalignment.csv", "sweep_clearance.png", "sweep_backlash_over_turn.png",
         "sweep_contact_path.png", "sweep_clearance_map.png", "sweep_backlash.png",
         "sweep_critical_vs_rc.png", "sweep_generation.png")
#: the stage ``load`` (the plots with ``plots``)
LOAD = ("load.csv", "load_summary.json", "loads_over_turn.csv", "contact_patches.csv",
        "load_tooth_load.png", "load_over_turn.png", "load_patches.png")
LOAD_STUDY = ("load_max_vs_misalignment.png", "load_moment_vs_misalignment.png")
Q_GRAPH = ("q_graph.csv", "load_q_graph.png")
#: the stage ``check`` and :func:`~gearcoupling.outputs.write_interference` (the overlap
#: where the worst pose has one)
INTERFERENCE = ("interference.csv", "interference.json", "interference.png",
                "worst_hub.stl", "worst_sleeve.stl", "worst_overlap.stl")
#: :func:`~gearcoupling.outputs.write_step_files`, and the listing it adds them to
STEP = (*(f"{part}.step" for part in PART_NAMES), "parts.json")
VIEWER = ("viewer.html",)
RATING = ("rating.json",)
CAPACITY = ("capacity.csv", "capacity.png")
DATASHEET = ("datasheet.json", "datasheet.csv", "stiffness_matrix.csv", "windup_curve.csv",
             "windup.png", "allowable_loads.csv", "allowable_loads.png")
#: :func:`~gearcoupling.outputs.program_files`; the stage ``hob`` adds the path's picture
HOB_PROGRAM = ("hob_path.csv", "hob_program.nc", "hob.json")
HOB = (*HOB_PROGRAM, "hob_path.png")
CHARTS = ("charts.png", "nominal_traces.csv", "charts.json")
INSPECTION = ("inspection.csv", "inspection.png", "deviation_map.png")
#: the stage ``wear`` and :func:`gearcoupling.wear.write_wear` (the plots last)
WEAR = ("wear.csv", "wear_depth.csv", "wear_summary.json", "wear_maps.png",
        "wear_history.png")
#: the whole coupling's stages (a double-engagement spec; docs/coupling.md)
ALIGNMENT = ("alignment.json",)
WHOLE_LOADS = ("machine_loads.csv", "whole_loads.json", "machine_loads.png")
WHOLE_CAPACITY = ("whole_capacity.json",)
ALLOWABLE_OFFSET = ("allowable_offset.json",)
WHOLE_DATASHEET = ("whole_datasheet.json", "whole_datasheet.csv", "torsion_chain.csv")
ASSEMBLY = ("coupling.glb", "assembly.json")
ASSEMBLY_STEP = ("coupling.step",)
RUN_SUMMARY = "run_summary.json"
REPORT = "report.html"
REPORT_PDF = "report.pdf"


def file_stem(part: str, teeth: Sequence[int] | None) -> str:
    """``hub`` or ``hub-teeth-0-1-2`` for a sector."""
    return part if teeth is None else f"{part}-teeth-{'-'.join(map(str, teeth))}"


def part_files(parts: Sequence[str] = PART_NAMES, formats: Sequence[str] = ("stl",),
               teeth: Sequence[int] | None = None) -> list[str]:
    """What :func:`~gearcoupling.outputs.write_parts` writes: each part in each format,
    then ``parts.json``."""
    return [f"{file_stem(part, teeth)}.{ext}" for part in parts for ext in formats] + \
        ["parts.json"]
