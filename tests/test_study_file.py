"""Study files: parsing, validation naming file:line and key, sampling, per-sample refusal."""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.errors import SpecError
from gearcoupling.study import evaluate, load_study, samples, study_names
from gearcoupling.study.file import OUTPUTS, TOLERANCE_OUTPUTS


def write(tmp_path, body: str):
    path = tmp_path / "s.toml"
    path.write_text(textwrap.dedent(body))
    return path


HEAD = """\
[study]
base = "renzo-1967"
outputs = ["min_backlash_mm"]
"""


def refuse(tmp_path, body: str, *needles: str):
    with pytest.raises(SpecError) as err:
        load_study(write(tmp_path, body))
    for needle in needles:
        assert needle in str(err.value), str(err.value)
    return str(err.value)


def test_unknown_spec_key_names_line_and_key(tmp_path):
    refuse(tmp_path, HEAD + '[[vary]]\nkey = "hub.crowning.raduis"\nvalues = [2.0]\n',
           "s.toml:5", "hub.crowning.raduis", "unknown key")


def test_unknown_study_key_and_output(tmp_path):
    refuse(tmp_path, HEAD + "[accuracy]\ntolerence_mm = 1e-6\n", "s.toml:5",
           "accuracy.tolerence_mm", "unknown key")
    refuse(tmp_path, '[study]\nbase = "renzo-1967"\noutputs = ["capacity_kNm"]\n',
           "s.toml:3", "capacity_kNm", "unknown output")


def test_empty_range_names_line(tmp_path):
    refuse(tmp_path, HEAD + '\n[[vary]]\nkey = "hub.crowning.radius"\nrange = [3.0, 3.0]\n'
           "steps = 4\n", "s.toml:6", "empty range")


def test_range_outside_spec_limits(tmp_path):
    msg = refuse(tmp_path, HEAD + '[[vary]]\nkey = "tooth.pressure_angle_deg"\n'
                 "range = [10.0, 20.0]\nsteps = 3\n", "s.toml:5", "tooth.pressure_angle_deg",
                 "refused by the spec")
    assert "14.5" in msg  # the spec's own limit is quoted
    refuse(tmp_path, HEAD + '[[vary]]\nkey = "misalignment_deg"\nvalues = [1.0, 7.0]\n',
           "s.toml:5", "must be a finite angle from 0.0 to 6.0 degrees")


def test_grid_is_the_cartesian_product_in_order(tmp_path):
    s = load_study(write(tmp_path, HEAD + '[[vary]]\nkey = "hub.crowning.radius"\n'
                         'range = [1.0, 3.0]\nsteps = 3\n[[vary]]\nkey = "misalignment_deg"\n'
                         "values = [0.5, 1.0]\n"))
    got = [(d["hub.crowning.radius"], d["misalignment_deg"]) for d in samples(s)]
    assert got == [(r, m) for r in (1.0, 2.0, 3.0) for m in (0.5, 1.0)]


def test_latin_hypercube_is_seeded_and_stratified(tmp_path):
    body = ('[study]\nbase = "renzo-1967"\nmethod = "lhs"\nsamples = 16\nseed = 7\n'
            'outputs = ["min_backlash_mm"]\n[[vary]]\nkey = "hub.crowning.radius"\n'
            'range = [1.0, 5.0]\n[[vary]]\nkey = "misalignment_deg"\nrange = [0.0, 2.0]\n')
    a, b = samples(load_study(write(tmp_path, body))), samples(load_study(write(tmp_path, body)))
    assert a == b
    for key, lo, hi in (("hub.crowning.radius", 1.0, 5.0), ("misalignment_deg", 0.0, 2.0)):
        u = (np.array([d[key] for d in a]) - lo) / (hi - lo)
        assert sorted(np.floor(u * 16).astype(int)) == list(range(16))  # one per stratum


def test_refused_combination_becomes_a_row(tmp_path):
    # each value alone is a valid renzo-1967 spec; together (R_c = 0.6 in, face 0.7 in) the
    # crown turns past the 45° the spec allows, so that sample is a row with the reason
    s = load_study(write(tmp_path, HEAD + '[[vary]]\nkey = "hub.crowning.radius"\n'
                         'values = [0.6]\n[[vary]]\nkey = "hub.face_width"\nvalues = [0.5, 0.7]\n'))
    rows = [evaluate(s.payload(), d) for d in samples(s)]
    assert rows[0]["error"] is None and rows[0]["min_backlash_mm"] > 0
    assert rows[1]["error"].startswith("SpecError") and rows[1]["min_backlash_mm"] is None


def test_rows_equal_single_spec_calls(tmp_path):
    from gearcoupling.clearance.design import critical_misalignment_deg, min_backlash_rad

    s = load_study(write(tmp_path, '[study]\nbase = "renzo-1967"\noutputs = '
                         '["critical_misalignment_deg", "min_backlash_mm"]\n[accuracy]\n'
                         'angle_tolerance_deg = 1e-2\nsteps = 4\n[[vary]]\n'
                         'key = "hub.crowning.radius"\nvalues = [2.0]\n'))
    row = evaluate(s.payload(), samples(s)[0])
    spec = gc.load_spec("renzo-1967", **{"hub.crowning.radius": 2.0})
    assert row["critical_misalignment_deg"] == critical_misalignment_deg(spec, tolerance_deg=1e-2)
    assert row["min_backlash_mm"] == min_backlash_rad(
        spec, 1.0, steps=4) * spec.tooth.pitch_radius
    assert row["spec_hash"] == gc.study.spec_hash(spec) and row["version"] == gc.__version__


def test_bundled_studies_load():
    names = study_names()
    assert {"wei-fig14", "renzo-tolerances", "renzo-capacity-vs-crown",
            "renzo-crown-optimum"} <= set(names)
    for name in names:
        s = load_study(name)
        if s.optimise is not None:  # bounds, not samples
            assert all(q.low < q.high for q in s.parameters)
            continue
        allowed = TOLERANCE_OUTPUTS if s.tolerances else OUTPUTS
        assert set(s.outputs) <= set(allowed) and len(samples(s)) >= 2


def test_tolerance_study_rows_are_seeded_per_sample(tmp_path):
    from gearcoupling.study.tolerance import Tolerances, summarise_rows, tolerance_sample

    s = load_study(write(tmp_path, '[study]\nbase = "renzo-1967"\nseed = 5\n[accuracy]\n'
                         'steps = 1\n[tolerances]\ndraws = 3\npitch_mm = 0.006\n'
                         'hub_runout_mm = 0.01\n'))
    assert s.tolerances["values"]["pitch_sd_mm"] == pytest.approx(0.002)  # limit / 3
    items = samples(s)
    assert [d["draw"] for d in items] == [0, 1, 2]
    rows = [evaluate(s.payload(), d, n) for n, d in enumerate(items)]
    spec = gc.load_spec("renzo-1967")
    for n, row in enumerate(rows):
        direct = tolerance_sample(spec, 1.0, Tolerances(pitch_sd_mm=0.002, hub_runout_mm=0.01),
                                  5, n, steps=1)
        assert row["K"] == direct["K"] < 1.0 and row["error"] is None
    summary = summarise_rows(s, rows)
    assert len(summary) == 1 and summary[0]["samples"] == 3
    assert summary[0]["K_mean"] == pytest.approx(np.mean([r["K"] for r in rows]), rel=1e-12)


def test_tolerance_table_refuses_mixed_forms(tmp_path):
    refuse(tmp_path, '[study]\nbase = "renzo-1967"\n[tolerances]\npitch_mm = 0.006\n'
           "pitch_sd_mm = 0.002\n", "tolerances.pitch_mm", "limit or a standard deviation")


def test_load_outputs_equal_the_load_package(tmp_path):
    from gearcoupling.loading import load
    from gearcoupling.loading.capacity import capacity

    s = load_study(write(tmp_path, '[study]\nbase = "renzo-1967"\noutputs = ["max_tooth_load_N",'
                         ' "q", "capacity_Nm"]\n[conditions]\ntorque_Nm = 1500.0\n'
                         'load_model = "linear"\n[accuracy]\nload_angles = 8\n[[vary]]\n'
                         'key = "misalignment_deg"\nvalues = [0.5]\n'))
    row = evaluate(s.payload(), samples(s)[0])
    spec = gc.load_spec("renzo-1967")
    res = load(spec, 0.5, np.arange(8) * 45.0, torque_Nm=1500.0, model="linear")
    assert row["max_tooth_load_N"] == float(np.max(res.tangential_force_N)) > 0
    assert row["q"] == res.q() and row["torque_Nm"] == 1500.0
    assert row["capacity_Nm"] == capacity(spec, 0.5, model="linear").capacity_Nm


def test_top_level_api_is_lazy():
    import subprocess
    import sys

    code = ("import sys, gearcoupling as gc; assert 'dask' not in sys.modules; "
            "from gearcoupling.study import load_study, run_study; "
            "assert gc.load_study is load_study and gc.run_study is run_study; "
            "assert 'pyarrow' not in sys.modules and 'distributed' not in sys.modules")
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.parametrize("name", study_names())
def test_every_bundled_study_runs_one_evaluation(name):
    """The first sample of each bundled study (the optimiser: the middle of its bounds)
    evaluates without error, every requested output present and finite or None (no limit
    reached within the range); a tolerance study's K lies in (0, 1]."""
    from gearcoupling.study.file import optimise_options
    from gearcoupling.study.optimise import crown_row

    s = load_study(name)
    if s.optimise is not None:
        row = crown_row(s, {q.key: 0.5 * (q.low + q.high) for q in s.parameters},
                        optimise_options(s))
        wanted = ["capacity_mean_Nm", "capacity_min_Nm", "critical_misalignment_deg"]
    else:
        row = evaluate(s.payload(), samples(s)[0])
        wanted = list(s.outputs)
    assert row.get("error") is None, row.get("error")
    for key in wanted:
        v = row[key]
        assert v is None or math.isfinite(v), (key, v)
    if s.tolerances:
        assert 0.0 < row["K"] <= 1.0
