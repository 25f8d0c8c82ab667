"""Coupling data for a rotor model: the API 671 data sheet, the stiffness matrix under load
and a ROSS rotor with this coupling (the ``rotordynamics`` extra: ross-rotordynamics).

Run: python examples/11_rotordynamics.py
"""

import math

import gearcoupling as gc
from gearcoupling.rotordynamics import import_ross, write_ross

spec = gc.load_spec("renzo-1967")
data = gc.coupling_data(spec)  # design angle and torque of the spec; CouplingData
assert isinstance(data, gc.CouplingData)
print(f"{spec.name} at {data.misalignment_deg:g}°, {data.torque_Nm:.0f} N·m "
      f"({data.model} model, {data.springs} springs), {data.seconds:.1f} s")
for name, m in data.mass.items():
    print(f"  {name}: {m.mass_kg:.3f} kg, Ip {m.polar_inertia_kg_m2:.3e} kg·m², "
          f"Id {m.transverse_inertia_kg_m2:.3e} kg·m²")
t = data.torsion
print(f"  torsion: secant {t.secant_Nm_per_rad:.4g}, tangent {t.tangent_Nm_per_rad:.4g} N·m/rad")
K = data.stiffness.matrix  # 6 x 6, SI: x, y, z, tilt_x, tilt_y, torsion
print("  K diagonal:", ", ".join(f"{v:.3g}" for v in K.diagonal()))
print("  cross-coupled tilt (torque held):",
      {k: round(v) for k, v in data.stiffness.cross_coupled().items() if "held_torque" in k})
a = data.allowable
print(f"  allowable misalignment {a.misalignment_deg:.2f}° ({a.criterion}); bending moment "
      f"up to {a.bending_moment_Nm.max():.0f} N·m")
print(data.to_dataframe().head())  # the same data as a DataFrame (the pandas extra)
paths = data.write("outputs/renzo-1967/datasheet")  # datasheet.json, .csv, stiffness_matrix.csv

# a ROSS rotor: disk - shaft - [hub | sleeve] - shaft - disk, free in torsion
rs = import_ross()
coupling = data.to_ross()
write_ross(coupling, "outputs/renzo-1967/datasheet/coupling.toml")  # ROSS's own file
steel = rs.materials.steel
length, diameter, J = 0.05, 0.15, 5.0  # m, m, kg·m² of each disk
shafts = [rs.ShaftElement(length, 0.0, diameter, material=steel), coupling,
          rs.ShaftElement(length, 0.0, diameter, material=steel)]
disks = [rs.DiskElement(n=0, m=100.0, Id=2.5, Ip=J), rs.DiskElement(n=3, m=100.0, Id=2.5, Ip=J)]
bearings = [rs.BearingElement(n=n, kxx=1e8, cxx=0) for n in (0, 3)]
rotor = rs.Rotor(shafts, disks, bearings)
modal = rotor.run_modal(speed=0, num_modes=40, sparse=False)
wn = min(w for w, s in zip(modal.wn, modal.shapes, strict=False)
         if s.mode_type == "Torsional" and w > 1.0)
k_shaft = steel.G_s * math.pi * diameter**4 / 32 / length
k = 1.0 / (2.0 / k_shaft + 1.0 / coupling.kr_z)
closed = math.sqrt(2.0 * k / J)
print(f"first torsional mode: ROSS {wn / (2 * math.pi):.2f} Hz, two-inertia closed form "
      f"{closed / (2 * math.pi):.2f} Hz ({wn / closed - 1:+.2%})")
