"""Text that leaves the program is data, never syntax.

A string that comes from a spec or a user (a spec ``name``, a file name, a label) goes out
through the function of its target, which keeps it on its one line and out of the
target's syntax. Characters a target does not take are shown escaped as Python spells
them (``\\x0a`` for a newline, ``\\x1b`` for ESC, ``\\u202e``, ``\\x28`` for ``(`` in a
G-code comment), so the text stays readable and nothing is silently lost.

========================  ===========================================================
target                    what the text may hold there
========================  ===========================================================
:func:`terminal_text`     printable characters (no control character, ESC, line or
                          paragraph separator, format character)
:func:`gcode_comment`     printable ASCII without ``( ) ; %``, inside ``( )``
:func:`inp_comment`       printable ASCII after ``**``, the line cut to 132 characters
:func:`vtk_header`        printable ASCII, at most 255 characters
:func:`step_text`         printable ASCII (OpenCASCADE quotes it)
:func:`xml_text`          printable characters, ``& < > " '`` as entities
:func:`csv_cell`          printable characters; a leading ``= + - @`` made text by ``'``
:func:`csv_comment`       :func:`csv_cell` rules for each comma-separated part, after
                          ``#``
:func:`plot_text`         printable characters, ``$`` escaped (no matplotlib mathtext)
:func:`markdown_text`     printable characters, markdown punctuation backslash-escaped,
                          ``& < >`` as entities (the viewer's markdown renders raw HTML)
========================  ===========================================================
"""

from __future__ import annotations

import html
import re
from collections.abc import Callable
from xml.sax.saxutils import escape as _xml_escape

INP_LINE = 132  # characters CalculiX reads of a line
VTK_HEADER = 255  # characters of the legacy VTK header line (256 with its newline)
_GCODE_SYNTAX = frozenset("();%")
_MARKDOWN = re.compile(r"([\\`*_{}\[\]()#+\-.!|~:@])")  # ``:`` ``@``: no autolinks
#: a cell a spreadsheet would take as a formula, and a CSV quote: at the start of a field
_FORMULA = re.compile(r'(^|,)(?=[=+\-@"])')


def _escape(ch: str) -> str:
    code = ord(ch)
    if code < 0x100:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def escaped(text: object, keep: Callable[[str], bool] | None = None) -> str:
    """``str(text)`` with every character that ``keep`` refuses shown as its escape
    (``\\x0a``, ``\\u202e``, ``\\U0001f600``); by default (None) the unprintable ones."""
    s = str(text)
    if keep is None:
        if s.isprintable():
            return s
        keep = str.isprintable
    elif all(map(keep, s)):
        return s
    return "".join(c if keep(c) else _escape(c) for c in s)


def _ascii(c: str) -> bool:
    return " " <= c <= "~"


def terminal_text(text: object) -> str:
    """``text`` for a terminal: control characters (ESC, newline, NUL, C1), separators
    and format characters shown escaped. Print it through rich as a ``rich.text.Text``
    (or :func:`rich.markup.escape` it) so that ``[bold]`` stays text."""
    return escaped(text)


def gcode_comment(text: object) -> str:
    """``(text)``: a G-code comment of one line, printable ASCII without the comment and
    block syntax ``( ) ; %``."""
    return f"({escaped(text, lambda c: _ascii(c) and c not in _GCODE_SYNTAX)})"


def inp_comment(text: object) -> str:
    """``** text``: a CalculiX/Abaqus comment line of printable ASCII, cut to the 132
    characters CalculiX reads."""
    return f"** {escaped(text, _ascii)}"[:INP_LINE]


def vtk_header(text: object) -> str:
    """The legacy VTK header line (without its newline): printable ASCII, at most 255
    characters."""
    return escaped(text, _ascii)[:VTK_HEADER]


def step_text(text: object) -> str:
    """A STEP string value (OpenCASCADE quotes ``'`` and ``\\``): printable ASCII, as
    ISO 10303-21 strings hold without encoding."""
    return escaped(text, _ascii)


def xml_text(text: object) -> str:
    """Text for XML character data or an attribute value: printable characters, with
    ``& < > " '`` as entities."""
    return _xml_escape(escaped(text), {'"': "&quot;", "'": "&apos;"})


def _number(s: str) -> bool:
    try:
        float(s)
    except ValueError:
        return False
    return True


def csv_cell(text: object) -> str:
    """A text cell of a CSV file: on one line (unprintable characters escaped) and never
    a formula: a leading ``= + - @`` gets a ``'`` before it, unless the cell is a number
    (``-1.5``, ``+inf``). The csv module adds the RFC 4180 quoting."""
    s = escaped(text)
    return f"'{s}" if s[:1] in ("=", "+", "-", "@") and not _number(s) else s


def csv_comment(text: object) -> str:
    """``# text``: a CSV comment line on one line whose comma-separated parts do not start
    with a formula character or a quote (``'`` put before them), so a spreadsheet that
    reads the line as cells finds text, and a quote cannot join it to the next line."""
    return "# " + _FORMULA.sub(r"\1'", escaped(text))


def plot_text(text: object) -> str:
    """Text for a matplotlib title, label or legend entry: unprintable characters escaped
    and ``$`` as ``\\$``, so that a name is drawn as given (never parsed as mathtext)."""
    return escaped(text).replace("$", r"\$")


def markdown_text(text: object) -> str:
    """Text for markdown (the viewer's panel, which renders raw HTML): unprintable
    characters escaped, markdown punctuation backslash-escaped and ``& < >`` as entities,
    so the text is shown as given and never becomes markup or an HTML element."""
    return html.escape(_MARKDOWN.sub(r"\\\1", escaped(text)), quote=False)
