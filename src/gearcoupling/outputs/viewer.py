"""``viewer.html``: the static viewer of the spec."""

from __future__ import annotations

from pathlib import Path

from ..spec import CouplingSpec
from ..viewer import write_html


def write_viewer(spec: CouplingSpec, out: Path) -> list[Path]:
    """The static viewer (:func:`~gearcoupling.viewer.write_html`) as ``viewer.html``."""
    return [write_html(spec, out / "viewer.html")]
