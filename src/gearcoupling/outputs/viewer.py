"""The stage ``viewer``: the static viewer of the coupling at the operating point
(``viewer.html``); of a double-engagement coupling, the whole coupling placed at its
alignment, each mesh coloured at its angle."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..io import write_text
from ..viewer import AssemblySettings, ViewSettings, static_html
from .stage import StageInputs


@dataclass(frozen=True)
class StaticViewer:
    """The viewer's page at a misalignment."""

    misalignment_deg: float
    html: str = field(repr=False)


def scene(inputs: StageInputs) -> StaticViewer:
    """The stage ``viewer``: hub and sleeve at the misalignment, rotation 0; a double-
    engagement coupling's parts at its alignment, rotation 0."""
    p = inputs.point
    if p.coupling is not None:
        a = p.coupling.alignment
        settings = AssemblySettings(a.offset_mm, a.offset_azimuth_deg, a.angle_deg,
                                    a.angle_azimuth_deg)
        return StaticViewer(p.misalignment_deg, static_html(inputs.spec, settings=settings))
    mis = p.misalignment_deg
    return StaticViewer(mis, static_html(inputs.spec,
                                         settings=ViewSettings(misalignment_deg=mis)))


def files(result: StaticViewer, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``viewer``'s ``viewer.html``."""
    return [write_text(folder / "viewer.html", result.html)]
