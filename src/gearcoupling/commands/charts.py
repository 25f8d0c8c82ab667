"""``gearcoupling charts``: nominal measuring-machine charts of the hub flanks.

Writes ``charts.png`` (profile and lead traces per flank with the evaluation ranges),
``nominal_traces.csv`` (points with normals, for a gear measuring machine) and
``charts.json`` (evaluation ranges, C_beta, f_Hbeta, f_Halpha per flank).
"""

from __future__ import annotations

from ..hob import measuring_charts
from ..outputs import chart_files, files
from .common import add_spec_arguments, count, number_in, output_dir, spec_from_args
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("charts", help="nominal profile/lead measuring charts and trace CSV")
    add_spec_arguments(p)
    p.add_argument("--points", type=count(5, 10_001), default=101, metavar="N",
                   help="points per trace, 5-10001 (default 101)")
    p.add_argument("--tip-exclusion", type=number_in(0.0, 0.5), default=0.08, metavar="SHARE",
                   help="share of the profile length left out of L_alpha at the tip, "
                        "0-0.5 (default 0.08)")
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    out = claim(output_dir(args, spec), spec.to_dict(), files.CHARTS)
    charts = measuring_charts(spec, args.points, args.tip_exclusion)
    written = chart_files(charts, out)
    for flank, v in charts.values.items():
        print(f"{flank}: C_beta {1e3 * v['C_beta_mm']:.2f} um, f_Hbeta "
              f"{1e3 * v['f_Hbeta_mm']:.2f} um, f_Halpha mid/ends "
              f"{1e3 * v['f_Halpha_mid_mm']:.2f} / {1e3 * v['f_Halpha_z_plus_mm']:.2f} um")
    for f in written:
        print(f)
    return 0
