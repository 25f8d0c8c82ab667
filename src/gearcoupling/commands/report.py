"""``gearcoupling report``: the design report (HTML, optionally PDF) of a spec.

Writes ``report.html`` (self-contained: figures inline, the 3D viewer embedded) and, beside
it, the files of the stages it shows (each figure's data); ``--pdf`` also prints
``report.pdf``. Exit status
1 when a judged check fails.
"""

from __future__ import annotations

from ..errors import ArgumentError
from ..hob import check_hob_diameter
from ..inspection import GRADES, LIMITS, grade_limits
from ..io import require_file
from ..loading import model_names, models_help
from ..outputs import run_folders
from ..reporting import KNOB_RANGES, ReportSettings, report, report_files
from .common import (
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
from .compare import parse_limits
from .engagement import checked_spec
from .folders import claim, holds_folders
from .run import add_wear_arguments, wear_asked, wear_options

#: the accuracy knobs the command takes, as options
KNOBS = {"angles": "rotations over a turn of the clearance sweep",
         "phases": "rotations per tooth pitch of the loads over a turn",
         "capacity_count": "misalignments of the capacity curve",
         "check_angles": "poses of the mesh interference check"}


def register(sub) -> None:
    p = sub.add_parser("report", help="design report: one self-contained HTML file (and "
                       "--pdf) with the verdict against the spec's limits")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--torque", type=torque(), default=None, metavar="NM",
                   help="signed torque in N·m, |T| from 1e-9 to 1e9 or 0 (default: the "
                        "spec's [load] torque)")
    p.add_argument("--model", choices=model_names(), default=None,
                   help=f"load model ({models_help()}; default: the spec's [load] model)")
    p.add_argument("--scan", default=None, metavar="FILE",
                   help="a measured hub (mesh or point cloud) to inspect against the nominal")
    p.add_argument("--units", default="mm", choices=("mm", "in", "m"),
                   help="units of the scan's coordinates (default mm)")
    p.add_argument("--grade", type=count(GRADES[0], GRADES[-1]), default=None, metavar="Q",
                   help="ISO 1328-1:2013 flank tolerance class 1-11 for the scan's limits")
    p.add_argument("--limit", action="append", default=[], metavar="NAME=MM",
                   help="a tolerance limit of the scan, repeatable; NAME one of "
                        + ", ".join(LIMITS))
    p.add_argument("--hob-diameter", type=positive_length, default=None, metavar="MM",
                   help="hob outside diameter of the feed program (default: an illustrative "
                        "max(50, 20 module) mm)")
    for name, text in KNOBS.items():
        lo, hi = KNOB_RANGES[name]
        default = getattr(ReportSettings(), name)
        p.add_argument(f"--{name.replace('_', '-')}", type=count(lo, hi), default=None,
                       metavar="N", help=f"{text}; {lo}-{hi} (default {default})")
    p.add_argument("--no-viewer", action="store_true", help="leave out the 3D view")
    p.add_argument("--no-datasheet", action="store_true",
                   help="leave out the API 671 data sheet (its stiffness matrix, wind-up curve "
                        "and allowable misalignment: the costliest section)")
    p.add_argument("--pdf", action="store_true",
                   help="also print report.pdf through headless chromium (browser extra)")
    add_alignment_arguments(p)
    add_wear_arguments(p)
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    spec, alignment = checked_spec(args)
    n = spec.coupling.engagements
    if args.hob_diameter is not None:
        check_hob_diameter(spec, args.hob_diameter, "--hob-diameter")
    if args.scan is not None:
        require_file(args.scan, "--scan", "a scan or mesh file (STL/PLY/OBJ, CSV/XYZ)",
                     ArgumentError)
    if args.grade is not None:
        grade_limits(spec, args.grade, "--grade")
    knobs = {k: getattr(args, k) for k in KNOBS if getattr(args, k) is not None}
    settings = ReportSettings(misalignment_deg=None if n == 2 else misalignment_deg(args, spec),
                              torque_Nm=args.torque, model=args.model, scan=args.scan,
                              scan_units=args.units, grade=args.grade,
                              limits=parse_limits(args.limit),
                              hob_diameter_mm=args.hob_diameter, viewer=not args.no_viewer,
                              datasheet=not args.no_datasheet,
                              **knobs, **alignment, **wear_options(args))
    wear_asked(settings, spec)  # a wear option without its pair: refused naming it
    out = claim(output_dir(args, spec), spec.to_dict(),
                report_files(settings, args.pdf, n, spec), run_folders(n))
    with progress(f"report {spec.name}", 1) as update:
        try:
            result = report(spec, out, pdf=args.pdf, settings=settings, progress=update)
        except ArgumentError as err:  # the scan read before any work: name the option
            if getattr(err, "field", None) != "scan":
                raise
            raise ArgumentError("--scan", args.scan, err.allowed) from None
    print(f"{spec.name}: {result.verdict_text} ({result.wall_seconds:.1f} s)")
    for path in (result.html, result.pdf):
        if path is not None:
            print(path)
    return 1 if result.verdict == "fail" else 0
