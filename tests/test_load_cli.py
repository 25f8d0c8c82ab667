"""``gearcoupling load`` / ``capacity`` outputs and the machine loads of the summary."""

import csv
import json

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import sweep
from gearcoupling.cli import main
from gearcoupling.loading import load_from_sweep
from gearcoupling.loading.summary import machine_loads

ISSUE_COLUMNS = ("theta_deg", "tooth", "flank", "gap_angle_deg", "deflection_mm",
                 "tangential_force_N", "normal_force_N", "contact_z_mm", "contact_r_mm",
                 "max_pressure_MPa", "interior_pressure_MPa", "edge_load_share",
                 "patch_length_mm", "patch_width_mm", "edge_contact")
SUMMARY_KEYS = ("torque_Nm", "model", "max_tooth_load_N", "q", "load_sharing_factor",
                "teeth_in_contact", "max_pressure_MPa", "mesh_torsional_stiffness_Nm_per_rad",
                "radial_force_N", "tilting_moment_Nm", "axial_force_N",
                "max_sliding_velocity_mm_per_rad", "pv_max_MPa_mm_per_rad_per_tooth",
                "archard_index_N_mm_per_rev_per_tooth")


def test_load_command_writes_csv_and_summary(tmp_path):
    out = tmp_path / "o"
    code = main(["load", "renzo-1967", "--angles", "8", "--torque", "-1500", "--quick-plots",
                 "-o", str(out)])
    assert code == 0
    with open(out / "load.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert tuple(rows[0])[:len(ISSUE_COLUMNS)] == ISSUE_COLUMNS
    assert len(rows) == 8 * 50 and {r["flank"] for r in rows} == {"cw"}
    total = sum(float(r["tangential_force_N"]) for r in rows[:50])
    assert total * gc.load_spec("renzo-1967").tooth.pitch_radius * 1e-3 == pytest.approx(
        1500, rel=1e-6)
    summary = json.loads((out / "load_summary.json").read_text())
    assert all(k in summary for k in SUMMARY_KEYS)
    json.dumps(summary, allow_nan=False)
    assert (out / "load_tooth_load.png").stat().st_size > 0


def test_load_prints_its_findings_and_exits_1_when_a_limit_is_exceeded(tmp_path, capsys):
    """Each load limit printed with its verdict; a root bending stress over the allowable
    (as load_summary.json's limits say) is a finding: exit status 1 (README)."""
    argv = ["load", "renzo-1967", "--angles", "8", "--no-plots", "--model", "linear",
            "-o", str(tmp_path)]
    assert main([*argv, "--torque", "1000"]) == 0
    printed = capsys.readouterr().out
    assert "pass: root bending stress ≤ allowable" in printed and "FAIL" not in printed
    assert main([*argv, "--torque", "6000"]) == 1
    printed = capsys.readouterr().out
    limits = json.loads((tmp_path / "load_summary.json").read_text())["limits"]
    assert "root bending stress exceeds the allowable" in limits
    assert "FAIL: root bending stress ≤ allowable" in printed


def test_capacity_command_writes_the_curve(tmp_path):
    out = tmp_path / "c"
    assert main(["capacity", "renzo-1967", "--compare", "renzo-1967-vari-crown", "--max", "1",
                 "--count", "2", "--no-plots", "-o", str(out)]) == 0
    with open(out / "capacity.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["spec"] for r in rows] == ["renzo-1967"] * 2 + ["renzo-1967-vari-crown"] * 2
    assert all(float(r["capacity_Nm"]) > 0 and r["governing"] for r in rows)
    # K N P_i R at zero misalignment for the tooth-load criterion (equal sharing)
    spec = gc.load_spec("renzo-1967")
    expect = 0.8 * 50 * spec.load.allowable_tooth_load_N * spec.tooth.pitch_radius * 1e-3
    assert float(rows[0]["tooth_load_Nm"]) == pytest.approx(expect, rel=1e-9)


@pytest.mark.parametrize("argv, field", [(["--angles", "0"], "--angles"),
                                         (["--torque", "nan"], "torque"),
                                         (["--misalignment", "7"], "misalignment")])
def test_bad_load_arguments_exit_2_with_one_line(tmp_path, capsys, argv, field):
    code = main(["load", "renzo-1967", "-o", str(tmp_path / "x"), "--no-plots", *argv])
    err = capsys.readouterr().err.strip()
    assert code == 2 and field in err and len(err.splitlines()) == 1
    assert not (tmp_path / "x" / "load.csv").exists()


def test_machine_loads_balance_when_aligned_without_friction():
    spec = gc.load_spec("renzo-1967", **{"load.friction": 0.0})
    sw = sweep(spec, 0.0, [0.0, 3.6])
    res = load_from_sweep(sw, torque_Nm=2000.0)
    ml = machine_loads(res)
    # the sleeve pushes back with exactly -T about the axis, no net radial force, no moment
    np.testing.assert_allclose(ml["torque_about_axis_Nm"], -2000.0, rtol=1e-9)
    assert np.all(ml["radial_force_N"] < 1e-9 * 2000e3 / spec.tooth.pitch_radius)
    assert np.all(ml["tilting_moment_Nm"] < 1e-9 * 2000.0)


def test_additional_moment_grows_with_misalignment_and_friction():
    """Wei Fig. 13: the additional moment increases with the misalignment angle."""
    spec = gc.load_spec("renzo-1967")
    dry = spec.replace(**{"load.friction": 0.0})
    moments, frictionless = [], []
    for i in (0.25, 0.5, 1.0):
        angles = np.linspace(0, 7.2, 4, endpoint=False)
        moments.append(np.mean(machine_loads(load_from_sweep(sweep(spec, i, angles)))
                               ["tilting_moment_Nm"]))
        frictionless.append(np.mean(machine_loads(load_from_sweep(sweep(dry, i, angles)))
                                    ["tilting_moment_Nm"]))
    assert moments[0] < moments[1] < moments[2]
    assert all(f < m for f, m in zip(frictionless, moments, strict=True))


def test_plots_return_figures_and_accept_ax():
    from gearcoupling.loading.plots import (
        plot_capacity,
        plot_patches,
        plot_q_graph,
        plot_tooth_load,
        plot_vs_misalignment,
    )
    from gearcoupling.plots import new_figure

    spec = gc.load_spec("renzo-1967")
    res = load_from_sweep(sweep(spec, 1.0, [0.0, 3.6]))
    fig, ax = new_figure()
    assert plot_tooth_load(res, ax=ax) is fig
    assert plot_patches(res).axes
    assert plot_q_graph({"x": [(0.25, 0.22)]}, ax=ax) is fig
    assert plot_vs_misalignment([0.5, 1.0], {"a": [1.0, 2.0]}, "y", ax=ax) is fig
    rows = gc.capacity_curve(gc.load_spec("renzo-1967"), [0.0, 0.5], angles_deg=[0.0])
    assert plot_capacity({"s": rows}, ax=ax) is fig


def test_run_skips_the_load_step_of_a_spec_without_torque(tmp_path, capsys):
    spec = tmp_path / "no-torque.toml"
    spec.write_text("[tooth]\nteeth = 38\nmodule = 2\n[hub]\nface_width = 20\n"
                    "[hub.crowning]\nkind = \"circular\"\nradius = 38\n")
    assert main(["run", str(spec), "--only", "load", "-o", str(tmp_path / "out")]) == 0
    assert "skipped: no [load] torque_Nm" in capsys.readouterr().err
    assert not (tmp_path / "out" / "load.csv").exists()


def test_run_and_load_say_what_the_report_will_judge_of_the_capacity(tmp_path, capsys):
    """The showcase's torque (Renzo's 20 000 lb in) is over the default model's capacity
    at 1° times K: ``run`` says so in one line and ``load`` fails the check, as the report
    does, with K in the row (a newcomer saw ``run`` and ``load`` pass and the report fail)."""
    spec = gc.load_spec("renzo-1967")
    cap = gc.capacity(spec, 1.0)
    K = spec.load.accuracy_factor
    assert abs(spec.load.torque_Nm) > cap.capacity_Nm  # the finding the lines must carry
    assert main(["run", "renzo-1967", "--only", "rating", "-o", str(tmp_path / "r")]) == 0
    err = capsys.readouterr().err
    line = next(ln for ln in err.splitlines() if "capacity at 1°" in ln)
    assert f"{cap.capacity_Nm:.4g} N·m = K × {cap.capacity_Nm / K:.4g} N·m" in line
    assert "is UNDER the torque" in line and f"K = {K:g}" in line
    rating = json.loads((tmp_path / "r" / "rating.json").read_text())
    assert rating["holds"] is False and rating["capacity_Nm"] == pytest.approx(
        cap.capacity_Nm, rel=1e-12)
    argv = ["load", "renzo-1967", "--no-plots", "-o", str(tmp_path / "l")]
    assert main(argv) == 1
    out = capsys.readouterr().out
    row = next(ln for ln in out.splitlines() if "torque ≤ capacity" in ln)
    assert row.strip().startswith("FAIL") and f"K = {K:g}" in row
