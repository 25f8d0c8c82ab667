"""Crown optimisation: every evaluation a row, constraints applied, the best is the best."""

from __future__ import annotations

import json

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.study import read_table
from gearcoupling.study.optimise import capacity_curve_Nm

STUDY = """\
[study]
base = "renzo-1967"
[accuracy]
steps = 1
angle_tolerance_deg = 1e-2
[optimise]
angles_deg = [0.5, 1.5]
max_evaluations = 6
model = "renzo"
compare = ["renzo-1967"]
[[vary]]
key = "hub.crowning.radius"
range = [1.0, 6.0]
"""


def test_optimisation_rows_constraints_and_best(tmp_path):
    path = tmp_path / "opt.toml"
    path.write_text(STUDY)
    out = tmp_path / "out"
    assert main(["study", str(path), "-o", str(out), "--no-plots"]) == 0
    rows = read_table(out / "study.parquet")
    report = json.loads((out / "optimum.json").read_text())
    assert 3 <= len(rows) <= 7 and [r["evaluation"] for r in rows] == list(range(len(rows)))
    for r in rows:
        spec = gc.load_spec("renzo-1967", **{"hub.crowning.radius": r["hub.crowning.radius"]})
        cap = capacity_curve_Nm(spec, [0.5, 1.5], model="renzo", steps=1)
        assert r["capacity_0.5deg_Nm"] == cap[0] and r["capacity_1.5deg_Nm"] == cap[1]
        crit = r["critical_misalignment_deg"]
        # feasible exactly when the contact stays off the face ends up to 1.5° and no binding
        assert r["feasible"] == ((crit is None or crit >= 1.5) and r["min_backlash_mm"] > 0)
    feasible = [r for r in rows if r["feasible"]]
    assert any(not r["feasible"] for r in rows) and feasible  # the bound is active
    best = report["best"]
    assert best["objective"] == max(r["objective"] for r in feasible)
    assert best["objective"] == best["capacity_mean_Nm"]
    base = report["capacity_curves_Nm"]["renzo-1967"]
    assert base["1.5"] == capacity_curve_Nm(gc.load_spec("renzo-1967"), [1.5], model="renzo",
                                            steps=1)[0]
