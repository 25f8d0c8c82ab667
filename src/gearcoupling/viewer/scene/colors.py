"""Flank colours (clearance, Renzo's separation or contact pressure) and their legend."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import ArgumentError
from ...spec import CouplingSpec
from .pose import PoseState

INTERFERENCE_RGB = (220, 20, 20)
NO_CONTACT_RGB = (150, 150, 150)
# clearance colour stops from 0 (touching) to the colour scale (free)
_STOPS = np.array([[0.0, 255, 215, 0], [0.35, 120, 200, 60], [0.7, 40, 170, 170],
                   [1.0, 40, 80, 200]])
COLOR_MODES = ("clearance", "separation", "pressure")
"""What the flank colours show: the clearance itself, or Renzo's separation (clearance
minus the smallest of its flank at this pose: 0 on the teeth that touch first when torque
closes the backlash), or the contact pressure at the spec's torque (the ``surface`` load
model's interior pressure of each tooth, against the allowable contact stress)."""
_PRESSURE_STOPS = np.array([[0.0, 40, 80, 200], [0.5, 40, 170, 170], [0.8, 255, 215, 0],
                            [1.0, 220, 20, 20]])


def flank_values(state: PoseState, mode: str = "clearance") -> NDArray[np.float64]:
    """The ``(2, N)`` values the flank colours show (:data:`COLOR_MODES`): the clearance,
    or the separation ``clearance - max(0, smallest clearance of the flank)``;
    interfering flanks stay negative (red) and unfaced ones infinite (grey) in both."""
    if mode not in COLOR_MODES:
        raise ArgumentError("color mode", mode, f"one of {COLOR_MODES}")
    c = state.clearance_mm
    if mode == "clearance":
        return c
    low = np.min(np.where(np.isfinite(c), c, np.inf), axis=1, keepdims=True)
    low = np.where(np.isfinite(low), np.maximum(low, 0.0), 0.0)  # 0 where it interferes
    with np.errstate(invalid="ignore"):
        sep = np.where(np.isfinite(c), c - low, np.inf)
    return np.where(state.interfering, c, np.maximum(sep, 0.0))


def flank_colors(state: PoseState, mode: str, scale_mm: float,
                 spec: CouplingSpec) -> NDArray[np.uint8]:
    """RGB ``(2, N, 3)`` of the flanks in a colour mode (:data:`COLOR_MODES`)."""
    if mode != "pressure":
        return clearance_colors(flank_values(state, mode), scale_mm)
    if state.pressure_MPa is None:
        raise ArgumentError("mode", mode, "needs a state from pose_state(..., loads=...)")
    return pressure_colors(state.pressure_MPa,
                           spec.material.hub.allowable_contact_stress_MPa)


def pressure_colors(pressure_MPa: ArrayLike, allowable_MPa: float) -> NDArray[np.uint8]:
    """RGB ``(..., 3) uint8``: grey without load, then blue through cyan and yellow to red
    at the allowable contact stress and above."""
    p = np.asarray(pressure_MPa, dtype=float)
    t = np.clip(p / allowable_MPa, 0.0, 1.0)
    rgb = np.stack([np.interp(t, _PRESSURE_STOPS[:, 0], _PRESSURE_STOPS[:, j])
                    for j in (1, 2, 3)], axis=-1)
    rgb = np.where((p <= 0)[..., None], np.asarray(NO_CONTACT_RGB, dtype=float), rgb)
    return np.rint(rgb).astype(np.uint8)


def default_color_scale_mm(spec: CouplingSpec) -> float:
    """Clearance shown at the free end of the colour scale: half the aligned backlash
    (the clearance of every flank when aligned)."""
    return 0.5 * float(spec.derived["aligned_backlash_mm"])


def clearance_colors(clearance_mm: ArrayLike, scale_mm: float) -> NDArray[np.uint8]:
    """RGB ``(..., 3) uint8`` of clearances: red below 0 (interference), yellow at 0
    (touching) through green and cyan to blue at ``scale_mm`` and above, grey where
    infinite (no sleeve flank faces the hub flank)."""
    if not (math.isfinite(scale_mm) and scale_mm > 0):
        raise ArgumentError("color_scale_mm", scale_mm, "must be a positive finite length (mm)")
    c = np.asarray(clearance_mm, dtype=float)
    t = np.clip(np.where(np.isfinite(c), c, 0.0) / scale_mm, 0.0, 1.0)
    rgb = np.stack([np.interp(t, _STOPS[:, 0], _STOPS[:, j]) for j in (1, 2, 3)], axis=-1)
    rgb = np.where((c < 0)[..., None], np.asarray(INTERFERENCE_RGB, dtype=float), rgb)
    rgb = np.where(np.isinf(c)[..., None], np.asarray(NO_CONTACT_RGB, dtype=float), rgb)
    return np.rint(rgb).astype(np.uint8)


def legend(scale_mm: float, steps: int = 4,
           mode: str = "clearance") -> list[tuple[str, tuple[int, int, int]]]:
    """Legend entries ``(label, rgb)``: interference, then ``steps + 1`` values from 0 to
    ``scale_mm``, then no contact."""
    if mode == "pressure":
        frac = np.linspace(0.0, 1.0, steps + 1)[1:]
        cols = pressure_colors(frac, 1.0)
        return ([(f"{f:.2f} x allowable contact stress" + (" and above" if f == 1 else ""),
                  _rgb(c)) for f, c in zip(frac, cols, strict=True)]
                + [("no load", NO_CONTACT_RGB)])
    values = np.linspace(0.0, scale_mm, steps + 1)
    cols = clearance_colors(values, scale_mm)
    out = [("< 0 mm (interference)", INTERFERENCE_RGB)]
    zero = " (touching)" if mode == "clearance" else " (first contact)"
    for v, c in zip(values, cols, strict=True):
        label = f"{v:.4f} mm" + (zero if v == 0 else "") + \
            (" and above" if v == scale_mm else "")
        out.append((label, _rgb(c)))
    out.append(("no sleeve flank opposite", NO_CONTACT_RGB))
    return out


def _rgb(c: NDArray[np.uint8]) -> tuple[int, int, int]:
    r, g, b = (int(x) for x in c)
    return r, g, b


def legend_title(mode: str = "clearance") -> str:
    if mode == "pressure":
        return "interior contact pressure at the spec's torque (surface model)"
    return ("flank clearance (circumferential)" if mode == "clearance" else
            "flank separation z (clearance minus the flank's smallest)")


def legend_markdown(scale_mm: float, mode: str = "clearance") -> str:
    """The legend as HTML-coloured markdown for the GUI."""
    rows = [f'<span style="color:rgb{rgb}">■■</span> {label}'
            for label, rgb in legend(scale_mm, mode=mode)]
    return f"**{legend_title(mode)}**<br/>" + "<br/>".join(rows)
