"""The io layer: one JSON rule, strict TOML with file:line errors, one override rule."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import CSV_COLUMNS
from gearcoupling.io import (
    NonFiniteError,
    Table,
    read_toml,
    set_dotted,
    write_csv_columns,
    write_csv_rows,
    write_json,
)


def test_json_writes_infinity_as_inf_and_refuses_nan_without_writing(tmp_path):
    path = write_json(tmp_path / "a.json", {"r": math.inf, "s": [-math.inf, 1.5], "n": None})
    assert json.loads(path.read_text()) == {"r": "inf", "s": ["-inf", 1.5], "n": None}
    with pytest.raises(NonFiniteError, match=r"b.json: x\[1\] is NaN"):
        write_json(tmp_path / "b.json", {"x": [0.0, math.nan]})
    assert not (tmp_path / "b.json").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["a.json"]  # no temporary left behind


def test_toml_syntax_and_unknown_keys_are_named_by_file_and_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[tooth]\nteeth = 50\nmodule = = 2\n")
    with pytest.raises(gc.SpecError, match=r"bad.toml:3"):
        read_toml(bad)
    text = "[study]\nname = 'x'\n\n[accuracy]\nsteps = 4\nstpes = 5\n"
    t = Table({"steps": 4, "stpes": 5}, "accuracy", source="s.toml", text=text, line=4)
    t.get("steps", int)
    with pytest.raises(gc.SpecError, match=r"s.toml:6 accuracy.stpes = 5: unknown key "
                                           r"\(did you mean 'steps'\?"):
        t.done(["steps"])


def test_an_override_of_one_unit_key_replaces_its_sibling():
    """renzo-1967 gives its torque in lbf·in: an SI override replaces it (and vice versa)."""
    spec = gc.load_spec("renzo-1967", **{"load.torque_Nm": 1000.0})
    assert spec.load.torque_Nm == 1000.0
    back = gc.load_spec("renzo-1967", **{"load.torque_lbf_in": 10_000.0})
    assert back.load.torque_Nm == pytest.approx(10_000.0 * 0.112984829, rel=1e-8)
    data = {"load": {"torque_Nm": 1.0}}
    assert set_dotted(data, "load.torque_lbf_in", 2.0, {"torque_lbf_in": "torque_Nm"}) == \
        {"load": {"torque_lbf_in": 2.0}}
    assert set_dotted(data, "load.torque_lbf_in", None) == {"load": {}}


def test_overrides_are_file_keys_in_the_file_units():
    """The same key means the file's unit: inches for renzo-1967, mm for its resolved file
    (``spec.replace``)."""
    inch = gc.load_spec("renzo-1967", **{"hub.crowning.radius": 3.0})
    assert inch.hub.crowning.radius == pytest.approx(3.0 * 25.4)
    mm = gc.load_spec("renzo-1967").replace(**{"hub.crowning.radius": 76.2,
                                                "tooth.pressure_angle_deg": 25.0})
    assert mm.hub.crowning.radius == pytest.approx(76.2)
    assert math.degrees(mm.tooth.pressure_angle) == pytest.approx(25.0)


@pytest.mark.parametrize("name", gc.template_names())
def test_the_resolved_file_reads_back_to_the_same_spec(name):
    spec = gc.load_spec(name)
    again = gc.spec_from_dict(spec.to_dict(), name=spec.name)
    assert again.to_dict() == spec.to_dict()


def test_a_table_by_columns_is_the_file_its_rows_make(tmp_path):
    # floats (inf, nan, tiny, huge), numpy and Python integers, strings, booleans, None
    columns = ("x", "n", "k", "name", "flag", "empty")
    x = np.array([0.1, -1.0 / 3.0, math.inf, math.nan, 1e-300, 12345678901.5])
    n = np.arange(6, dtype=np.int64) * 1_000_003
    data = [x, n, list(range(6)), ["cw", "a,b", 'q"t', "", "ccw", "x"],
            [True, False] * 3, [None] * 6]
    rows = [tuple(col[i] for col in data) for i in range(6)]
    by_rows = write_csv_rows(tmp_path / "rows.csv", columns, rows, comments=["mm"])
    by_columns = write_csv_columns(tmp_path / "cols.csv", columns, data, comments=["mm"])
    assert by_columns.read_bytes() == by_rows.read_bytes()
    with pytest.raises(gc.GearCouplingError, match="non-finite x"):
        write_csv_columns(tmp_path / "bad.csv", columns, data, finite=True)
    assert not (tmp_path / "bad.csv").exists()


def test_sweep_csv_by_columns_is_the_file_of_its_rows(tmp_path):
    res = gc.sweep("renzo-1967", 1.0, np.arange(0.0, 360.0, 7.5))
    by_rows = write_csv_rows(tmp_path / "rows.csv", CSV_COLUMNS, res.rows())
    assert res.write_csv(tmp_path / "sweep.csv").read_bytes() == by_rows.read_bytes()
