"""``gearcoupling sweep``: clearance, contact and backlash of every tooth over a turn."""

from __future__ import annotations

from ..arguments import GAP_TOLERANCE_MM
from ..outputs import write_sweep
from .common import (
    MAX_ANGLES,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    output_dir,
    positive_length,
    spec_from_args,
)


def register(sub) -> None:
    p = sub.add_parser("sweep", help="clearance, contact and backlash of every tooth over a "
                       "turn at a misalignment (CSV, summary JSON, plots)")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--angles", type=count(1, MAX_ANGLES), default=360, metavar="N",
                   help=f"rotations over one turn, 1-{MAX_ANGLES} (default 360)")
    p.add_argument("--tolerance", type=positive_length, default=GAP_TOLERANCE_MM, metavar="MM",
                   help="accuracy of every minimum in mm (default %(default)g)")
    p.add_argument("--no-design", action="store_true",
                   help="skip the critical and binding angles (root finding, a few seconds)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV and JSON")
    p.add_argument("--quick-plots", action="store_true",
                   help="skip the backlash, R_c and generation studies among the plots")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = spec_from_args(args)
    mis = misalignment_deg(args, spec)
    out = output_dir(args, spec)
    _, paths = write_sweep(spec, out, mis, args.angles, tolerance_mm=args.tolerance,
                           design=not args.no_design, plots=not args.no_plots,
                           studies=not args.quick_plots)
    for path in paths:
        print(path)
    return 0
