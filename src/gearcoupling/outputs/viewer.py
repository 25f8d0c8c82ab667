"""The stage ``viewer``: the static viewer of the coupling at the operating point
(``viewer.html``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..io import write_text
from ..viewer import ViewSettings, static_html
from .stage import StageInputs


@dataclass(frozen=True)
class StaticViewer:
    """The viewer's page at a misalignment."""

    misalignment_deg: float
    html: str = field(repr=False)


def scene(inputs: StageInputs) -> StaticViewer:
    """The stage ``viewer``: hub and sleeve at the misalignment, rotation 0."""
    mis = inputs.point.misalignment_deg
    return StaticViewer(mis, static_html(inputs.spec,
                                         settings=ViewSettings(misalignment_deg=mis)))


def files(result: StaticViewer, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``viewer``'s ``viewer.html``."""
    return [write_text(folder / "viewer.html", result.html)]
