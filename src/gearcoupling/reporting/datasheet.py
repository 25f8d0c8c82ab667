"""The report's data-sheet section: the coupling's data for a rotor model, laid out like an
API 671 coupling data sheet (docs/rotordynamics.md)."""

from __future__ import annotations

from ..rotordynamics import DOFS, CouplingData
from .document import Block, Note, Row, Table
from .view import View

PARTS = ("hub", "sleeve", "coupling")


def datasheet(v: View) -> list[Block]:
    """The data sheet's tables and figures (the stage ``datasheet``)."""
    data = v.get("datasheet", CouplingData)
    if data is None:
        return [Note(f"Not made: {v.why('datasheet')}.", "skip")]
    acc = data.accuracy()
    return [_rating(data), _mass(data, acc["mass"]), *_stiffness(data, acc),
            v.figure("windup", "Torque against wind-up, to the capacity", "windup.png",
                     f"{data.model} model ({data.springs} springs), mean over "
                     f"{data.stiffness.steps['rotations']} rotations of one pitch; bodies in "
                     "closed form.", "windup_curve.csv"),
            v.figure("allowable-loads", "Loads on the shafts over a turn at the allowable "
                     "misalignment", "allowable_loads.png", f"{data.model} model, "
                     f"{data.allowable.angles_deg.size} rotations over the turn.",
                     "allowable_loads.csv"),
            Note("Not modelled: " + "; ".join(data.not_modelled) + ".")]


def _rating(data: CouplingData) -> Table:
    a = data.allowable
    limit = a.criterion + (f" ({a.capacity_criterion.replace('_', ' ')})"
                           if a.capacity_criterion else "")
    rows = [("operating torque", data.torque_Nm, "N·m"),
            ("operating misalignment", data.misalignment_deg, "deg"),
            ("capacity at the operating misalignment", data.capacity_Nm, "N·m"),
            ("allowable misalignment at the torque", a.misalignment_deg, f"deg ({limit})"),
            ("critical misalignment (contact onto a face end)", a.critical_misalignment_deg,
             "deg"),
            ("load model, tooth springs, friction",
             f"{data.model}, {data.springs}, {data.spec.load.friction:g}", "")]
    return Table(("rating", "value", "unit"), rows, "Operating point and rating.")


def _mass(data: CouplingData, accuracy: str) -> Table:
    m = [data.mass[p] for p in PARTS]
    rows = [("mass", *(x.mass_kg for x in m), "kg"),
            ("centre of gravity from the midplane", *(float(x.centre_of_gravity_mm[2])
                                                      for x in m), "mm"),
            ("polar inertia", *(x.polar_inertia_kg_m2 for x in m), "kg·m²"),
            ("transverse inertia about the centre of gravity",
             *(x.transverse_inertia_kg_m2 for x in m), "kg·m²")]
    return Table(("mass elastic data", *PARTS, "unit"), rows,
                 f"From the solids, density {data.spec.material.hub.density_kg_per_m3:g} / "
                 f"{data.spec.material.sleeve.density_kg_per_m3:g} kg/m³ (hub / sleeve); "
                 f"{accuracy}.")


def _stiffness(data: CouplingData, acc: dict[str, str]) -> list:
    s, t = data.stiffness, data.torsion
    torsion = Table(("torsional stiffness", "value", "unit"), [
        ("secant at the torque (teeth and bodies)", t.secant_Nm_per_rad, "N·m/rad"),
        ("tangent at the torque (teeth and bodies)", t.tangent_Nm_per_rad, "N·m/rad"),
        ("bodies alone (bore to sleeve outside diameter)", s.body_torsional_Nm_per_rad,
         "N·m/rad")], acc["torsion"] + ".")
    cc = s.cross_coupled()
    cross = Table(("cross-coupled tilt", "held wind-up", "held torque", "unit"), [
        (name, cc[f"{key}_held_windup_Nm_per_rad"], cc[f"{key}_held_torque_Nm_per_rad"],
         "N·m/rad") for name, key in (("k_xy (moment about -x per tilt about y)", "k_xy"),
                                      ("k_yx (moment about -y per tilt about x)", "k_yx"),
                                      ("antisymmetric part (k_xy - k_yx) / 2",
                                       "antisymmetric"))],
        f"x is the tilt axis of the misalignment; friction {s.friction:g}. The axial slip "
        f"force is {s.axial_slip_force_N:.4g} N.")
    K = s.matrix
    matrix = Table(("K", *DOFS), [(dof, *K[i]) for i, dof in enumerate(DOFS)],
                   "6 x 6 stiffness of hub bore against sleeve outside diameter, K = -dQ/dq "
                   "(Q on the hub; rows N and N·m, columns per m and per rad); "
                   f"{acc['stiffness']}.")
    return [Row([torsion, cross]), matrix]
