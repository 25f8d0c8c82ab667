"""Options and helpers shared by the CLI commands."""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Callable
from contextlib import contextmanager
from pathlib import Path
from typing import TypeVar

from ..arguments import MAXIMA, parse_count, parse_number
from ..arguments import torque_Nm as check_torque_Nm
from ..errors import ArgumentError, brief
from ..interrupts import check as check_interrupt
from ..io import default_output_dir, output_folder, parse_override, terminal_text
from ..spec import TEETH_RANGE, CouplingSpec, check_misalignment_deg, load_spec

MAX_ANGLES = MAXIMA["angles"]  # rotation angles per turn (memory grows with it)
MAX_TEETH = TEETH_RANGE[1]  # the largest coupling

T = TypeVar("T")

# argparse types: each reads the text with the one number parser of
# gearcoupling.arguments (digits as a person writes them: 0_5, 0x10, nan refused) and
# says what is allowed; argparse prefixes the option's name


def _quoted(text: str) -> str:
    return brief(repr(text), 60)


def _typed(check: Callable[[str], T], text: str) -> T:
    """``check(text)``, its :class:`ArgumentError` as argparse's message (the rule)."""
    try:
        return check(text)
    except ArgumentError as err:
        raise argparse.ArgumentTypeError(f"{_quoted(text)}: {err.allowed}") from None


def finite_float(text: str) -> float:
    """argparse type: a finite number (``nan``, ``inf`` and ``0_5`` refused)."""
    return _typed(lambda t: parse_number(t, ""), text)


def number_in(lo: float, hi: float = math.inf, unit: str = "", *,
              open_lo: bool = False) -> Callable[[str], float]:
    """argparse type: a finite number from ``lo`` to ``hi`` (``lo`` excluded if ``open_lo``)."""
    what = (f"{'>' if open_lo else '>='} {lo:g}" if math.isinf(hi) else
            f"in {'(' if open_lo else '['}{lo:g}, {hi:g}]") + (f" {unit}" if unit else "")

    def parse(text: str) -> float:
        value = finite_float(text)
        if not ((lo < value if open_lo else lo <= value) and value <= hi):
            raise argparse.ArgumentTypeError(f"{_quoted(text)}: must be {what}")
        return value

    parse.__name__ = "number"
    return parse


def positive(unit: str, hi: float = math.inf) -> Callable[[str], float]:
    """argparse type: a finite number > 0 (at most ``hi``) in ``unit``."""
    return number_in(0.0, hi, unit, open_lo=True)


#: argparse type: a length in mm > 0
positive_length = positive("mm")


def torque(*, zero: bool = True) -> Callable[[str], float]:
    """argparse type: a signed torque in N·m in the one range of every entry point
    (:data:`~gearcoupling.arguments.TORQUE_RANGE_NM`; 0 where ``zero``)."""
    def parse(text: str) -> float:
        return _typed(lambda t: check_torque_Nm(parse_number(t, ""), "", zero=zero), text)

    parse.__name__ = "torque"
    return parse


def count(lo: int, hi: int) -> Callable[[str], int]:
    """argparse type: a whole number from ``lo`` to ``hi``."""
    def parse(text: str) -> int:
        value = _typed(lambda t: parse_count(t, ""), text)
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


#: the options of a double-engagement coupling's shaft alignment, each with the keyword of
#: :class:`~gearcoupling.StageSettings` it sets
ALIGNMENT_OPTIONS = {"--offset": "offset_mm", "--offset-azimuth": "offset_azimuth_deg",
                     "--shaft-angle": "shaft_angle_deg", "--angle-azimuth": "angle_azimuth_deg"}


def add_alignment_arguments(parser: argparse.ArgumentParser) -> None:
    """``--offset MM``, ``--offset-azimuth DEG``, ``--shaft-angle DEG`` and
    ``--angle-azimuth DEG``: a double-engagement spec's ``[alignment]``, key by key."""
    group = parser.add_argument_group(
        "shaft alignment", "a double-engagement spec ([coupling] engagements = 2): each in "
        "place of its key of the spec's [alignment] (docs/coupling.md); each mesh is analysed "
        "at the angle and rotation phase it gives")
    group.add_argument("--offset", type=number_in(0.0, unit="mm"), default=None, metavar="MM",
                       help="parallel offset of shaft B at the coupling's centre, >= 0 mm")
    group.add_argument("--offset-azimuth", type=number_in(-720.0, 720.0, "degrees"),
                       default=None, metavar="DEG", help="its direction about shaft A")
    group.add_argument("--shaft-angle", type=number_in(0.0, 12.0, "degrees"), default=None,
                       metavar="DEG", help="angle between the shafts, 0-12 degrees")
    group.add_argument("--angle-azimuth", type=number_in(-720.0, 720.0, "degrees"),
                       default=None, metavar="DEG", help="the direction shaft B leans toward")


def alignment_given(args: argparse.Namespace) -> dict[str, float]:
    """The alignment options given, by option (:data:`ALIGNMENT_OPTIONS`)."""
    values = {o: getattr(args, o.removeprefix("--").replace("-", "_"), None)
              for o in ALIGNMENT_OPTIONS}
    return {o: v for o, v in values.items() if v is not None}


def spec_from_args(args: argparse.Namespace) -> CouplingSpec:
    overrides = dict(parse_override(text) for text in args.overrides)
    return load_spec(args.spec, **overrides)


def output_dir(args: argparse.Namespace, spec: CouplingSpec) -> Path:
    """``-o DIR`` if given, else ``outputs/<sanitised spec name>``: a spec's ``name`` never
    chooses where files go (see :func:`~gearcoupling.io.default_output_dir`)."""
    given = getattr(args, "output", None)
    return writing_into(default_output_dir(spec.name) if given is None else given)


#: the output folders of the command running in this process, for the line an
#: interruption prints (:func:`gearcoupling.cli.main`), and those of them it made (removed
#: again, when left empty, if the command fails)
WRITING: list[Path] = []
CREATED: list[Path] = []


def writing_into(out: str | Path, field: str = "-o", *, create: bool = True) -> Path:
    """The output folder ``out``, made unless ``create`` is False (an empty path, a file,
    device or pipe in the way, or an unwritable place is an
    :class:`~gearcoupling.errors.ArgumentError` naming ``field``,
    :func:`~gearcoupling.io.output_folder`), and remembered as where this command writes
    (:data:`WRITING`, :data:`CREATED`)."""
    new = not os.path.lexists(out) if isinstance(out, str | Path) and str(out) else False
    folder = output_folder(out, field, create=False) if create else Path(out)
    # named before it is made: an interruption from here on says where it wrote
    WRITING.append(folder)
    if new and create:
        CREATED.append(folder)
    if create:
        output_folder(out, field)
    return folder


@contextmanager
def progress(description: str, total: int):
    """A rich progress bar on stderr with the time left; yields ``update(done, total)``, the
    library's progress callback. The bar redraws on each update (no refresh thread, so
    :func:`gearcoupling.run` may fork beside it). ``description`` is shown as text
    (:func:`~gearcoupling.io.terminal_text`), never as rich markup. Each update first
    raises an interruption a library dropped (:func:`gearcoupling.interrupts.check`)."""
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    # transient until the work is done: an error or an interruption, also one that comes
    # while the bar starts, leaves no bar behind (a pipe would get its last frame): the
    # command's one line says it all
    with Progress(TextColumn("{task.description}", markup=False), BarColumn(),
                  TextColumn("{task.completed}/{task.total}"), TimeElapsedColumn(),
                  TimeRemainingColumn(),
                  console=Console(stderr=True), transient=True, auto_refresh=False) as bar:
        task = bar.add_task(terminal_text(description), total=total)  # data, not markup

        def update(done: int, total: int) -> None:
            check_interrupt()  # a signal whose exception a library dropped stops here
            bar.update(task, completed=done, total=total, refresh=True)

        yield update
        bar.live.transient = False  # done: the bar stays, a pipe gets its last frame
