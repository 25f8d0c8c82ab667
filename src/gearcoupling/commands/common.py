"""Options and helpers shared by the CLI commands."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from contextlib import contextmanager
from pathlib import Path

from ..errors import ArgumentError
from ..io import default_output_dir, output_folder, parse_override
from ..spec import CouplingSpec, check_misalignment_deg, load_spec

MAX_ANGLES = 100_000  # rotation angles per turn a command accepts (memory grows with it)
MAX_TEETH = 300  # the documented range of teeth is 6-300


def positive_length(text: str) -> float:
    """argparse type: a finite length > 0 in mm (``0``, negatives, ``nan`` and ``inf`` refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number (mm)") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite length > 0 (mm)")
    return value


def finite_float(text: str) -> float:
    """argparse type: a finite number (``nan`` and ``inf`` refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r}: must be finite")
    return value


def number_in(lo: float, hi: float, unit: str = "", *,
              open_lo: bool = False) -> Callable[[str], float]:
    """argparse type: a finite number from ``lo`` to ``hi`` (``lo`` excluded if ``open_lo``)."""
    what = f"{'(' if open_lo else '['}{lo:g}, {hi:g}]" + (f" {unit}" if unit else "")

    def parse(text: str) -> float:
        value = finite_float(text)
        if not ((lo < value if open_lo else lo <= value) and value <= hi):
            raise argparse.ArgumentTypeError(f"{text!r}: must be in {what}")
        return value

    parse.__name__ = "number"
    return parse


def count(lo: int, hi: int) -> Callable[[str], int]:
    """argparse type: a whole number from ``lo`` to ``hi``."""
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(f"{value}: must be from {lo} to {hi}")
        return value

    parse.__name__ = "count"
    return parse


def add_spec_arguments(parser: argparse.ArgumentParser, *, output: bool = True) -> None:
    """``SPEC`` (template name or TOML path), ``--set KEY=VALUE`` and ``-o DIR``."""
    parser.add_argument("spec", metavar="SPEC", help="template name or path to a TOML spec")
    parser.add_argument("--set", dest="overrides", action="append", default=[],
                        metavar="KEY=VALUE",
                        help="override a spec value in the file's units, e.g. "
                             "hub.crowning.radius=80 (repeatable)")
    if output:
        parser.add_argument("-o", "--output", metavar="DIR", default=None,
                            help="output folder (default: outputs/<spec name>)")


def add_misalignment_argument(parser: argparse.ArgumentParser) -> None:
    """``--misalignment DEG``, default the spec's design angle (:func:`misalignment_deg`)."""
    parser.add_argument("--misalignment", type=finite_float, default=None, metavar="DEG",
                        help="misalignment in degrees, 0-6 (default: the spec's design angle)")


def misalignment_deg(args: argparse.Namespace, spec: CouplingSpec) -> float:
    """The ``--misalignment`` given, else the spec's design misalignment, in degrees (0-6°,
    checked once by :func:`~gearcoupling.spec.check_misalignment_deg`)."""
    if args.misalignment is None:
        return spec.design_misalignment_deg
    return check_misalignment_deg(args.misalignment, "--misalignment", ArgumentError)


def spec_from_args(args: argparse.Namespace) -> CouplingSpec:
    overrides = dict(parse_override(text) for text in args.overrides)
    return load_spec(args.spec, **overrides)


def output_dir(args: argparse.Namespace, spec: CouplingSpec) -> Path:
    """``-o DIR`` if given, else ``outputs/<sanitised spec name>``: a spec's ``name`` never
    chooses where files go (see :func:`~gearcoupling.io.default_output_dir`)."""
    given = getattr(args, "output", None)
    return writing_into(ensure_dir(default_output_dir(spec.name) if given is None else given))


def ensure_dir(out: str | Path, field: str = "-o") -> Path:
    """Create the folder ``out``; an empty path, a file, device or pipe in the way, or an
    unwritable place is an :class:`~gearcoupling.errors.ArgumentError` naming ``field``
    (:func:`~gearcoupling.io.output_folder`)."""
    return output_folder(out, field)


#: the output folders of the command running in this process, for the line an
#: interruption prints (:func:`gearcoupling.cli.main`)
WRITING: list[Path] = []


def writing_into(folder: Path) -> Path:
    """Remember ``folder`` as where this command writes (:data:`WRITING`); returns it."""
    WRITING.append(folder)
    return folder


@contextmanager
def progress(description: str, total: int):
    """A rich progress bar on stderr with the time left; yields ``update(done, total)``, the
    library's progress callback. The bar redraws on each update (no refresh thread, so
    :func:`gearcoupling.run` may fork beside it)."""
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/"
                  "{task.total}"), TimeElapsedColumn(), TimeRemainingColumn(),
                  console=Console(stderr=True), transient=False, auto_refresh=False) as bar:
        task = bar.add_task(description, total=total)

        def update(done: int, total: int) -> None:
            bar.update(task, completed=done, total=total, refresh=True)

        try:
            yield update
        except BaseException:  # an error or an interruption: its one line says it all
            bar.live.transient = True
            raise
