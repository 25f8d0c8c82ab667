"""Coupling data for rotordynamics: mass properties, torsional stiffness, the 6 x 6
stiffness matrix under load, the loads at the allowable misalignment, and a ROSS coupling
element (docs/rotordynamics.md)."""

from __future__ import annotations

from ..loading import TOOTH_LOAD_RATIO, WINDUP_ERROR_PCT
from .allowable import AllowableLoads, allowable_loads, allowable_misalignment
from .data import (
    DATASHEET_COLUMNS,
    FILES,
    MAX_TORQUE_NM,
    CouplingData,
    DatasheetPlan,
    StartedCouplingData,
    check_inputs,
    coupling_data,
    datasheet_plan,
)
from .mass import MassProperties, combine, mass_properties, mesh_mass_properties
from .plots import plot_allowable_loads, plot_windup
from .pose import generalized_forces, tilt_pose, translation_gap_offsets
from .ross import ROSS_SUFFIXES, coupling_element, import_ross, write_ross
from .stiffness import (
    DEFAULT_STEPS,
    DIFFERENCES,
    DOFS,
    StiffnessMatrix,
    default_rotations,
    pitch_rotations,
    stiffness_matrix,
)
from .torsion import TorsionalStiffness, windup_beyond_touch
from .wrench import hub_wrench

__all__ = [
    "DATASHEET_COLUMNS",
    "DEFAULT_STEPS",
    "DIFFERENCES",
    "DOFS",
    "FILES",
    "MAX_TORQUE_NM",
    "ROSS_SUFFIXES",
    "TOOTH_LOAD_RATIO",
    "WINDUP_ERROR_PCT",
    "AllowableLoads",
    "CouplingData",
    "DatasheetPlan",
    "MassProperties",
    "StartedCouplingData",
    "StiffnessMatrix",
    "TorsionalStiffness",
    "allowable_loads",
    "allowable_misalignment",
    "check_inputs",
    "combine",
    "coupling_data",
    "coupling_element",
    "datasheet_plan",
    "default_rotations",
    "generalized_forces",
    "hub_wrench",
    "import_ross",
    "mass_properties",
    "mesh_mass_properties",
    "pitch_rotations",
    "plot_allowable_loads",
    "plot_windup",
    "stiffness_matrix",
    "tilt_pose",
    "translation_gap_offsets",
    "windup_beyond_touch",
    "write_ross",
]
