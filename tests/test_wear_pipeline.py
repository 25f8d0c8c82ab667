"""The wear history in the pipeline and the report (issue 41): the stage ``wear`` runs where
the spec's ``[wear]`` (or the settings) gives a speed and hours, writes what ``gc.wear``
computes, and the report's wear section judges the life against ``[wear] required_life_h``
only where the spec sets one. Coarse knobs (16 x 8 cells, one rotation per pitch)."""

from __future__ import annotations

import csv
import dataclasses
import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.outputs import Results, StageSettings, run_files
from gearcoupling.outputs.files import RUN_SUMMARY, WEAR
from gearcoupling.outputs.wear import NOT_ASKED
from gearcoupling.reporting import ReportSettings
from gearcoupling.reporting import sections as report_sections
from gearcoupling.reporting.build import report_stages
from gearcoupling.reporting.document import Figure, Note, Section, Table, render
from gearcoupling.reporting.verdict import FAIL, OPEN, PASS
from gearcoupling.reporting.view import View

KNOBS = {"wear_grid": (16, 8), "wear_phases": 1}
POINT = {"misalignment_deg": 1.0, "torque_Nm": 2000.0}
REQUIRED_H = 1e5  # far beyond the life at 1°, 2000 N·m (some thousand hours): a FAIL


@pytest.fixture(scope="module")
def worn(renzo, tmp_path_factory):
    """renzo-1967 with a ``[wear]`` table (200 h at 1800 rpm, a required life), its stage
    ``wear`` run alone: ``(spec, folder, RunResult)``."""
    spec = renzo.replace(**{"wear.speed_rpm": 1800.0, "wear.hours": 200.0,
                            "wear.required_life_h": REQUIRED_H})
    out = tmp_path_factory.mktemp("wear-stage")
    res = gc.run(spec, out, only=["wear"], workers=1, **POINT, **KNOBS)
    return spec, out, res


def test_wear_is_a_default_stage_only_where_the_spec_asks(renzo, worn):
    spec = worn[0]
    assert not StageSettings().wear_asked(renzo)
    assert StageSettings().wear_asked(spec)
    assert StageSettings(wear_hours=10.0, wear_speed_rpm=900.0).wear_asked(renzo)
    assert not set(WEAR) & set(run_files())  # renzo-1967's run is as it was
    assert set(WEAR) <= set(run_files(wear=True))
    assert "wear" not in report_stages(ReportSettings(), 1, renzo)
    assert "wear" in report_stages(ReportSettings(), 1, spec)


def test_the_stage_writes_what_gc_wear_computes(worn):
    spec, out, res = worn
    assert [p.name for p in res.files] == [*WEAR, RUN_SUMMARY]
    assert res.skipped == {}
    direct = gc.wear(spec, POINT["misalignment_deg"], POINT["torque_Nm"], grid=(16, 8),
                     phases=1)  # speed and hours: the spec's [wear]
    assert direct.duty[0].speed_rpm == 1800.0 and direct.hours_requested == 200.0
    written = json.loads((out / "wear_summary.json").read_text())
    assert written == json.loads(json.dumps(direct.summary()))
    assert written["steps"] >= 1 and written["max_depth_mm"]["hub"] > 0
    with open(out / "wear.csv", newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    assert len(rows) == direct.steps + 2  # the header, then a row per state
    assert all(math.isfinite(float(x)) for r in rows[1:] for x in r)


def test_without_wear_the_stage_is_skipped_with_its_reason(renzo, tmp_path):
    res = gc.run(renzo, tmp_path / "r", only=["wear"], workers=1)
    assert res.skipped == {"wear": NOT_ASKED}
    assert [p.name for p in res.files] == [RUN_SUMMARY]


@pytest.mark.parametrize("given, missing", [({"wear_hours": 100.0}, "wear_speed_rpm"),
                                            ({"wear_speed_rpm": 900.0}, "wear_hours")])
def test_one_wear_setting_without_the_other_is_refused_before_any_work(renzo, tmp_path,
                                                                       given, missing):
    out = tmp_path / "r"
    with pytest.raises(gc.ArgumentError, match=missing):
        gc.run(renzo, out, **given)
    assert not out.exists()


def test_a_bad_wear_value_of_the_spec_is_refused_before_any_work(renzo, tmp_path):
    spec = renzo.replace(**{"wear.speed_rpm": -5.0, "wear.hours": 100.0})
    out = tmp_path / "r"
    with pytest.raises(gc.SpecError, match=r"wear\.speed_rpm"):
        gc.run(spec, out, only=["spec"])
    assert not out.exists()


@pytest.mark.parametrize("command", ["run", "report"])
def test_cli_wear_option_without_its_pair_exits_2_naming_it(tmp_path, capsys, command):
    out = tmp_path / "r"
    code = main([command, "renzo-1967", "--wear-hours", "100", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "--wear-speed" in err, err
    assert not out.exists()


# --------------------------------------------------------------------------- the report


def _view(spec, out, results) -> View:
    s = ReportSettings(**POINT, **KNOBS)
    return View(spec, s, s.resolve(spec), results, out)


def test_the_wear_section_shows_the_life_its_band_and_the_plots(worn):
    spec, out, res = worn
    view = _view(spec, out, res.results)
    blocks = report_sections.wear(view)
    summary = json.loads((out / "wear_summary.json").read_text())
    table = next(b for b in blocks if isinstance(b, Table))
    rows = {r[0]: r for r in table.rows}
    assert rows["life to the wear limit"][1] == pytest.approx(summary["life_h"], rel=1e-12)
    lo, hi = summary["life_band_h"]
    assert rows["life across the grease band"][1] == f"{lo:.4g} – {hi:.4g}"
    figures = [b for b in blocks if isinstance(b, Figure)]
    assert [f.data_file for f in figures] == ["wear_depth.csv", "wear.csv"]
    assert all(f.png == (out / name).read_bytes()
               for f, name in zip(figures, ("wear_maps.png", "wear_history.png"), strict=True))
    page = render("t", "s", ("open", "x"), [Section("wear", "Wear", blocks)])
    assert 'href="wear.csv"' in page and 'href="wear_depth.csv"' in page


def test_the_life_is_judged_against_the_required_life_with_its_band(worn):
    spec, out, res = worn
    summary = json.loads((out / "wear_summary.json").read_text())
    (row,) = report_sections.wear_verdicts(_view(spec, out, res.results))
    assert summary["life_h"] < REQUIRED_H and row.verdict == FAIL
    lo, hi = summary["life_band_h"]
    assert row.band_crosses == (lo < REQUIRED_H <= hi)
    assert row.source == "[wear] required_life_h"
    result = res.results.get("wear", gc.WearResult)
    easy = dataclasses.replace(result, settings=dataclasses.replace(
        result.settings, required_life_h=0.5 * summary["life_h"]))
    (row,) = report_sections.wear_verdicts(_view(spec, out, Results({"wear": easy})))
    assert row.verdict == PASS


def test_without_a_required_life_the_life_is_not_judged(worn):
    spec, out, res = worn
    result = res.results.get("wear", gc.WearResult)
    free = dataclasses.replace(result, settings=dataclasses.replace(
        result.settings, required_life_h=None))
    (row,) = report_sections.wear_verdicts(_view(spec, out, Results({"wear": free})))
    assert row.verdict == OPEN and "[wear] required_life_h" in row.reason
    # no wear computed (a spec without [wear]): no row, the report's verdict as it was
    assert report_sections.wear_verdicts(_view(spec, out, Results())) == []


def test_partial_slip_is_said_in_the_section(worn):
    spec, out, res = worn
    result = res.results.get("wear", gc.WearResult)
    stats = dict(result.stats)
    stats["partial_slip_share"] = np.full_like(stats["partial_slip_share"], 0.25)
    slipping = dataclasses.replace(result, stats=stats)
    notes = [b.text for b in report_sections.wear(_view(spec, out, Results({"wear": slipping})))
             if isinstance(b, Note)]
    assert any("partial slip (fretting): 25 %" in n for n in notes)
    stats["partial_slip_share"] = np.zeros_like(stats["partial_slip_share"])
    gross = dataclasses.replace(result, stats=stats)
    notes = [b.text for b in report_sections.wear(_view(spec, out, Results({"wear": gross})))
             if isinstance(b, Note)]
    assert not any("partial slip" in n for n in notes)


@pytest.mark.parametrize("options, field", [
    ({"wear_hours": float("nan"), "wear_speed_rpm": 900.0}, "wear_hours"),
    ({"wear_hours": 10.0, "wear_speed_rpm": -1.0}, "wear_speed_rpm"),
    ({"wear_hours": 1e300, "wear_speed_rpm": 900.0}, "wear_hours"),
    ({"wear_grid": (2, 8)}, "wear_grid"),
    ({"wear_grid": "16x8"}, "wear_grid"),
    ({"wear_phases": 0}, "wear_phases"),
])
def test_bad_wear_settings_are_refused_naming_the_field(options, field):
    with pytest.raises(gc.ArgumentError, match=field):
        StageSettings(**options)


def test_a_spec_name_is_drawn_as_written_in_the_wear_plots(worn):
    from gearcoupling.wear import plot_wear_history, plot_wear_maps

    result = worn[2].results.get("wear", gc.WearResult)
    hostile = dataclasses.replace(result, spec=result.spec.replace(name="a$b_{x}$"))
    for fig in (plot_wear_maps(hostile), plot_wear_history(hostile)):
        assert fig.get_suptitle().startswith(r"a\$b_{x}\$: "), fig.get_suptitle()
