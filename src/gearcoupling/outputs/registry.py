"""Every stage of the pipeline, one :class:`~.stage.Stage` each, in an order where each
follows the stages it needs (``gc.run`` and ``gc.report`` compute from this table). A
stage's level says where it runs: in each mesh's scope of a double-engagement coupling
(the default), once for the spec, for a single engagement only, or for the whole coupling
only (:attr:`~.stage.Stage.level`).

Adding a stage is adding its entry here and its module's functions (docs/api.md,
"Extending"). Costs are CPU seconds of the stage on renzo-1967 with the default settings
(``benchmarks/bench_stages.py`` measures them: the seconds it prints, halved for the load
of the machine it ran on; the whole coupling's stages on spacer-double, on the same
scale): the workers balance them and the progress bar counts them.
"""

from __future__ import annotations

from . import files
from .stage import Stage

FIGURES, MESHES, KERNELS, LOADS = "figures", "meshes", "kernels", "loads"
SPEC, SINGLE, WHOLE = "spec", "single", "whole"

STAGES: dict[str, Stage] = {s.name: s for s in (
    Stage("spec", "resolved spec (spec.json)", (), "spec:resolve", "spec:files", 0.01,
          writes=files.SPEC, level=SPEC),
    Stage("sections", "transverse sections and the crown profile", (), "spec:profile",
          "spec:profile_files", 0.7, uses=(FIGURES,), writes=files.SECTIONS, level=SPEC),
    Stage("parts", "hub and sleeve STL", (), "parts:build", "parts:files", 0.7,
          uses=(MESHES,), writes=tuple(files.part_files()), level=SPEC),
    Stage("step", "hub and sleeve STEP", (), "parts:step", "parts:step_files", 1.9,
          after=("parts",), writes=files.STEP, level=SPEC),
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
          "interference:files", 0.8, uses=(FIGURES, MESHES, KERNELS),
          writes=files.INTERFERENCE),
    Stage("viewer", "static 3D viewer", (), "viewer:scene", "viewer:files", 0.5,
          uses=(MESHES, KERNELS, LOADS), writes=files.VIEWER, level=SPEC),
    Stage("rating", "capacity at the operating point, the torque against it", (),
          "capacity:rating", "capacity:rating_files", 1.3, uses=(KERNELS, LOADS),
          writes=files.RATING),
    Stage("capacity", "capacity per criterion against misalignment", ("design", "rating"),
          "capacity:plan", "capacity:files", 4.7, parallel=True,
          uses=(FIGURES, KERNELS, LOADS), writes=files.CAPACITY),
    Stage("wear", "wear over life at the operating point, the life to the wear limit", (),
          "wear:history", "wear:files", 55.0, uses=(FIGURES, KERNELS, LOADS),
          writes=files.WEAR),
    Stage("mass", "masses and inertias of the solids", (), "datasheet:mass", None, 0.1,
          uses=(MESHES,), level=SINGLE),
    Stage("datasheet", "coupling data sheet for a rotor model (API 671)",
          ("capacity", "mass"), "datasheet:plan", "datasheet:files", 9.4, parallel=True,
          uses=(FIGURES, KERNELS, LOADS), writes=files.DATASHEET, level=SINGLE),
    Stage("hob", "hob centre path and G-code", (), "manufacturing:hob",
          "manufacturing:hob_files", 0.1, uses=(FIGURES,), writes=files.HOB, level=SPEC),
    Stage("charts", "nominal measuring charts", (), "manufacturing:charts",
          "manufacturing:charts_files", 0.25, uses=(FIGURES,), writes=files.CHARTS, level=SPEC),
    Stage("inspection", "a measured hub against the nominal", (), "inspection:inspect",
          "inspection:files", 3.0, uses=(FIGURES, MESHES), writes=files.INSPECTION,
          level=SPEC),
    Stage("alignment", "each mesh's angle and tilt axis at the shaft alignment", (),
          "whole:alignment", "whole:alignment_files", 0.01, writes=files.ALIGNMENT,
          level=WHOLE),
    Stage("whole_loads", "loads on the machines over a turn, the floating member's balance",
          ("load",), "whole:whole_loads", "whole:whole_loads_files", 0.2, uses=(FIGURES,),
          writes=files.WHOLE_LOADS, level=WHOLE),
    Stage("whole_capacity", "the whole coupling's capacity: the smaller mesh's",
          ("rating",), "whole:whole_capacity", "whole:whole_capacity_files", 0.01,
          writes=files.WHOLE_CAPACITY, level=WHOLE),
    Stage("allowable_offset", "allowable parallel offset at the span", (), "whole:offset",
          "whole:offset_files", 6.0, uses=(KERNELS, LOADS), writes=files.ALLOWABLE_OFFSET,
          level=WHOLE),
    Stage("whole_datasheet", "the whole coupling's data sheet (AGMA 9009 halves, torsion, "
          "lateral frequency)", (), "whole:datasheet", "whole:datasheet_files", 6.0,
          uses=(MESHES, KERNELS, LOADS), writes=files.WHOLE_DATASHEET, level=WHOLE),
    Stage("assembly", "every part placed at the alignment (glTF)", (), "whole:assembly",
          "whole:assembly_files", 0.3, uses=(MESHES,), writes=files.ASSEMBLY, level=WHOLE),
    Stage("assembly_step", "the placed assembly as STEP AP214", (), "whole:assembly_step",
          "whole:assembly_step_files", 2.0, after=("assembly",), writes=files.ASSEMBLY_STEP,
          level=WHOLE),
)}

#: what ``gc.run`` computes by default: everything a spec alone gives but the capacity
#: curve, the data sheet and the manufacturing files (their own commands and the report
#: make those); the rating says whether the capacity carries the torque
RUN = ("spec", "sections", "parts", "step", "sweep", "load", "load_study", "q_graph",
       "rating", "check", "viewer")
#: what ``gc.run`` adds for a double-engagement coupling: the whole coupling's stages but
#: its data sheet (each mesh's stages of :data:`RUN` run in its own folder)
RUN_WHOLE = ("alignment", "whole_loads", "whole_capacity", "allowable_offset", "assembly",
             "assembly_step")


#: what ``gc.run`` adds where the spec (or the settings) asks for wear: a speed and hours
RUN_WEAR = ("wear",)


def run_stages(engagements: int = 1, wear: bool = False) -> tuple[str, ...]:
    """What ``gc.run`` computes by default for a spec of one or two ``engagements``, with
    the wear history where ``wear`` (the spec asks for it)."""
    return (*RUN, *(RUN_WEAR if wear else ()), *(RUN_WHOLE if engagements == 2 else ()))
