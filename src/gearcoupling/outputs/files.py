"""The names of the files the writers of :mod:`gearcoupling.outputs` make, without their
modules: what a command checks before any work (a light import; each writer is tested
to write no other name)."""

from __future__ import annotations

from collections.abc import Sequence

PART_NAMES = ("hub", "sleeve")
SPEC = ("spec.json",)
SECTIONS = ("sections.png",)
#: :func:`~gearcoupling.outputs.write_sweep` (the plots with ``plots``, some of them with
#: ``design`` and ``studies`` only)
SWEEP = ("sweep.csv", "sweep_summary.json", "sweep_clearance.png", "sweep_contact_path.png",
         "sweep_clearance_map.png", "sweep_backlash.png", "sweep_critical_vs_rc.png",
         "sweep_generation.png")
#: :func:`~gearcoupling.outputs.write_load` (the plots with ``plots``, the studies' three
#: with ``with_studies``)
LOAD = ("load.csv", "load_summary.json", "load_tooth_load.png", "load_patches.png",
        "load_max_vs_misalignment.png", "load_moment_vs_misalignment.png", "load_q_graph.png")
#: :func:`~gearcoupling.outputs.write_interference` (the overlap where the worst pose has
#: one)
INTERFERENCE = ("interference.csv", "interference.json", "interference.png",
                "worst_hub.stl", "worst_sleeve.stl", "worst_overlap.stl")
#: :func:`~gearcoupling.outputs.write_step_files`, and the listing it adds them to
STEP = (*(f"{part}.step" for part in PART_NAMES), "parts.json")
VIEWER = ("viewer.html",)
RUN_SUMMARY = "run_summary.json"


def file_stem(part: str, teeth: Sequence[int] | None) -> str:
    """``hub`` or ``hub-teeth-0-1-2`` for a sector."""
    return part if teeth is None else f"{part}-teeth-{'-'.join(map(str, teeth))}"


def part_files(parts: Sequence[str] = PART_NAMES, formats: Sequence[str] = ("stl",),
               teeth: Sequence[int] | None = None) -> list[str]:
    """What :func:`~gearcoupling.outputs.write_parts` writes: each part in each format,
    then ``parts.json``."""
    return [f"{file_stem(part, teeth)}.{ext}" for part in parts for ext in formats] + \
        ["parts.json"]
