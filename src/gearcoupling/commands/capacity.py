"""``gearcoupling capacity``: torque capacity and q vs misalignment, per criterion."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import ArgumentError, SpecError
from ..io import parse_override
from ..loading import Capacity, capacity_curve, plot_capacity, write_capacity_csv
from ..loadspec import LOAD_MODELS
from ..plots import save_figure
from ..spec import load_spec
from .common import (
    add_spec_arguments,
    count,
    number_in,
    output_dir,
    progress,
    spec_from_args,
)

MAX_COUNT = 200  # misalignments of a curve (each one is a sweep over a tooth pitch)

def register(sub) -> None:
    p = sub.add_parser("capacity", help="torque capacity and q vs misalignment per criterion "
                       "(capacity.csv, capacity.png), optionally against other specs")
    add_spec_arguments(p)
    p.add_argument("--compare", nargs="+", default=[], metavar="SPEC",
                   help="more specs (templates or files) to overlay, same --set applied")
    p.add_argument("--model", choices=LOAD_MODELS, default=None,
                   help="load model (default: each spec's [load] model)")
    p.add_argument("--max", type=number_in(0.0, 6.0, "degrees", open_lo=True), default=None,
                   metavar="DEG", help="largest misalignment, in (0, 6] degrees (default: the "
                   "spec's design angle, >= 0.5)")
    p.add_argument("--count", type=count(2, MAX_COUNT), default=25, metavar="N",
                   help=f"misalignments from 0 to --max, 2-{MAX_COUNT} (default 25)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV")
    p.set_defaults(func=run)


def capacity_files(specs: list, out: Path, misalignments_deg: np.ndarray, *,
                   model: str | None = None, plots: bool = True) -> list[Path]:
    """Capacity curves of ``specs`` (first one names the folder) to CSV and plot."""
    curves: dict[str, list[Capacity]] = {}
    n = len(specs) * misalignments_deg.size
    with progress("capacity", n) as update:
        for k, spec in enumerate(specs):
            curves[spec.name] = capacity_curve(
                spec, misalignments_deg, model=model,
                progress=lambda i, _n, k=k: update(k * misalignments_deg.size + i, n))
    paths = [write_capacity_csv(curves, out / "capacity.csv")]
    if plots:
        paths.append(save_figure(plot_capacity(curves), out / "capacity.png"))
    return paths


def _compared_spec(text: str, overrides: dict):
    """A ``--compare`` spec; its errors name ``--compare``."""
    try:
        return load_spec(text, **overrides)
    except SpecError as err:
        raise ArgumentError("--compare", text, err.allowed if err.field == "spec" else str(err)) \
            from None


def run(args) -> int:
    spec = spec_from_args(args)
    overrides = dict(parse_override(t) for t in args.overrides)
    others = [_compared_spec(s, overrides) for s in args.compare]
    top = args.max if args.max is not None else max(math.degrees(spec.design_misalignment), 0.5)
    out = output_dir(args, spec)
    for path in capacity_files([spec, *others], out, np.linspace(0.0, top, args.count),
                               model=args.model, plots=not args.no_plots):
        print(path)
    return 0
