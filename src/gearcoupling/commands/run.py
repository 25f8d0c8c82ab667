"""``gearcoupling run``: everything the project can make for a spec, into one folder.

Steps are registered in :data:`STEPS` as ``(key, label, function(spec, out_dir) -> [paths])``;
each imports its stage only when it runs. ``--only``/``--skip`` take comma-separated keys.
A step whose optional back-end is missing (STEP, viewer) says so and writes nothing.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

from ..atomic import write_json
from ..errors import BackendError, SpecError
from ..plots import plot_sections
from ..viewer import write_html
from .check import run_step
from .common import add_spec_arguments, output_dir, progress, spec_from_args
from .generate import parts_step, step_step
from .load import load_files
from .spec import resolved
from .sweep import sweep_files

Step = Callable[[object, Path], list[Path]]


class SkipStep(Exception):
    """A step that does not apply to this spec (said on stderr; the other steps run)."""


def _spec(spec, out: Path) -> list[Path]:
    return [write_json(out / "spec.json", resolved(spec))]


def _sections(spec, out: Path) -> list[Path]:
    return [plot_sections(spec, out / "sections.png")]


def _parts(spec, out: Path) -> list[Path]:
    return parts_step(spec, out)


def _step_files(spec, out: Path) -> list[Path]:
    return step_step(spec, out)


def _sweep(spec, out: Path) -> list[Path]:
    return sweep_files(spec, out, spec.design_misalignment_deg, 360)


def _load(spec, out: Path) -> list[Path]:
    if spec.load.torque_Nm is None:
        raise SkipStep("no [load] torque_Nm in the spec")
    return load_files(spec, out, spec.design_misalignment_deg, 360)


def _check(spec, out: Path) -> list[Path]:
    return run_step(spec, out)


def _viewer(spec, out: Path) -> list[Path]:
    return [write_html(spec, out / "viewer.html")]


STEPS: list[tuple[str, str, Step]] = [
    ("spec", "resolved spec", _spec),
    ("sections", "section plots", _sections),
    ("parts", "hub and sleeve STL", _parts),
    ("step", "hub and sleeve STEP", _step_files),
    ("sweep", "sweep at the design angle", _sweep),
    ("load", "loaded contact at the design angle", _load),
    ("check", "interference check at the design angle", _check),
    ("viewer", "static viewer HTML", _viewer),
]
STEP_KEYS = tuple(key for key, _, _ in STEPS)


def register(sub) -> None:
    p = sub.add_parser("run", help="write everything for a spec into outputs/<spec>/")
    add_spec_arguments(p)
    p.add_argument("--only", metavar="KEYS", default=None,
                   help=f"comma-separated steps to run, from {','.join(STEP_KEYS)}")
    p.add_argument("--skip", metavar="KEYS", default="", help="comma-separated steps to skip")
    p.set_defaults(func=run)


def _keys(option: str, text: str | None) -> set[str]:
    keys = {k.strip() for k in (text or "").split(",") if k.strip()}
    unknown = keys - set(STEP_KEYS)
    if unknown:
        raise SpecError(option, ",".join(sorted(unknown)), f"steps are {','.join(STEP_KEYS)}")
    return keys


def run(args) -> int:
    only = _keys("--only", args.only) if args.only is not None else set(STEP_KEYS)
    chosen = [s for s in STEPS if s[0] in only - _keys("--skip", args.skip)]
    spec = spec_from_args(args)
    out = output_dir(args, spec)
    written: list[Path] = []
    with progress(spec.name, len(chosen)) as advance:
        for _, label, step in chosen:
            try:
                written.extend(step(spec, out))
            except (BackendError, SkipStep) as err:  # an extra missing: the others stand
                print(f"gearcoupling: {label} skipped: {err}", file=sys.stderr)
            advance(label)
    for path in written:
        print(path)
    return 0
