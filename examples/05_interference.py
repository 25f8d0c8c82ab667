"""Interference and minimum gap of the posed meshes over the turn (python-fcl).

Run: python examples/05_interference.py
"""

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
res: gc.InterferenceResult = gc.check_interference(spec, 0.75, [0.0, 45.0, 90.0])
print("interferes:", res.interferes, "smallest gap", float(res.min_gap_mm.min()), "mm")
overlaps: list[gc.Overlap] = res.overlaps_at(0)  # the overlapping pieces at the first angle
print(len(overlaps), "overlaps at 0°")
