"""The frozen result of a wear history, its summary and its long-form rows."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..geometry import FLANKS
from ..tables import dataframe
from .kernels import FlankGrid
from .settings import LIFE_CAP_H, Accuracy, DutyPoint, WearSettings

#: the loads of every operating point at every state (``(S, P)`` arrays of the result)
POINT_STATS = ("max_tooth_load_N", "q", "max_pressure_MPa", "max_interior_pressure_MPa",
               "teeth_in_contact", "edge_contact_teeth", "approach_mm",
               "archard_work_N_mm_per_rev", "partial_slip_share", "slip_to_half_width")

#: ``wear.csv``: a row per state of the history and operating point
CSV_COLUMNS = ("step", "hours", "point", "misalignment_deg", "torque_Nm", "speed_rpm",
               *(f"{m}_depth_{b}_{f}_mm" for m in ("max", "mean") for b in ("hub", "sleeve")
                 for f in FLANKS),
               "hub_thickness_loss_mm", "sleeve_thickness_loss_mm", "wear_fraction",
               "backlash_mm", "max_tooth_load_N", "q", "max_pressure_MPa",
               "max_interior_pressure_MPa", "teeth_in_contact", "edge_contact_teeth",
               "approach_mm", "partial_slip_share")

#: ``wear_depth.csv``: the final depth map of every worn flank
DEPTH_COLUMNS = ("tooth", "body", "flank", "z_mm", "s_mm", "r_mm", "depth_mm")


@dataclass(frozen=True, eq=False)
class WearResult:
    """A wear history: the state after every step (worn depths and the loads solved on
    them) at the coefficient of ``settings``, and the life to the wear limit.

    Arrays over the states are ``(S, ...)`` (state 0 unworn, one more per step); per
    loaded flank ``(cw, ccw)``; per operating point of ``duty`` ``(S, P)``. ``hub_maps``,
    ``sleeve_maps`` ``(S, 2, nz, ns)`` are the worst tooth's depth (mm along the flank
    normal) over each flank grid, ``bearing_MPa`` the largest pressure each hub flank cell
    saw over the turn (the tooth bearing picture); ``hub_depth_mm``, ``sleeve_depth_mm``
    ``(2, T, nz, ns)`` the final maps of every tooth (``T = 1``: the teeth wear alike).
    ``exposure`` is the coefficient times the hours (mm³/(N·m)·h): the history is a
    function of it alone, so another coefficient reads it at ``exposure / k``
    (:meth:`life_h_at`).
    """

    spec: Any = field(repr=False)
    duty: tuple[DutyPoint, ...]
    settings: WearSettings
    accuracy: Accuracy
    hours_requested: float
    exposure: NDArray[np.float64]
    hub_max_mm: NDArray[np.float64]
    hub_mean_mm: NDArray[np.float64]
    sleeve_max_mm: NDArray[np.float64]
    sleeve_mean_mm: NDArray[np.float64]
    thickness_loss_mm: NDArray[np.float64]
    wear_ratio: NDArray[np.float64]
    backlash_mm: NDArray[np.float64]
    stats: dict[str, NDArray[np.float64]] = field(repr=False)
    hub_maps: NDArray[np.float64] = field(repr=False)
    sleeve_maps: NDArray[np.float64] = field(repr=False)
    bearing_MPa: NDArray[np.float64] = field(repr=False)
    hub_depth_mm: NDArray[np.float64] = field(repr=False)
    sleeve_depth_mm: NDArray[np.float64] = field(repr=False)
    hub_grid: FlankGrid = field(repr=False)
    sleeve_grid: FlankGrid = field(repr=False)
    life_exposure: float | None = None
    extrapolated_exposure: float = math.inf
    solves: int = 0
    steps_kept: tuple = field(default=(), repr=False)

    @classmethod
    def from_history(cls, spec, duty, settings, accuracy, hours, arrays, maps, life,
                     extrapolated, solves, kept=()) -> WearResult:
        """The result of :func:`~.history.run_history`'s records."""
        return cls(spec, tuple(duty), settings, accuracy, float(hours), arrays["exposure"],
                   arrays["hub_max_mm"], arrays["hub_mean_mm"], arrays["sleeve_max_mm"],
                   arrays["sleeve_mean_mm"], arrays["thickness_loss_mm"],
                   arrays["wear_ratio"], arrays["backlash_mm"],
                   {name: arrays[name] for name in POINT_STATS}, arrays["hub_maps"],
                   arrays["sleeve_maps"], arrays["bearing_MPa"], maps.hub, maps.sleeve,
                   maps.hub_grid, maps.sleeve_grid, life, extrapolated, solves, tuple(kept))

    # ------------------------------------------------------------------ time and life
    @property
    def hub_thickness_mm(self) -> float:
        """The hub tooth's thickness at the pitch circle (arc)."""
        return thicknesses_mm(self.spec)[0]

    @property
    def hours(self) -> NDArray[np.float64]:
        """Hours of every state at the result's coefficient."""
        return self.exposure / self.settings.coefficient_mm3_per_Nm

    @property
    def steps(self) -> int:
        return int(self.exposure.size - 1)

    @property
    def limit_reached(self) -> bool:
        return self.life_exposure is not None

    @property
    def life_basis(self) -> str:
        """``reached`` (the history ran to the limit), ``extrapolated`` (from the last
        step's rate of wear) or ``no wear``."""
        if self.life_exposure is not None:
            return "reached"
        return "extrapolated" if math.isfinite(self.extrapolated_exposure) else "no wear"

    def life_h_at(self, coefficient_mm3_per_Nm: float) -> float:
        """Hours to the wear limit at another coefficient (at most :data:`LIFE_CAP_H`)."""
        x = self.life_exposure if self.life_exposure is not None else \
            self.extrapolated_exposure
        return min(x / coefficient_mm3_per_Nm, LIFE_CAP_H)

    @property
    def life_h(self) -> float:
        """Hours to the wear limit at the result's coefficient: the scalar a study takes as
        its response."""
        return self.life_h_at(self.settings.coefficient_mm3_per_Nm)

    @property
    def life_band_h(self) -> tuple[float, float]:
        """The life at the band's high and low coefficient."""
        lo, hi = self.settings.band_mm3_per_Nm
        return self.life_h_at(hi), self.life_h_at(lo)

    # ------------------------------------------------------------------ summary
    def summary(self) -> dict[str, Any]:
        """``wear_summary.json``: plain data, every number finite, units in the keys."""
        s, k = self.settings, self.settings.coefficient_mm3_per_Nm
        th, ts = thicknesses_mm(self.spec)
        first = {n: [float(v) for v in self.stats[n][0]] for n in _LOAD_KEYS}
        last = {n: [float(v) for v in self.stats[n][-1]] for n in _LOAD_KEYS}
        out: dict[str, Any] = {
            "spec": self.spec.name,
            "duty": [{"misalignment_deg": p.misalignment_deg, "torque_Nm": p.torque_Nm,
                      "speed_rpm": p.speed_rpm, "hours": p.hours,
                      "axial_float_mm": p.axial_float_mm} for p in self.duty],
            "regime": s.regime, "coefficient_mm3_per_Nm": k,
            "coefficient_band_mm3_per_Nm": list(s.band_mm3_per_Nm),
            "coefficient_source": s.source, "sleeve_factor": s.sleeve_factor,
            "hours_requested": self.hours_requested, "hours": float(self.hours[-1]),
            "steps": self.steps, "turn_solves": self.solves,
            "limit_fraction": s.limit_fraction,
            "limit_thickness_loss_mm": {"hub": s.limit_fraction * th,
                                        "sleeve": s.limit_fraction * ts},
            "limit_reached": self.limit_reached,
            "life_h": self.life_h, "life_band_h": list(self.life_band_h),
            "life_basis": self.life_basis,
            "wear_fraction": float(self.wear_ratio[-1]),
            "max_depth_mm": {"hub": float(np.max(self.hub_max_mm[-1])),
                             "sleeve": float(np.max(self.sleeve_max_mm[-1]))},
            "thickness_loss_mm": {"hub": float(self.thickness_loss_mm[-1, 0]),
                                  "sleeve": float(self.thickness_loss_mm[-1, 1])},
            "backlash_mm": {"start": [float(v) for v in self.backlash_mm[0]],
                            "end": [float(v) for v in self.backlash_mm[-1]]},
            "loads_start": first, "loads_end": last,
            "partial_slip_share": float(np.max(self.stats["partial_slip_share"])),
            "accuracy": {"step_fraction": self.accuracy.step_fraction,
                         "grid": list(self.accuracy.grid), "phases": self.accuracy.phases},
            "notes": self.notes(),
        }
        ratio = self.stats["slip_to_half_width"]
        if np.any(np.isfinite(ratio)):
            out["min_slip_to_half_width"] = float(np.min(ratio[np.isfinite(ratio)]))
        if s.required_life_h is not None:
            out["required_life_h"] = s.required_life_h
            out["meets_required_life"] = bool(self.life_h >= s.required_life_h)
            out["meets_required_life_across_band"] = bool(self.life_band_h[0]
                                                          >= s.required_life_h)
        return out

    def notes(self) -> list[str]:
        """Plain-language notes on what the numbers rest on."""
        notes = []
        share = float(np.max(self.stats["partial_slip_share"]))
        if share > 0:
            notes.append(f"partial slip (fretting): {100 * share:.0f} % of the wear work is "
                         "done in passes whose slip amplitude is below the contact "
                         "half-width, where gross-slip Archard wear with a sliding "
                         "coefficient does not hold; the 'dry' regime's fretting "
                         "coefficients are the published ones for it")
        if self.life_basis == "extrapolated":
            notes.append("the wear limit lies beyond the history: its life is extrapolated "
                         "at the last step's rate of wear")
        if self.life_basis == "no wear":
            notes.append("nothing slides under load (no misalignment, no axial float): no "
                         f"wear, the life is reported as {LIFE_CAP_H:g} h")
        mat = self.spec.material
        allowable = min(mat.hub.allowable_contact_stress_MPa,
                        mat.sleeve.allowable_contact_stress_MPa)
        if np.max(self.stats["max_interior_pressure_MPa"]) > allowable:
            notes.append(f"the interior contact pressure exceeds the allowable {allowable:g} "
                         "MPa at some state: the flanks are taken as elastic (no pitting or "
                         "plastic flow)")
        if self.life_h >= LIFE_CAP_H:
            notes.append(f"lives beyond {LIFE_CAP_H:g} h are reported as {LIFE_CAP_H:g} h")
        return notes

    # ------------------------------------------------------------------ rows
    def rows(self) -> Iterator[tuple]:
        """``wear.csv`` rows (:data:`CSV_COLUMNS` order), state-major per operating point."""
        hours = self.hours
        for i in range(self.exposure.size):
            depth = [float(a[i, f]) for a in (self.hub_max_mm, self.sleeve_max_mm)
                     for f in (0, 1)]
            mean = [float(a[i, f]) for a in (self.hub_mean_mm, self.sleeve_mean_mm)
                    for f in (0, 1)]
            for j, p in enumerate(self.duty):
                yield (i, float(hours[i]), j, p.misalignment_deg, p.torque_Nm, p.speed_rpm,
                       *depth, *mean, float(self.thickness_loss_mm[i, 0]),
                       float(self.thickness_loss_mm[i, 1]), float(self.wear_ratio[i]),
                       float(self.backlash_mm[i, j]),
                       *(float(self.stats[n][i, j]) for n in _CSV_STATS))

    def to_dataframe(self):
        """:meth:`rows` as a pandas DataFrame with the columns of ``wear.csv``."""
        return dataframe(CSV_COLUMNS, self.rows())

    def depth_columns(self) -> list[NDArray | list]:
        """``wear_depth.csv`` by columns (:data:`DEPTH_COLUMNS`): every (body, flank,
        tooth) map with any wear; ``tooth`` is ``all`` where the teeth wear alike."""
        r_b = self.spec.tooth.base_radius
        cols: list[list] = [[] for _ in DEPTH_COLUMNS]
        for body, maps, grid in (("hub", self.hub_depth_mm, self.hub_grid),
                                 ("sleeve", self.sleeve_depth_mm, self.sleeve_grid)):
            z, s = np.meshgrid(grid.z_mm, grid.s_mm, indexing="ij")
            r = np.sqrt(r_b * r_b + 2 * r_b * s)
            for f, name in enumerate(FLANKS):
                for t in range(maps.shape[1]):
                    if not np.any(maps[f, t] > 0):
                        continue
                    n = z.size
                    label = "all" if maps.shape[1] == 1 else str(t)
                    for c, v in zip(cols, ([label] * n, [body] * n, [name] * n, z.ravel(),
                                           s.ravel(), r.ravel(), maps[f, t].ravel()),
                                    strict=True):
                        c.append(v)
        text = [[x for part in c for x in part] for c in cols[:3]]  # text: str lists
        return [*text, *(np.concatenate(c) if c else np.zeros(0) for c in cols[3:])]


_LOAD_KEYS = ("q", "max_tooth_load_N", "max_pressure_MPa", "max_interior_pressure_MPa",
              "edge_contact_teeth", "teeth_in_contact")
_CSV_STATS = ("max_tooth_load_N", "q", "max_pressure_MPa", "max_interior_pressure_MPa",
              "teeth_in_contact", "edge_contact_teeth", "approach_mm", "partial_slip_share")


def thicknesses_mm(spec) -> tuple[float, float]:
    """The hub's and the sleeve's tooth thickness at the pitch circle (arc, mm)."""
    pitch = 2 * math.pi * spec.tooth.pitch_radius / spec.tooth.teeth
    return spec.hub.tooth_thickness, pitch - spec.sleeve.space_width


__all__ = ["CSV_COLUMNS", "DEPTH_COLUMNS", "POINT_STATS", "WearResult", "thicknesses_mm"]
