"""The real CalculiX solver on gmsh meshes: a cantilever against Timoshenko, the tooth
compliance table (physical trends, cache, protocol), solver errors with their log."""

import numpy as np
import pytest

from fresh_python import run_fresh
from gearcoupling import load_spec
from gearcoupling.cli import main
from gearcoupling.errors import ArgumentError, BackendError

# skipped, with the reason, without gmsh or ccx
pytestmark = [pytest.mark.needs_fea, pytest.mark.slow]


@pytest.mark.parametrize("size", [5.0, 3.0])
def test_cantilever_tip_deflection_within_2_percent_of_timoshenko(size):
    from gearcoupling.fea.validation import cantilever_tip_deflection

    res = cantilever_tip_deflection(size)
    assert abs(res["ratio"] - 1.0) < 0.02, res


@pytest.fixture(scope="module")
def table(fe_table_industrial):
    """The session's default industrial-m2 table (tests/conftest.py) and its cache folder."""
    base, t = fe_table_industrial
    return t, base / "fea"


def test_compliance_grows_with_load_height_and_toward_the_face_end(table):
    t, _ = table
    assert np.all(t.hub_mm_per_N > 0) and np.all(t.sleeve_mm_per_N > 0)
    # hub: higher load (larger r) bends the tooth more; nearer the face end less support
    assert np.all(t.hub_mm_per_N[:, 1] > 1.2 * t.hub_mm_per_N[:, 0])
    assert np.all(t.hub_mm_per_N[1] > t.hub_mm_per_N[0])
    # sleeve: internal teeth point inward, so a load at smaller r is farther from its root
    assert np.all(t.sleeve_mm_per_N[:, 0] > t.sleeve_mm_per_N[:, 1])


def test_the_last_row_is_flush_with_the_face_end_and_softest(table):
    """Three rows evenly to 0.8 of the hub half face and a fourth whose load patch ends at
    the face end, where a misaligned patch runs: there the tooth has support on one side
    only, so both parts are softer than at 0.8 at every radius."""
    t, _ = table
    half = 0.5 * load_spec("industrial-m2").hub.face_width
    np.testing.assert_allclose(t.z_mm, [0.0, 0.4 * half, 0.8 * half,
                                        half - t.info["patch_mm"]], rtol=1e-12)
    assert np.all(t.hub_mm_per_N[3] > t.hub_mm_per_N[2])
    assert np.all(t.sleeve_mm_per_N[3] > t.sleeve_mm_per_N[2])
    assert np.all(t.far_field_mm_per_N[3] > 1.1 * t.far_field_mm_per_N[2])


def test_mesh_stiffness_is_of_the_order_of_iso_6336(table):
    """ISO 6336 single-pair stiffness c' ~ 14 N/(mm µm) of face width for external spur
    gears under a line load; coupling teeth are shorter (addendum m) but the sleeve tooth is
    internal, and C is for a patch of module / 2 at mid-face, not a line load over the face
    (lower per width): the FE value per hub face width must lie within a factor 3 of it
    (5.3 on the default mesh)."""
    t, _ = table
    per_width = t.mesh_stiffness_N_per_mm / 16.0 / 1e3
    assert 14 / 3 < per_width < 14 * 3, per_width


def test_table_is_cached_and_implements_the_protocol(table):
    from gearcoupling.fea import tooth_compliance_table

    t, cache = table
    files = list(cache.glob("industrial-m2-*.json"))
    assert len(files) == 1
    again = tooth_compliance_table(load_spec("industrial-m2"), cache=cache)
    np.testing.assert_array_equal(again.hub_mm_per_N, t.hub_mm_per_N)
    np.testing.assert_array_equal(again.near_field_mm_per_N, t.near_field_mm_per_N)
    # the table depends on the solids, not on the load section: same cache entry
    loaded = load_spec("industrial-m2", **{"load.torque_Nm": 123.0, "load.stiffness": "fe"})
    tooth_compliance_table(loaded, cache=cache)
    assert list(cache.glob("industrial-m2-*.json")) == files
    far = t.hub_mm_per_N + t.sleeve_mm_per_N - t.near_field_mm_per_N.sum(axis=0)
    grid = t.pair_compliance_mm_per_N(t.z_mm[:, None], t.r_mm[None, :])
    np.testing.assert_allclose(grid, far, rtol=1e-12)
    # even in z, bilinear: the middle of the first cell is the mean of its corners
    mid = t.pair_compliance_mm_per_N(-t.z_mm[:2].mean(), t.r_mm[:2].mean())
    assert mid == pytest.approx(far[:2, :2].mean(), rel=1e-12)
    assert t.pair_compliance_mm_per_N(np.zeros((4, 1)), np.full(3, 38.0)).shape == (4, 3)


def test_near_field_is_a_positive_part_of_the_fe_compliance(table):
    """The half-space work of the patch loads is a part of the FE compliance: positive,
    below the hub's whole compliance, and the pair's far field stays positive."""
    t, _ = table
    near = t.near_field_mm_per_N
    assert np.all(near > 0) and np.all(near[0] < t.hub_mm_per_N)
    assert np.all(t.far_field_mm_per_N > 0)


def test_a_one_tooth_sector_is_refused_for_the_near_field_split(tmp_path):
    """Fixed cuts at the loaded tooth make the FE compliance smaller than its own
    half-space part: refused with the settings to change, not a negative compliance.
    Size 1 mm (module / 2, the coarsest allowed) and a 2 x 2 grid: the smallest table that
    reaches the check."""
    from gearcoupling.fea import compute_compliance_table

    with pytest.raises(ArgumentError, match="sector at least 3"):
        compute_compliance_table(load_spec("industrial-m2"), size_mm=1.0, sector=1, nz=2, nr=2)


@pytest.mark.parametrize("a, b", [(1.0, 1.0), (2.0, 0.7), (0.3, 5.0)])
def test_rectangle_halfspace_work_matches_the_integral_of_the_boussinesq_kernel(a, b):
    """Uniform pressure on an a x b rectangle (total force P): the work is
    (1 - nu²) / (pi E) (P / ab)² times the integral of 1 / |x - y| over pairs of points of
    the rectangle. Here that integral is computed independently: the inner integral in
    closed form (four corner rectangles, p asinh(q / p) + q asinh(p / q) each), the outer
    one by Gauss-Legendre; 2.9732 for the unit square (Johnson, Contact Mechanics, ch. 3)."""
    import math

    from gearcoupling.fea.stiffness import rectangle_halfspace_work_mm_per_N

    def corner(p, q):
        return p * np.arcsinh(q / p) + q * np.arcsinh(p / q)

    g, w = np.polynomial.legendre.leggauss(200)
    x, wx = 0.5 * a * (g + 1), 0.5 * a * w
    y, wy = 0.5 * b * (g + 1), 0.5 * b * w
    X, Y = np.meshgrid(x, y, indexing="ij")
    inner = corner(X, Y) + corner(a - X, Y) + corner(X, b - Y) + corner(a - X, b - Y)
    integral = float(wx @ inner @ wy)
    E, nu, P = 206_000.0, 0.3, 2.5
    work = rectangle_halfspace_work_mm_per_N(P, a, b, E, nu)
    assert work == pytest.approx((1 - nu**2) / (math.pi * E) * (P / (a * b))**2 * integral,
                                 rel=1e-6)
    assert rectangle_halfspace_work_mm_per_N(1.0, b, a, E, nu) == pytest.approx(
        rectangle_halfspace_work_mm_per_N(1.0, a, b, E, nu), rel=1e-12)
    if a == b:
        assert integral == pytest.approx(2.973209598247378, rel=1e-6)


@pytest.fixture(scope="module")
def loaded_hub(tmp_path_factory):
    """industrial-m2's hub sector as the table meshes it, at size 1 mm (module / 2)."""
    from gearcoupling.fea.stiffness import _loaded_sector

    spec = load_spec("industrial-m2")
    return spec, _loaded_sector(spec, "hub", 3, 1.0, (-1.0, 7.4))


def test_load_case_is_a_uniform_pressure_on_the_patch(loaded_hub):
    """The consistent nodal forces of a uniform pressure on the (z, r) patch of the loaded
    hub flank: their moment about the axis is 1 N x R (a unit tangential load at the pitch
    radius R; exact, since the quadratic shape functions reproduce the linear moment arm);
    they push into the tooth along one normal; their patch area is the involute's: 2a times
    the developed arc length between r - a and r + a (the crowned flank at mid-face)."""
    from gearcoupling.fea.stiffness import load_case
    from gearcoupling.geometry import developed_arc

    spec, vm = loaded_hub
    R, rb, a = spec.tooth.pitch_radius, spec.tooth.base_radius, 0.5
    case, area, length = load_case(vm, 0.0, R, R, a)
    x, f = vm.nodes[case.nodes], case.forces
    assert float(np.sum(x[:, 0] * f[:, 1] - x[:, 1] * f[:, 0])) == pytest.approx(-R, rel=1e-9)
    n = f.sum(axis=0) / np.linalg.norm(f.sum(axis=0))
    np.testing.assert_allclose(np.cross(f, n), 0.0, atol=1e-12)
    assert length == pytest.approx(2 * a, rel=1e-12)
    exact = 2 * a * float(developed_arc(R + a, rb) - developed_arc(R - a, rb))
    assert area == pytest.approx(exact, rel=0.01)


@pytest.mark.parametrize("size", [5.0])
def test_green_functions_equal_one_static_step_per_load_case(size, tmp_path):
    """Every load case as one Green function of one factorisation (the table's deck) gives
    the work and the element stresses of one static step per case (three cases on the
    Timoshenko cantilever's mesh, 433 C3D10: both decks are solved by SPOOLES). The third
    loads the first's nodes again, as overlapping load patches do: an equation led by a
    degree of freedom another equation holds stops ccx ("zero coefficient on the dependent
    side")."""
    from gearcoupling.fea.ccx import run_ccx
    from gearcoupling.fea.deck import LoadCase, green_deck, principal_max, static_deck
    from gearcoupling.fea.validation import cantilever_mesh

    vm = cantilever_mesh(100.0, 10.0, 10.0, size)
    tip = vm.node_set("TIP")
    top = np.flatnonzero(np.isclose(vm.nodes[:, 2], 10.0) & (vm.nodes[:, 0] > 40.0))
    cases = [LoadCase(tip, np.tile([0.0, 0.3, 1.0], (len(tip), 1)) / len(tip)),
             LoadCase(top, np.tile([0.0, 0.0, -1.0], (len(top), 1)) * np.linspace(
                 0.5, 1.5, len(top))[:, None] / len(top)),
             LoadCase(tip, np.tile([0.0, 1.0, 0.2], (len(tip), 1)) * np.linspace(
                 0.5, 1.5, len(tip))[:, None] / len(tip))]
    kw = {"youngs_modulus_MPa": 210e3, "poisson_ratio": 0.3, "fixed": ["ROOT"],
          "cases": cases, "stress_sets": ["ROOT"]}
    prints = [(f"P{i}", c.nodes) for i, c in enumerate(cases)]
    static = run_ccx(static_deck(vm, node_print=prints, **kw), tmp_path, "static")
    green = run_ccx(green_deck(vm, **kw), tmp_path, "green")
    work = green.get("displacements", "LOADS")
    for i, case in enumerate(cases):
        u = static.get("displacements", f"P{i}")[i]
        f = case.forces[np.argsort(case.nodes)]
        expected = float(np.sum(f * u[np.argsort(u[:, 0]), 1:4]))
        assert work[i][i, 1] == pytest.approx(expected, rel=1e-6)
        s_static = principal_max(static.get("stresses", "ROOT")[i][:, 2:8])
        s_green = principal_max(green.get("stresses", "ROOT")[i][:, 2:8])
        np.testing.assert_allclose(s_green, s_static, rtol=1e-5, atol=1e-9 * np.abs(
            s_static).max())


def test_root_stress_is_positive_and_finite(table):
    t, _ = table
    assert np.all(np.isfinite(t.root_stress_MPa_per_N)) and np.all(t.root_stress_MPa_per_N > 0)


def test_failed_solver_run_keeps_its_log(tmp_path):
    from gearcoupling.fea.ccx import run_ccx

    bad = "*NODE\n1, 0, 0, 0\n*STEP\n*STATIC\n*BOGUS CARD\n*END STEP\n"
    with pytest.raises(BackendError, match=r"its log is .*bad\.log") as err:
        run_ccx(bad, tmp_path, "bad")
    assert (tmp_path / "bad.log").read_text().strip()
    assert str(tmp_path / "bad.inp") in str(err.value)
    # a default (temporary) solver folder survives a failure, and goes after a success
    from gearcoupling.fea.ccx import solver_dir

    with pytest.raises(BackendError), solver_dir() as work:
        run_ccx(bad, work, "bad")
    assert (work / "bad.log").exists() and (work / "bad.inp").exists()
    __import__("shutil").rmtree(work)
    with solver_dir() as ok:
        (ok / "x").write_text("x")
    assert not ok.exists()


def test_a_ctrl_c_while_the_solver_starts_kills_and_reaps_it(tmp_path):
    """A SIGINT arriving as ``Popen`` returns, ccx already started (injected at the end of
    ``Popen.__init__``, in a fresh interpreter where it is the only child): the interrupt
    still comes out of :func:`run_ccx`, and the solver is killed and reaped, not left
    running unregistered (raised inside ``Popen``, it used to be)."""
    run_fresh("""
        import os, signal, subprocess, sys
        from gearcoupling.fea.ccx import RUNNING, run_ccx

        signal.signal(signal.SIGINT, signal.default_int_handler)
        start = subprocess.Popen.__init__

        def started_then_ctrl_c(self, *args, **kwargs):
            start(self, *args, **kwargs)
            os.kill(os.getpid(), signal.SIGINT)  # Python runs its handler here

        subprocess.Popen.__init__ = started_then_ctrl_c
        deck = "*NODE\\n1, 0, 0, 0\\n*STEP\\n*STATIC\\n*END STEP\\n"
        try:
            run_ccx(deck, sys.argv[1], "job")
        except KeyboardInterrupt:
            pass
        else:
            raise AssertionError("the interrupt was lost")
        assert not RUNNING, RUNNING
        assert_no_child_left("the solver")
    """, str(tmp_path))


def test_missing_solver_names_the_package(monkeypatch, tmp_path):
    from gearcoupling.fea.backends import CCX_ENV, ccx_path

    monkeypatch.setenv(CCX_ENV, str(tmp_path / "no-ccx-here"))
    with pytest.raises(BackendError, match="calculix-ccx"):
        ccx_path()
    assert main(["stiffness", "industrial-m2", "-o", str(tmp_path)]) == 2


def test_stiffness_cli_refuses_an_even_sector(tmp_path, capsys):
    assert main(["stiffness", "industrial-m2", "--sector", "2", "-o", str(tmp_path)]) == 2
    assert "odd number of teeth" in capsys.readouterr().err
    with pytest.raises(ArgumentError):
        from gearcoupling.fea import compute_compliance_table

        compute_compliance_table(load_spec("industrial-m2"), sector=4)


def test_fe_table_drives_the_compliance_load_model(table):
    """The compliance load model takes the FE table through the protocol: at misalignment 0
    every tooth carries T / (N R), and the wind-up differs from the cantilever model's by
    exactly P (c_fe - c_cantilever) / R at the load centre (same gaps and contact law)."""
    pytest.importorskip("gearcoupling.loading.models.compliance")
    from gearcoupling.clearance import sweep
    from gearcoupling.loading.contact import contact_model, patch_centre_radius
    from gearcoupling.loading.kernels.cantilever import CantileverCompliance
    from gearcoupling.loading.models.compliance import solve_compliance

    t, _ = table
    spec = load_spec("industrial-m2")
    sw = sweep(spec, 0.0, [0.0, 3.0])
    g, z, r = sw.gap_angle_rad[1], sw.contact_z_mm[1], sw.contact_r_mm[1]
    T = 500e3  # N mm
    cant = CantileverCompliance(spec)
    fe = solve_compliance(spec, g, z, r, T, t)
    ref = solve_compliance(spec, g, z, r, T, cant)
    R, N = spec.tooth.pitch_radius, spec.tooth.teeth
    P = T / (N * R)
    np.testing.assert_allclose(fe["tangential_force_N"], P, rtol=1e-6)
    r_load = patch_centre_radius(*contact_model(spec).depth_limits(z[0]))
    dc = t.pair_compliance_mm_per_N(z[0], r_load) - cant.pair_compliance_mm_per_N(z[0], r_load)
    np.testing.assert_allclose(fe["windup_rad"] - ref["windup_rad"], P * dc / R,
                               rtol=0.02, atol=1e-9)


def test_stiffness_cli_writes_the_table_from_the_cache(table, tmp_path):
    import csv
    import json

    t, cache = table
    argv = ["stiffness", "industrial-m2", "--cache", str(cache), "-o", str(tmp_path)]
    assert main(argv) == 0
    rows = list(csv.DictReader((tmp_path / "stiffness.csv").read_text().splitlines()))
    assert len(rows) == t.hub_mm_per_N.size == 12  # 4 rows along the face x 3 radii
    for row, (h, s) in zip(rows, zip(t.hub_mm_per_N.ravel(), t.sleeve_mm_per_N.ravel(),
                                     strict=True), strict=True):
        assert float(row["pair_um_per_N"]) == pytest.approx(1e3 * (h + s), rel=1e-5)
    summary = json.loads((tmp_path / "stiffness.json").read_text())["pitch_point"]
    assert summary["mesh_stiffness_N_per_mm"] == pytest.approx(t.mesh_stiffness_N_per_mm)


def test_fe_springs_keep_the_nominal_root_stress_criterion(table):
    """With ``stiffness = "fe"`` the bending criterion stays the nominal (cantilever) root
    stress the allowable is meant for: it was silently dropped (root stress 0, no bending
    criterion in the capacity). The table's fillet stresses hold the fillet's stress
    concentration; they are reported, not judged."""
    from gearcoupling.loading.kernels.cantilever import CantileverCompliance
    from gearcoupling.loading.models.compliance import solve_compliance

    t, _ = table
    spec = load_spec("industrial-m2")
    N, R = spec.tooth.teeth, spec.tooth.pitch_radius
    zeros = np.zeros((N, 1))
    out = solve_compliance(spec, zeros, zeros, np.full((N, 1), R), 400e3, t)
    nominal = CantileverCompliance(spec).root_stress_MPa(out["normal_force_N"], zeros,
                                                         np.full((N, 1), R))
    np.testing.assert_allclose(out["root_stress_MPa"], nominal, rtol=1e-12)
    assert np.all(nominal > 0)
    from gearcoupling.loading.limits import limit_loads

    limits = limit_loads(spec, zeros, np.full((N, 1), R), t)
    assert np.all(np.isfinite(limits["bending_stress"]) & (limits["bending_stress"] > 0))


def test_default_springs_reproduce_the_fe_table(table):
    """The default springs (``fe-fit``: the shipped fit of FE tables, no solver) against
    this session's FE table of industrial-m2 at every load point of its grid: the far field
    within 10 %, the issue's target (the fit's error table in docs/load.md gives -4.9 % at
    worst on this spec) and the whole compliance, far + half-space near field, within 4 %
    (what a load model adds up); the cantilever, the default springs before the fit, is
    1.4-5.0 times the far field (the least at the face-end corner of the grid)."""
    from gearcoupling.loading import CantileverCompliance, FittedCompliance

    t, _ = table
    spec = load_spec("industrial-m2")
    Z, R = np.meshgrid(t.z_mm, t.r_mm, indexing="ij")
    fit = FittedCompliance(spec).pair_compliance_mm_per_N(Z, R)
    near = t.near_field_mm_per_N.sum(axis=0)
    np.testing.assert_allclose(fit, t.far_field_mm_per_N, rtol=0.10)
    np.testing.assert_allclose(fit + near, t.far_field_mm_per_N + near, rtol=0.04)
    cantilever = CantileverCompliance(spec).pair_compliance_mm_per_N(Z, R)
    assert np.all(cantilever > 1.25 * t.far_field_mm_per_N)


def test_the_fe_springs_follow_the_fe_solved_between_the_tables_rows(table):
    """``stiffness = "fe"`` between the table's rows: the table of this session's
    industrial-m2 solved again with rows at 0.2 and 0.6 of the half face too (``nz=5``)
    against the fit-shaped interpolation of the standard table there, within 6 % (the
    largest over four specs solved between their rows: −6.2 … +4.8 %). Linear between rows
    (the table's own ``pair_compliance_mm_per_N``) it is more than 6 % soft at 0.6: the far
    field rises toward the face end faster than a chord (+5 … +25 % on those specs). The
    load models read both springs held at 0.8 of the half face (``HeldAlongFace``)."""
    from gearcoupling.fea import compute_compliance_table
    from gearcoupling.loading.kernels.fitted import FittedCompliance
    from gearcoupling.loading.springs import FitShapedTable, HeldAlongFace, tooth_compliance

    t, _ = table
    spec = load_spec("industrial-m2")
    fine = compute_compliance_table(spec, nz=5)
    half = 0.5 * spec.hub.face_width
    np.testing.assert_allclose(fine.z_mm[[1, 3]], [0.2 * half, 0.6 * half], rtol=1e-12)
    Z, R = np.meshgrid(fine.z_mm[[1, 3]], fine.r_mm, indexing="ij")
    fe = fine.far_field_mm_per_N[[1, 3]]
    shaped = FitShapedTable(t, FittedCompliance(spec))
    np.testing.assert_allclose(shaped.pair_compliance_mm_per_N(Z, R), fe, rtol=0.06)
    assert np.any(t.pair_compliance_mm_per_N(Z, R)[1] > 1.06 * fe[1])
    Zt, Rt = np.meshgrid(t.z_mm, t.r_mm, indexing="ij")  # exact at the table's points
    np.testing.assert_allclose(shaped.pair_compliance_mm_per_N(Zt, Rt), t.far_field_mm_per_N,
                               rtol=1e-12)
    held = tooth_compliance(spec.replace(**{"load.stiffness": "fe-fit"}))
    assert isinstance(held, HeldAlongFace) and held.z_hold_mm == pytest.approx(0.8 * half)
    r = np.full(3, t.r_mm[1])
    np.testing.assert_allclose(held.pair_compliance_mm_per_N([0.8 * half, 0.9 * half, half], r),
                               held.pair_compliance_mm_per_N(0.8 * half, r[0]), rtol=1e-12)
