"""The stage ``wear``: the wear history of the flanks at the operating point's angle and
torque over the hours at the speed the spec's ``[wear]`` (or the settings) gives
(``wear.csv``, ``wear_depth.csv``, ``wear_summary.json``, ``wear_maps.png``,
``wear_history.png``; docs/wear.md); skipped where neither asks for wear or there is no
torque."""

from __future__ import annotations

from pathlib import Path

from ..wear import WearResult, wear, write_wear
from .stage import SkipStage, StageInputs

#: why the stage is skipped on a spec that does not ask for wear
NOT_ASKED = ("no wear asked: set [wear] speed_rpm and hours in the spec (or --wear-speed and "
             "--wear-hours)")


def history(inputs: StageInputs) -> WearResult:
    """The stage ``wear``: :func:`gearcoupling.wear` at the operating point, with the
    settings' speed, hours and accuracy knobs (the spec's ``[wear]`` where not given)."""
    s, p = inputs.settings, inputs.point
    if not s.wear_asked(inputs.spec):
        raise SkipStage(NOT_ASKED)
    if not p.torque_Nm:
        raise SkipStage("no torque: set [load] torque_Nm or --torque (a wear history needs "
                        "a non-zero torque)")
    return wear(inputs.spec, p.misalignment_deg, p.torque_Nm, s.wear_speed_rpm, s.wear_hours,
                grid=s.wear_grid, phases=s.wear_phases)


def files(result: WearResult, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``wear``'s data and plots (:func:`gearcoupling.wear.write_wear`)."""
    return write_wear(result, folder, dpi=inputs.settings.dpi)
