"""What a report computes and how finely: the stages' operating point and accuracy knobs
(:class:`~gearcoupling.outputs.StageSettings`) and what the report shows, checked once."""

from __future__ import annotations

from dataclasses import dataclass

from ..arguments import flag
from ..outputs import KNOB_RANGES, StageSettings

__all__ = ["KNOB_RANGES", "ReportSettings"]


@dataclass(frozen=True)
class ReportSettings(StageSettings):
    """The stages' settings (:class:`~gearcoupling.outputs.StageSettings`: misalignment,
    torque, model, angles, tolerance, phases, capacity_count, check_angles, patch_teeth,
    hob diameter, scan and its limits, dpi) and what the report shows.

    Attributes
    ----------
    viewer : bool
        Embed the 3D viewer (the ``viewer`` extra).
    datasheet : bool
        The API 671 data sheet (its stiffness matrix, wind-up curve and allowable
        misalignment: the report's costliest stage).
    """

    viewer: bool = True
    datasheet: bool = True

    def __post_init__(self):
        super().__post_init__()
        flag(self.viewer, "viewer")
        flag(self.datasheet, "datasheet")
