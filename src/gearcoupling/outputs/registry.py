"""Every stage of the pipeline, one :class:`~.stage.Stage` each, in an order where each
follows the stages it needs (``gc.run`` and ``gc.report`` compute from this table).

Adding a stage is adding its entry here and its module's functions (docs/api.md,
"Extending"). Costs are CPU seconds of the stage on renzo-1967 with the default settings
(``benchmarks/bench_stages.py`` measures them: the seconds it prints, halved for the load
of the machine it ran on): the workers balance them and the progress bar counts them.
"""

from __future__ import annotations

from . import files
from .stage import Stage

FIGURES, MESHES, KERNELS, LOADS = "figures", "meshes", "kernels", "loads"

STAGES: dict[str, Stage] = {s.name: s for s in (
    Stage("spec", "resolved spec (spec.json)", (), "spec:resolve", "spec:files", 0.01,
          writes=files.SPEC),
    Stage("sections", "transverse sections and the crown profile", (), "spec:profile",
          "spec:profile_files", 0.7, uses=(FIGURES,), writes=files.SECTIONS),
    Stage("parts", "hub and sleeve STL", (), "parts:build", "parts:files", 0.7,
          uses=(MESHES,), writes=tuple(files.part_files())),
    Stage("step", "hub and sleeve STEP", (), "parts:step", "parts:step_files", 1.9,
          after=("parts",), writes=files.STEP),
    Stage("design", "critical and binding angles", (), "sweep:design", None, 0.5,
          uses=(KERNELS,)),
    Stage("backlash", "smallest backlash against misalignment", ("design",),
          "sweep:backlash", None, 0.05, uses=(KERNELS,)),
    Stage("sweep", "clearance and backlash over a turn", ("design", "backlash"),
          "sweep:turn", "sweep:files", 1.2, uses=(FIGURES, KERNELS), writes=files.SWEEP),
    Stage("load", "loads over a turn at the operating point", (), "load:turn_loads",
          "load:files", 2.6, uses=(FIGURES, KERNELS, LOADS), writes=files.LOAD),
    Stage("load_study", "tooth load and moment against misalignment", (), "load:study",
          "load:study_files", 2.5, uses=(FIGURES, KERNELS, LOADS),
          writes=files.LOAD_STUDY),
    Stage("q_graph", "Renzo's load proportion q against z_c / z0", (), "load:q_stage",
          "load:q_stage_files", 0.3, uses=(FIGURES, KERNELS, LOADS), writes=files.Q_GRAPH),
    Stage("check", "mesh interference check over a turn", (), "interference:check",
          "interference:files", 1.6, uses=(FIGURES, MESHES, KERNELS),
          writes=files.INTERFERENCE),
    Stage("viewer", "static 3D viewer", (), "viewer:scene", "viewer:files", 0.5,
          uses=(MESHES, KERNELS, LOADS), writes=files.VIEWER),
    Stage("rating", "capacity at the operating point, the torque against it", (),
          "capacity:rating", "capacity:rating_files", 1.3, uses=(KERNELS, LOADS),
          writes=files.RATING),
    Stage("capacity", "capacity per criterion against misalignment", ("design", "rating"),
          "capacity:plan", "capacity:files", 4.7, parallel=True,
          uses=(FIGURES, KERNELS, LOADS), writes=files.CAPACITY),
    Stage("mass", "masses and inertias of the solids", (), "datasheet:mass", None, 0.1,
          uses=(MESHES,)),
    Stage("datasheet", "coupling data sheet for a rotor model (API 671)",
          ("capacity", "mass"), "datasheet:plan", "datasheet:files", 11.7, parallel=True,
          uses=(FIGURES, KERNELS, LOADS), writes=files.DATASHEET),
    Stage("hob", "hob centre path and G-code", (), "manufacturing:hob",
          "manufacturing:hob_files", 0.1, uses=(FIGURES,), writes=files.HOB),
    Stage("charts", "nominal measuring charts", (), "manufacturing:charts",
          "manufacturing:charts_files", 0.25, uses=(FIGURES,), writes=files.CHARTS),
    Stage("inspection", "a measured hub against the nominal", (), "inspection:inspect",
          "inspection:files", 3.0, uses=(FIGURES, MESHES), writes=files.INSPECTION),
)}

#: what ``gc.run`` computes by default: everything a spec alone gives but the capacity
#: curve, the data sheet and the manufacturing files (their own commands and the report
#: make those); the rating says whether the capacity carries the torque
RUN = ("spec", "sections", "parts", "step", "sweep", "load", "load_study", "q_graph",
       "rating", "check", "viewer")
