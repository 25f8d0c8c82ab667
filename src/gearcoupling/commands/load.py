"""``gearcoupling load``: load sharing, pressures and machine loads of every tooth over a turn."""

from __future__ import annotations

from ..arguments import GAP_TOLERANCE_MM, TORQUE_RANGE_NM
from ..loading import PHASES, capacity, model_names, models_help
from ..outputs import files, write_load
from ..reporting import capacity_verdict, load_verdicts
from .common import (
    MAX_ANGLES,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    output_dir,
    positive_length,
    progress,
    spec_from_args,
    torque,
)
from .findings import print_findings
from .folders import claim, holds_folders


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
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
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
