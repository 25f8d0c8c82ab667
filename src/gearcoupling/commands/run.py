"""``gearcoupling run``: everything the project can make for a spec, into one folder.

Steps are registered in :data:`STEPS` as ``(label, function(spec, out_dir) -> [paths])``;
later features add theirs (parts, STEP, sweep, viewer) without touching this loop.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from ..atomic import write_json
from .common import add_spec_arguments, output_dir, progress, spec_from_args

Step = Callable[[object, Path], list[Path]]


def _spec_step(spec, out: Path) -> list[Path]:
    from .spec import resolved

    return [write_json(out / "spec.json", resolved(spec))]


def _sections_step(spec, out: Path) -> list[Path]:
    from ..plots import plot_sections

    return [plot_sections(spec, out / "sections.png")]


def _viewer_step(spec, out: Path) -> list[Path]:
    import sys

    from ..errors import BackendError
    from ..viewer.html import write_html

    try:
        return [write_html(spec, out / "viewer.html")]
    except BackendError as err:  # viser is an optional extra: the other outputs stand
        print(f"gearcoupling: viewer.html skipped: {err}", file=sys.stderr)
        return []


def _parts_step(spec, out: Path) -> list[Path]:
    from .generate import parts_step

    return parts_step(spec, out)


def _step_step(spec, out: Path) -> list[Path]:
    from .generate import step_step

    return step_step(spec, out)


def _sweep_step(spec, out: Path) -> list[Path]:
    import math

    from .sweep import sweep_files

    return sweep_files(spec, out, math.degrees(spec.design_misalignment), 360)


def _check_step(spec, out: Path) -> list[Path]:
    from .check import run_step

    return run_step(spec, out)


STEPS: list[tuple[str, Step]] = [
    ("resolved spec", _spec_step),
    ("section plots", _sections_step),
    ("parts", _parts_step),
    ("STEP", _step_step),
    ("static viewer HTML", _viewer_step),
    ("interference check", _check_step),
    ("sweep at the design angle", _sweep_step),
]


def register(sub) -> None:
    p = sub.add_parser("run", help="write everything for a spec into outputs/<spec>/")
    add_spec_arguments(p)
    p.set_defaults(func=run)


def run(args) -> int:
    spec = spec_from_args(args)
    out = output_dir(args, spec)
    written: list[Path] = []
    with progress(f"{spec.name}", len(STEPS)) as advance:
        for label, step in STEPS:
            written.extend(step(spec, out))
            advance(label)
    for path in written:
        print(path)
    return 0
