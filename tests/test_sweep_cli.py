"""``gearcoupling sweep`` and the run step: files, columns, summary, bad input."""

from __future__ import annotations

import csv
import json

import pytest

from gearcoupling.clearance import CSV_COLUMNS
from gearcoupling.cli import main


def test_sweep_command_writes_csv_json_and_plots(tmp_path, capsys):
    out = tmp_path / "o"
    code = main(["sweep", "renzo-1967", "--misalignment", "1", "--angles", "12", "-o",
                 str(out), "--quick-plots"])
    assert code == 0
    with open(out / "sweep.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    assert tuple(rows[0]) == CSV_COLUMNS
    assert len(rows) - 1 == 12 * 50 * 2
    flanks = {r[2] for r in rows[1:]}
    assert flanks == {"cw", "ccw"}
    clear = [float(r[3]) for r in rows[1:]]
    normal = [float(r[4]) for r in rows[1:]]
    assert all(n < c for n, c in zip(normal, clear, strict=True))  # r_b / r < 1
    summary = json.loads((out / "sweep_summary.json").read_text())
    z0_in = summary["renzo_z0_mm"] / 25.4
    assert z0_in == pytest.approx(0.00105, abs=5e-6)
    assert 1.5 < summary["binding_angle_deg"] < summary["critical_misalignment_deg"] < 2.5
    for name in ("sweep_clearance.png", "sweep_contact_path.png", "sweep_clearance_map.png"):
        assert (out / name).stat().st_size > 10_000
    assert [p.name for p in out.glob(".*")] == [".gearcoupling.json"]  # no temporary left
    printed = capsys.readouterr().out.split()
    assert str(out / "sweep.csv") in printed


def test_sweep_command_defaults_to_the_design_angle(tmp_path):
    out = tmp_path / "d"
    assert main(["sweep", "industrial-m2", "--angles", "4", "-o", str(out), "--no-plots",
                 "--no-design"]) == 0
    summary = json.loads((out / "sweep_summary.json").read_text())
    assert summary["misalignment_deg"] == pytest.approx(0.75)
    assert "critical_misalignment_deg" not in summary


@pytest.mark.parametrize("argv, needle", [
    (["--misalignment", "7"], "--misalignment"),
    (["--angles", "0"], "--angles"),
])
def test_sweep_command_bad_input_exits_2(tmp_path, capsys, argv, needle):
    code = main(["sweep", "renzo-1967", "-o", str(tmp_path / "x"), "--no-plots", *argv])
    assert code == 2
    assert needle in capsys.readouterr().err
    assert not (tmp_path / "x" / "sweep.csv").exists()


def test_run_has_the_sweep_step():
    from gearcoupling.outputs import STEPS

    assert "sweep" in STEPS


def test_sweep_prints_its_results_and_exits_1_on_a_finding(tmp_path, capsys):
    """The critical angle, the binding angle and the smallest backlash are printed as in
    sweep_summary.json, with a progress bar on stderr; past the binding angle the teeth
    bind: a finding, exit status 1 (README)."""
    out = tmp_path / "o"
    assert main(["sweep", "renzo-1967", "--angles", "24", "--no-plots", "-o", str(out)]) == 0
    got = capsys.readouterr()
    summary = json.loads((out / "sweep_summary.json").read_text())
    assert f"{summary['critical_misalignment_deg']:.4f}°" in got.out
    assert f"{summary['binding_angle_deg']:.4f}°" in got.out
    assert f"{summary['min_backlash_mm'] * 1e3:.2f} µm at least" in got.out
    assert "FAIL" not in got.out and "3/3" in got.err  # the bar, finished
    assert main(["sweep", "renzo-1967", "--angles", "24", "--no-plots", "--misalignment",
                 "3", "-o", str(out)]) == 1
    printed = capsys.readouterr().out
    assert "FAIL: teeth do not bind" in printed and "FAIL: contact stays off" in printed
    assert summary["binding_angle_deg"] < 3 and summary["critical_misalignment_deg"] < 3
