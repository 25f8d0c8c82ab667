"""The wear life as a study response: :func:`gearcoupling.wear`'s ``life_h`` of a sample's
spec at the study's angle and torque, with the speed and hours of the spec's ``[wear]``
and the ``[accuracy]`` wear knobs (:data:`~.file.WEAR_ACCURACY`)."""

from __future__ import annotations

from typing import Any

from numpy.typing import ArrayLike

from ..spec import CouplingSpec
from ..wear import wear
from .file import WEAR_ACCURACY


def wear_life_h(spec: CouplingSpec, misalignment_deg: float, torque_Nm: float | None,
                accuracy: dict[str, Any], gap_offset_rad: ArrayLike | None = None) -> float:
    """Hours to the wear limit (at most ``gearcoupling.wear.LIFE_CAP_H``); ``torque_Nm``
    None: the spec's; ``gap_offset_rad`` a tolerance draw's per-tooth offsets (the teeth
    then wear each on its own)."""
    knobs = {**WEAR_ACCURACY, **{k: v for k, v in accuracy.items() if k in WEAR_ACCURACY}}
    res = wear(spec, misalignment_deg, torque_Nm,
               grid=(int(knobs["wear_face_cells"]), int(knobs["wear_depth_cells"])),
               phases=int(knobs["wear_phases"]), gap_offset_rad=gap_offset_rad)
    return float(res.life_h)


__all__ = ["wear_life_h"]
