"""``gearcoupling hob``: hob centre path and a two-axis feed program for the spec's hub.

Writes ``hob_path.csv`` (exact path samples), ``hob_program.nc`` (G-code: X infeed,
Z feed, G2/G3 arcs where the path is circular) and ``hob.json`` (settings, measured
chordal deviation, start/end positions, crown drop at the tooth ends).
"""

from __future__ import annotations

from ..hob import FEED_RANGE_MM_PER_REV, check_hob_diameter, hob_program
from ..outputs import files, program_files
from .common import add_spec_arguments, number_in, output_dir, positive_length, spec_from_args
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("hob", help="hob centre path and feed program (CSV, G-code)")
    add_spec_arguments(p)
    p.add_argument("--hob-diameter", type=positive_length, required=True, metavar="MM",
                   help="hob outside diameter in mm, above 2 (dedendum + module) "
                        "and at most 1000")
    p.add_argument("--tolerance", type=positive_length, default=None, metavar="MM",
                   help="largest chordal deviation of the program in mm, > 0 "
                        "(default: module / 1000)")
    p.add_argument("--feed", type=number_in(*FEED_RANGE_MM_PER_REV, "mm/rev"), default=1.0,
                   metavar="MM_PER_REV", help="axial feed per workpiece revolution written as "
                   f"F, {FEED_RANGE_MM_PER_REV[0]:g} to {FEED_RANGE_MM_PER_REV[1]:g} (default 1)")
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    check_hob_diameter(spec, args.hob_diameter, "--hob-diameter")
    out = claim(output_dir(args, spec), spec.to_dict(), files.HOB_PROGRAM)
    prog = hob_program(spec, args.hob_diameter, tolerance_mm=args.tolerance)
    written = program_files(prog, out, args.feed)
    s = prog.summary()
    print(f"hob: {s['arc_moves']} arc and {s['line_moves']} line moves, max chordal deviation "
          f"{s['max_deviation_mm']:.3g} mm (tolerance {s['tolerance_mm']:.3g} mm), "
          f"Z {s['z_start_mm']:.4f} .. {s['z_end_mm']:.4f} mm, crown drop at ends "
          f"{s['crown_drop_end_mm']:.5f} mm")
    for f in written:
        print(f)
    return 0
