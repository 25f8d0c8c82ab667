"""``gearcoupling templates``: list the bundled templates with the first line of their header."""

from __future__ import annotations

from ..io import bundled_dir
from ..spec import template_names


def register(sub) -> None:
    p = sub.add_parser("templates", help="list the bundled templates")
    p.set_defaults(func=run)


def run(args) -> int:
    for name in template_names():
        head = (bundled_dir("templates") / f"{name}.toml").read_text().splitlines()[0]
        print(f"{name:24s} {head.lstrip('# ').split(' — ', 1)[-1]}")
    return 0
