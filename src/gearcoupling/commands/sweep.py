"""``gearcoupling sweep``: clearance, contact and backlash of every tooth over a turn."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..atomic import write_json
from ..clearance import design_quantities, plot_all, require_finite, sweep
from ..errors import SpecError
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
    p.add_argument("--tolerance", type=positive_length, default=1e-7, metavar="MM",
                   help="accuracy of every minimum in mm (default 1e-7)")
    p.add_argument("--no-design", action="store_true",
                   help="skip the critical and binding angles (root finding, a few seconds)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV and JSON")
    p.add_argument("--quick-plots", action="store_true",
                   help="skip the backlash, R_c and generation studies among the plots")
    p.set_defaults(func=run)


def sweep_files(spec, out: Path, misalignment_deg: float, angles: int, *,
                tolerance_mm: float = 1e-7, design: bool = True, plots: bool = True,
                studies: bool = True) -> list[Path]:
    """Run a sweep and write ``sweep.csv``, ``sweep_summary.json`` and the plots."""
    if angles < 1:
        raise SpecError("--angles", angles, "must be at least 1")
    psi = np.arange(angles) * 360.0 / angles
    result = sweep(spec, misalignment_deg, psi, tolerance_mm=tolerance_mm).check_finite()
    summary = result.summary()
    extra = design_quantities(spec, misalignment_deg) if design else {}
    summary.update(extra)
    require_finite(summary, "sweep_summary.json")  # nothing is written before this
    paths = [result.write_csv(out / "sweep.csv"),
             write_json(out / "sweep_summary.json", summary)]
    if plots:
        paths += plot_all(result, spec, out, design=extra if design else None, studies=studies)
    return paths


def run(args) -> int:
    spec = spec_from_args(args)
    mis = misalignment_deg(args, spec)
    out = output_dir(args, spec)
    for path in sweep_files(spec, out, mis, args.angles, tolerance_mm=args.tolerance,
                            design=not args.no_design, plots=not args.no_plots,
                            studies=not args.quick_plots):
        print(path)
    return 0
