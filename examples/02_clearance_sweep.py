"""Clearance, backlash and contact of every tooth over the turn, and the design angles.

Run: python examples/02_clearance_sweep.py
"""

import numpy as np

import gearcoupling as gc

spec = gc.load_spec("renzo-1967")
sw = gc.sweep(spec, 1.0, np.arange(0.0, 360.0, 2.0))  # SweepResult, (flank, tooth, angle)
assert isinstance(sw, gc.SweepResult) and sw.spec is spec
print(sw.clearance_mm.shape, float(sw.backlash_mm.min()), sw.summary()["renzo_z0_mm"])
print("critical", gc.critical_misalignment_deg(spec), "binding", gc.binding_angle_deg(spec))
print("backlash at 1°", gc.min_backlash_rad(spec, 1.0) * spec.tooth.pitch_radius, "mm")
print(gc.contact_travel(spec, 1.0))
print(gc.design_quantities(spec, 1.0)["critical_misalignment_deg"])
two = gc.double_engagement(spec, offset_mm=5.0, angle_deg=0.5, span_mm=600.0,
                           angles_deg=[0.0, 90.0])
angles, hub_mesh, sleeve_mesh = two  # the two gear meshes of a double-engagement coupling
assert isinstance(angles, gc.MeshAngles) and isinstance(hub_mesh, gc.SweepResult)
print(angles)
