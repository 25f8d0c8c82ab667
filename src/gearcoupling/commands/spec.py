"""``gearcoupling spec``: print the resolved spec with derived values (text from the spec
as data: control characters shown escaped, no rich markup; numbers to
:data:`DIGITS` significant digits, so 5.2 in prints as 132.08 mm, infinity as the project's
JSON writes it, ``"inf"``)."""

from __future__ import annotations

import json
import math

from ..io import plain, terminal_text
from ..outputs import resolved_spec
from .common import add_spec_arguments, spec_from_args

#: significant digits of a printed number: the inch to mm conversion's rounding
#: (132.07999999999998 for 5.2 in) goes, a micrometre of a 10 m part stays
DIGITS = 12


def register(sub) -> None:
    p = sub.add_parser("spec", help="print the resolved spec and derived values")
    add_spec_arguments(p, output=False)
    p.add_argument("--json", action="store_true", help="print JSON instead of tables")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = spec_from_args(args)
    data = resolved_spec(spec)
    if args.json:
        print(json.dumps(rounded(plain(data, "spec")), indent=2, allow_nan=False))
        return 0
    from rich.console import Console

    console = Console()
    head = {k: v for k, v in data.items() if k != "derived"}
    for path, rows in [*_sections(spec.name, head), ("derived", data["derived"])]:
        console.print(_table(path, rows))
    return 0


def rounded(data):
    """``data`` (plain JSON data) with every float to :data:`DIGITS` significant digits."""
    if isinstance(data, dict):
        return {k: rounded(v) for k, v in data.items()}
    if isinstance(data, list):
        return [rounded(v) for v in data]
    if isinstance(data, float):
        return float(f"{data:.{DIGITS}g}")
    return data


def _sections(title: str, data: dict, prefix: str = "") -> list[tuple[str, dict]]:
    """``(heading, scalar rows)`` of ``data`` and its sub-tables (headings the dotted paths
    of the file), in the spec's order: a table before its sub-tables, as in the file."""
    rows = {k: v for k, v in data.items() if not isinstance(v, dict)}
    out = [(title, rows)] if rows else []
    for key, value in data.items():
        if isinstance(value, dict):
            out += _sections(prefix + key, value, f"{prefix}{key}.")
    return out


def _cell(section: str, value) -> str:
    """A value as printed: unset limits (None, or infinite in [inspection]) as "not set"."""
    if value is None or (section.startswith("inspection") and value == math.inf):
        return "not set"
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def _table(path: str, rows: dict):
    """One section as a rich table under its ``[path]`` heading (a heading that never
    wraps, whatever the width of the table or the terminal); keys and values are
    :class:`rich.text.Text` of :func:`~gearcoupling.io.terminal_text`, never markup."""
    from rich.console import Group
    from rich.table import Table
    from rich.text import Text

    t = Table(show_header=False)
    for key, value in rows.items():
        t.add_row(Text(terminal_text(key)), Text(terminal_text(_cell(path, value))))
    return Group(Text(f"[{terminal_text(path)}]", style="bold", no_wrap=True,
                      overflow="ignore"), t)
