"""The 3D scene as a static HTML page, a pose's clearance state, and the design report.

Run: python examples/10_viewer_and_report.py  (``gc.serve(spec)`` starts the live viewer:
a ``gc.ViewerApp`` whose ``url`` a browser opens and whose ``stop()`` ends it)
"""

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
state: gc.PoseState = gc.pose_state(spec, 0.75, 0.0)
print("backlash", state.backlash_mm, "mm")
print(gc.write_html(spec, "outputs/examples/viewer.html"))
settings = gc.ReportSettings(angles=36, capacity_count=5, phases=2, viewer=False)
rep = gc.report(spec, "outputs/examples/report", settings=settings)
assert isinstance(rep, gc.ReportResult)
print(rep.html, rep.verdict)
assert callable(gc.serve)
