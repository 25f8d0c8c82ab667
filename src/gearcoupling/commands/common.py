"""Options and helpers shared by the CLI commands."""

from __future__ import annotations

import argparse
import math
from contextlib import contextmanager
from pathlib import Path

from ..spec import CouplingSpec, load_spec, parse_override


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
    parser.add_argument("--misalignment", type=float, default=None, metavar="DEG",
                        help="misalignment in degrees (default: the spec's design angle)")


def misalignment_deg(args: argparse.Namespace, spec: CouplingSpec) -> float:
    """The ``--misalignment`` given, else the spec's design misalignment, in degrees."""
    if args.misalignment is None:
        return math.degrees(spec.design_misalignment)
    return args.misalignment


def spec_from_args(args: argparse.Namespace) -> CouplingSpec:
    overrides = dict(parse_override(text) for text in args.overrides)
    return load_spec(args.spec, **overrides)


def output_dir(args: argparse.Namespace, spec: CouplingSpec) -> Path:
    out = Path(args.output) if getattr(args, "output", None) else Path("outputs") / spec.name
    out.mkdir(parents=True, exist_ok=True)
    return out


@contextmanager
def progress(description: str, total: int):
    """A rich progress bar on stderr; yields ``advance(label)``."""
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/"
                  "{task.total}"), TimeElapsedColumn(), console=Console(stderr=True),
                  transient=False) as bar:
        task = bar.add_task(description, total=total)

        def advance(label: str | None = None) -> None:
            bar.update(task, advance=1, description=label or description)

        yield advance


def write_rows_csv(path: str | Path, columns, rows) -> Path:
    """A CSV written atomically: floats as ``%.9g``, booleans ``true``/``false``, None empty."""
    import csv

    from ..atomic import atomic_path

    def cell(v):
        if v is None:
            return ""
        if isinstance(v, bool):
            return str(v).lower()
        return f"{v:.9g}" if isinstance(v, float) else v

    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(columns)
        w.writerows([cell(v) for v in row] for row in rows)
    return Path(path)
