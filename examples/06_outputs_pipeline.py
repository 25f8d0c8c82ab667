"""Every file of ``gearcoupling run``, from Python: the same pipeline.

Run: python examples/06_outputs_pipeline.py
"""

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
res = gc.run(spec, "outputs/examples/run", only=["spec", "sections", "sweep"], workers=1)
assert isinstance(res, gc.RunResult)
print([p.name for p in res.files], res.seconds)
