"""``gearcoupling templates``: list the bundled templates with the first sentence of their
header, wrapped to the terminal."""

from __future__ import annotations

import re
import shutil
import textwrap

from ..io import bundled_dir
from ..spec import template_names

NAME_WIDTH = 24


def register(sub) -> None:
    p = sub.add_parser("templates", help="list the bundled templates")
    p.set_defaults(func=run)


def description(header: str) -> str:
    """The first sentence of a template's header comment (``# name — sentence. More.``),
    joined across its lines."""
    lines = []
    for line in header.splitlines():
        if not line.startswith("#"):
            break
        lines.append(line.lstrip("# ").strip())
    text = " ".join(lines).split(" — ", 1)[-1]
    return re.split(r"(?<=\.)\s+(?=[A-Z])", text, maxsplit=1)[0]


def run(args) -> int:
    width = max(shutil.get_terminal_size().columns, NAME_WIDTH + 40)
    for name in template_names():
        text = description((bundled_dir("templates") / f"{name}.toml").read_text())
        print(textwrap.fill(text, width, initial_indent=f"{name:{NAME_WIDTH}s} ",
                            subsequent_indent=" " * (NAME_WIDTH + 1)))
    return 0
