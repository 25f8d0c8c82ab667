"""``gearcoupling compare``: a measured hub (mesh or point cloud) against the nominal.

``compare SPEC FILE`` writes ``inspection.csv`` (one row per measured tooth),
``inspection.json`` (registration, part values, limits, pass/fail),
``inspection.png``, ``deviation_map.png`` and ``deviation.ply`` (coloured points on the
part). ``compare SPEC A B`` inspects both and writes ``comparison.csv`` /
``comparison.json`` (B - A per tooth). Each limit is printed with its verdict: ``pass``,
``fail`` or ``not judged`` (no limit set: a quantity without a limit is never passed).
Exit status 1 when a limit fails.
"""

from __future__ import annotations

from pathlib import Path

from ..arguments import parse_number
from ..errors import ArgumentError, SpecError
from ..inspection import (
    GRADES,
    LIMITS,
    STAGES,
    check_limits,
    compare_part,
    grade_limits,
    plot_deviation_map,
    plot_inspection,
    write_deviation_ply,
)
from ..io import require_file, write_csv_records, write_json
from ..plots import save_figure
from .common import add_spec_arguments, count, output_dir, progress, spec_from_args
from .folders import claim, holds_folders

#: the files of a comparison of two scans, and of the inspection of one
FILES = {2: ("comparison.csv", "comparison.json"),
         1: ("inspection.csv", "inspection.png", "deviation_map.png", "deviation.ply",
             "inspection.json")}

MAX_FIT_POINTS = 1_000_000


def register(sub) -> None:
    p = sub.add_parser("compare", help="measured hub (mesh / point cloud) vs nominal, per tooth")
    add_spec_arguments(p)
    p.add_argument("files", nargs="+", metavar="FILE",
                   help="scan or mesh (STL/PLY/OBJ, CSV/XYZ); two files: compare B with A")
    p.add_argument("--units", default="mm", choices=("mm", "in", "m"),
                   help="units of the file coordinates (default mm)")
    p.add_argument("--limit", action="append", default=[], metavar="NAME=MM",
                   help="tolerance limit, repeatable, overriding --grade and the spec's "
                        "[inspection] table; NAME one of " + ", ".join(LIMITS))
    p.add_argument("--grade", type=count(GRADES[0], GRADES[-1]), default=None, metavar="Q",
                   help="ISO 1328-1:2013 flank tolerance class 1-11: limits fpt, Fp, Fr, "
                        "f_Halpha, f_Hbeta for the hub's size (overriding [inspection])")
    p.add_argument("--coarse", default="auto", choices=("auto", "none"),
                   help="auto: find axis and teeth; none: the file is in the hub frame")
    p.add_argument("--fit-points", type=count(100, MAX_FIT_POINTS), default=20_000,
                   metavar="N", help=f"points used by the fine registration, "
                   f"100-{MAX_FIT_POINTS} (default 20000)")
    p.set_defaults(func=run)


def parse_limits(items: list[str]) -> dict[str, float]:
    """``NAME=MM`` items -> limits, each checked (known name, finite length > 0)."""
    out: dict[str, float] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep:
            raise ArgumentError("--limit", item, "NAME=MM, e.g. fpt=0.012")
        try:
            out.update(check_limits({key.strip(): parse_number(value, "--limit")}))
        except ArgumentError as err:
            raise ArgumentError("--limit", item, err.allowed) from None
    return out


@holds_folders
def run(args) -> int:
    if len(args.files) > 2:
        raise SpecError("FILE", args.files, "one scan, or two (A B) to compare")
    spec = spec_from_args(args)
    graded = {} if args.grade is None else grade_limits(spec, args.grade, "--grade")
    limits = {**graded, **parse_limits(args.limit)}
    for f in args.files:  # before the output folder is made (the reader checks the rest)
        require_file(f, "file", "a scan or mesh file (STL/PLY/OBJ, CSV/XYZ)", ArgumentError)
    out = claim(output_dir(args, spec), spec.to_dict(), FILES[len(args.files)])
    with progress("compare", 2 + STAGES * len(args.files)) as update:
        result = compare_part(spec, *args.files, units=args.units, limits=limits,
                              coarse=args.coarse, fit_points=args.fit_points, progress=update)
    units = ["lengths in mm, + = material excess / toward increasing polar angle"]
    if len(args.files) == 2:
        files = [write_csv_records(out / "comparison.csv", result.rows(), units)]
        files.append(write_json(out / "comparison.json", {**result.summary(),
                                                          "files": [str(f) for f in files]}))
        reports = [result.a, result.b]
    else:
        reports = [result]
        files = [write_csv_records(out / "inspection.csv", result.rows(), units),
                 save_figure(plot_inspection(result), out / "inspection.png"),
                 save_figure(plot_deviation_map(result), out / "deviation_map.png"),
                 write_deviation_ply(result, out / "deviation.ply")]
        files.append(write_json(out / "inspection.json", {**result.summary(),
                                                          "files": [str(f) for f in files]}))
    failed = False
    for rep in reports:
        failed |= rep.part["pass"] is False
        for line in verdict_lines(rep):
            print(line)
    for f in files:
        print(f)
    return 1 if failed else 0


def verdict_lines(rep) -> list[str]:
    """The inspection of one part as printed: a headline, then one line per limit with
    the worst measured value, the limit and the verdict."""
    s = rep.summary()
    part = s["part"]
    name = Path(rep.source).name
    lines = [f"{name}: {part['teeth_measured']} teeth, registration rms "
             f"{1e3 * rep.registration.rms_mm:.2f} um"]
    for v in part["verdicts"]:
        value = "-" if v["measured_mm"] is None else f"{1e3 * v['measured_mm']:.2f} um"
        limit = "no limit" if v["limit_mm"] is None else f"limit {1e3 * v['limit_mm']:.2f} um"
        verdict = v["verdict"].upper() if v["verdict"] != "not judged" else \
            f"not judged ({v['reason']})"
        lines.append(f"  {v['limit']:<9} {value:>11}  {limit:<17} {verdict}")
    if part["pass"] is None:
        lines.append(f"{name}: NOT JUDGED: no limit is set (give --limit NAME=MM, --grade Q "
                     "or an [inspection] table)")
    else:
        open_ = f"; not judged: {', '.join(part['not_judged'])}" if part["not_judged"] else ""
        teeth = f" (teeth {s['failed_teeth']})" if s["failed_teeth"] else ""
        lines.append(f"{name}: {'PASS' if part['pass'] else 'FAIL' + teeth} on the limits "
                     f"set{open_}")
    return lines
