"""``gearcoupling wear``: the wear of the flanks over hours of running and the life to the
wear limit (wear.csv, wear_depth.csv, wear_summary.json, plots)."""

from __future__ import annotations

import argparse

from ..arguments import parse_number
from ..errors import ArgumentError
from ..wear import (
    DEFAULT_PHASES,
    DEFAULT_STEP_FRACTION,
    MAX_PHASES,
    REGIMES,
    WearSettings,
    wear,
    write_wear,
)
from .common import (
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    number_in,
    output_dir,
    positive,
    progress,
    spec_from_args,
    torque,
)


def _point(text: str) -> tuple[float, ...]:
    """argparse type: ``DEG,NM,RPM,HOURS`` (an operating point of a duty)."""
    parts = text.split(",")
    if len(parts) != 4:
        raise argparse.ArgumentTypeError(f"{text[:60]!r}: must be DEG,NM,RPM,HOURS "
                                         "(misalignment, torque, speed, hours)")
    try:
        return tuple(parse_number(t, "--point") for t in parts)
    except ArgumentError as err:
        raise argparse.ArgumentTypeError(f"{text[:60]!r}: {err.allowed}") from None


def _grid(text: str) -> tuple[int, int]:
    """argparse type: ``NFxND`` cells along the face and across the depth."""
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
        raise argparse.ArgumentTypeError(f"{text[:60]!r}: must be NFxND, e.g. 48x32")
    return int(parts[0]), int(parts[1])


def register(sub) -> None:
    p = sub.add_parser("wear", help="wear of the flanks over hours of running and the life to "
                       "the wear limit (wear.csv, wear_depth.csv, wear_summary.json, plots)")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--torque", type=torque(zero=False), default=None, metavar="NM",
                   help="torque in N·m, non-zero; the sign picks the loaded flank; write a "
                        "negative one as --torque=-5e3 (default: the spec's)")
    p.add_argument("--speed", type=positive("rpm"), default=None, metavar="RPM",
                   help="speed in rpm, > 0 (default: the spec's [wear] speed_rpm; required "
                        "without it unless --point gives the duty)")
    p.add_argument("--hours", type=positive("h"), default=None, metavar="H",
                   help="hours of running, > 0 (default: the sum of the --point hours, else the "
                        "spec's [wear] hours)")
    p.add_argument("--point", dest="points", action="append", type=_point, default=[],
                   metavar="DEG,NM,RPM,HOURS",
                   help="an operating point of a duty (repeatable; the points run "
                        "interleaved, each for its share of the hours; instead of "
                        "--misalignment, --torque and --speed)")
    p.add_argument("--regime", choices=tuple(REGIMES), default=None,
                   help="lubrication regime giving the coefficient and its band (default: "
                        "the spec's [wear] regime, else grease)")
    p.add_argument("--coefficient", type=number_in(0.0, 1.0, "mm³/(N·m)", open_lo=True),
                   default=None, metavar="K",
                   help="Archard's coefficient of each flank in mm³/(N·m) (default: the "
                        "regime's)")
    p.add_argument("--limit-fraction", type=number_in(0.0, 1.0, open_lo=True), default=None,
                   metavar="F", help="wear limit: tooth thickness loss as a share of the "
                                     "thickness, in (0, 1] (default: the spec's, else 0.1)")
    p.add_argument("--axial-float", type=number_in(0.0, 100.0, "mm"), default=0.0,
                   metavar="MM", help="amplitude of an axial float of the hub, once per "
                                      "revolution (default 0)")
    p.add_argument("--step-fraction", type=number_in(0.0, 1.0, open_lo=True),
                   default=DEFAULT_STEP_FRACTION, metavar="F",
                   help="a step removes at most this share of the elastic approach "
                        "(default %(default)g)")
    p.add_argument("--grid", type=_grid, default=None, metavar="NFxND",
                   help="surface model cells per loaded tooth (default: the wear default)")
    p.add_argument("--phases", type=count(1, MAX_PHASES), default=DEFAULT_PHASES,
                   metavar="N", help=f"rotations per tooth pitch, 1-{MAX_PHASES} "
                                     "(default %(default)s)")
    p.add_argument("--no-plots", action="store_true", help="write only the CSV and JSON")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = spec_from_args(args)
    duty = None
    if args.points:
        for flag, value in (("--misalignment", args.misalignment), ("--torque", args.torque),
                            ("--speed", args.speed)):
            if value is not None:
                raise ArgumentError(flag, value, "give the duty by --point alone")
        duty = args.points
    elif args.speed is None and WearSettings.from_spec(spec).speed_rpm is None:
        raise ArgumentError("--speed", None, "is required (rpm, > 0) unless the spec's "
                            "[wear] sets speed_rpm, or give --point")
    mis = None if duty else misalignment_deg(args, spec)
    out = output_dir(args, spec)
    with progress(f"wear {spec.name}", 1000) as update:
        res = wear(spec, mis, args.torque, args.speed, args.hours, duty=duty,
                   coefficient_mm3_per_Nm=args.coefficient, regime=args.regime,
                   limit_fraction=args.limit_fraction, axial_float_mm=args.axial_float,
                   step_fraction=args.step_fraction, grid=args.grid, phases=args.phases,
                   progress=update)
    paths = write_wear(res, out, plots=not args.no_plots)
    lo, hi = res.life_band_h
    print(f"{spec.name}: wear life {res.life_h:.4g} h ({res.life_basis}), {lo:.4g}-{hi:.4g} h "
          f"across the {res.settings.regime} band; {res.steps} steps")
    status = 0
    need = res.settings.required_life_h
    if need is not None:
        ok = res.life_h >= need
        print(f"  {'pass' if ok else 'FAIL'}: wear life: {res.life_h:.4g} h (required "
              f"{need:.4g} h)")
        status = 0 if ok else 1
    for path in paths:
        print(path)
    return status
