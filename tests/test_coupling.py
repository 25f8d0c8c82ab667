"""The whole coupling (docs/coupling.md): mesh angles and phases against an independent
vector computation, two meshes against two single engagements, the floating member's
equilibrium and torque balance, capacity and allowable offset, torsion against its parts'
closed forms, the lateral frequency against Euler-Bernoulli, masses against the STEP
solids, the placed assembly read back by gmsh and its overlap where the sweep binds, and a
ROSS train against the three-inertia closed form."""

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.coupling import (
    CouplingLayout,
    ShaftAlignment,
    allowable_offset,
    coupling_geometry,
    whole_capacity,
    whole_coupling_data,
    whole_loads,
)
from gearcoupling.coupling.assembly import coupling_assembly
from gearcoupling.coupling.beam import (
    Segment,
    annulus_EI_Nm2,
    beam_frequencies_Hz,
    pinned_pinned_Hz,
)
from gearcoupling.loading import body_windup_rad, machine_loads
from gearcoupling.rotordynamics import allowable_misalignment, combine, windup_beyond_touch
from gearcoupling.rotordynamics.stiffness import pitch_rotations
from gearcoupling.rotordynamics.wrench import contact_frames, sliding_direction

M2 = "industrial-m2"
MODEL = "compliance"  # the cheap model: what is tested here is the coupling's composition
T = 400.0
SPAN = 300.0
#: an API 671-like spacer coupling around industrial-m2: flanged half-sleeves, a tube
SPACER = dict(sleeve="flanged", flange_outer_diameter_mm=140.0, flange_thickness_mm=12.0,
              spacer_outer_diameter_mm=110.0, spacer_inner_diameter_mm=90.0,
              spacer_length_mm=200.0)
ALIGNMENTS = [ShaftAlignment(0.4, 30.0, 0.2, 100.0),  # offset and angle in other planes
              ShaftAlignment(2.0, 0.0, 0.0, 0.0),  # pure offset
              ShaftAlignment(0.0, 0.0, 1.5, 45.0),  # pure angle
              ShaftAlignment(1.3, -120.0, 0.7, 10.0)]


@pytest.fixture(scope="module")
def m2():
    return gc.load_spec(M2)


@pytest.fixture(scope="module")
def spacer_data(m2):
    """The spacer coupling's data sheet without the matrices (cheap model)."""
    return whole_coupling_data(m2, CouplingLayout(**SPACER), None, T, model=MODEL,
                               matrices=False)


# --------------------------------------------------------------------- angles and phases


def _rot(axis, angle):
    """Rotation matrix by ``angle`` about unit ``axis`` (exp of the skew matrix, scipy)."""
    from scipy.linalg import expm

    k = np.asarray(axis, float) * angle
    return expm(np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]))


def _angle(u, v):
    """Angle between unit vectors by the chord, 2 asin(|u - v| / 2) (degrees)."""
    return math.degrees(2.0 * math.asin(min(1.0, 0.5 * np.linalg.norm(u - v))))


def _independent(al, span):
    """Shaft B's axis, the floating axis and the frame the sleeve carries shaft A's x to,
    from rotation matrices: shaft B leans by the angle toward its azimuth, crosses the
    plane halfway along the span at the offset, and hub B lies half the span beyond."""
    z = np.array([0.0, 0.0, 1.0])
    rz = _rot(z, math.radians(al.angle_azimuth_deg))
    b = rz @ _rot([0.0, 1.0, 0.0], math.radians(al.angle_deg)) @ z
    q = _rot(z, math.radians(al.offset_azimuth_deg)) @ [al.offset_mm, 0.0, 0.0]
    ob = q + [0.0, 0.0, 0.5 * span] + 0.5 * span * b
    s = ob / np.linalg.norm(ob)
    e0 = np.array([1 - s[0] ** 2 / (1 + s[2]), -s[0] * s[1] / (1 + s[2]), -s[0]])
    return b, s, ob, np.column_stack([e0, np.cross(s, e0), s])


@pytest.mark.parametrize("al", ALIGNMENTS)
def test_mesh_angles_and_phases_against_an_independent_vector_computation(m2, al):
    """Each mesh's angle (shaft against the floating axis) within 1e-9°, and its pose: at
    the coupling rotation psi the single-engagement pose of each mesh, turned into space
    by its frame, is the floating member turned by psi about its axis (the sleeve), shaft
    A turned by psi (hub A) and a turn about shaft B's axis (hub B), within 1e-12."""
    g = coupling_geometry(m2, CouplingLayout(span_mm=SPAN), al)
    b, s, ob, ref = _independent(al, SPAN)
    z = np.array([0.0, 0.0, 1.0])
    assert g.misalignment_deg("A") == pytest.approx(_angle(z, s), abs=1e-9)
    assert g.misalignment_deg("B") == pytest.approx(_angle(b, s), abs=1e-9)
    assert g.centre_b_mm == pytest.approx(ob, abs=1e-12 * SPAN)
    for psi in (0.0, 37.0, 211.5):
        sleeve = ref @ _rot(z, math.radians(psi))
        for m, h in (("A", z), ("B", b)):
            F = g.mesh_frame(m)
            i = math.radians(g.misalignment_deg(m))
            psi_m = math.radians(float(g.mesh_rotations_deg(m, psi)))
            assert F @ _rot(z, psi_m) == pytest.approx(sleeve, abs=1e-12)
            hub = F @ _rot([1.0, 0.0, 0.0], i) @ _rot(z, psi_m)
            assert hub[:, 2] == pytest.approx(h, abs=1e-12)
            if m == "A":
                assert hub == pytest.approx(_rot(z, math.radians(psi)), abs=1e-12)


def test_an_angle_alone_splits_evenly_and_an_offset_alone_tilts_both_alike(m2):
    lay = CouplingLayout(span_mm=SPAN)
    g = coupling_geometry(m2, lay, ShaftAlignment(angle_deg=1.5, angle_azimuth_deg=30.0))
    assert g.misalignment_deg("A") == pytest.approx(0.75, abs=1e-12)
    assert g.misalignment_deg("B") == pytest.approx(0.75, abs=1e-12)
    assert g.tilt_axis_deg("B") - g.tilt_axis_deg("A") == pytest.approx(180.0, abs=1e-9)
    g = coupling_geometry(m2, lay, ShaftAlignment(offset_mm=2.0, offset_azimuth_deg=30.0))
    both = math.degrees(math.atan(2.0 / SPAN))
    assert [g.misalignment_deg(m) for m in "AB"] == pytest.approx([both, both], abs=1e-12)
    assert g.tilt_axis_deg("A") == pytest.approx(g.tilt_axis_deg("B"), abs=1e-9)


# --------------------------------------------------------------------------- loads


def test_two_meshes_at_half_the_shaft_angle_are_two_single_engagements(m2):
    """No offset, a shaft angle split evenly: each mesh is the single-engagement analysis at
    half the angle (loads, wind-up, capacity within 1e-9), hub B's on its cw flanks at -T,
    which the mirror symmetry of the teeth makes the ccw analysis's loads again (to the
    sweep's tolerance)."""
    lay = CouplingLayout(span_mm=SPAN)
    al = ShaftAlignment(angle_deg=1.5)
    psi = np.arange(16) * 360.0 / (38 * 16) * 3.0
    w = whole_loads(m2, lay, al, T, angles_deg=psi, model=MODEL)
    g = w.geometry
    for m, torque in (("A", T), ("B", -T)):
        single = gc.load(m2, 0.75, psi - g.tilt_axis_deg(m), torque_Nm=torque, model=MODEL)
        got = w.results[m]
        assert got.tangential_force_N == pytest.approx(single.tangential_force_N, rel=1e-9,
                                                       abs=1e-9 * T)
        assert got.windup_rad == pytest.approx(single.windup_rad, rel=1e-9)
    a, b = w.results["A"], w.results["B"]
    # the cw and ccw flanks are mirror images: their sweeps agree to the clearance search's
    # tolerance (1e-7 mm; the tracking search does not reach both bit for bit), which moves
    # a tooth load by up to about 1e-6 of it
    mirrored = 1e-5
    assert np.max(b.tangential_force_N) == pytest.approx(np.max(a.tangential_force_N),
                                                         rel=mirrored)
    assert w.windup_rad() == pytest.approx(a.windup_rad - b.windup_rad, rel=1e-12)
    assert np.mean(w.windup_rad()) == pytest.approx(2 * np.mean(a.windup_rad), rel=mirrored)
    cap = whole_capacity(m2, lay, al, model=MODEL)
    for m, flank in (("A", "ccw"), ("B", "cw")):
        single = gc.capacity(m2, 0.75, model=MODEL, loaded_flank=flank)
        assert cap.meshes[m].capacity_Nm == pytest.approx(single.capacity_Nm, rel=1e-9)
    ccw = gc.capacity(m2, 0.75, model=MODEL).capacity_Nm
    assert cap.capacity_Nm == pytest.approx(ccw, rel=mirrored)


def _space_wrench(res, H, mu):
    """Force and moment (about the mesh centre) of every tooth on the hub, in space: each
    tooth's contact point and normal from the exact flank, friction against its sliding,
    turned by the hub frame ``H`` (N, N·m; (N, M, 3))."""
    p, n = contact_frames(res.spec, res.loaded_flank, res.theta_deg, res.contact_z_mm,
                          res.contact_r_mm)
    t = sliding_direction(math.radians(res.misalignment_deg), p, n)
    f = -res.normal_force_N[..., None] * (n + mu * t)
    return f @ H.T, 1e-3 * np.cross(p, f) @ H.T


@pytest.mark.parametrize("al", ALIGNMENTS[:2])
def test_the_floating_member_is_in_equilibrium_over_a_turn(m2, al):
    """Every tooth's force of both meshes taken to space tooth by tooth, with the shear,
    thrust and torque the floating member takes from the hubs: the residual force and
    moment (about a point off the axis) are below 1e-6 of the largest tooth force and of
    the largest mesh moment, at every rotation of a turn."""
    w = whole_loads(m2, CouplingLayout(**SPACER), al, T, model=MODEL)
    g = w.geometry
    mu = m2.load.friction
    origin = np.array([30.0, -20.0, 100.0])  # any point: the sum of moments is zero about all
    F = np.zeros((w.angles_deg.size, 3))
    M = np.zeros_like(F)
    for m in ("A", "B"):
        f, mom = _space_wrench(w.results[m], g.hub_frame(m), mu)
        arm = 1e-3 * (g.centre_mm(m) - origin)
        F -= f.sum(axis=0)
        M -= mom.sum(axis=0) + np.cross(arm, f.sum(axis=0))
        F += w.shear_N[m] + w.thrust_share_N[:, None] * g.sleeve_axis
        M += np.cross(arm, w.shear_N[m] + w.thrust_share_N[:, None] * g.sleeve_axis)
    M += w.torque_share_Nm[:, None] * g.sleeve_axis
    largest_f = max(np.max(r.normal_force_N) for r in w.results.values())
    largest_m = max(np.max(np.linalg.norm(v, axis=1)) for v in w.tooth_moment_Nm.values())
    assert np.max(np.linalg.norm(F, axis=1)) < 1e-6 * largest_f
    assert np.max(np.linalg.norm(M, axis=1)) < 1e-6 * largest_m
    eq = w.summary()["equilibrium"]
    assert eq["relative_force"] < 1e-6 and eq["relative_moment"] < 1e-6


@pytest.mark.parametrize("al", ALIGNMENTS[::2])
def test_the_torque_lost_between_the_shafts_is_the_teeths_friction_work(m2, al):
    """What the floating member's torque balance takes off shaft B's torque is, over a
    turn, the work of the teeth's Coulomb friction per radian (sum of mu W |v|, v the
    sliding speed per unit speed): the energy balance, within 0.1 %."""
    w = whole_loads(m2, CouplingLayout(span_mm=SPAN), al, T, model=MODEL)
    work = sum(np.mean(m2.load.friction * np.sum(
        r.normal_force_N * machine_loads(r)["sliding_mm_per_rad"], axis=0)) * 1e-3
        for r in w.results.values())
    loss = w.summary()["torque_loss_Nm"]
    assert loss > 0
    assert loss == pytest.approx(work, rel=1e-3)


def test_capacity_is_the_smaller_mesh_and_the_allowable_offset_is_where_a_mesh_reaches_its_limit(
        m2):
    lay = CouplingLayout(span_mm=SPAN)
    cap = whole_capacity(m2, lay, ALIGNMENTS[0], model=MODEL)
    assert cap.capacity_Nm == min(c.capacity_Nm for c in cap.meshes.values())
    assert cap.criterion == cap.meshes[cap.governing_mesh].governing
    limit = allowable_misalignment(m2, T, model=MODEL)[0]
    pure = allowable_offset(m2, lay, None, T, model=MODEL)
    assert pure.offset_mm == pytest.approx(SPAN * math.tan(math.radians(limit)), abs=1e-6)
    tilted = allowable_offset(m2, lay, ShaftAlignment(0.0, 0.0, 0.3, 90.0), T, model=MODEL)
    gov = tilted.governing_mesh
    assert tilted.mesh_angles_deg[gov] == pytest.approx(limit, abs=1e-9)
    g = coupling_geometry(m2, lay, ShaftAlignment(tilted.offset_mm, 0.0, 0.3, 90.0))
    assert max(g.misalignment_deg(m) for m in "AB") == pytest.approx(limit, abs=1e-6)


# --------------------------------------------------------------------- mass and torsion


def test_torsion_is_its_parts_in_series(m2, spacer_data):
    """The whole coupling's compliance is the sum of its parts: each mesh's wind-up beyond
    first touch from the load model, the hub bodies and sleeve rings (annulus torsion),
    the flanges (annular disks, by hand) and the spacer (L / (G J), J = pi (D^4 - d^4) /
    32), within 1e-9."""
    g = spacer_data.geometry
    G = m2.material.sleeve.shear_modulus_MPa
    parts = 0.0
    for m, torque in (("A", T), ("B", -T)):
        res = gc.load(m2, g.misalignment_deg(m), pitch_rotations(m2, 8), torque_Nm=torque,
                      model=MODEL)
        parts += abs(windup_beyond_touch(res)) / T + body_windup_rad(m2, T)["body_rad"] / T
    D, d, L = 110.0, 90.0, 200.0
    J = math.pi * (D**4 - d**4) / 32.0
    spacer = L / (G * J) * 1e3  # rad per N·m
    assert spacer_data.torsion.secant_rad_per_Nm["spacer"] == pytest.approx(spacer, rel=1e-9)
    a, b = 0.5 * m2.sleeve.outer_diameter, 0.25 * (D + d)
    flange = 1e3 / (4 * math.pi * G * 12.0) * abs(1 / a**2 - 1 / b**2) if a != b else 0.0
    whole = parts + spacer + 2 * flange
    assert 1.0 / spacer_data.torsion.secant_Nm_per_rad == pytest.approx(whole, rel=1e-9)
    assert spacer_data.torsion.tangent_Nm_per_rad > spacer_data.torsion.secant_Nm_per_rad


def test_euler_bernoulli_beam_against_the_pinned_pinned_formula():
    """The finite-element beam of a uniform tube pinned at its ends against ``pi / (2 L²)
    sqrt(E I / m)`` within 1 % (it converges to 1e-7); an end mass at a pin changes
    nothing, an overhang and a mass between the pins lower it."""
    EI = annulus_EI_Nm2(45.0, 55.0, 206_000.0)
    m = 7850.0 * math.pi * (0.055**2 - 0.045**2)
    formula = pinned_pinned_Hz(0.3, EI, m)
    got = beam_frequencies_Hz([Segment(0.0, 0.3, EI, m)], [0.0, 0.3])[0]
    assert got == pytest.approx(formula, rel=0.01)
    assert got == pytest.approx(formula, rel=1e-6)
    pinned_mass = beam_frequencies_Hz([Segment(0.0, 0.3, EI, m)], [0.0, 0.3],
                                      point_masses=[(0.0, 50.0)])[0]
    assert pinned_mass == pytest.approx(got, rel=1e-9)
    loaded = beam_frequencies_Hz([Segment(0.0, 0.15, EI, m), Segment(0.15, 0.3, EI, m)],
                                 [0.0, 0.3], point_masses=[(0.15, 1.0)])[0]
    assert loaded < got


def test_floating_member_frequency_is_near_its_spacer_alone(spacer_data):
    """The floating member pinned at the meshes (rings and flanges at the ends of the
    spacer) against the spacer alone over the span: the end parts sit near the pins, so
    the two agree within a few percent."""
    assert spacer_data.lateral_frequency_Hz == pytest.approx(spacer_data.spacer_formula_Hz,
                                                             rel=0.05)


def test_the_halves_and_the_floating_member_make_the_whole(spacer_data):
    d = spacer_data
    for parts in ([d.halves["A"], d.halves["B"]],
                  [d.parts["hub A"], d.parts["hub B"], d.floating]):
        both = combine(parts)
        assert both.mass_kg == pytest.approx(d.whole.mass_kg, rel=1e-12)
        assert both.centre_of_gravity_mm == pytest.approx(d.whole.centre_of_gravity_mm,
                                                          abs=1e-9)
        assert both.inertia_kg_m2 == pytest.approx(d.whole.inertia_kg_m2, rel=1e-9)
    assert d.halves["A"].mass_kg == pytest.approx(d.halves["B"].mass_kg, rel=1e-12)
    half = d.parts["hub A"].mass_kg + 0.5 * d.floating.mass_kg
    assert d.halves["A"].mass_kg == pytest.approx(half, rel=1e-12)  # AGMA 9009
    assert d.cg_from_shaft_end_mm("A") == pytest.approx(d.cg_from_shaft_end_mm("B"),
                                                        rel=1e-9)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize("make, field", [
    (lambda s: coupling_geometry(s, CouplingLayout(span_mm=30.0), ShaftAlignment()),
     "span_mm"),
    (lambda s: coupling_geometry(s, CouplingLayout(span_mm=SPAN), ShaftAlignment(40.0)),
     "offset_mm"),
    (lambda s: coupling_geometry(s, CouplingLayout(span_mm=SPAN),
                                 ShaftAlignment(angle_deg=12.0, offset_mm=10.0)),
     "offset_mm"),
    (lambda s: CouplingLayout(**{**SPACER, "spacer_outer_diameter_mm": 150.0}),
     "spacer_outer_diameter_mm"),
    (lambda s: coupling_geometry(s, CouplingLayout(**{**SPACER,
                                                      "spacer_outer_diameter_mm": 80.0,
                                                      "spacer_inner_diameter_mm": 60.0}),
                                 ShaftAlignment()), "spacer_outer_diameter_mm"),
    (lambda s: coupling_geometry(s, CouplingLayout(**{**SPACER, "span_mm": 250.0}),
                                 ShaftAlignment()), "spacer_length_mm"),
    (lambda s: CouplingLayout(span_mm=SPAN, spacer_outer_diameter_mm=110.0,
                              spacer_inner_diameter_mm=90.0), "sleeve"),
    (lambda s: CouplingLayout(sleeve="flanged", span_mm=SPAN), "flange_outer_diameter_mm"),
    (lambda s: coupling_geometry(s, CouplingLayout(**{**SPACER,
                                                      "flange_outer_diameter_mm": 90.0,
                                                      "spacer_outer_diameter_mm": 85.0,
                                                      "spacer_inner_diameter_mm": 60.0}),
                                 ShaftAlignment()), "flange_outer_diameter_mm"),
    (lambda s: coupling_geometry(s, CouplingLayout(engagements=1), ShaftAlignment(1.0)),
     "offset_mm"),
    (lambda s: CouplingLayout(engagements=3, span_mm=SPAN), "engagements"),
    (lambda s: CouplingLayout(span_mm=float("nan")), "span_mm"),
    (lambda s: ShaftAlignment(offset_mm=-1.0), "offset_mm"),
    (lambda s: ShaftAlignment(angle_deg="1"), "angle_deg"),
    (lambda s: CouplingLayout(sleeve="welded", span_mm=SPAN), "sleeve"),
])
def test_bad_input_is_refused_in_one_line_naming_the_field(m2, make, field):
    with pytest.raises(gc.ArgumentError) as err:
        make(m2)
    assert err.value.field == field
    assert "\n" not in str(err.value)


# ------------------------------------------------------------------------------ assembly


@pytest.fixture(scope="module")
def binding(m2):
    """The spacer coupling at its design alignment (0.75° a mesh) and at 4° a mesh, beyond
    industrial-m2's binding angle (2.75°)."""
    lay = CouplingLayout(**SPACER)
    span = coupling_geometry(m2, lay, ShaftAlignment()).span_mm
    return lay, {deg: ShaftAlignment(span * math.tan(math.radians(deg)), 20.0)
                 for deg in (0.75, 4.0)}


@pytest.mark.slow
def test_placed_hub_and_sleeve_overlap_where_the_sweep_binds(m2, binding):
    """The placed hub and sleeve ring of each mesh (manifold3d intersection of the closed
    meshes at module / 100): no overlap where the sweep's smallest normal clearance at that
    mesh's angle and rotation is positive by more than the two meshes' tolerances, an
    overlap where it is negative by as much."""
    lay, alignments = binding
    tol = m2.tooth.module / 100
    for deg, al in alignments.items():
        for psi in (0.0, 4.0):
            asm = coupling_assembly(m2, lay, al, psi)
            for m in ("A", "B"):
                g = asm.geometry
                sw = gc.sweep(m2, g.misalignment_deg(m), [float(g.mesh_rotations_deg(m, psi))])
                clearance = float(np.min(sw.normal_clearance_mm))
                overlap = asm.overlap_mm3(m, tolerance_mm=tol)
                assert abs(clearance) > 2 * tol
                assert (overlap > 0) == (clearance < 0), (deg, psi, m, clearance, overlap)
        assert (deg > 2.75) == (clearance < 0)


@pytest.mark.slow
@pytest.mark.needs_fea
def test_assembly_step_and_glb_hold_every_part_named_where_it_was_placed(m2, tmp_path):
    """The STEP assembly read by OpenCASCADE through gmsh: one volume per part, named, its
    volume the solid's and its centre of gravity and axis where the placement put them;
    the GLB's nodes carry the same names and transforms."""
    import gmsh
    import trimesh

    asm = coupling_assembly(m2, CouplingLayout(**SPACER), ALIGNMENTS[0], 10.0)
    own = asm.own_meshes()
    step = asm.write_step(tmp_path / "coupling.step")
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.importShapes(str(step))
        gmsh.model.occ.synchronize()
        found = {}
        for _, tag in gmsh.model.getEntities(3):
            name = gmsh.model.getEntityName(3, tag).split("/")[-1]
            found[name] = (gmsh.model.occ.getMass(3, tag),
                           np.array(gmsh.model.occ.getCenterOfMass(3, tag)),
                           np.reshape(gmsh.model.occ.getMatrixOfInertia(3, tag), (3, 3)))
    finally:
        gmsh.finalize()
    assert sorted(found) == sorted(p.name for p in asm.parts)
    for p in asm.parts:
        volume, cg, inertia = found[p.name]
        assert volume == pytest.approx(own[p.name].volume, rel=5e-3)
        assert cg == pytest.approx(p.place(own[p.name].center_mass), abs=1e-3)
        w, v = np.linalg.eigh(inertia)  # the polar moment is the one unlike the other two
        polar = v[:, 0 if abs(w[1] - w[2]) < abs(w[0] - w[1]) else 2]
        assert abs(polar @ p.rotation[:, 2]) == pytest.approx(1.0, abs=1e-6)
    scene = trimesh.load(asm.write_glb(tmp_path / "coupling.glb"))
    for p in asm.parts:
        placed, _ = scene.graph[p.name]
        assert placed == pytest.approx(p.placement, abs=1e-9)


@pytest.mark.slow
@pytest.mark.needs_fea
def test_mass_properties_of_each_half_against_the_step_solids(m2, spacer_data):
    """Each half (hub, sleeve ring, flange and half the spacer, cut at the centre plane) as
    OpenCASCADE integrates its solids: mass, centre of gravity and inertias within 0.5 %."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.BRepGProp import BRepGProp
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Pnt, gp_Trsf
    from OCP.GProp import GProp_GProps

    g = spacer_data.geometry
    asm = coupling_assembly(m2, CouplingLayout(**SPACER), ShaftAlignment(), 0.0)
    solids = asm.solids()
    rho = {"hub": m2.material.hub.density_kg_per_m3,
           "sleeve": m2.material.sleeve.density_kg_per_m3,
           "annulus": m2.material.sleeve.density_kg_per_m3}
    half_z, big = 0.5 * g.span_mm, 1e4
    boxes = {"A": BRepPrimAPI_MakeBox(gp_Pnt(-big, -big, -big), gp_Pnt(big, big, half_z)),
             "B": BRepPrimAPI_MakeBox(gp_Pnt(-big, -big, half_z), gp_Pnt(big, big, big))}
    for side in ("A", "B"):
        total = GProp_GProps()
        for p in asm.parts:
            trsf = gp_Trsf()
            trsf.SetValues(*p.placement[:3].ravel().tolist())
            placed = BRepBuilderAPI_Transform(solids[p.name], trsf, True).Shape()
            piece = BRepAlgoAPI_Common(placed, boxes[side].Shape()).Shape()
            props = GProp_GProps()
            BRepGProp.VolumeProperties_s(piece, props, 1e-6)
            if props.Mass() > 0:
                total.Add(props, rho[p.kind] * 1e-9)
        c, tensor = total.CentreOfMass(), total.MatrixOfInertia()
        inertia = np.array([[tensor.Value(i, j) for j in (1, 2, 3)] for i in (1, 2, 3)]) * 1e-6
        got = spacer_data.halves[side]
        assert got.mass_kg == pytest.approx(total.Mass(), rel=5e-3)
        assert got.centre_of_gravity_mm == pytest.approx([c.X(), c.Y(), c.Z()],
                                                         abs=5e-3 * g.span_mm)
        assert got.polar_inertia_kg_m2 == pytest.approx(inertia[2, 2], rel=5e-3)
        assert got.transverse_inertia_kg_m2 == pytest.approx(
            0.5 * (inertia[0, 0] + inertia[1, 1]), rel=5e-3)


# ---------------------------------------------------------------------------------- ROSS


@pytest.mark.slow
@pytest.mark.needs_ross
def test_ross_train_first_torsional_frequency_against_three_inertias(m2):
    """Motor rotor, the whole coupling's ROSS pieces and a driven rotor: ROSS's first
    torsional frequency against the three-inertia closed form (motor with hub A, the
    floating member, driven rotor with hub B; springs: each shaft, its side's coupling
    element and half the spacer in series) within 1 %."""
    from gearcoupling.rotordynamics import import_ross

    data = whole_coupling_data(m2, CouplingLayout(**SPACER), None, T, model=MODEL,
                               rotations=2)
    rs = import_ross()
    steel = rs.materials.steel
    L, D, J1, J3 = 0.1, 0.05, 0.2, 0.3
    pieces = data.to_ross(n=2)
    last = pieces.last_node
    shafts = ([rs.ShaftElement(L, 0.0, D, material=steel, n=i) for i in (0, 1)]
              + pieces.elements
              + [rs.ShaftElement(L, 0.0, D, material=steel, n=last + i) for i in (0, 1)])
    disks = [rs.DiskElement(n=0, m=20.0, Id=0.1, Ip=J1), *pieces.disks,
             rs.DiskElement(n=last + 2, m=20.0, Id=0.1, Ip=J3)]
    bearings = [rs.BearingElement(n=n, kxx=1e8, cxx=0) for n in (0, 1, last + 1, last + 2)]
    modal = rs.Rotor(shafts, disks, bearings).run_modal(speed=0, num_modes=40, sparse=False)
    ross = min(w for w, s in zip(modal.wn, modal.shapes, strict=False)
               if s.mode_type == "Torsional" and w > 1.0)
    t = data.torsion
    k_shaft = steel.G_s * math.pi * D**4 / 32 / (2 * L)
    half_spacer = 0.5 * t.tangent_rad_per_Nm["spacer"]
    k1 = 1 / (1 / k_shaft + 1 / t.side_Nm_per_rad("A") + half_spacer)
    k2 = 1 / (half_spacer + 1 / t.side_Nm_per_rad("B") + 1 / k_shaft)
    j_shaft = steel.rho * math.pi * D**4 / 32 * 2 * L
    J = [J1 + 0.5 * j_shaft + data.parts["hub A"].polar_inertia_kg_m2,
         data.floating.polar_inertia_kg_m2,
         J3 + 0.5 * j_shaft + data.parts["hub B"].polar_inertia_kg_m2]
    # three inertias on two springs, free: w^2 from J1 J2 J3 w^4 - b w^2 + c = 0
    b = k1 * J[2] * (J[0] + J[1]) + k2 * J[0] * (J[1] + J[2])
    c = k1 * k2 * sum(J)
    a = J[0] * J[1] * J[2]
    closed = math.sqrt((b - math.sqrt(b * b - 4 * a * c)) / (2 * a))
    assert ross == pytest.approx(closed, rel=0.01)
