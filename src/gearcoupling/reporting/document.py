"""The report as data (sections of tables, figures, notes and the viewer) and its HTML.

The HTML is one file: styles inline, figures as ``data:`` PNG images, the 3D viewer as an
``<iframe srcdoc>`` holding viser's self-contained scene; nothing is fetched. Each figure
links its data file (CSV, relative to the report) and states the model and accuracy
settings it was made with. Print styles start each section on a new page (A4).
"""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

VERDICT_CLASS = {"pass": "pass", "fail": "fail", "not judged": "open"}


@dataclass(frozen=True)
class Table:
    """Rows of cells under ``columns``; a cell is text or a number (formatted here)."""

    columns: tuple[str, ...]
    rows: list[tuple[Any, ...]]
    caption: str = ""
    verdict_column: int | None = None  # cells there are pass / fail / not judged


@dataclass(frozen=True)
class Figure:
    """A PNG with its title, the settings it was made with and its data file."""

    key: str
    title: str
    png: bytes
    settings: str
    data_file: str | None = None
    note: str = ""


@dataclass(frozen=True)
class Note:
    """A paragraph of plain text (escaped when rendered); ``kind`` styles it."""

    text: str
    kind: str = ""  # "" | "warn" | "skip"


@dataclass(frozen=True)
class Viewer:
    """The static 3D scene (viser's HTML) and what it shows."""

    scene_html: str
    caption: str


@dataclass(frozen=True)
class Row:
    """Tables side by side (stacked when the page is narrow)."""

    tables: list[Table]


Block = Table | Row | Figure | Note | Viewer


@dataclass
class Section:
    key: str
    title: str
    blocks: list[Block] = field(default_factory=list)
    seconds: float = 0.0


def fmt(value: Any, digits: int = 4) -> str:
    """A cell: numbers to ``digits`` significant digits, None as a dash."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isinf(value):
            return "∞" if value > 0 else "−∞"
        if value == 0:
            return "0"
        return f"{value:.{digits}g}"
    return str(value)


CSS = """
body { font: 14px/1.45 "DejaVu Sans", Arial, sans-serif; color: #1d2330; margin: 0;
       background: #f4f5f7; }
main { max-width: 1180px; margin: 0 auto; padding: 24px 32px 60px; background: #fff; }
h1 { font-size: 26px; margin: 0 0 4px; }
h2 { font-size: 20px; margin: 38px 0 10px; padding-top: 6px; border-top: 2px solid #2c3e66; }
h3 { font-size: 15px; margin: 18px 0 6px; }
.sub { color: #555; margin: 0 0 14px; }
table { border-collapse: collapse; margin: 8px 0 14px; font-size: 13px; max-width: 100%; }
th, td { border: 1px solid #cfd4dc; padding: 3px 8px; text-align: left; vertical-align: top;
         overflow-wrap: break-word; }
th { background: #eef1f6; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
caption { caption-side: bottom; text-align: left; color: #555; font-size: 12px;
          padding-top: 4px; }
.verdict { font-weight: bold; min-width: 18em; }
.pass { color: #17702f; } .fail { color: #b3141b; } .open { color: #8a5a00; }
.banner { padding: 10px 14px; border-radius: 4px; margin: 10px 0 18px; font-size: 15px; }
.banner.pass { background: #e5f4e8; } .banner.fail { background: #fbe6e6; }
.banner.open { background: #fff4dc; }
figure { margin: 14px 0 22px; break-inside: avoid; }
figure img { max-width: 100%; height: auto; border: 1px solid #e3e6ea; }
figcaption { font-size: 12px; color: #444; margin-top: 4px; }
figcaption .settings { color: #666; }
p.warn { color: #8a5a00; } p.skip { color: #666; font-style: italic; }
.viewer iframe { width: 100%; height: 560px; border: 1px solid #cfd4dc; }
.viewer .print-only { display: none; }
nav ol { columns: 2; font-size: 13px; }
.row { display: flex; flex-wrap: wrap; gap: 28px; align-items: flex-start; }
@page { size: A4; margin: 14mm 12mm; }
@media print {
  body { background: #fff; font-size: 11px; }
  main { max-width: none; padding: 0; }
  h2 { break-before: page; border-top: none; }
  h2.first { break-before: auto; }
  nav { display: none; }
  table, figure, .banner { break-inside: avoid; }
  .viewer iframe { display: none; }
  .viewer .print-only { display: block; }
  a { color: inherit; text-decoration: none; }
}
"""


def _table(t: Table) -> str:
    head = "".join(f"<th>{html.escape(c)}</th>" for c in t.columns)
    body = []
    for row in t.rows:
        cells = []
        for i, v in enumerate(row):
            text = html.escape(fmt(v))
            if i == t.verdict_column:
                key = str(v).split(":")[0].split(" ")[0]  # "pass: margin ..." is a pass
                cells.append(f'<td class="verdict {VERDICT_CLASS.get(key, "open")}">{text}</td>')
            elif isinstance(v, int | float) and not isinstance(v, bool):
                cells.append(f'<td class="num">{text}</td>')
            else:
                cells.append(f"<td>{text}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    cap = f"<caption>{html.escape(t.caption)}</caption>" if t.caption else ""
    return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def _figure(f: Figure) -> str:
    src = "data:image/png;base64," + base64.b64encode(f.png).decode("ascii")
    data = (f' Data: <a href="{html.escape(f.data_file)}">{html.escape(f.data_file)}</a>.'
            if f.data_file else "")
    note = f" {html.escape(f.note)}" if f.note else ""
    return (f'<figure id="fig-{html.escape(f.key)}"><img src="{src}" alt="{html.escape(f.title)}">'
            f"<figcaption><b>{html.escape(f.title)}.</b>{note}{data}<br>"
            f'<span class="settings">{html.escape(f.settings)}</span></figcaption></figure>')


def _viewer(v: Viewer) -> str:
    return (f'<div class="viewer"><iframe title="3D view" srcdoc="{html.escape(v.scene_html)}">'
            f'</iframe><p class="print-only">The interactive 3D view is in the HTML version '
            f"of this report.</p><p>{html.escape(v.caption)}</p></div>")


def _block(b) -> str:
    if isinstance(b, Table):
        return _table(b)
    if isinstance(b, Figure):
        return _figure(b)
    if isinstance(b, Viewer):
        return _viewer(b)
    if isinstance(b, Row):
        return '<div class="row">' + "".join(_table(t) for t in b.tables) + "</div>"
    if isinstance(b, Note):
        cls = f' class="{b.kind}"' if b.kind else ""
        return f"<p{cls}>{html.escape(b.text)}</p>"
    raise TypeError(f"unknown report block {type(b).__name__}")  # pragma: no cover


def render(title: str, subtitle: str, banner: tuple[str, str], sections: Sequence[Section]
           ) -> str:
    """The whole report as one HTML document; ``banner`` is ``(verdict class, text)``."""
    toc = "".join(f'<li><a href="#{s.key}">{html.escape(s.title)}</a></li>' for s in sections)
    parts = []
    for n, s in enumerate(sections):
        first = ' class="first"' if n == 0 else ""
        body = "".join(_block(b) for b in s.blocks)
        parts.append(f'<section id="{s.key}"><h2{first}>{n + 1}. {html.escape(s.title)}</h2>'
                     f"{body}</section>")
    cls, text = banner
    return ("<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>{html.escape(title)}</title><style>{CSS}</style></head><body><main>"
            f"<h1>{html.escape(title)}</h1><p class=\"sub\">{html.escape(subtitle)}</p>"
            f'<div class="banner {cls}">{html.escape(text)}</div>'
            f"<nav><ol>{toc}</ol></nav>{''.join(parts)}</main></body></html>\n")

