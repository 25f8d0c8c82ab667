"""A command on a double-engagement spec (docs/coupling.md; the spec and its alignment
options checked by :mod:`.engagement`): the command's stages of the pipeline for each mesh
(at its own angle, torque and rotation phase, into ``mesh-a/`` and ``mesh-b/``) and for the
whole coupling, and the checks printed per mesh."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import ArgumentError
from ..outputs import (
    MESH_SCOPES,
    STEPS,
    Results,
    compute,
    default_workers,
    jobs,
    run_folders,
    stage_files,
)
from ..reporting import ReportSettings, Verdict, section_verdicts
from ..spec import CouplingSpec
from .common import output_dir, progress
from .findings import print_findings
from .folders import claim


def compute_whole(args: argparse.Namespace, spec: CouplingSpec, stages: Sequence[str],
                  settings: ReportSettings, title: str) -> tuple[Results, Path, list[Path]]:
    """The ``stages`` (and what they need) of a double-engagement spec into the command's
    output folder, with a progress bar; says which were skipped. Returns the results,
    the folder and the files written, in the order of the stages."""
    out = claim(output_dir(args, spec), spec.to_dict(), stage_files(stages, 2),
                run_folders(2))
    with progress(f"{title} {spec.name}", 1) as update:
        results = compute(spec, settings, list(stages), folder=out,
                          workers=default_workers(None), progress=update)
    for key, reason in results.skipped.items():
        name = key.split("/")[-1]
        where = f" ({key.split('/')[0]})" if "/" in key else ""
        print(f"gearcoupling: {STEPS[name]}{where} skipped: {reason}", file=sys.stderr)
    order = [j.key for j in jobs(list(stages), MESH_SCOPES)]
    return results, out, results.all_files(order)


def findings(spec: CouplingSpec, settings: ReportSettings, results: Results, folder: Path,
             sections: Sequence[str], title: str) -> int:
    """Print the checks of the report's ``sections`` (each mesh's saying which) and
    return the exit status (1: a check fails)."""
    rows: list[Verdict] = section_verdicts(spec, settings, results, folder, sections)
    return print_findings(title, rows)


def print_paths(paths: Sequence[Path]) -> None:
    for path in paths:
        print(path)


def refuse_options(args: argparse.Namespace, options: dict[str, object]) -> None:
    """Refuse, naming it, the first of ``options`` (attribute -> its default) given other
    than its default: a single engagement's option."""
    for name, default in options.items():
        value = getattr(args, name, default)
        if value != default:
            option = "--" + name.replace("_", "-")
            raise ArgumentError(option, value, "not for a double-engagement spec: its meshes "
                                "are analysed at the angles the shaft alignment gives")


def capacity(args: argparse.Namespace, spec: CouplingSpec, alignment: dict[str, Any]
             ) -> int:
    """``capacity`` on a double-engagement spec: each mesh's capacity against
    misalignment (its folder) and at its angle, the whole coupling's (the smaller), and
    the allowable parallel offset at the span."""
    refuse_options(args, {"compare": [], "max": None, "misalignments": None})
    settings = ReportSettings(model=args.model, **alignment,
                              **({} if args.count is None else {"capacity_count": args.count}))
    stages = ["alignment", "capacity", "whole_capacity", "allowable_offset"]
    res, _, paths = compute_whole(args, spec, stages, settings, "capacity")
    for m, scope in zip("AB", MESH_SCOPES, strict=True):
        rating = res.scope(scope).values.get("rating")
        if rating is not None:
            print(f"mesh {m}: {rating.sentence()}")
    whole = res.values.get("whole_capacity")
    if whole is not None:
        cap = whole.capacity_Nm
        print(f"whole coupling: capacity {'unlimited' if cap is None else f'{cap:.4g} N·m'} "
              f"(mesh {whole.governing_mesh}, {whole.criterion.replace('_', ' ')} governs)")
    off = res.values.get("allowable_offset")
    if off is not None:
        what = off.criterion + (f", {off.capacity_criterion.replace('_', ' ')}"
                                if off.capacity_criterion else "")
        print(f"allowable parallel offset at the span {off.span_mm:.4g} mm: "
              f"{off.offset_mm:.4g} mm at {off.torque_Nm:.4g} N·m (mesh {off.governing_mesh}"
              f" reaches its allowable angle {off.allowable_deg[off.governing_mesh]:.4g}°: "
              f"{what}); the alignment's offset is {off.alignment.offset_mm:.4g} mm")
    print_paths(paths)
    return 0


def check(args: argparse.Namespace, spec: CouplingSpec, alignment: dict[str, Any]) -> int:
    """``check`` on a double-engagement spec: both meshes of the placed assembly over the
    turn, each at its angle and phase (its folder), and the assembly at rotation 0."""
    refuse_options(args, {"method": "boolean", "tolerance": None, "teeth": "sweep",
                          "hub_rotation": 0.0, "backlash": False})
    settings = ReportSettings(check_angles=args.angles, **alignment)
    res, out, paths = compute_whole(args, spec, ["alignment", "check", "assembly"], settings,
                                    "check")
    status = findings(spec, settings, res, out, ["interference"], f"{spec.name}: each mesh "
                      "of the placed assembly over the turn:")
    asm = res.values.get("assembly")
    if asm is not None:
        print("  placed at rotation 0, hub and sleeve ring overlap: " + ", ".join(
            f"{v:.3g} mm³ (mesh {m})" for m, v in asm.overlap_mm3.items()))
    print_paths(paths)
    return status


def datasheet(args: argparse.Namespace, spec: CouplingSpec, alignment: dict[str, Any]
              ) -> int:
    """``datasheet`` on a double-engagement spec: the whole coupling's data sheet and, with
    ``--ross``, its ROSS pieces in one file."""
    refuse_options(args, {"rotations": None, "differences": None, "step": None,
                          "angles": None})
    settings = ReportSettings(torque_Nm=args.torque, model=args.model, **alignment)
    res, _, paths = compute_whole(args, spec, ["alignment", "whole_datasheet"], settings,
                                  "datasheet")
    data = res.values.get("whole_datasheet")
    if data is not None:
        for m in data.geometry.meshes:
            h = data.halves[m]
            print(f"half {m}: {h.mass_kg:.4g} kg, polar {h.polar_inertia_kg_m2:.4g} kg·m², "
                  f"transverse {h.transverse_inertia_kg_m2:.4g} kg·m², centre of gravity "
                  f"{data.cg_from_shaft_end_mm(m):.4g} mm from the shaft end")
        t = data.torsion
        print(f"torsional stiffness {t.secant_Nm_per_rad:.4g} N·m/rad secant, "
              f"{t.tangent_Nm_per_rad:.4g} tangent; floating member's first lateral "
              f"frequency {data.lateral_frequency_Hz:.4g} Hz (pinned at the meshes)")
        if args.ross is not None:
            paths.append(data.to_ross().write(args.ross))
    print_paths(paths)
    return 0
