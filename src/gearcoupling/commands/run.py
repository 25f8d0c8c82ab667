"""``gearcoupling run``: everything the project can make for a spec, into one folder
(:func:`gearcoupling.run`)."""

from __future__ import annotations

import sys
from typing import Any

from ..errors import ArgumentError
from ..outputs import STEPS, Rating, StageSettings, run_files, run_folders
from ..outputs import run as run_all
from .common import (
    add_alignment_arguments,
    add_spec_arguments,
    count,
    output_dir,
    positive,
    progress,
)
from .engagement import checked_spec
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("run", help="write everything for a spec into outputs/<spec>/")
    add_spec_arguments(p)
    p.add_argument("--only", metavar="KEYS", default=None,
                   help=f"comma-separated steps to run, from {','.join(STEPS)}")
    p.add_argument("--skip", metavar="KEYS", default="", help="comma-separated steps to skip")
    p.add_argument("--workers", type=count(1, 2), default=None,
                   help="1: one process; 2: two (default where there are two cores)")
    add_alignment_arguments(p)
    add_wear_arguments(p)
    p.set_defaults(func=run)


def add_wear_arguments(parser) -> None:
    """``--wear-hours`` and ``--wear-speed``: the stage ``wear`` at the operating point
    (``run`` and ``report``)."""
    group = parser.add_argument_group(
        "wear over life", "the stage wear at the operating point's angle and torque, run "
        "where a speed and hours are given here or in the spec's [wear] (docs/wear.md)")
    group.add_argument("--wear-hours", type=positive("h", 1e7), default=None, metavar="H",
                       help="hours of running, > 0 (default: the spec's [wear] hours)")
    group.add_argument("--wear-speed", type=positive("rpm", 1e6), default=None, metavar="RPM",
                       help="speed in rpm, > 0 (default: the spec's [wear] speed_rpm)")


#: each wear option's keyword of :class:`~gearcoupling.StageSettings`
WEAR_OPTIONS = {"wear_hours": "--wear-hours", "wear_speed_rpm": "--wear-speed"}


def wear_options(args) -> dict[str, Any]:
    """The wear options given, as keywords of :class:`~gearcoupling.StageSettings`."""
    given = {"wear_hours": args.wear_hours, "wear_speed_rpm": args.wear_speed}
    return {k: v for k, v in given.items() if v is not None}


def wear_asked(settings: StageSettings, spec) -> bool:
    """:meth:`~gearcoupling.StageSettings.wear_asked`, a refusal naming the option."""
    try:
        return settings.wear_asked(spec)
    except ArgumentError as err:
        if err.field not in WEAR_OPTIONS:
            raise
        raise ArgumentError(WEAR_OPTIONS[err.field], err.value, err.allowed) from None


def _keys(option: str, text: str | None) -> list[str]:
    keys = [k.strip() for k in (text or "").split(",") if k.strip()]
    unknown = sorted(set(keys) - set(STEPS))
    if unknown:
        raise ArgumentError(option, ",".join(unknown), f"steps are {','.join(STEPS)}")
    return keys


@holds_folders
def run(args) -> int:
    only = _keys("--only", args.only) if args.only is not None else None
    skip = _keys("--skip", args.skip)
    spec, alignment = checked_spec(args)
    n = spec.coupling.engagements
    settings = StageSettings(**alignment, **wear_options(args))
    out = claim(output_dir(args, spec), spec.to_dict(),
                run_files(only, skip, n, wear_asked(settings, spec)), run_folders(n))
    with progress(spec.name, 1) as update:
        res = run_all(spec, out, only=only, skip=skip, workers=args.workers, progress=update,
                      settings=settings)
    for key, reason in res.skipped.items():
        scope, _, name = key.rpartition("/")
        where = f" ({scope})" if scope else ""
        print(f"gearcoupling: {STEPS[name]}{where} skipped: {reason}", file=sys.stderr)
    for scope in ("", *run_folders(n)):  # what the report will judge: said now
        rating = res.results.scope(scope).values.get("rating")
        if isinstance(rating, Rating):
            where = f"{scope}: " if scope else ""
            print(f"gearcoupling: {where}{rating.sentence()}", file=sys.stderr)
    steps = ", ".join(f"{k} {s:.1f} s" for k, s in res.seconds.items())
    print(f"gearcoupling: {len(res.files)} files in {res.wall_seconds:.1f} s with "
          f"{res.workers} worker(s) ({steps})", file=sys.stderr)
    for path in res.files:
        print(path)
    return 0
