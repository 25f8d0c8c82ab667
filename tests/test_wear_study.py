"""The wear life as a study response (issue 41): a design study and a tolerance Monte Carlo
on a real dask cluster (a ``dask scheduler`` and two ``dask worker`` processes on loopback,
the fixture of tests/test_study_dask.py), and a crown optimisation for life; each row's
life is held to ``gc.wear`` run here. Coarse wear knobs, short histories."""

from __future__ import annotations

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.study import load_study, optimise_crown, read_table, run_study
from gearcoupling.study.file import build_spec
from gearcoupling.study.tolerance import Tolerances, draw_errors, gap_offsets_rad
from test_study_dask import cluster  # noqa: F401  (the real scheduler and workers)

WEAR = """\
[set]
"wear.speed_rpm" = 1800.0
"wear.hours" = {hours}
[conditions]
misalignment_deg = 1.0
torque_Nm = 2000.0
[accuracy]
steps = 4
angle_tolerance_deg = 1e-2
wear_face_cells = 16
wear_depth_cells = 8
wear_phases = 1
"""
KNOBS = {"grid": (16, 8), "phases": 1}


def _study(tmp_path, head: str, body: str, hours: float = 100.0):
    path = tmp_path / "wear-study.toml"
    path.write_text(head + WEAR.format(hours=hours) + body)
    return load_study(path)


DESIGN = """\
[study]
base = "renzo-1967"
chunk = 2
outputs = ["wear_life_h", "q"]
"""
COEFFICIENTS = """\
[[vary]]
key = "wear.coefficient_mm3_per_Nm"
values = [1e-8, 2e-8]
"""


@pytest.mark.needs_dask
@pytest.mark.slow
def test_a_design_study_on_dask_gives_the_wear_life_of_each_sample(cluster, tmp_path):  # noqa: F811
    from distributed import Client

    study = _study(tmp_path, DESIGN, COEFFICIENTS, hours=20.0)
    with Client(cluster[0], timeout=60) as client:
        run = run_study(study, tmp_path / "out", client=client)
    rows = sorted(read_table(run.table), key=lambda r: r["sample"])
    assert [r["error"] for r in rows] == [None, None]
    base = gc.load_spec("renzo-1967").replace(**{"wear.speed_rpm": 1800.0, "wear.hours": 20.0})
    for row, k in zip(rows, (1e-8, 2e-8), strict=True):  # each row: gc.wear run here
        here = gc.wear(base.replace(**{"wear.coefficient_mm3_per_Nm": k}), 1.0, 2000.0, **KNOBS)
        assert row["wear_life_h"] == pytest.approx(here.life_h, rel=1e-12)
    assert rows[1]["wear_life_h"] < rows[0]["wear_life_h"]  # more wear per N·m: shorter


MONTE_CARLO = """\
[study]
base = "renzo-1967"
chunk = 1
seed = 7
outputs = ["K", "wear_life_h"]
[tolerances]
draws = 1
index_sd_mm = 0.004
"""


@pytest.mark.needs_dask
@pytest.mark.slow
def test_a_tolerance_monte_carlo_gives_a_life_per_draw(cluster, tmp_path):  # noqa: F811
    from distributed import Client

    study = _study(tmp_path, MONTE_CARLO, "", hours=5.0)
    with Client(cluster[0], timeout=60) as client:
        run = run_study(study, tmp_path / "out", client=client)
    (row,) = read_table(run.table)
    assert row["error"] is None and row["K"] > 0
    spec = gc.load_spec("renzo-1967").replace(**{"wear.speed_rpm": 1800.0, "wear.hours": 5.0})
    err = draw_errors(Tolerances(index_sd_mm=0.004), spec.tooth.teeth,
                      np.random.default_rng([7, 0]))  # the draw of sample 0, seed 7
    here = gc.wear(spec, 1.0, 2000.0, gap_offset_rad=gap_offsets_rad(spec, err), **KNOBS)
    assert row["wear_life_h"] == pytest.approx(here.life_h, rel=1e-12)
    ideal = gc.wear(spec, 1.0, 2000.0, **KNOBS).life_h
    assert abs(row["wear_life_h"] / ideal - 1) > 1e-3  # the draw's teeth wear on their own


OPTIMISE = """\
[study]
base = "renzo-1967"
[optimise]
angles_deg = [0.5, 1.0]
objective = "wear_life_h"
max_evaluations = 3
model = "renzo"
[[vary]]
key = "hub.crowning.radius"
range = [1.5, 3.0]
"""


@pytest.mark.slow
def test_a_crown_optimisation_for_wear_life_keeps_the_longest_life(tmp_path):
    study = _study(tmp_path, OPTIMISE, "")
    result = optimise_crown(study)
    feasible = [r for r in result.rows if r["feasible"]]
    assert feasible and result.best is not None
    assert result.best["wear_life_h"] == max(r["wear_life_h"] for r in feasible)
    assert result.best["objective"] == result.best["wear_life_h"]
    spec = build_spec(study.base_name, study.base_text,  # the best crown, in file units
                      {**study.fixed, "hub.crowning.radius": result.best["hub.crowning.radius"]})
    assert result.best["wear_life_h"] == pytest.approx(
        gc.wear(spec, 1.0, 2000.0, **KNOBS).life_h, rel=1e-12)  # at the largest angle


def test_the_wear_life_without_speed_and_hours_is_refused_naming_the_output(tmp_path):
    path = tmp_path / "no-speed.toml"
    path.write_text(DESIGN + COEFFICIENTS)
    with pytest.raises(gc.SpecError, match=r"study\.outputs.*speed_rpm and hours"):
        load_study(path)
