"""Coupling data for rotordynamics (docs/rotordynamics.md): mass properties against
independent integrations, the pose against a direct geometric computation, the stiffness
matrix against closed forms and its symmetry, torsion against the CalculiX reference, the
data sheet files and command, and a real ROSS rotor."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.geometry import form_radius, hub_model, inv, tip_radius
from gearcoupling.io.lock import RECORD_NAME
from gearcoupling.loading import (
    PHASES,
    machine_loads,
    mesh_stiffness_N_per_mm,
    springs_name,
    turn_phases,
)
from gearcoupling.rotordynamics import (
    FILES,
    WINDUP_ERROR_PCT,
    coupling_data,
    hub_wrench,
    mass_properties,
    mesh_mass_properties,
    stiffness_matrix,
    tilt_pose,
    translation_gap_offsets,
)
from gearcoupling.rotordynamics.mass import combine
from gearcoupling.rotordynamics.stiffness import pitch_rotations
from gearcoupling.rotordynamics.torsion import mesh_windup_from_touch

STEEL = 7850.0
GOLDEN = Path(__file__).parent / "golden" / "fe_contact_reference.json"


# --------------------------------------------------------------------------- mass


def _annulus(inner, outer, length, z=0.0):
    import trimesh

    mesh = trimesh.creation.annulus(inner, outer, length, sections=4000)
    mesh.apply_translation([0.0, 0.0, z])
    return mesh


def _hollow_cylinder(inner, outer, length):
    """Closed form: mass, polar and transverse inertia about the centre (kg, kg·m²)."""
    m = STEEL * math.pi * (outer**2 - inner**2) * length * 1e-9
    ip = 0.5 * m * (inner**2 + outer**2) * 1e-6
    it = m * (3 * (inner**2 + outer**2) + length**2) / 12 * 1e-6
    return m, ip, it


def test_mass_properties_of_a_hollow_cylinder_against_the_closed_form():
    m, ip, it = _hollow_cylinder(44.45, 76.2, 25.4)
    got = mesh_mass_properties(_annulus(44.45, 76.2, 25.4), STEEL, "body")
    assert got.mass_kg == pytest.approx(m, rel=5e-3)
    assert got.polar_inertia_kg_m2 == pytest.approx(ip, rel=5e-3)
    assert got.transverse_inertia_kg_m2 == pytest.approx(it, rel=5e-3)


def test_combined_bodies_move_their_inertia_to_the_common_centre():
    """Two equal hollow cylinders 40 mm either side of O: the transverse inertia about O is
    twice each one's plus m d² each (parallel axes), the polar twice each one's."""
    a = mesh_mass_properties(_annulus(20.0, 50.0, 30.0, z=-40.0), STEEL, "a")
    b = mesh_mass_properties(_annulus(20.0, 50.0, 30.0, z=40.0), STEEL, "b")
    both = combine([a, b])
    m, ip, it = _hollow_cylinder(20.0, 50.0, 30.0)
    assert both.centre_of_gravity_mm == pytest.approx([0, 0, 0], abs=1e-9)
    assert both.polar_inertia_kg_m2 == pytest.approx(2 * ip, rel=5e-3)
    assert both.transverse_inertia_kg_m2 == pytest.approx(2 * (it + m * 0.04**2), rel=5e-3)


def _polygon_moments(poly):
    """Area and polar second moment of a counter-clockwise polygon (shoelace sums)."""
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * np.sum(cross)
    ixx = np.sum(cross * (y**2 + y * yn + yn**2)) / 12
    iyy = np.sum(cross * (x**2 + x * xn + xn**2)) / 12
    return area, ixx + iyy


def test_sleeve_against_its_extruded_transverse_section(renzo):
    """The sleeve is its section extruded over the face width: area and polar moment of
    the section polygon (outer circle less the toothed bore), integrated by hand."""
    s = renzo.sleeve
    bore = gc.transverse_section(renzo, "sleeve", 0.0, 1e-4)
    a_bore, j_bore = _polygon_moments(bore)
    ro = 0.5 * s.outer_diameter
    area = math.pi * ro**2 - a_bore
    polar = 0.5 * math.pi * ro**4 - j_bore
    got = mass_properties(renzo)["sleeve"]
    m = STEEL * area * s.face_width * 1e-9
    assert got.mass_kg == pytest.approx(m, rel=5e-3)
    assert got.polar_inertia_kg_m2 == pytest.approx(STEEL * polar * s.face_width * 1e-15,
                                                    rel=5e-3)
    # transverse: half the polar moment of the section plus the length term
    it = STEEL * s.face_width * 1e-15 * 0.5 * polar + m * s.face_width**2 / 12 * 1e-6
    assert got.transverse_inertia_kg_m2 == pytest.approx(it, rel=5e-3)


def _step_mass_properties(shape):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    c, inertia = props.CentreOfMass(), props.MatrixOfInertia()
    return (props.Mass(), np.array([c.X(), c.Y(), c.Z()]),
            np.array([[inertia.Value(i, j) for j in (1, 2, 3)] for i in (1, 2, 3)]))


@pytest.mark.parametrize("part", ["hub", "sleeve"])
def test_mesh_mass_properties_against_the_step_solid(part):
    """The part mesh against OpenCASCADE's integration over the STEP solid (B-spline
    faces, not triangles): volume, centre of gravity and inertias within 0.5 %."""
    pytest.importorskip("OCP", reason="pip install 'gearcoupling[step]'")
    from gearcoupling.parts import default_tolerance, part_solid

    spec = gc.load_spec("industrial-m2")
    volume, cg, inertia = _step_mass_properties(
        part_solid(spec, part, default_tolerance(spec)))
    got = mass_properties(spec)[part]
    assert got.volume_mm3 == pytest.approx(volume, rel=5e-3)
    assert got.centre_of_gravity_mm == pytest.approx(cg, abs=5e-3 * spec.hub.face_width)
    rho = STEEL * 1e-15
    assert got.polar_inertia_kg_m2 == pytest.approx(rho * inertia[2, 2], rel=5e-3)
    assert got.transverse_inertia_kg_m2 == pytest.approx(
        rho * 0.5 * (inertia[0, 0] + inertia[1, 1]), rel=5e-3)


def test_density_of_another_material_is_required(renzo):
    spec = gc.load_spec("renzo-1967", **{"material.youngs_modulus_psi": 10.0e6})
    with pytest.raises(gc.SpecError, match=r"material\.hub\.density_kg_per_m3"):
        mass_properties(spec)
    given = gc.load_spec("renzo-1967", **{"material.youngs_modulus_psi": 10.0e6,
                                          "material.density_lb_per_in3": 0.0975})
    steel = mass_properties(renzo)["hub"].mass_kg
    assert mass_properties(given)["hub"].mass_kg == pytest.approx(
        steel * 0.0975 * 27679.9047 / STEEL, rel=1e-6)


# --------------------------------------------------------------------------- the pose


def _normal_gaps(spec, rotvec, psi_deg, teeth, around=None, shifts=((0.0, 0.0, 0.0),)):
    """Smallest normal gap (mm) of each hub tooth's ccw flank to the sleeve, directly,
    ``(len(shifts), len(teeth))``: hub flank points posed by ``exp([rotvec]) Rz(psi)`` and
    moved by each shift (mm), their normal distance to the straight involute sleeve flank
    ``r_b (s / 2R + inv phi - beta - inv(arccos(r_b / rho)))``, on a (z, r) grid over the
    face, finer within ``around`` ``(z, half width)`` mm per tooth."""
    from scipy.spatial.transform import Rotation

    m = hub_model(spec)
    N, R = spec.tooth.teeth, spec.tooth.pitch_radius
    phi = spec.tooth.pressure_angle
    rb = R * math.cos(phi)
    r_form = 0.5 * spec.sleeve.minor_diameter + spec.sleeve.tip_chamfer
    pose = Rotation.from_rotvec(rotvec).as_matrix()
    psi = math.radians(psi_deg)

    def rz(a):
        return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0],
                         [0, 0, 1]])

    out = np.zeros((len(shifts), len(teeth)))
    for i, k in enumerate(teeth):
        z = np.linspace(-m.half_face, m.half_face, 201)
        if around is not None:
            zc, half = around[i]
            z = np.union1d(z, np.linspace(max(zc - half, -m.half_face),
                                          min(zc + half, m.half_face), 121))
        zz, tt = np.meshgrid(z, np.linspace(0.0, 1.0, 61), indexing="ij")
        lo, hi = form_radius(m, zz), tip_radius(m, zz)
        p0, _ = gc.hub_flank(spec, "ccw", zz, lo + tt * (hi - lo))
        p0 = p0 @ rz(2 * math.pi * k / N).T @ (pose @ rz(psi)).T
        for j, d in enumerate(shifts):
            p = (p0 + np.asarray(d)) @ rz(-psi).T  # the sleeve's body frame
            rho = np.hypot(p[..., 0], p[..., 1])
            beta = (np.arctan2(p[..., 1], p[..., 0]) - 2 * math.pi * k / N + math.pi) \
                % (2 * math.pi) - math.pi
            gap = rb * (spec.sleeve.space_width / (2 * R) + inv(phi) - beta
                        - inv(np.arccos(np.clip(rb / rho, -1, 1))))
            # the sleeve flank spans r_form (the tip chamfer's edge) to the major radius;
            # where a grid column crosses r_form, the gap there by linear interpolation
            ok = (rho >= r_form) & (rho <= 0.5 * spec.sleeve.major_diameter)
            a, b = rho[:, :-1] - r_form, rho[:, 1:] - r_form
            cross = (a < 0) & (b >= 0)
            w = np.where(cross, -a / np.where(cross, b - a, 1.0), 0.0)
            edge = np.where(cross, gap[:, :-1] + w * (gap[:, 1:] - gap[:, :-1]), np.inf)
            out[j, i] = min(np.min(np.where(ok, gap, np.inf)), np.min(edge))
    return out


TEETH = [0, 2, 24, 12, 37]  # pivot, near pivot, opposite pivot, swing, swing


def test_direct_normal_gaps_reproduce_the_sweep(renzo):
    """The direct computation the pose tests rely on agrees with the sweep."""
    sw = gc.sweep(renzo, 1.0, [3.0])
    direct = _normal_gaps(renzo, [math.radians(1.0), 0, 0], 3.0, TEETH)[0]
    assert direct == pytest.approx(sw.normal_clearance_mm[1][TEETH, 0], abs=3e-6)


def test_translation_moves_each_gap_as_the_first_order_formula_says(renzo):
    """A hub translation ``d`` changes each tooth's gap angle by -(d . n)/|(a x p) . n|:
    against the direct normal gaps of every fifth tooth (central difference of +-1 µm,
    refined round the first touch), turned into gap angles by the sweep's own ratio of gap
    angle to normal gap. First order at the first-touch point: on a near-conformal profile
    the smallest gap moves along it (a kink: the two sides differ by 6 % on renzo-1967's
    tooth 27), so single teeth within 1 % of the largest change, the median within 0.5 %;
    an axial shift changes no gap at all (the sleeve's teeth are straight)."""
    teeth = list(range(0, 50, 5))
    sw = gc.sweep(renzo, 1.0, [0.0])
    ratio = sw.gap_angle_rad[1][teeth, 0] / sw.normal_clearance_mm[1][teeth, 0]
    around = [(z, 0.2) for z in sw.contact_z_mm[1][teeth, 0]]
    rot = [math.radians(1.0), 0.0, 0.0]
    moves = np.array([[1e-3, 0, 0], [0, 1e-3, 0], [6e-4, -8e-4, 5e-4], [0, 0, 1e-3]])
    gaps = _normal_gaps(renzo, rot, 0.0, teeth, around, [*moves, *-moves])
    for d, plus, minus in zip(moves, gaps[:4], gaps[4:], strict=True):
        direct = 0.5 * (plus - minus) * ratio
        formula = translation_gap_offsets(renzo, sw, "ccw", 0, d)[teeth]
        if d[0] == d[1] == 0:
            assert np.abs(direct).max() < 1e-12 and np.abs(formula).max() < 1e-12
            continue
        scale = np.abs(direct).max()
        assert np.abs(formula - direct).max() < 0.01 * scale, d
        assert np.median(np.abs(formula / direct - 1)) < 0.005, d


def test_a_tilt_about_y_is_the_misalignment_turned(renzo):
    """The hub at tilt vector (i, b): the sweep at sqrt(i² + b²) and rotation psi - phi
    (phi = atan(b / i)) gives each tooth's gap, against the direct pose."""
    for b_deg in (0.3, -0.5):
        a, b = math.radians(1.0), math.radians(b_deg)
        A, phi = tilt_pose(a, 0.0, b)
        sw = gc.sweep(renzo, math.degrees(A), [2.0 - math.degrees(phi)])
        around = [(z, 0.2) for z in sw.contact_z_mm[1][TEETH, 0]]
        direct = _normal_gaps(renzo, [a, b, 0.0], 2.0, TEETH, around)[0]
        assert direct == pytest.approx(sw.normal_clearance_mm[1][TEETH, 0], abs=5e-7)


def test_hub_wrench_is_the_machine_loads_as_vectors(renzo):
    res = gc.load(renzo, 1.0, np.arange(0, 7.2, 0.9))
    F, M = hub_wrench(res)
    ml = machine_loads(res)
    assert np.hypot(F[:, 0], F[:, 1]) == pytest.approx(ml["radial_force_N"], abs=1e-6)
    assert F[:, 2] == pytest.approx(ml["axial_force_N"], abs=1e-6)
    assert np.hypot(M[:, 0], M[:, 1]) == pytest.approx(ml["tilting_moment_Nm"], rel=1e-9)


# --------------------------------------------------------------------------- the matrix


def test_linear_model_aligned_against_equal_tooth_springs(renzo):
    """Aligned, every tooth pair is a spring C (tangential, at R) along its flank normal:
    radial stiffness N C / (2 cos² phi) in every direction, torsion N C R² (the teeth);
    the bodies add their torsion in series."""
    K = stiffness_matrix(renzo, 0.0, model="linear")
    C, N = mesh_stiffness_N_per_mm(renzo), renzo.tooth.teeth
    phi, R = renzo.tooth.pressure_angle, renzo.tooth.pitch_radius
    radial = N * C / (2 * math.cos(phi) ** 2) * 1e3  # N/m
    assert K.mesh_matrix[0, 0] == pytest.approx(radial, rel=1e-6)
    assert K.mesh_matrix[1, 1] == pytest.approx(radial, rel=1e-6)
    assert abs(K.mesh_matrix[0, 1]) < 1e-9 * radial
    torsion = N * C * R**2 * 1e-3
    assert K.mesh_matrix[5, 5] == pytest.approx(torsion, rel=1e-6)
    kb = K.body_torsional_Nm_per_rad
    assert K.matrix[5, 5] == pytest.approx(torsion * kb / (torsion + kb), rel=1e-9)


def _asymmetry(K):
    """Largest |K_ij - K_ji| / sqrt(|K_ii K_jj|) over the pairs with a stiff diagonal."""
    d = np.abs(np.diag(K))
    worst = 0.0
    for i in range(6):
        for j in range(i):
            scale = math.sqrt(d[i] * d[j])
            if scale > 1e-6 * math.sqrt(d.max() * np.sort(d)[1]):
                worst = max(worst, abs(K[i, j] - K[j, i]) / scale)
    return worst


@pytest.fixture(scope="module")
def frictionless(renzo):
    return {m: stiffness_matrix(renzo, 1.0, model=m, friction=0.0)
            for m in ("linear", "compliance")}


def test_matrix_is_symmetric_without_friction(frictionless):
    """Without friction the forces derive from the teeth's elastic energy: the matrix is
    symmetric. The linear model's springs are constant: within 1.5 % (the differences and
    the sweep's first-order gap angles); the compliance model's spring moves with the load
    point, which the energy does not see: within 6 %."""
    assert _asymmetry(frictionless["linear"].mesh_matrix) < 0.015
    assert _asymmetry(frictionless["compliance"].mesh_matrix) < 0.06


def test_tilting_stiffness_about_y_is_the_moment_over_the_angle(frictionless):
    """At a misalignment the moment about the tilt axis turns with it: K_yy = -M_x / i."""
    for K in frictionless.values():
        assert K.matrix[4, 4] == pytest.approx(-K.operating_forces[3] / math.radians(1.0),
                                               rel=1e-9)
        assert K.operating_forces[3] < 0 < K.matrix[3, 3]


def _friction_moment(spec, deg, model=None):
    """mu sum W r |cos theta|: the teeth slide axially at a speed proportional to
    r cos(theta), so each tooth's friction pushes it along the axis at radius r."""
    N = spec.tooth.teeth
    res = gc.load(spec, deg, np.arange(8) * 360.0 / N / 8, model=model)
    cos = np.abs(np.cos(np.radians(res.theta_deg)))
    return spec.load.friction * np.mean(np.sum(res.normal_force_N * res.contact_r_mm * cos,
                                               axis=0)) * 1e-3


@pytest.mark.parametrize("name, deg", [("renzo-1967", 1.0), ("industrial-m2", 0.75)])
def test_friction_adds_the_antisymmetric_part_of_its_moment(name, deg):
    """With the torque held, friction adds to the tilt block k_xy = M_f / i and
    k_yx = -dM_f/di, so an antisymmetric part (M_f / i + dM_f/di) / 2, where M_f is the
    friction moment from the tooth loads alone (:func:`_friction_moment`)."""
    spec = gc.load_spec(name)
    with_f = stiffness_matrix(spec, deg, model="compliance").at_constant_torque()
    without = stiffness_matrix(spec, deg, model="compliance", friction=0.0).at_constant_torque()
    anti = 0.5 * ((with_f[3, 4] - with_f[4, 3]) - (without[3, 4] - without[4, 3]))
    a, h = math.radians(deg), 0.02 * math.radians(deg)
    mf = _friction_moment(spec, deg, "compliance")
    dmf = (_friction_moment(spec, math.degrees(a + h), "compliance")
           - _friction_moment(spec, math.degrees(a - h), "compliance")) / (2 * h)
    assert anti == pytest.approx(0.5 * (mf / a + dmf), rel=0.05)
    assert with_f[3, 4] == pytest.approx(mf / a, rel=0.05)


def test_the_torques_sign_mirrors_the_frictionless_matrix(renzo):
    """The cw flanks are the mirror image of the ccw ones: without friction a reversed
    torque gives the same diagonal and reversed tilt-torsion terms."""
    ahead = stiffness_matrix(renzo, 1.0, 2000.0, model="compliance", friction=0.0,
                             rotations=2).matrix
    back = stiffness_matrix(renzo, 1.0, -2000.0, model="compliance", friction=0.0,
                            rotations=2).matrix
    assert np.diag(back) == pytest.approx(np.diag(ahead), rel=1e-6)
    assert back[3, 5] == pytest.approx(-ahead[3, 5], rel=1e-6)


def test_the_matrix_is_continuous_at_the_end_of_the_range(renzo):
    """Within a step of 6° the tilt difference turns backward (second order too): the
    matrix at 6° continues the one at 5.99°."""
    inside = stiffness_matrix(renzo, 5.99, model="compliance", rotations=2).matrix
    end = stiffness_matrix(renzo, 6.0, model="compliance", rotations=2).matrix
    assert np.diag(end) == pytest.approx(np.diag(inside), rel=0.01)


def test_forward_differences_against_central(renzo):
    """Forward differences (one solve per column, the surface model's default) against
    central ones at 1° (measured: diagonal within 0.4 % with the compliance model, whose
    springs switch within a step, 0.12 % with surface; docs/rotordynamics.md). The axial
    column is zero either way (an axial shift changes no gap); aligned the scheme is
    central (the wind-up is even in the pose)."""
    central = stiffness_matrix(renzo, 1.0, model="compliance", differences="central")
    forward = stiffness_matrix(renzo, 1.0, model="compliance", differences="forward")
    assert forward.steps["differences"] == "forward"
    assert forward.steps["relative_step"] < central.steps["relative_step"]
    d = np.diag(central.matrix)
    assert np.diag(forward.matrix) == pytest.approx(d, rel=0.01)
    scale = np.sqrt(np.abs(np.outer(d, d)))
    assert np.max(np.abs(forward.matrix - central.matrix)[d > 0][:, d > 0]
                  / scale[d > 0][:, d > 0]) < 0.02
    assert not np.any(forward.matrix[:, 2]) and not np.any(central.matrix[:, 2])
    aligned = stiffness_matrix(renzo, 0.0, model="compliance", differences="forward")
    assert aligned.steps["differences"] == "central"
    with pytest.raises(gc.ArgumentError, match="differences = 'backward'"):
        stiffness_matrix(renzo, 1.0, model="compliance", differences="backward")


def test_aligned_friction_is_left_out_and_said_so(renzo):
    K = stiffness_matrix(renzo, 0.0, model="compliance")
    assert K.friction == 0.0 and any("friction" in n for n in K.notes)
    assert K.axial_slip_force_N == pytest.approx(
        renzo.load.friction * renzo.load.torque_Nm * 1e3
        / (renzo.tooth.pitch_radius * math.cos(renzo.tooth.pressure_angle)), rel=1e-3)


def test_zero_torque_is_refused(renzo):
    with pytest.raises(gc.ArgumentError, match="torque_Nm"):
        coupling_data(renzo, 1.0, 0.0)
    with pytest.raises(gc.ArgumentError, match="workers = 3: 1 or 2"):
        coupling_data(renzo, 1.0, workers=3)


@pytest.mark.slow
@pytest.mark.parametrize("given", [False, True], ids=["alone", "known capacity"])
def test_data_sheet_is_the_same_in_one_process_and_over_two(renzo, given):
    """The surface model starts each solve on a sweep from the last one on it, so the
    numbers depend on which solves follow which: the two chains (the matrix with half the
    wind-up curve, the allowable misalignment; the curve's other half joins the first
    alone, the second with known capacities, as in the report) run the same solves in the
    same order in one process as in two forked ones, and every number agrees to the last
    bit. Small knobs (one rotation, three curve torques, a torque the critical angle still
    carries: no capacity search) keep it to a few seconds."""
    knobs = dict(model="surface", rotations=1, curve_points=3, turn_angles=8)
    known = [gc.capacity(renzo, 1.0, model="surface")] if given else []
    one, two = (coupling_data(renzo, 1.0, 200.0, workers=w, known=known, **knobs)
                for w in (1, 2))
    a, b = one.as_dict(), two.as_dict()
    a.pop("seconds"), b.pop("seconds")
    assert json.dumps(a) == json.dumps(b)
    assert np.array_equal(one.stiffness.matrix, two.stiffness.matrix)


# --------------------------------------------------------------------------- torsion


@pytest.mark.parametrize("name", ["renzo-1967", "industrial-m2", "mill-spindle"])
def test_torsional_stiffness_against_the_calculix_reference(name):
    """Aligned wind-up from first touch plus the bodies at the reference torques, against
    the CalculiX contact reference, within the accuracy ladder's band for the data sheet's
    model and springs (docs/load.md; 0.5 points of rounding)."""
    spec = gc.load_spec(name)
    model = spec.load.model  # the data sheet's: the spec's, the validated default
    lo, hi = WINDUP_ERROR_PCT[(model, springs_name(spec, model))]
    refs = json.loads(GOLDEN.read_text())["references"][name]
    sw = gc.sweep(spec, 0.0, [0.0])
    for torque, ref in refs.items():
        T = float(torque)
        w = mesh_windup_from_touch(sw, T, model) + gc.body_windup_rad(spec, T)["body_rad"]
        error = 100 * (w / ref["windup_from_first_touch_rad"] - 1)
        assert lo - 0.5 <= error <= hi + 0.5, (T, error)


# --------------------------------------------------------------------------- the data sheet


@pytest.fixture(scope="module")
def data(renzo):
    return coupling_data(renzo, rotations=4, curve_points=5)  # the default turn


def test_the_default_turn_holds_the_loads_of_one_three_times_as_fine(data, renzo):
    """The data sheet's turn at the allowable misalignment: PHASES rotations per tooth pitch
    by default (8 poses with ideal teeth; 360 rotations held 360 / gcd(360, N) poses a
    pitch: 36 here, 2 on 180 teeth, 360 on 37). The loads summed over the teeth hardly
    move within a pitch: the max and the mean of each over the turn agree with a turn of
    3 x PHASES a pitch within 0.05 % (of the moment; of the largest slip force for the
    forces, which cancel between opposite teeth), measured within 0.01 % against 72 a
    pitch on even tooth counts, up to 0.13 % on odd ones (benchmarks/bench_rotordynamics.py
    --only turn)."""
    a = data.allowable
    assert np.allclose(a.angles_deg, turn_phases(renzo))
    fine = gc.load(renzo, a.misalignment_deg, turn_phases(renzo, 3 * PHASES),
                   torque_Nm=a.torque_Nm)
    ml = machine_loads(fine)
    slip = renzo.load.friction * np.sum(fine.normal_force_N, axis=0)
    force = float(np.max(slip))
    for got, ref, scale in ((a.bending_moment_Nm, ml["tilting_moment_Nm"], None),
                            (a.axial_force_N, ml["axial_force_N"], force),
                            (a.radial_force_N, ml["radial_force_N"], force),
                            (a.axial_slip_force_N, slip, force)):
        got, ref = np.abs(got), np.abs(np.asarray(ref))
        for stat in (np.max, np.mean):
            assert abs(stat(got) - stat(ref)) <= 5e-4 * (scale or stat(ref))


def test_coupling_data_is_consistent(data, renzo):
    assert data.misalignment_deg == renzo.design_misalignment_deg
    assert data.torque_Nm == pytest.approx(renzo.load.torque_Nm)
    t = data.torsion
    assert t.tangent_Nm_per_rad == data.stiffness.matrix[5, 5]
    assert t.torque_Nm[0] == 0 and t.windup_rad[0] == 0
    assert np.all(np.diff(t.windup_rad) > 0)
    # the curve runs to the capacity, or to the torque where that is higher
    assert t.torque_Nm[-1] == pytest.approx(max(data.capacity_Nm, abs(data.torque_Nm)))
    assert t.tangent_Nm_per_rad > t.secant_Nm_per_rad  # the contact stiffens
    # the curve's point at the torque is the matrix's operating point, not solved again
    at = int(np.flatnonzero(t.torque_Nm == data.torque_Nm)[0])
    assert t.mesh_windup_rad[at] == data.stiffness.operating_windup_rad
    sw = gc.sweep(renzo, data.misalignment_deg, pitch_rotations(renzo, 4))
    assert t.mesh_windup_rad[at] == pytest.approx(
        mesh_windup_from_touch(sw, data.torque_Nm, data.model), rel=1e-5)
    a = data.allowable
    assert a.misalignment_deg <= a.critical_misalignment_deg
    if a.criterion == "capacity":
        cap = gc.capacity(renzo, a.misalignment_deg, model=data.model).capacity_Nm
        assert cap == pytest.approx(abs(data.torque_Nm), rel=0.01)
    assert np.all(a.bending_moment_Nm > 0)
    coupling = data.mass["coupling"]
    assert coupling.mass_kg == pytest.approx(data.mass["hub"].mass_kg
                                             + data.mass["sleeve"].mass_kg)
    for entry in ("torsion", "stiffness"):
        assert "CalculiX" in data.accuracy()[entry]


def test_data_sheet_files_and_dataframe(data, tmp_path):
    paths = data.write(tmp_path)
    assert [p.name for p in paths] == list(FILES)
    sheet = json.loads((tmp_path / "datasheet.json").read_text())
    assert sheet["stiffness"]["matrix"] == data.stiffness.matrix.tolist()
    lines = [ln for ln in (tmp_path / "stiffness_matrix.csv").read_text().splitlines()
             if not ln.startswith("#")]
    assert lines[0].startswith("row,force_unit,x_per_m") and len(lines) == 7
    assert float(lines[4].split(",")[5]) == pytest.approx(data.stiffness.matrix[3, 3])
    pd = pytest.importorskip("pandas")
    frame = data.to_dataframe()
    assert list(frame.columns) == ["section", "quantity", "value", "unit", "source"]
    assert frame["value"].dtype == float
    assert isinstance(frame, pd.DataFrame)
    mass = frame[frame.quantity == "coupling mass"]["value"].item()
    assert mass == pytest.approx(data.mass["coupling"].mass_kg)


def test_datasheet_command_writes_the_files_and_prints_its_key_figures(tmp_path, capsys):
    """The files, and before their paths the key figures as datasheet.json holds them (4
    significant digits): masses, secant and tangent torsional stiffness, the allowable
    misalignment and the capacity. Not the model: the compliance model, a second of
    solves."""
    code = main(["datasheet", "industrial-m2", "--model", "compliance", "--rotations", "2",
                 "--angles", "36", "-o", str(tmp_path)])
    assert code == 0
    assert {p.name for p in tmp_path.iterdir()} == {*FILES, RECORD_NAME}
    lines = capsys.readouterr().out.splitlines()
    assert lines[-len(FILES):] == [str(tmp_path / f) for f in FILES]
    data = json.loads((tmp_path / "datasheet.json").read_text(encoding="utf-8"))
    a, t = data["allowable"], data["torsion"]
    assert lines[:-len(FILES)] == [
        f"industrial-m2: i = {data['misalignment_deg']:g}°, T = {data['torque_Nm']:.4g} N·m "
        f"(compliance model, {data['springs']} springs)",
        "  mass: " + ", ".join(f"{k} {data['mass'][k]['mass_kg']:.4g} kg"
                               for k in ("hub", "sleeve", "coupling")),
        f"  torsional stiffness at the torque: secant {t['secant_Nm_per_rad']:.4g} N·m/rad, "
        f"tangent {t['tangent_Nm_per_rad']:.4g} N·m/rad",
        f"  allowable misalignment: {a['misalignment_deg']:.4g}° (limited by the "
        f"{a['criterion']}, {a['capacity_criterion'].replace('_', ' ')})",
        f"  capacity at {data['misalignment_deg']:g}°: {data['capacity_Nm']:.4g} N·m (K = "
        f"{gc.load_spec('industrial-m2').load.accuracy_factor:g} applied)"]


@pytest.mark.parametrize("argv, words", [  # more in tests/test_cli_bad_input.py
    (["--torque", "2e9"], "--torque"),
    (["--misalignment", "7"], "--misalignment = 7"),
    (["--differences", "backward"], "--differences"),
    (["--set", "material.density_kg_per_m3=-7850"], "density_kg_per_m3 = -7850"),
    (["--set", "material.youngs_modulus_MPa=70000"], "density_kg_per_m3 = None"),
])
def test_datasheet_bad_input_is_one_line_and_exit_2(argv, words, tmp_path, capsys):
    assert main(["datasheet", "renzo-1967", "-o", str(tmp_path), *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err, err
    assert not list(tmp_path.iterdir())


# --------------------------------------------------------------------------- ROSS


@pytest.mark.slow
@pytest.mark.needs_ross
def test_ross_rotor_first_torsional_frequency(data, tmp_path):
    """Two steel shafts and two disks joined by this coupling in ROSS (the element from
    ``to_ross`` and again read back from ROSS's own file): ROSS's first torsional natural
    frequency against the two-inertia closed form ``sqrt(k (1/J1 + 1/J2))`` with ``k`` the
    shafts' and the coupling's torsional stiffnesses in series, within 1 %."""
    from gearcoupling.rotordynamics import import_ross, write_ross

    rs = import_ross()
    element = data.to_ross()
    path = write_ross(element, tmp_path / "coupling.toml")
    again = rs.CouplingElement.load(path)
    assert again.kr_z == pytest.approx(data.stiffness.matrix[5, 5])
    assert again.m_l == pytest.approx(data.mass["hub"].mass_kg)
    steel = rs.materials.steel
    length, d, J = 0.05, 0.15, 5.0
    k_shaft = steel.G_s * math.pi * d**4 / 32 / length
    for coupling in (element, again):
        shafts = [rs.ShaftElement(length, 0.0, d, material=steel), coupling,
                  rs.ShaftElement(length, 0.0, d, material=steel)]
        disks = [rs.DiskElement(n=0, m=100.0, Id=2.5, Ip=J),
                 rs.DiskElement(n=3, m=100.0, Id=2.5, Ip=J)]
        bearings = [rs.BearingElement(n=0, kxx=1e8, cxx=0), rs.BearingElement(n=3, kxx=1e8,
                                                                               cxx=0)]
        modal = rs.Rotor(shafts, disks, bearings).run_modal(speed=0, num_modes=40,
                                                            sparse=False)
        torsional = [w for w, s in zip(modal.wn, modal.shapes, strict=False)
                     if s.mode_type == "Torsional" and w > 1.0]
        k = 1.0 / (2.0 / k_shaft + 1.0 / coupling.kr_z)
        assert min(torsional) == pytest.approx(math.sqrt(k * 2.0 / J), rel=0.01)


def test_known_capacities_must_be_of_the_spec_and_model(renzo):
    """The allowable search reuses capacities only of its own spec, model and flank: one of
    another model would move the answer silently, so it is refused by name."""
    from gearcoupling.errors import ArgumentError
    from gearcoupling.rotordynamics.allowable import capacity_limit_deg

    other = gc.capacity(renzo, 1.0, model="compliance")
    with pytest.raises(ArgumentError, match=r"known = .*surface model"):
        capacity_limit_deg(renzo, 2000.0, 2.0, model="surface", known=[other])
    cw = gc.capacity(renzo, 1.0, model="compliance", loaded_flank="cw")
    with pytest.raises(ArgumentError, match="ccw flank"):
        capacity_limit_deg(renzo, 2000.0, 2.0, model="compliance", known=[cw])
