"""``gearcoupling sweep``: clearance, contact and backlash of every tooth over a turn."""

from __future__ import annotations

from typing import Any

from ..arguments import GAP_TOLERANCE_MM
from ..outputs import files, write_sweep
from ..reporting import ReportSettings, geometry_verdicts
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
)
from .engagement import checked_spec
from .findings import print_findings
from .folders import claim, holds_folders
from .whole import compute_whole, findings, print_paths


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
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def run_double(args, spec, alignment: dict[str, Any]) -> int:
    """Both meshes of a double-engagement spec, each into its folder (the sweep with its
    design angles and plots)."""
    settings = ReportSettings(angles=args.angles, tolerance_mm=args.tolerance, **alignment)
    res, out, paths = compute_whole(args, spec, ["alignment", "sweep"], settings, "sweep")
    status = findings(spec, settings, res, out, ["design-angles"], f"{spec.name}: checks at "
                      "each mesh's angle:")
    print_paths(paths)
    return status


@holds_folders
def run(args) -> int:
    spec, alignment = checked_spec(args)
    if spec.coupling.engagements == 2:
        return run_double(args, spec, alignment)
    mis = misalignment_deg(args, spec)
    out = claim(output_dir(args, spec), spec.to_dict(), files.SWEEP)
    with progress(f"sweep {spec.name}", 3) as update:
        result, point, paths = write_sweep(spec, out, mis, args.angles,
                                           tolerance_mm=args.tolerance,
                                           design=not args.no_design, plots=not args.no_plots,
                                           studies=not args.quick_plots, progress=update)
    summary = result.summary()
    print(f"{spec.name}: backlash {summary['aligned_backlash_mm'] * 1e3:.2f} µm aligned, "
          f"{summary['min_backlash_mm'] * 1e3:.2f} µm at least over the turn at {mis:g}°")
    critical = binding = None
    if point is not None:
        critical, binding = point.critical_deg, point.binding_deg
        print("critical misalignment (contact reaches a face end): "
              + (f"{critical:.4f}°" if critical is not None else "none up to 6°"))
        print("binding angle (smallest backlash over a turn = 0): "
              + (f"{binding:.4f}°" if binding is not None else "none up to 6°"))
    verdicts = geometry_verdicts(mis, summary["min_backlash_mm"], critical, binding)
    status = print_findings(f"checks at {mis:g}°:", verdicts if critical is not None
                            else verdicts[:1])  # the face-end check needs the design angles
    for path in paths:
        print(path)
    return status
