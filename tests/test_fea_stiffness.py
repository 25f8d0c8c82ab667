"""The real CalculiX solver on gmsh meshes: a cantilever against Timoshenko, the tooth
compliance table (physical trends, cache, protocol), solver errors with their log."""

import numpy as np
import pytest

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
def table(tmp_path_factory):
    from gearcoupling.fea import tooth_compliance_table

    cache = tmp_path_factory.mktemp("cache")
    spec = load_spec("industrial-m2")
    return tooth_compliance_table(spec, size_mm=1.0, sector=3, nz=2, nr=2, cache=cache), cache


def test_compliance_grows_with_load_height_and_toward_the_face_end(table):
    t, _ = table
    assert np.all(t.hub_mm_per_N > 0) and np.all(t.sleeve_mm_per_N > 0)
    # hub: higher load (larger r) bends the tooth more; nearer the face end less support
    assert np.all(t.hub_mm_per_N[:, 1] > 1.2 * t.hub_mm_per_N[:, 0])
    assert np.all(t.hub_mm_per_N[1] > t.hub_mm_per_N[0])
    # sleeve: internal teeth point inward, so a load at smaller r is farther from its root
    assert np.all(t.sleeve_mm_per_N[:, 0] > t.sleeve_mm_per_N[:, 1])


def test_mesh_stiffness_is_of_the_order_of_iso_6336(table):
    """ISO 6336 single-pair stiffness c' ~ 14 N/(mm µm) of face width for external spur
    gears; coupling teeth are shorter (addendum m) but the sleeve tooth is internal: the FE
    value per hub face width must lie within a factor 2.5 of it (coarse mesh)."""
    t, _ = table
    per_width = t.mesh_stiffness_N_per_mm / 16.0 / 1e3
    assert 14 / 2.5 < per_width < 14 * 2.5, per_width


def test_table_is_cached_and_implements_the_protocol(table):
    from gearcoupling.fea import tooth_compliance_table

    t, cache = table
    files = list(cache.glob("industrial-m2-*.json"))
    assert len(files) == 1
    again = tooth_compliance_table(load_spec("industrial-m2"), size_mm=1.0, sector=3, nz=2,
                                   nr=2, cache=cache)
    np.testing.assert_array_equal(again.hub_mm_per_N, t.hub_mm_per_N)
    np.testing.assert_array_equal(again.near_field_mm_per_N, t.near_field_mm_per_N)
    # the table depends on the solids, not on the load section: same cache entry
    loaded = load_spec("industrial-m2", **{"load.torque_Nm": 123.0, "load.stiffness": "fe"})
    tooth_compliance_table(loaded, size_mm=1.0, sector=3, nz=2, nr=2, cache=cache)
    assert list(cache.glob("industrial-m2-*.json")) == files
    far = t.hub_mm_per_N + t.sleeve_mm_per_N - t.near_field_mm_per_N.sum(axis=0)
    grid = t.pair_compliance_mm_per_N(t.z_mm[:, None], t.r_mm[None, :])
    np.testing.assert_allclose(grid, far, rtol=1e-12)
    mid = t.pair_compliance_mm_per_N(-t.z_mm.mean(), t.r_mm.mean())  # even in z, bilinear
    assert mid == pytest.approx(far.mean(), rel=1e-12)
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
    half-space part: refused with the settings to change, not a negative compliance."""
    from gearcoupling.fea import compute_compliance_table

    with pytest.raises(ArgumentError, match="sector at least 3"):
        compute_compliance_table(load_spec("industrial-m2"), size_mm=1.0, sector=1, nz=2, nr=2)


@pytest.mark.parametrize("n", [10, 20])
def test_halfspace_work_of_a_uniform_square_matches_the_closed_form(n):
    """Uniform pressure on a square of side a (total force 1 N): the mean deflection is
    (1 - nu²) / (pi E a) times the mean inverse distance of the unit square, 2.9732
    (Johnson, Contact Mechanics, ch. 3); nodal forces on an n x n grid converge to it from
    below at first order, within 2.5 % at n = 10 and 1.5 % at n = 20."""
    import math

    from gearcoupling.fea.stiffness import halfspace_work_mm_per_N

    a, E, nu = 2.0, 206_000.0, 0.3
    x = (np.arange(n) + 0.5) / n * a
    X, Y = np.meshgrid(x, x)
    pts = np.stack([X.ravel(), Y.ravel(), np.zeros(n * n)], axis=1)
    forces = np.tile([0.0, 0.0, 1.0 / n**2], (n * n, 1))
    exact = (1 - nu**2) / (math.pi * E * a) * 2.973209598247378
    work = halfspace_work_mm_per_N(pts, forces, a * a, E, nu)
    assert work == pytest.approx(exact, rel=0.025 if n == 10 else 0.015)
    # invariant under a rigid rotation of the plane and its forces
    rot = np.array([[1, 0, 0], [0, 0.6, -0.8], [0, 0.8, 0.6]])
    assert halfspace_work_mm_per_N(pts @ rot.T, forces @ rot.T, a * a, E, nu) == \
        pytest.approx(work, rel=1e-12)


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
    pytest.importorskip("gearcoupling.loading.compliance")
    from gearcoupling.clearance import sweep
    from gearcoupling.loading.cantilever import CantileverCompliance
    from gearcoupling.loading.compliance import solve_compliance
    from gearcoupling.loading.contact import contact_model, patch_centre_radius

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
    argv = ["stiffness", "industrial-m2", "--size", "1", "--sector", "3", "--nz", "2", "--nr",
            "2", "--cache", str(cache), "-o", str(tmp_path)]
    assert main(argv) == 0
    rows = list(csv.DictReader((tmp_path / "stiffness.csv").read_text().splitlines()))
    assert len(rows) == 4
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
    from gearcoupling.loading.cantilever import CantileverCompliance
    from gearcoupling.loading.compliance import solve_compliance

    t, _ = table
    spec = load_spec("industrial-m2")
    N, R = spec.tooth.teeth, spec.tooth.pitch_radius
    zeros = np.zeros((N, 1))
    out = solve_compliance(spec, zeros, zeros, np.full((N, 1), R), 400e3, t)
    nominal = CantileverCompliance(spec).root_stress_MPa(out["normal_force_N"], zeros,
                                                         np.full((N, 1), R))
    np.testing.assert_allclose(out["root_stress_MPa"], nominal, rtol=1e-12)
    assert np.all(nominal > 0)
    from gearcoupling.loading.capacity import limit_loads

    limits = limit_loads(spec, zeros, np.full((N, 1), R), t)
    assert np.all(np.isfinite(limits["bending_stress"]) & (limits["bending_stress"] > 0))
