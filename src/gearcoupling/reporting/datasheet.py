"""The report's data-sheet section: the coupling's data for a rotor model, laid out like an
API 671 coupling data sheet (docs/rotordynamics.md)."""

from __future__ import annotations

from ..errors import SpecError
from ..io import plot_text, write_csv_rows
from ..rotordynamics import (
    DOFS,
    CouplingData,
    StartedCouplingData,
    plot_allowable_loads,
    plot_windup,
)
from .document import Note, Row, Section, Table
from .sections import Context

PARTS = ("hub", "sleeve", "coupling")


def start_datasheet(ctx: Context) -> None:
    """Start the data sheet's work (forked workers where the machine has two cores), after
    the capacity section, whose curve it reuses (``known=``): it runs while the sections
    after it are built. A data sheet that is not made leaves its reason instead
    (``ctx.datasheet_run`` a string). The caller stops it in a ``finally``."""
    if ctx.torque_Nm is None or ctx.torque_Nm == 0:
        ctx.datasheet_run = ("Not made: the stiffness and the loads are those of loaded teeth; "
                             "give [load] torque_Nm or --torque.")
        return
    try:
        ctx.datasheet_run = StartedCouplingData(ctx.spec, ctx.misalignment_deg, ctx.torque_Nm,
                                                model=ctx.model,
                                                known=ctx.found.get("capacity_curve", ()))
    except SpecError as err:
        ctx.datasheet_run = f"Not made: {err}"


def datasheet(ctx: Context) -> Section:
    sec = Section("datasheet", "Coupling data sheet for rotordynamics, after API 671")
    if ctx.datasheet_run is None:
        start_datasheet(ctx)
    if isinstance(ctx.datasheet_run, str):
        sec.blocks.append(Note(ctx.datasheet_run, "skip"))
        return sec
    data = ctx.datasheet_run.result()
    ctx.found["datasheet"] = data
    for path in data.write(ctx.data_dir):
        ctx.files.append(path)
    acc = data.accuracy()
    sec.blocks += [_rating(data), _mass(data, acc["mass"]), *_stiffness(data, acc)]
    sec.blocks.append(_windup_figure(ctx, data))
    sec.blocks.append(_allowable_figure(ctx, data))
    sec.blocks.append(Note("Not modelled: " + "; ".join(data.not_modelled) + "."))
    return sec


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


def _windup_figure(ctx: Context, data: CouplingData):
    name = "windup_curve.csv"
    write_csv_rows(ctx.data_path(name), ("torque_Nm", "mesh_windup_rad", "body_windup_rad",
                                         "windup_rad"), data.torsion.rows())
    return ctx.figure("windup", "Torque against wind-up, to the capacity",
                      plot_windup(data.torsion, f"{plot_text(data.spec.name)}, i = "
                                  f"{data.misalignment_deg:g}°"),
                      f"{data.model} model ({data.springs} springs), mean over "
                      f"{data.stiffness.steps['rotations']} rotations of one pitch; bodies "
                      "in closed form.", name)


def _allowable_figure(ctx: Context, data: CouplingData):
    a = data.allowable
    name = "allowable_loads.csv"
    write_csv_rows(ctx.data_path(name), ("psi_deg", *a.loads()), a.rows())
    return ctx.figure("allowable-loads", "Loads on the shafts over a turn at the allowable "
                      "misalignment", plot_allowable_loads(a, f"i = {a.misalignment_deg:.3g}°, "
                                                          f"T = {a.torque_Nm:.4g} N·m"),
                      f"{data.model} model, {a.angles_deg.size} rotations over the turn.", name)
