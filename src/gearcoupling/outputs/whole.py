"""The whole coupling's stages (a double-engagement spec, docs/coupling.md): ``alignment``
(each mesh's angle and tilt axis), ``whole_loads`` (what each mesh puts on its machine over
a turn, from both meshes' ``load`` results, and the floating member's balance),
``whole_capacity`` (the smaller of the meshes' ratings), ``allowable_offset`` (the
catalogue's allowable parallel offset at the span), ``whole_datasheet`` (the mass-elastic
data of the whole coupling) and ``assembly`` / ``assembly_step`` (every part placed: glTF
and STEP AP214)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import numpy as np

from ..coupling import (
    MACHINE_LOADS,
    AllowableOffset,
    CouplingAssembly,
    CouplingGeometry,
    WholeCapacity,
    WholeCouplingData,
    WholeLoads,
    allowable_offset,
    coupling_assembly,
    loads_from_results,
    whole_coupling_data,
)
from ..errors import BackendError
from ..io import plot_text, write_csv_rows, write_json
from ..loading import LoadResult, turn_phases
from ..plots import fixed_layout, new_figure, save_figure
from .capacity import Rating
from .load import NO_TORQUE
from .settings import scope_name
from .stage import SkipStage, StageInputs

NO_DATASHEET_TORQUE = ("the stiffness and the loads are those of loaded teeth; give [load] "
                       "torque_Nm or a torque")


def geometry(inputs: StageInputs) -> CouplingGeometry:
    """The resolved coupling of the root's operating point."""
    geom = inputs.point.coupling
    assert geom is not None  # the executor runs whole stages for two engagements only
    return geom


# ------------------------------------------------------------------------- alignment


def alignment(inputs: StageInputs) -> CouplingGeometry:
    """The stage ``alignment``: each mesh's angle and tilt axis at the shaft alignment."""
    return geometry(inputs)


def alignment_files(geom: CouplingGeometry, inputs: StageInputs, folder: Path) -> list[Path]:
    """``alignment.json``: the span, the alignment, each mesh's angle, tilt axis and
    folder, the floating axis."""
    data = geom.summary()
    for m in geom.meshes:
        data[f"mesh_{m}"]["folder"] = scope_name(m)
    return [write_json(folder / "alignment.json", data)]


# ------------------------------------------------------------------------- loads


def whole_loads(inputs: StageInputs) -> WholeLoads:
    """The stage ``whole_loads``: both meshes' loads over the turn (the stage ``load`` in
    each mesh's scope, at the coupling's rotations less its phase), their reactions on
    the floating member and what each puts on its machine."""
    geom, p = geometry(inputs), inputs.point
    if p.torque_Nm is None:
        raise SkipStage(NO_TORQUE)
    psi = turn_phases(inputs.spec, inputs.settings.phases)
    results = {m: inputs.results.scope(scope_name(m)).get("load", LoadResult)
               for m in geom.meshes}
    for m, res in results.items():  # each at its rotations of this turn
        if not np.allclose(res.angles_deg, geom.mesh_rotations_deg(m, psi), atol=1e-9):
            raise RuntimeError(f"mesh {m}'s loads are not at the coupling's turn")
    return loads_from_results(geom, p.torque_Nm, psi, results)


def whole_loads_files(loads: WholeLoads, inputs: StageInputs, folder: Path) -> list[Path]:
    """``machine_loads.csv`` (per rotation and mesh), ``whole_loads.json`` (the summary
    with the floating member's equilibrium) and ``machine_loads.png``."""
    return [loads.write_csv(folder / "machine_loads.csv"),
            write_json(folder / "whole_loads.json", loads.summary()),
            save_figure(plot_machine_loads(loads, inputs.spec.name),
                        folder / "machine_loads.png", inputs.settings.dpi)]


LABELS = {"bending_moment_Nm": "bending moment (N·m)", "radial_force_N": "radial force (N)",
          "axial_force_N": "axial force (N)", "torque_Nm": "torque (N·m)"}


def plot_machine_loads(loads: WholeLoads, name: str):
    """What each mesh puts on its shaft over the coupling's turn: bending moment, radial
    and axial force, one line per mesh."""
    shown = MACHINE_LOADS[:3]
    fig, axes = new_figure(len(shown), 1, figsize=(8, 7.2), sharex=True)
    fixed_layout(fig, 0.95, 0.2, 0.6, 0.55)
    psi = loads.angles_deg
    for ax, key in zip(axes, shown, strict=True):
        for m in loads.meshes:
            ax.plot(psi, loads.machine_loads(m)[key], label=f"mesh {m} on shaft {m}")
        ax.set_ylabel(LABELS[key])
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("coupling rotation ψ, shaft A's turn (deg)")
    g = loads.geometry
    angles = ", ".join(f"mesh {m} {g.misalignment_deg(m):.3g}°" for m in g.meshes)
    axes[0].set_title(f"{plot_text(name)}: loads on the machines at T = {loads.torque_Nm:.4g} "
                      f"N·m\n{angles}; axial force positive toward the coupling's centre",
                      fontsize=10)
    return fig


# ------------------------------------------------------------------------- capacity


def whole_capacity(inputs: StageInputs) -> WholeCapacity:
    """The stage ``whole_capacity``: the smaller of the meshes' capacities at their angles
    on their loaded flanks (the stage ``rating`` in each mesh's scope)."""
    geom = geometry(inputs)
    caps = {m: inputs.results.scope(scope_name(m)).get("rating", Rating).capacity
            for m in geom.meshes}

    def key(m: str) -> float:
        c = caps[m].capacity_Nm
        return math.inf if c is None else c

    gov = min(caps, key=key)
    return WholeCapacity(geom, caps, caps[gov].capacity_Nm, gov, caps[gov].governing)


def whole_capacity_files(result: WholeCapacity, inputs: StageInputs, folder: Path
                         ) -> list[Path]:
    """``whole_capacity.json`` with the torque against it."""
    T = inputs.point.torque_Nm
    data = {**result.summary(), "torque_Nm": T,
            "holds": None if T is None or result.capacity_Nm is None
            else abs(T) <= result.capacity_Nm}
    return [write_json(folder / "whole_capacity.json", data)]


def offset(inputs: StageInputs) -> AllowableOffset:
    """The stage ``allowable_offset``: the parallel offset at the span (in the alignment's
    offset direction, its shaft angle held) at which the first mesh reaches its
    allowable misalignment at the torque."""
    geom, p = geometry(inputs), inputs.point
    if p.torque_Nm is None:
        raise SkipStage(NO_TORQUE)
    return allowable_offset(inputs.spec, geom.layout, geom.alignment, p.torque_Nm,
                            model=p.model)


def offset_files(result: AllowableOffset, inputs: StageInputs, folder: Path) -> list[Path]:
    """``allowable_offset.json`` with the offset of the alignment against it."""
    given = result.alignment.offset_mm
    data = {**result.summary(), "offset_mm": given,
            "within": given <= result.offset_mm}
    return [write_json(folder / "allowable_offset.json", data)]


# ------------------------------------------------------------------------- data sheet


def datasheet(inputs: StageInputs) -> WholeCouplingData:
    """The stage ``whole_datasheet``: :func:`~gearcoupling.coupling.whole_coupling_data`
    at the alignment and torque (both meshes' 6 x 6 included)."""
    geom, p = geometry(inputs), inputs.point
    if not p.torque_Nm:
        raise SkipStage(NO_DATASHEET_TORQUE)
    return whole_coupling_data(inputs.spec, geom.layout, geom.alignment, p.torque_Nm,
                               model=p.model)


HALF_ROWS = (("mass", "mass_kg", "kg"), ("polar inertia", "polar_inertia_kg_m2", "kg·m²"),
             ("transverse inertia about the centre of gravity", "transverse_inertia_kg_m2",
              "kg·m²"))


def datasheet_rows(data: WholeCouplingData) -> list[tuple[str, str, float, str]]:
    """The data sheet as ``(item, quantity, value, unit)`` rows: each half's AGMA 9009
    lumps, the floating member, the whole, the torsion and the lateral frequency."""
    rows: list[tuple[str, str, float, str]] = []
    lumps = {**{f"half {m}": data.halves[m] for m in data.geometry.meshes},
             "floating member": data.floating, "coupling": data.whole}
    for item, mp in lumps.items():
        rows += [(item, what, float(getattr(mp, attr)), unit) for what, attr, unit in HALF_ROWS]
        if item.startswith("half"):
            rows.append((item, "centre of gravity from the shaft end",
                         data.cg_from_shaft_end_mm(item[-1]), "mm"))
    t = data.torsion
    rows += [("coupling", "torsional stiffness, secant", t.secant_Nm_per_rad, "N·m/rad"),
             ("coupling", "torsional stiffness, tangent", t.tangent_Nm_per_rad, "N·m/rad"),
             ("floating member", "first lateral frequency, pinned at the meshes",
              data.lateral_frequency_Hz, "Hz")]
    if data.spacer_formula_Hz is not None:
        rows.append(("floating member", "spacer alone, Euler-Bernoulli pinned-pinned",
                     data.spacer_formula_Hz, "Hz"))
    return rows


def datasheet_files(data: WholeCouplingData, inputs: StageInputs, folder: Path
                    ) -> list[Path]:
    """``whole_datasheet.json`` (the summary), ``whole_datasheet.csv`` (its rows) and
    ``torsion_chain.csv`` (each part's compliance, shaft A to shaft B)."""
    t = data.torsion
    return [write_json(folder / "whole_datasheet.json", data.summary()),
            write_csv_rows(folder / "whole_datasheet.csv", ("item", "quantity", "value",
                                                            "unit"), datasheet_rows(data)),
            write_csv_rows(folder / "torsion_chain.csv",
                           ("part", "secant_rad_per_Nm", "tangent_rad_per_Nm"),
                           ((k, v, t.tangent_rad_per_Nm[k])
                            for k, v in t.secant_rad_per_Nm.items()))]


# ------------------------------------------------------------------------- assembly


@dataclass(frozen=True)
class Assembly:
    """The parts placed at the alignment (rotation 0) and the volume each mesh's placed
    hub and sleeve ring share (0: apart)."""

    assembly: CouplingAssembly = field(repr=False)
    overlap_mm3: dict[str, float]

    def summary(self) -> dict[str, Any]:
        return {**self.assembly.summary(), "overlap_mm3": dict(self.overlap_mm3)}


def assembly(inputs: StageInputs) -> Assembly:
    """The stage ``assembly``: every part placed, each mesh's overlap measured."""
    geom = geometry(inputs)
    asm = coupling_assembly(inputs.spec, geom.layout, geom.alignment)
    return Assembly(asm, {m: asm.overlap_mm3(m) for m in geom.meshes})


def assembly_files(result: Assembly, inputs: StageInputs, folder: Path) -> list[Path]:
    """``coupling.glb`` (one named node per part) and ``assembly.json``."""
    return [result.assembly.write_glb(folder / "coupling.glb"),
            write_json(folder / "assembly.json", result.summary())]


@dataclass(frozen=True)
class AssemblyStep:
    """The STEP assembly to write (its files are the work; OpenCASCADE found)."""

    parts: tuple[str, ...]


def assembly_step(inputs: StageInputs) -> AssemblyStep:
    """The stage ``assembly_step``; without OpenCASCADE a
    :class:`~gearcoupling.errors.BackendError` names the extra."""
    if find_spec("OCP") is None:
        raise BackendError("STEP files need OpenCASCADE: pip install 'gearcoupling[step]'")
    geom = geometry(inputs)
    return AssemblyStep(tuple(p.name for p in coupling_assembly(
        inputs.spec, geom.layout, geom.alignment).parts))


def assembly_step_files(result: AssemblyStep, inputs: StageInputs, folder: Path
                        ) -> list[Path]:
    """``coupling.step``: every part a named solid at its placement (AP214)."""
    geom = geometry(inputs)
    asm = coupling_assembly(inputs.spec, geom.layout, geom.alignment)
    return [asm.write_step(folder / "coupling.step")]
