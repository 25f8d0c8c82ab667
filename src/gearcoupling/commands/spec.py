"""``gearcoupling spec``: print the resolved spec with derived values."""

from __future__ import annotations

import json

from ..io import plain
from ..outputs import resolved_spec
from .common import add_spec_arguments, spec_from_args


def register(sub) -> None:
    p = sub.add_parser("spec", help="print the resolved spec and derived values")
    add_spec_arguments(p, output=False)
    p.add_argument("--json", action="store_true", help="print JSON instead of tables")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = spec_from_args(args)
    data = resolved_spec(spec)
    if args.json:
        print(json.dumps(plain(data, "spec"), indent=2, allow_nan=False))
        return 0
    from rich.console import Console
    from rich.table import Table

    console = Console()

    def table(title: str, rows: dict, prefix: str = "") -> None:
        t = Table(title=title, show_header=False, title_justify="left")
        for key, value in rows.items():
            if isinstance(value, dict):
                table(f"{title}.{key}", value)
                continue
            t.add_row(prefix + key, f"{value:.6g}" if isinstance(value, float) else str(value))
        console.print(t)

    head = {k: v for k, v in data.items() if k not in ("tooth", "hub", "sleeve", "derived")}
    table(spec.name, head)
    for section in ("tooth", "hub", "sleeve", "derived"):
        table(section, data[section])
    return 0
