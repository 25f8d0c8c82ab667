"""The hob feed program, the measuring charts, and a measured hub against the nominal.

Run: python examples/09_manufacturing_and_inspection.py
"""

import numpy as np

import gearcoupling as gc

spec = gc.load_spec("renzo-1967")
prog: gc.HobProgram = gc.hob_program(spec, hob_diameter_mm=80.0)
print(len(prog.moves), "moves, chordal deviation", prog.max_deviation_mm, "mm")
charts: gc.MeasuringCharts = gc.measuring_charts(spec)
print(sorted(charts.values["cw"])[:4])
# a "scan": the nominal hub's vertices (a real scan is a mesh or an x y z point file)
scan = np.asarray(gc.build_part(spec, "hub").vertices)
# ISO 1328-1 class 6 limits for its size; with a second part, gc.compare_part(spec, a, b)
# inspects both and returns their gc.PartComparison (B - A)
report: gc.InspectionReport = gc.compare_part(spec, scan, grade=6)
print(report.part["teeth_measured"], "teeth measured, whole part passes:", report.part["pass"])
