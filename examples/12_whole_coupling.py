"""The whole coupling: two crowned hubs in flanged half-sleeves with a spacer, at a parallel
offset and an angle of the shafts: each mesh's angle and phase, the loads on both machines
with the floating member's balance, the capacity and the allowable offset, the data sheet
of the whole coupling, and the placed assembly (docs/coupling.md).

Run: python examples/12_whole_coupling.py
"""

import importlib.util

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
layout = gc.CouplingLayout(sleeve="flanged", flange_outer_diameter_mm=140.0,
                           flange_thickness_mm=12.0, spacer_outer_diameter_mm=110.0,
                           spacer_inner_diameter_mm=90.0, spacer_length_mm=200.0)
shafts = gc.ShaftAlignment(offset_mm=0.4, offset_azimuth_deg=30.0, angle_deg=0.2,
                           angle_azimuth_deg=100.0)
geom = gc.coupling_geometry(spec, layout, shafts)
assert isinstance(geom, gc.CouplingGeometry)
print(f"span {geom.span_mm:g} mm; mesh A {geom.misalignment_deg('A'):.4f}°, "
      f"mesh B {geom.misalignment_deg('B'):.4f}° (tilt axes at {geom.tilt_axis_deg('A'):.1f}°"
      f" and {geom.tilt_axis_deg('B'):.1f}°)")

model = "compliance"  # a quick load model for the example; the spec's default is "surface"
loads = gc.whole_loads(spec, layout, shafts, 400.0, model=model)
assert isinstance(loads, gc.WholeLoads)
s = loads.summary()
for m in ("A", "B"):
    print(f"  shaft {m}: bending moment up to {s[f'mesh_{m}']['bending_moment_Nm']['max']:.1f} "
          f"N·m, radial force up to {s[f'mesh_{m}']['radial_force_N']['max']:.1f} N")
print(f"  torque lost to friction {s['torque_loss_Nm']:.3f} N·m; floating member residual "
      f"{s['equilibrium']['relative_moment']:.1e} of the largest moment")
loads.write_csv("outputs/whole-coupling/loads.csv")

cap = gc.whole_capacity(spec, layout, shafts, model=model)
assert isinstance(cap, gc.WholeCapacity)
offset = gc.allowable_offset(spec, layout, None, 400.0, model=model)
assert isinstance(offset, gc.AllowableOffset)
print(f"capacity {cap.capacity_Nm:.0f} N·m (mesh {cap.governing_mesh}, {cap.criterion}); "
      f"allowable offset at 400 N·m {offset.offset_mm:.2f} mm (mesh {offset.governing_mesh}, "
      f"{offset.criterion})")

data = gc.whole_coupling_data(spec, layout, shafts, 400.0, model=model,
                              matrices=importlib.util.find_spec("ross") is not None)
assert isinstance(data, gc.WholeCouplingData)
for m in ("A", "B"):
    h = data.halves[m]
    print(f"  half {m}: {h.mass_kg:.3f} kg, WR² {h.polar_inertia_kg_m2:.3e} kg·m², CG "
          f"{data.cg_from_shaft_end_mm(m):.1f} mm from the shaft end")
print(f"  torsion: secant {data.torsion.secant_Nm_per_rad:.4g}, tangent "
      f"{data.torsion.tangent_Nm_per_rad:.4g} N·m/rad; spacer's lateral frequency "
      f"{data.lateral_frequency_Hz:.0f} Hz")
if data.matrices:  # the rotordynamics extra: the pieces of a ROSS train
    pieces = data.to_ross(n=2)
    assert isinstance(pieces, gc.RossPieces)
    print("  ROSS:", pieces.summary())

assembly = gc.coupling_assembly(spec, layout, shafts, psi_deg=0.0)
assert isinstance(assembly, gc.CouplingAssembly)
assert all(isinstance(p, gc.PlacedPart) for p in assembly.parts)
assembly.write_glb("outputs/whole-coupling/coupling.glb")  # one named node per part
print("parts:", ", ".join(p.name for p in assembly.parts), "; overlap of mesh A",
      assembly.overlap_mm3("A"), "mm³")
if importlib.util.find_spec("OCP") is not None:  # the step extra
    assembly.write_step("outputs/whole-coupling/coupling.step")

# The same kind of coupling from a spec file: the template spacer-double's [coupling] and
# [alignment] tables. Every command and gc.run / gc.report analyse each mesh at its own
# angle and rotation phase (mesh-a/, mesh-b/) and the whole coupling at the top.
double = gc.load_spec("spacer-double")
resolved = gc.spec_geometry(double, {"offset_mm": 0.3})  # its alignment, the offset changed
print(f"spacer-double at 0.3 mm: mesh A {resolved.misalignment_deg('A'):.4f}°, mesh B "
      f"{resolved.misalignment_deg('B'):.4f}° over the span {resolved.span_mm:g} mm")
scopes = gc.StageSettings(offset_mm=0.3).scopes(double)  # where gc.run analyses what
assert all(isinstance(s, gc.Scope) for s in scopes.values())
for name, scope in scopes.items():
    if name:  # a mesh: its spec, angle, torque (hub B's the negative) and rotation phase
        p = scope.point
        print(f"  {name}: i = {p.misalignment_deg:.4f}°, T = {p.torque_Nm:g} N·m, phase "
              f"{p.phase_deg:.2f}°")
# what the viewer draws: every part placed, each mesh's clearance at its pose
pose = gc.assembly_pose(double, psi_deg=0.0, changes={"offset_mm": 0.3})
assert isinstance(pose, gc.AssemblyPose)
print("  smallest clearance of mesh B's flanks:", pose.states["B"].min_clearance_mm, "mm")
# with the viewer extra: gc.write_html(double, "coupling.html", settings=view) writes the
# static scene; gc.serve(double) starts a gc.AssemblyApp with sliders for offset and angle
view = gc.AssemblySettings(offset_mm=0.3, psi_deg=0.0)
assert view.changes() == {"offset_mm": 0.3}
