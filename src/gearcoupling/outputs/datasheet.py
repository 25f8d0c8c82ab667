"""The data-sheet stages: ``mass`` (masses and inertias of the solids) and ``datasheet``
(the coupling's data for a rotor model after API 671: ``datasheet.json``,
``datasheet.csv``, ``stiffness_matrix.csv``, the wind-up curve and the loads at the
allowable misalignment, with their pictures)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..io import plot_text, write_csv_rows
from ..plots import save_figure
from ..rotordynamics import (
    CouplingData,
    DatasheetPlan,
    MassProperties,
    check_inputs,
    datasheet_plan,
    mass_properties,
    plot_allowable_loads,
    plot_windup,
)
from .capacity import CapacityAgainstMisalignment
from .stage import SkipStage, StageInputs

NO_TORQUE = ("the stiffness and the loads are those of loaded teeth; give [load] torque_Nm "
             "or a torque")


@dataclass(frozen=True)
class Masses:
    """Mass properties of ``hub``, ``sleeve`` and ``coupling``."""

    parts: dict[str, MassProperties]


def mass(inputs: StageInputs) -> Masses:
    """The stage ``mass``: from the solids at the default tolerance."""
    return Masses(mass_properties(inputs.spec))


def plan(inputs: StageInputs) -> DatasheetPlan:
    """The stage ``datasheet``: its two chains (:class:`~gearcoupling.rotordynamics.
    DatasheetPlan`), the capacity curve's points reused."""
    p = inputs.point
    if not p.torque_Nm:
        raise SkipStage(NO_TORQUE)
    check_inputs(inputs.spec, p.torque_Nm)
    curve = inputs.get("capacity", CapacityAgainstMisalignment).curve
    return datasheet_plan(inputs.spec, p.misalignment_deg, p.torque_Nm, model=p.model,
                          known=curve, mass=inputs.get("mass", Masses).parts)


def files(data: CouplingData, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``datasheet``'s data files and pictures."""
    dpi = inputs.settings.dpi
    a = data.allowable
    return [*data.write(folder),
            write_csv_rows(folder / "windup_curve.csv", ("torque_Nm", "mesh_windup_rad",
                                                         "body_windup_rad", "windup_rad"),
                           data.torsion.rows()),
            save_figure(plot_windup(data.torsion, f"{plot_text(data.spec.name)}, i = "
                                                  f"{data.misalignment_deg:g}°"),
                        folder / "windup.png", dpi),
            write_csv_rows(folder / "allowable_loads.csv", ("psi_deg", *a.loads()), a.rows()),
            save_figure(plot_allowable_loads(a, f"i = {a.misalignment_deg:.3g}°, T = "
                                                f"{a.torque_Nm:.4g} N·m"),
                        folder / "allowable_loads.png", dpi)]
