"""``gearcoupling capacity``: torque capacity and q vs misalignment, per criterion."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..arguments import MAXIMA
from ..errors import ArgumentError, SpecError, brief
from ..io import parse_override, terminal_text
from ..loading import model_names, models_help, plot_capacity, write_capacity_csv
from ..outputs import CapacityComparison, compare_capacity, comparison_range
from ..plots import save_figure
from ..spec import MISALIGNMENT_RANGE_DEG, load_spec
from . import whole
from .common import (
    add_alignment_arguments,
    add_spec_arguments,
    count,
    number_in,
    output_dir,
    progress,
)
from .engagement import checked_spec
from .folders import claim, holds_folders

FILES = ("capacity.csv", "capacity.png")

MAX_COUNT = MAXIMA["misalignments"]  # of a curve (each one is a sweep over a tooth pitch)
DEFAULT_COUNT = 13


def register(sub) -> None:
    p = sub.add_parser("capacity", help="torque capacity and q vs misalignment per criterion "
                       "(capacity.csv, capacity.png), optionally against other specs")
    add_spec_arguments(p)
    p.add_argument("--compare", nargs="+", default=[], metavar="SPEC",
                   help="more specs (templates or files) to overlay, same --set applied")
    p.add_argument("--model", choices=model_names(), default=None,
                   help=f"load model ({models_help()}; default: each spec's [load] model)")
    p.add_argument("--max", type=number_in(*MISALIGNMENT_RANGE_DEG, "degrees", open_lo=True),
                   default=None,
                   metavar="DEG", help="largest misalignment, in (0, 6] degrees (default: the "
                   "largest critical misalignment of the specs, at least their design angles "
                   "and 0.5)")
    p.add_argument("--count", type=count(2, MAX_COUNT), default=None, metavar="N",
                   help=f"misalignments from 0 to --max, 2-{MAX_COUNT} (default "
                        f"{DEFAULT_COUNT}; each a capacity search)")
    p.add_argument("--misalignments", type=degree_list, default=None, metavar="DEG,DEG,...",
                   help="the misalignments themselves, comma-separated degrees 0-6 "
                        "(instead of --max and --count)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV")
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def degree_list(text: str) -> list[float]:
    """argparse type: comma-separated misalignments, 2 to ``MAX_COUNT`` different
    numbers in [0, 6] degrees."""
    rule = f"2 to {MAX_COUNT} different angles from 0 to 6 degrees, e.g. 0,0.5,1,2"
    items = [item.strip() for item in text.split(",") if item.strip()]
    if not 2 <= len(items) <= MAX_COUNT:  # before reading them: 5000 values are refused
        raise argparse.ArgumentTypeError(f"{len(items)} values: {rule}")
    parse = number_in(*MISALIGNMENT_RANGE_DEG, "degrees")
    values = [parse(item) for item in items]
    if len(set(values)) < 2:
        raise argparse.ArgumentTypeError(f"{brief(repr(text), 60)}: {rule}")
    return values


def capacity_files(comparison: CapacityComparison, out: Path, *,
                   plots: bool = True) -> list[Path]:
    """``capacity.csv`` and ``capacity.png`` of a comparison."""
    paths = [write_capacity_csv(comparison.curves, out / "capacity.csv")]
    if plots:
        fig = plot_capacity(comparison.curves, critical_deg=comparison.critical_deg)
        paths.append(save_figure(fig, out / "capacity.png"))
    return paths


def _compared_spec(text: str, overrides: dict):
    """A ``--compare`` spec; its errors name ``--compare``."""
    try:
        return load_spec(text, **overrides)
    except SpecError as err:
        raise ArgumentError("--compare", text, err.allowed if err.field == "spec" else str(err)) \
            from None


@holds_folders
def run(args) -> int:
    if args.misalignments is not None and (args.max is not None or args.count is not None):
        raise ArgumentError("--misalignments", ",".join(map(str, args.misalignments)),
                            "give either --misalignments or --max/--count")
    spec, alignment = checked_spec(args)
    if spec.coupling.engagements == 2:
        return whole.capacity(args, spec, alignment)
    overrides = dict(parse_override(t) for t in args.overrides)
    specs = [spec, *(_compared_spec(s, overrides) for s in args.compare)]
    names = [s.name for s in specs]
    if len(set(names)) < len(names):  # before any work: the same curve twice
        raise ArgumentError("--compare", " ".join(args.compare), f"specs of other names than "
                            f"{', '.join(sorted({n for n in names if names.count(n) > 1}))}: "
                            "each compared spec needs its own name")
    mis = args.misalignments
    if mis is None:
        mis, _ = comparison_range(specs, args.count or DEFAULT_COUNT, args.max)
    out = claim(output_dir(args, spec), [s.to_dict() for s in specs], FILES)
    with progress("capacity", len(specs) * len(mis)) as update:
        comparison = compare_capacity(specs, mis, model=args.model, progress=update)
    paths = capacity_files(comparison, out, plots=not args.no_plots)
    for line in capacity_lines(comparison):
        print(line)
    for path in paths:
        print(path)
    return 0


def capacity_lines(comparison: CapacityComparison) -> list[str]:
    """Per spec (its name as :func:`~gearcoupling.io.terminal_text`), a heading with its
    critical misalignment, then per misalignment the capacity (K applied), the governing
    criterion and K."""
    lines = []
    for name, curve in comparison.curves.items():
        crit = comparison.critical_deg.get(name)
        lines += [f"{terminal_text(name)}: capacity per misalignment ({curve[0].model} model), "
                  "critical misalignment " + ("none up to 6°" if crit is None else
                                              f"{crit:.4g}°"),
                  f"  {'i°':>6}  {'capacity N·m':>12}  {'governing':<16}  K"]
        for c in curve:
            cap = "no limit" if c.capacity_Nm is None else f"{c.capacity_Nm:.4g}"
            lines.append(f"  {c.misalignment_deg:>6.3g}  {cap:>12}  "
                         f"{c.governing.replace('_', ' '):<16}  {c.accuracy_factor:g}")
    return lines
