"""``gearcoupling load``: load sharing, pressures and machine loads of every tooth over a turn."""

from __future__ import annotations

from typing import Any

from ..arguments import GAP_TOLERANCE_MM, TORQUE_RANGE_NM
from ..errors import ArgumentError
from ..loading import PHASES, capacity, model_names, models_help
from ..outputs import files, write_load
from ..reporting import ReportSettings, capacity_verdict, load_verdicts
from .common import (
    MAX_ANGLES,
    add_alignment_arguments,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    output_dir,
    positive_length,
    progress,
    torque,
)
from .engagement import checked_spec
from .findings import print_findings
from .folders import claim, holds_folders
from .whole import compute_whole, findings, print_paths


def register(sub) -> None:
    p = sub.add_parser("load", help="tooth loads, contact pressure, wind-up and machine loads "
                       "over a turn under torque (load.csv, load_summary.json, plots)")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--model", choices=model_names(), default=None,
                   help=f"load model ({models_help()}; default: the spec's [load] model)")
    p.add_argument("--torque", type=torque(), default=None, metavar="NM",
                   help=f"torque in N·m, |T| from {TORQUE_RANGE_NM[0]:g} to "
                        f"{TORQUE_RANGE_NM[1]:g} or 0; the sign picks the loaded flank; write a "
                        "negative one as --torque=-5e3 (default: the spec's)")
    p.add_argument("--angles", type=count(1, MAX_ANGLES), default=None, metavar="N",
                   help=f"rotations evenly over one turn, 1-{MAX_ANGLES} (default "
                        f"{PHASES} per tooth pitch: a turn of {PHASES} distinct poses)")
    p.add_argument("--tolerance", type=positive_length, default=GAP_TOLERANCE_MM, metavar="MM",
                   help="sweep accuracy of every gap in mm, > 0 (default %(default)g)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV and JSON")
    p.add_argument("--quick-plots", action="store_true",
                   help="only the tooth-load and patch plots (skip the misalignment studies)")
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def run_double(args, spec, alignment: dict[str, Any]) -> int:
    """Both meshes of a double-engagement spec at one torque, each into its folder, and
    the loads on the machines (``machine_loads.csv``, ``whole_loads.json``, plot)."""
    stages = ["alignment", "load", "rating", "whole_loads"]
    if not args.quick_plots:
        stages[2:2] = ["load_study", "q_graph"]
    settings = ReportSettings(torque_Nm=args.torque, model=args.model,
                              tolerance_mm=args.tolerance, **alignment)
    res, out, paths = compute_whole(args, spec, stages, settings, "load")
    status = findings(spec, settings, res, out, ["loads", "capacity"], f"{spec.name}: each "
                      "mesh at its angle:")
    if res.has("whole_loads"):
        eq = res.values["whole_loads"].summary()
        for m in ("A", "B"):
            mesh = eq[f"mesh_{m}"]
            print(f"  mesh {m} on shaft {m}: bending moment up to "
                  f"{mesh['bending_moment_Nm']['max']:.4g} N·m, radial force up to "
                  f"{mesh['radial_force_N']['max']:.4g} N, axial force "
                  f"{mesh['axial_force_N']['min']:.4g} to {mesh['axial_force_N']['max']:.4g} N")
    print_paths(paths)
    return status


@holds_folders
def run(args) -> int:
    spec, alignment = checked_spec(args)
    if spec.coupling.engagements == 2:
        if args.angles is not None:
            raise ArgumentError("--angles", args.angles, f"not for a double-engagement spec: "
                                f"its meshes take {PHASES} rotations per tooth pitch over "
                                "the coupling's turn")
        return run_double(args, spec, alignment)
    mis = misalignment_deg(args, spec)
    out = claim(output_dir(args, spec), spec.to_dict(),
                (*files.LOAD, *files.LOAD_STUDY, *files.Q_GRAPH))
    # one bar: the turn's poses, then the studies' misalignments
    with progress(f"load {spec.name}", args.angles or PHASES) as update:
        res, paths = write_load(spec, out, mis, args.angles, torque_Nm=args.torque,
                                model=args.model, tolerance_mm=args.tolerance,
                                plots=not args.no_plots, with_studies=not args.quick_plots,
                                progress=update)
    # the torque against the capacity at this misalignment: what the report judges too
    at = capacity(spec, mis, model=res.model, loaded_flank=res.loaded_flank)
    status = print_findings(f"{spec.name}: {res.model} model, T = {res.torque_Nm:.4g} N·m at "
                            f"{mis:g}°:", [*load_verdicts(spec, res),
                                           capacity_verdict(spec, res, at)])
    for path in paths:
        print(path)
    return status
