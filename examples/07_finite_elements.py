"""Finite elements: a quadratic tet mesh of a hub sector, the CalculiX tooth stiffness and
the contact reference, aligned and misaligned (the fea extra and Debian's calculix-ccx).

Run: python examples/07_finite_elements.py [--contact] [--misaligned]
(the contact references take minutes of solver time: only with the flags;
tests/test_fea_contact.py runs the same calls)
"""

import sys

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
mesh: gc.VolumeMesh = gc.mesh_part(spec, "hub", sector=1, size_mm=1.0)
print(gc.write_mesh(mesh, "outputs/examples/hub-sector-1.inp"), mesh.quality["elements"])
# the FE tooth springs at the default mesh: half a minute of solver time once, then read
# from the cache ($GEARCOUPLING_CACHE, default ~/.cache/gearcoupling)
table: gc.ComplianceTable = gc.tooth_compliance_table(spec)
print("mesh stiffness C", round(table.mesh_stiffness_N_per_mm), "N/mm; far field at the pitch "
      "point", round(1e3 * float(table.pair_compliance_mm_per_N(0.0, 38.0)), 5), "µm/N")
if "--contact" in sys.argv:
    # the aligned contact reference: one pitch in CalculiX contact, loaded by the torque
    ref: gc.FEContactResult = gc.fe_contact(spec, torque_Nm=400.0, size_mm=1.0)
    print("wind-up beyond first touch", round(ref.windup_from_first_touch_rad * 1e6, 1),
          "µrad; tooth load", round(ref.tooth_load_N, 1), "N of",
          round(ref.equilibrium_tooth_load_N, 1))
    # the reference's wind-up runs from the bore to the sleeve's outside diameter: the
    # bodies' torsion is part of it (the load models' wind-up is at the teeth)
    print("of which the bodies' torsion",
          round(gc.body_windup_rad(spec, 400.0)["body_rad"] * 1e6, 1), "µrad")
    # the same deck a misaligned pose uses, on one tooth at 0°: the hub bore turned to the
    # reference's wind-up carries the reference's tooth load
    one: gc.FESectorResult = gc.fe_contact_sector(
        spec, misalignment_deg=0.0, rotation_deg=0.0, windup_rad=ref.windup_rad, sector=1,
        size_mm=1.0)
    print("turned to that wind-up, one tooth carries", round(one.tangential_force_N[0], 1), "N")
# misaligned: the load model at the pose, then a five-tooth sector on its most loaded tooth
# turned by the model's wind-up plus the bodies' (a coarse mesh; 10-20 min of solver time,
# so only with --misaligned; tests/test_fea_contact.py runs the same check)
if "--misaligned" in sys.argv:
    chk: gc.SectorCheck = gc.sector_check(spec, 1.0, rotation_deg=7.1, torque_Nm=400.0,
                                          sector=5, size_mm=1.0)
    for k, ratio in zip(chk.compared, chk.ratio, strict=True):
        print("tooth", chk.fe.teeth[k], "FE", round(chk.fe.tangential_force_N[k]), "N;",
              chk.model, round(chk.model_tangential_force_N[k]), "N; FE / model",
              round(ratio, 3))
