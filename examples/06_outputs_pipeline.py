"""Every file of ``gearcoupling run``, from Python: the same pipeline, its stages'
results typed, and one stage's settings changed.

Run: python examples/06_outputs_pipeline.py
"""

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
res = gc.run(spec, "outputs/examples/run", only=["spec", "sections", "sweep"], workers=1)
assert isinstance(res, gc.RunResult)
print([p.name for p in res.files], res.seconds)
sw = res.results.get("sweep", gc.SweepResult)  # the stage's result, checked to be a sweep
print("smallest backlash over the turn", sw.summary()["min_backlash_mm"], "mm")
# the same stages at another misalignment and a coarser turn
settings = gc.StageSettings(misalignment_deg=1.5, angles=72)
point: gc.OperatingPoint = settings.resolve(spec)  # the spec's torque and model at 1.5°
print(point.misalignment_deg, point.torque_Nm, point.model, point.flank)
res = gc.run(spec, "outputs/examples/run-1.5", only=["sweep"], settings=settings)
print(res.results.get("sweep", gc.SweepResult).misalignment_deg)
