"""``gearcoupling compare``: a measured hub (mesh or point cloud) against the nominal.

``compare SPEC FILE`` writes ``inspection.csv`` (one row per measured tooth),
``inspection.json`` (registration, part values, limits, pass/fail),
``inspection.png``, ``deviation_map.png`` and ``deviation.ply`` (coloured points on the
part). ``compare SPEC A B`` inspects both and writes ``comparison.csv`` /
``comparison.json`` (B - A per tooth). Exit status 1 when a tooth fails a limit.
"""

from __future__ import annotations

from pathlib import Path

from ..atomic import require_file, write_json
from ..errors import SpecError
from ..hob import write_csv
from ..inspection import (
    LIMITS,
    STAGES,
    check_limits,
    compare_part,
    plot_deviation_map,
    plot_inspection,
    write_deviation_ply,
)
from ..plots import save_figure
from .common import add_spec_arguments, count, output_dir, progress, spec_from_args

MAX_FIT_POINTS = 1_000_000


def register(sub) -> None:
    p = sub.add_parser("compare", help="measured hub (mesh / point cloud) vs nominal, per tooth")
    add_spec_arguments(p)
    p.add_argument("files", nargs="+", metavar="FILE",
                   help="scan or mesh (STL/PLY/OBJ, CSV/XYZ); two files: compare B with A")
    p.add_argument("--units", default="mm", choices=("mm", "in", "m"),
                   help="units of the file coordinates (default mm)")
    p.add_argument("--limit", action="append", default=[], metavar="NAME=MM",
                   help="tolerance limit, repeatable, overriding the spec's [inspection] "
                        "table; NAME one of " + ", ".join(LIMITS))
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
            raise SpecError("--limit", item, "NAME=MM, e.g. fpt=0.012")
        try:
            out.update(check_limits({key.strip(): value.strip()}))
        except SpecError as err:
            raise SpecError("--limit", item, err.allowed) from None
    return out


def run(args) -> int:
    if len(args.files) > 2:
        raise SpecError("FILE", args.files, "one scan, or two (A B) to compare")
    spec = spec_from_args(args)
    limits = parse_limits(args.limit)
    for f in args.files:  # before the output folder is made (the reader checks the rest)
        require_file(f, "file", "a scan or mesh file (STL/PLY/OBJ, CSV/XYZ)")
    out = output_dir(args, spec)
    with progress("compare", 2 + STAGES * len(args.files)) as update:
        result = compare_part(spec, args.files[0],
                              args.files[1] if len(args.files) == 2 else None,
                              units=args.units, limits=limits,
                              coarse=args.coarse, fit_points=args.fit_points, progress=update)
    units = ["lengths in mm, + = material excess / toward increasing polar angle"]
    if len(args.files) == 2:
        files = [write_csv(out / "comparison.csv", result.rows(), units)]
        files.append(write_json(out / "comparison.json", {**result.summary(),
                                                          "files": [str(f) for f in files]}))
        reports = [result.a, result.b]
    else:
        reports = [result]
        files = [write_csv(out / "inspection.csv", result.rows(), units),
                 save_figure(plot_inspection(result), out / "inspection.png"),
                 save_figure(plot_deviation_map(result), out / "deviation_map.png"),
                 write_deviation_ply(result, out / "deviation.ply")]
        files.append(write_json(out / "inspection.json", {**result.summary(),
                                                          "files": [str(f) for f in files]}))
    failed = False
    for rep in reports:
        s = rep.summary()
        part = s["part"]
        failed |= not part["pass"]
        print(f"{Path(rep.source).name}: {part['teeth_measured']} teeth, registration rms "
              f"{1e3 * rep.registration.rms_mm:.2f} um, F_p {1e3 * part['F_p_mm']:.2f} um, "
              f"f_pt max {1e3 * (part['f_pt_max_mm'] or 0):.2f} um, "
              f"{'PASS' if part['pass'] else 'FAIL teeth ' + str(s['failed_teeth'])}")
    for f in files:
        print(f)
    return 1 if failed else 0
