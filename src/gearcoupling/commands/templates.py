"""``gearcoupling templates``: list the bundled templates with the first line of their header."""

from __future__ import annotations

from ..spec import template_dir, template_names


def register(sub) -> None:
    p = sub.add_parser("templates", help="list the bundled templates")
    p.set_defaults(func=run)


def run(args) -> int:
    for name in template_names():
        head = (template_dir() / f"{name}.toml").read_text().splitlines()[0]
        print(f"{name:24s} {head.lstrip('# ').split(' — ', 1)[-1]}")
    return 0
