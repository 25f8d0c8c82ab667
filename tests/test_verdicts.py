"""Verdicts only against limits: "not judged" where no limit is set, ISO 1328-1:2013 classes.

The class limits are checked against the standard's formulas worked by hand for the
renzo-1967 hub (d = 127 mm, m_n = 2.54 mm, b = 12.7 mm) and against the class step
sqrt(2); a measured part with a 0.15 mm thick tooth error is "not judged" without limits
and fails once a thickness limit is set.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.hob import MAX_HOB_DIAMETER_MM, check_hob_diameter
from gearcoupling.inspection import LIMITS, grade_limits
from gearcoupling.inspection.iso1328 import iso_round_um, tolerances_um
from inspection_synth import synthetic_hub


def test_class_6_limits_of_renzo_match_the_formulas_worked_by_hand(renzo):
    # class 6: step sqrt(2); f_pT = (0.127 + 1.016 + 5) 1.4142 = 8.69 -> 8.5 (0.5 um steps)
    # F_pT = (0.254 + 0.55 sqrt(127) + 1.778 + 12) 1.4142 = 28.61 -> 29, F_rT = 25.75 -> 26
    # f_HaT = (1.016 + 0.127 + 4) 1.4142 = 7.27 -> 7.5, f_HbT = (0.563 + 1.247 + 4) 1.4142
    # = 8.22 -> 8.0
    lim = grade_limits(renzo, 6)
    expected_um = {"fpt": 8.5, "Fp": 29.0, "Fr": 26.0, "f_Halpha": 7.5, "f_Hbeta": 8.0}
    assert {k: round(v * 1e3, 3) for k, v in lim.items()} == expected_um
    assert set(lim) < set(LIMITS)  # crown height and thickness have no ISO 1328 limit


def test_two_classes_double_every_tolerance_before_rounding():
    for grade in range(1, 10):
        a, b = tolerances_um(500.0, 8.0, 100.0, grade), tolerances_um(500.0, 8.0, 100.0,
                                                                       grade + 2)
        for key in a:  # rounding moves a value by at most half its step (1 um above 10)
            assert b[key] == pytest.approx(2 * a[key], abs=1.5), (grade, key)


@pytest.mark.parametrize("value, rounded", [(12.49, 12.0), (12.5, 13.0), (7.27, 7.5),
                                            (5.0, 5.0), (4.96, 5.0), (4.94, 4.9),
                                            (0.349, 0.3)])
def test_rounding_follows_clause_5_2_3(value, rounded):
    assert iso_round_um(value) == rounded


def test_classes_and_sizes_outside_the_standard_are_refused(renzo):
    for grade in (0, 12, 5.5, True):
        with pytest.raises(gc.ArgumentError, match="1 \\(finest\\) to 11"):
            grade_limits(renzo, grade)
    tiny = gc.spec_from_dict({"tooth": {"teeth": 40, "module": 0.3, "pressure_angle_deg": 20},
                              "hub": {"face_width": 5.0, "crowning": {"radius": 12.0}}})
    with pytest.raises(gc.ArgumentError, match=r"module m_n .* outside ISO 1328-1:2013's range"):
        grade_limits(tiny, 6)


@pytest.fixture(scope="module")
def thick_scan(renzo, tmp_path_factory):
    """A hub whose teeth are 0.15 mm too thick and whose tooth 4 is indexed 10 um."""
    path = tmp_path_factory.mktemp("scan") / "thick.xyz"
    np.savetxt(path, synthetic_hub(renzo, per_flank=120, thickness_mm=0.15,
                                   index_mm={4: 0.01}))
    return path


def test_no_limits_means_not_judged_never_pass(renzo, thick_scan):
    rep = gc.compare_part(renzo, thick_scan, coarse="none", fit_points=3000)
    assert rep.part["pass"] is None
    assert rep.passed is None and "pass" not in rep.rows()[0]
    assert rep.part["not_judged"] == list(LIMITS)
    thickness = next(v for v in rep.part["verdicts"] if v["limit"] == "thickness")
    assert thickness["measured_mm"] == pytest.approx(0.15, rel=0.02)
    assert thickness["verdict"] == "not judged" and thickness["reason"] == "no limit set"


def test_a_set_limit_judges_only_its_quantity(renzo, thick_scan):
    rep = gc.compare_part(renzo, thick_scan, coarse="none", fit_points=3000,
                          limits={"thickness": 0.05})
    assert rep.part["pass"] is False
    by = {v["limit"]: v["verdict"] for v in rep.part["verdicts"]}
    assert by["thickness"] == "fail"
    assert {k for k, v in by.items() if v == "not judged"} == set(LIMITS) - {"thickness"}


def test_compare_prints_not_judged_and_grade_verdicts(thick_scan, tmp_path, capsys):
    argv = ["compare", "renzo-1967", str(thick_scan), "-o", str(tmp_path), "--coarse", "none",
            "--fit-points", "3000"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "PASS" not in out and "NOT JUDGED: no limit is set" in out
    assert out.count("not judged (no limit set)") == len(LIMITS)
    # class 6: the 10 um index error fails f_pT = 8.5 um; thickness stays not judged
    assert main([*argv, "--grade", "6"]) == 1
    out = capsys.readouterr().out
    fpt = next(line for line in out.splitlines() if line.strip().startswith("fpt"))
    assert "limit 8.50 um" in fpt and fpt.endswith("FAIL")
    assert "not judged: C_beta, thickness" in out
    assert main([*argv, "--grade", "6", "--limit", "fpt=0.02", "--limit", "Fr=0.05"]) == 0
    assert "PASS on the limits set" in capsys.readouterr().out


def test_hob_diameter_range(renzo):
    depth = 3.175 + 2.54  # dedendum 0.125 in + module
    assert check_hob_diameter(renzo, 80.0) == 80.0
    with pytest.raises(gc.ArgumentError, match=r"too small to carry teeth 5\.715 mm deep"):
        check_hob_diameter(renzo, 2 * depth)
    with pytest.raises(gc.ArgumentError, match="larger than any hob made") as err:
        check_hob_diameter(renzo, 1e9)
    assert f"{math.sqrt(depth * (1e9 - depth)):.4g} mm" in str(err.value)
    assert check_hob_diameter(renzo, MAX_HOB_DIAMETER_MM) == MAX_HOB_DIAMETER_MM
