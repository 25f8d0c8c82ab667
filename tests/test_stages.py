"""The pipeline's stages (gearcoupling.outputs): one table of records, each stage computed
once per call in an order its needs allow, over two forked workers or in this process with
the same results; a skipped stage skips what needs it; adding a stage and a report section
is one record each."""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import dataclass

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.outputs import STAGES, SkipStage, Stage, StageSettings, compute
from gearcoupling.outputs.executor import plan
from gearcoupling.outputs.load import q_graph, study_misalignments

RUN_STEPS = ["spec", "sweep", "viewer"]  # quick, and the sweep pulls two more stages


def test_every_stage_follows_the_stages_it_needs():
    seen: set[str] = set()
    for name, stage in STAGES.items():
        assert set(stage.needs) <= seen, name
        seen.add(name)
    assert [s.name for s in plan(["sweep"])] == ["design", "backlash", "sweep"]
    assert [s.name for s in plan(["datasheet"])] == ["design", "rating", "capacity", "mass",
                                                     "datasheet"]
    with pytest.raises(gc.ArgumentError, match="bogus"):
        plan(["bogus"])


def test_q_graph_is_the_linear_capacity_at_the_study_grid():
    """Each q point is the linear model's tooth-load capacity over the aligned capacity
    (:func:`gearcoupling.capacity` at the same misalignment, 25 rotations per pitch), at
    the study grid."""
    spec = gc.load_spec("renzo-1967")
    pts = q_graph(spec, spec.design_misalignment_deg).points
    assert len(pts) == 7
    assert [p.misalignment_deg for p in pts] == list(study_misalignments(spec))
    for p in pts[::3]:
        c = gc.capacity(spec, p.misalignment_deg, model="linear")
        assert p.q_linear == pytest.approx(c.criteria_Nm["tooth_load"] / c.aligned_capacity_Nm,
                                           rel=1e-12)


@dataclass(frozen=True)
class Toy:
    smallest_backlash_mm: float


def _toy(inputs):
    sw = inputs.get("sweep", gc.SweepResult)
    return Toy(float(np.min(sw.backlash_mm)))


def _toy_files(toy, inputs, folder):
    from gearcoupling.io import write_text

    return [write_text(folder / "toy.txt", f"{toy.smallest_backlash_mm!r}\n")]


@pytest.fixture
def toy_stage(monkeypatch):
    """A toy stage (the smallest backlash of the sweep), added with one record."""
    stages = dict(STAGES)
    stages["toy"] = Stage("toy", "the smallest backlash", ("sweep",), _toy, _toy_files, 0.1)
    monkeypatch.setattr("gearcoupling.outputs.registry.STAGES", stages)
    return stages


@pytest.mark.parametrize("workers", [1, 2])
def test_a_stage_is_one_record_and_computes_once_from_its_needs(toy_stage, tmp_path,
                                                                workers):
    spec = gc.load_spec("industrial-m2")
    res = compute(spec, StageSettings(angles=36), ["toy"], folder=tmp_path, workers=workers)
    sw = res.get("sweep", gc.SweepResult)
    toy = res.get("toy", Toy)
    assert toy.smallest_backlash_mm == float(np.min(sw.backlash_mm))
    fresh = gc.sweep(spec, spec.design_misalignment_deg, np.arange(36) * 10.0)
    assert np.array_equal(sw.backlash_mm, fresh.backlash_mm)
    assert float((tmp_path / "toy.txt").read_text()) == toy.smallest_backlash_mm
    assert set(res.values) == {"design", "backlash", "sweep", "toy"}


def test_a_toy_report_section_is_one_record(toy_stage, tmp_path, monkeypatch):
    """A section renders a stage's result and judges it; the report computes its stage."""
    from gearcoupling.reporting import sections
    from gearcoupling.reporting.document import Note
    from gearcoupling.reporting.verdict import PASS, Verdict
    from gearcoupling.reporting.view import ReportSection

    def render(view):
        return [Note(f"toy backlash {view.get('toy', Toy).smallest_backlash_mm:.6f} mm")]

    def verdicts(view):
        toy = view.get("toy", Toy)
        return [Verdict("toy: some backlash", f"{toy.smallest_backlash_mm:.6f} mm", "> 0",
                        "toy", PASS)] if toy else []

    monkeypatch.setattr(sections, "SECTIONS", (
        ReportSection("toy", "A toy", ("toy",), render, verdicts),))
    spec = gc.load_spec("industrial-m2")
    res = gc.report(spec, tmp_path, angles=36, workers=1)
    text = res.html.read_text(encoding="utf-8")
    value = float((tmp_path / "toy.txt").read_text())
    assert f"toy backlash {value:.6f} mm" in text and 'id="toy"' in text
    assert "toy: some backlash" in text and res.verdict == "pass"


def test_a_skipped_stage_skips_the_stages_that_need_it(toy_stage, tmp_path, monkeypatch):
    def no(inputs):
        raise SkipStage("no reason to")

    stages = dict(toy_stage, sweep=Stage("sweep", "refused", (), no, None, 0.1))
    monkeypatch.setattr("gearcoupling.outputs.registry.STAGES", stages)
    res = compute(gc.load_spec("industrial-m2"), StageSettings(), ["toy"])
    assert res.skipped == {"sweep": "no reason to", "toy": "needs sweep: no reason to"}
    assert not res.has("toy")


def test_a_run_without_torque_skips_its_loads(tmp_path):
    spec = gc.load_spec("industrial-m2").replace(**{"load.torque_Nm": None})
    res = gc.run(spec, tmp_path, only=["spec", "load", "load_study"], workers=1)
    assert set(res.skipped) == {"load", "load_study"}
    assert "no torque" in res.skipped["load"]
    summary = json.loads((tmp_path / "run_summary.json").read_text())
    assert summary["skipped"] == res.skipped and summary["files"] == ["spec.json"]


def test_an_error_in_a_stage_stops_the_workers_and_is_raised(toy_stage, tmp_path,
                                                             monkeypatch):
    def broken(inputs):
        raise ValueError("broken toy")

    stages = dict(toy_stage, toy=Stage("toy", "broken", ("spec",), broken, None, 5.0))
    monkeypatch.setattr("gearcoupling.outputs.registry.STAGES", stages)
    import multiprocessing

    with pytest.raises(ValueError, match="broken toy"):
        compute(gc.load_spec("industrial-m2"), StageSettings(), ["toy", "sections"],
                folder=tmp_path, workers=2)
    assert multiprocessing.active_children() == []


@pytest.mark.slow
def test_two_workers_write_the_same_files_as_one(tmp_path):
    """The forked workers write byte-identical files; the summary says two workers were
    used and gives every stage's time."""
    one = gc.run(gc.load_spec("industrial-m2"), tmp_path / "one", only=RUN_STEPS, workers=1)
    code = (f"import gearcoupling as gc; gc.run(gc.load_spec('industrial-m2'), "
            f"{str(tmp_path / 'two')!r}, only={RUN_STEPS!r}, workers=2)")
    subprocess.run([sys.executable, "-c", code], check=True)
    two = json.loads((tmp_path / "two" / "run_summary.json").read_text())
    assert one.workers == 1 and two["workers"] == 2
    assert two["files"] == [p.name for p in one.files[:-1]]  # the same order
    assert set(two["step_seconds"]) == {"spec", "design", "backlash", "sweep", "viewer"}
    assert all(s > 0 for s in two["step_seconds"].values())
    for name in ("spec.json", "sweep.csv", "sweep_summary.json", "backlash_over_turn.csv"):
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()


def test_stages_are_checked_before_anything_is_written(tmp_path):
    with pytest.raises(gc.ArgumentError, match="stl"):
        gc.run(gc.load_spec("industrial-m2"), tmp_path / "x", only=["spec", "stl"])
    with pytest.raises(gc.ArgumentError, match="workers"):
        gc.run(gc.load_spec("industrial-m2"), tmp_path / "x", workers=3)
    with pytest.raises(gc.ArgumentError, match="angles"):
        gc.run(gc.load_spec("industrial-m2"), tmp_path / "x", angles=0)
    assert not (tmp_path / "x").exists()


def test_the_cli_forks_beside_its_signal_watcher(tmp_path):
    """``gearcoupling run`` uses two workers on two cores: the CLI's signal-watching thread
    (which only waits on a socket) does not stop the fork (it did: one worker)."""
    code = ("import sys; "
            "from gearcoupling.cli import main; "
            f"sys.exit(main(['run', 'renzo-1967', '--only', 'spec,viewer', '--workers', '2', "
            f"'-o', {str(tmp_path)!r}]))")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)
    assert json.loads((tmp_path / "run_summary.json").read_text())["workers"] == 2
