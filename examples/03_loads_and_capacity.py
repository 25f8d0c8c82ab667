"""Tooth loads under torque and the torque capacity per criterion.

Run: python examples/03_loads_and_capacity.py
"""

import gearcoupling as gc

spec = gc.load_spec("renzo-1967")
# LoadResult of the default surface model with the default fe-fit springs (docs/load.md)
res = gc.load(spec, 1.0, range(0, 360, 45), torque_Nm=2000.0)
assert isinstance(res, gc.LoadResult)
print("q", round(res.q(), 3), "max tooth load", res.tangential_force_N.max(), "N")
sw = gc.sweep(spec, 1.0, [0.0])  # one sweep, several loads: the sweep carries its spec
for model in ("linear", "compliance", "surface"):
    print(model, gc.load_from_sweep(sw, torque_Nm=2000.0, model=model).tangential_force_N.max())
cap: gc.Capacity = gc.capacity(spec, 1.0)  # per criterion, the governing one, q
print(cap.capacity_Nm, cap.governing, cap.criteria_Nm)
curve: gc.CapacityCurve = gc.capacity_curve(spec, [0.5, 1.5])  # about 2 s a point
print([round(c.capacity_Nm) for c in curve])
comparison: gc.CapacityComparison = gc.compare_capacity(  # the quick compliance model
    [spec, gc.load_spec("renzo-1967-vari-crown")], [0.5, 1.0], model="compliance")
print(type(comparison).__name__)
