"""What a newcomer meets in the first hour (issue 39, items 6 and 7): ``capacity`` and
``datasheet`` print their numbers, the data sheet's progress a step per solve, the setup
script says what it does before the long install, ``spec --json`` prints the mm values an
inch file means, the data sheet's and a study's plots read without guessing."""

from __future__ import annotations

import csv
import json
import math
import os
import re
import shutil
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from fresh_python import run_fresh
from gearcoupling.cli import main
from gearcoupling.forked import can_fork

ROOT = Path(__file__).resolve().parents[1]
M2 = "industrial-m2"

# --------------------------------------------------------------------------- capacity


def test_capacity_prints_capacity_governing_criterion_and_k_per_misalignment(tmp_path,
                                                                          capsys):
    """Per spec and misalignment: the capacity (K applied), its governing criterion and K,
    the numbers of capacity.csv, before the paths of the files."""
    out = tmp_path / "cap"
    assert main(["capacity", M2, "--misalignments", "0.5,1.5", "--model", "compliance",
                 "--no-plots", "-o", str(out)]) == 0
    lines = capsys.readouterr().out.splitlines()
    rows = list(csv.DictReader(line for line in (out / "capacity.csv").read_text(
        encoding="utf-8").splitlines() if not line.startswith("#")))
    assert lines[0].startswith(f"{M2}: capacity per misalignment (compliance model), critical "
                               "misalignment ")
    assert len(rows) == 2
    k = gc.load_spec(M2).load.accuracy_factor
    for row in rows:
        printed = next(line.split() for line in lines
                       if line.split()[:1] == [f"{float(row['misalignment_deg']):.3g}"])
        assert float(printed[1]) == pytest.approx(float(row["capacity_Nm"]), rel=5e-4)
        assert " ".join(printed[2:-1]) == row["governing"].replace("_", " ")
        assert float(printed[-1]) == k
    assert lines[-1] == str(out / "capacity.csv")


# --------------------------------------------------------------------------- datasheet


@pytest.mark.skipif(not can_fork(), reason="needs the fork start method")
def test_datasheet_progress_has_a_step_per_solve_from_both_workers():
    """In two forked workers (a fresh interpreter: forking needs one without threads) the
    progress counts every step: the masses, the capacity, the matrix, each torque of the
    wind-up curve but the operating one, each capacity of the allowable misalignment's
    search (as many as the search solved: counted here by wrapping the library's
    capacity in each worker) and the turn there; done never falls, is below the total
    until the end, and ends at it."""
    out = run_fresh(f"""
        import json
        import gearcoupling as gc
        from gearcoupling.rotordynamics import allowable

        solved = allowable.capacity
        def counted(*args, **kwargs):
            print("search", flush=True)  # from the worker that runs the search
            return solved(*args, **kwargs)
        allowable.capacity = counted

        calls = []
        data = gc.coupling_data(gc.load_spec("{M2}"), model="compliance", rotations=1,
                                turn_angles=4, workers=2,
                                progress=lambda d, t: calls.append((d, t)))
        print(json.dumps({{"calls": calls, "curve": len(data.torsion.torque_Nm)}}))
    """)
    lines = out.splitlines()
    result = json.loads(lines[-1])
    calls, searched = result["calls"], lines.count("search")
    steps = 2 + 1 + (result["curve"] - 1) + searched + 1
    assert searched >= 1
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[-1] == steps
    assert calls[-1] == [steps, steps]
    assert all(d < t for d, t in calls[:-1])
    assert sorted(set(done)) == list(range(steps + 1))  # every step told, one at a time


@pytest.mark.skipif(not can_fork(), reason="needs the fork start method")
def test_forked_map_passes_each_items_ticks_to_the_parent():
    run_fresh("""
        import os
        from gearcoupling.forked import ForkedMap

        def work(n, tick):
            for _ in range(n):
                tick()
            return os.getpid()

        for workers in (2, 1):
            ticks = []
            started = ForkedMap(work, [3, 4, 5], workers, ticking=True)
            try:
                pids = started.results(tick=lambda: ticks.append(1))
            finally:
                started.stop()
            assert len(ticks) == 12, (workers, ticks)
            assert (os.getpid() in pids) == (workers == 1), pids
        assert_no_child_left("a worker")
    """)


# --------------------------------------------------------------------------- spec --json


def test_spec_json_prints_the_mm_values_without_the_conversions_rounding(capsys):
    """renzo-1967 is an inch file: 5.2 in is 132.08 mm, printed so (not
    132.07999999999998); every number to 12 significant digits of the spec's own; infinity as the
    project's JSON writes it, "inf"."""
    assert main(["spec", "renzo-1967", "--json"]) == 0
    text = capsys.readouterr().out
    assert re.search(r'"diameter": 132\.08,?\n', text) and "132.0799" not in text
    assert not re.search(r"\d\.\d*(9999|0000)\d+", text), text
    spec = gc.load_spec("renzo-1967")
    printed, own = json.loads(text), spec.to_dict()
    assert printed["hub"]["crowning"]["end_radius"] == "inf"

    def close(a, b, where):
        if isinstance(b, dict):
            for k in b:
                close(a[k], b[k], f"{where}.{k}")
        elif isinstance(b, float) and math.isfinite(b):
            assert a == pytest.approx(b, rel=5e-12, abs=0), where

    close(printed, own, "spec")


# --------------------------------------------------------------------------- README


def test_readme_report_example_writes_where_the_cli_does():
    """The README's Python example gives gc.report the folder `gearcoupling report
    renzo-1967` writes into (its report.html there), the folder gc.run gets too."""
    from gearcoupling.io import default_output_dir

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = text.split("```python\n", 1)[1].split("```", 1)[0]
    spec = re.search(r'gc\.load_spec\("([^"]+)"\)', block).group(1)
    run_out = re.search(r'gc\.run\(spec, "([^"]+)"\)', block).group(1)
    report_out = re.search(r'gc\.report\(spec, "([^"]+)"\)', block).group(1)
    assert Path(report_out) == Path(run_out) == default_output_dir(spec)


# --------------------------------------------------------------------------- plots


def _allowable(moment_Nm):
    from gearcoupling.rotordynamics import AllowableLoads

    psi = np.linspace(0.0, 360.0, moment_Nm.size, endpoint=False)
    return AllowableLoads(1.0, "capacity", 2.0, 1.0, "bending_stress", 2260.0, psi,
                          moment_Nm, 0.5 * np.sin(np.radians(psi)), 30.0 + 0 * psi,
                          226.0 + 0 * psi)


def test_bending_moment_ticks_read_as_the_values():
    """A bending moment even to 1e-4 over the turn (246.13 N·m): the tick labels carry no
    offset ("+2.461e2" over ticks of 0.01-0.05) and read in the hundreds, as the moment
    does."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from gearcoupling.rotordynamics import plot_allowable_loads

    psi = np.linspace(0.0, 360.0, 72, endpoint=False)
    fig = plot_allowable_loads(_allowable(246.13 + 0.02 * np.cos(np.radians(8 * psi))))
    FigureCanvasAgg(fig).draw()  # the labels and the offset are made at the draw
    for ax in fig.axes:
        assert ax.yaxis.get_offset_text().get_text() == ""
    moment = fig.axes[0]
    values = [float(t.get_text().replace("−", "-")) for t in moment.get_yticklabels()
              if t.get_text()]
    lo, hi = moment.get_ylim()
    shown = [v for v in values if lo <= v <= hi]
    assert max(shown) >= 200 and lo <= 0.0 + 1e-9, (shown, lo, hi)
    assert hi > 1.05 * 246.15  # the line clear of the frame


ROWS_6 = [{"hub.crowning.radius": R, "tooth.pressure_angle_deg": pa, "sleeve.tip_chamfer": ch,
           "critical_misalignment_deg": 0.03 * R * pa / 20 if 0.03 * R * pa / 20 <= 6 else None,
           "error": None}
          for pa in (20.0, 25.0, 30.0) for ch in (0.2, 0.5)
          for R in (25.0, 40.0, 60.0, 100.0, 140.0, 200.0)]
GROUP = ["tooth.pressure_angle_deg", "sleeve.tip_chamfer"]


def test_study_lines_on_each_other_all_stay_visible():
    """Six groups, the tip chamfer changing nothing: each pair of lines lies on each
    other. Every line's own colour still shows in the picture (at least a tenth of the
    pixels of the line drawn alone)."""
    from matplotlib.colors import to_rgb

    from gearcoupling.browser import png_pixels
    from gearcoupling.plots import figure_png
    from gearcoupling.study.plots import plot_study

    def pixels_of(rows, colour):
        fig = plot_study(rows, "hub.crowning.radius", "critical_misalignment_deg", GROUP)
        fig.axes[0].get_legend().remove()  # the lines' own pixels only
        rgb = np.array(to_rgb(colour)) * 255
        return int(np.sum(np.abs(png_pixels(figure_png(fig, 80)) - rgb).max(axis=-1) < 30))

    groups = sorted({(r[GROUP[0]], r[GROUP[1]]) for r in ROWS_6}, key=str)
    for k, key in enumerate(groups):
        alone = [r for r in ROWS_6 if (r[GROUP[0]], r[GROUP[1]]) == key]
        shown = pixels_of(ROWS_6, f"C{k}")
        # drawn alone, the line is the first: colour C0
        assert shown > 0.1 * pixels_of(alone, "C0"), (key, shown)


def test_study_plot_labels_its_axes_with_units_and_draws_angles_above_6_deg():
    """x label from the key with the study's length unit; critical misalignments above
    6° (empty in the rows) drawn at 6° and counted in the legend; rows with an error left
    out and counted."""
    from gearcoupling.study.plots import plot_study

    rows = [*ROWS_6, {**ROWS_6[0], "error": "refused"}]
    fig = plot_study(rows, "hub.crowning.radius", "critical_misalignment_deg", GROUP,
                     units="in")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "hub crowning radius (in)"
    assert ax.get_ylabel() == "critical misalignment (°)"
    above = [(r["hub.crowning.radius"], 6.0) for r in ROWS_6
             if r["critical_misalignment_deg"] is None]
    assert above
    drawn = {(float(x), float(y)) for line in ax.get_lines()
             for x, y in zip(line.get_xdata(), line.get_ydata(), strict=True)}
    assert set(above) <= drawn
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert f"none up to 6° ({len(above)}, drawn at 6°)" in labels
    assert "left out: 1 row with an error" in labels
    assert "tooth pressure angle = 20°, sleeve tip chamfer = 0.2 in" in labels


def test_study_plots_take_the_units_of_the_studys_spec():
    from gearcoupling.study import load_study
    from gearcoupling.study.plots import study_units

    assert study_units(load_study("renzo-capacity-vs-crown")) == "in"
    assert study_units(load_study("wei-fig14")) == "mm"


# --------------------------------------------------------------------------- setup script


FAKE_PYTHON = """#!/bin/bash
# python3 for the setup scripts' tests: makes a venv of itself, "installs" slowly
echo "$(basename "$0") $*" >> "$FAKE_LOG"
case "$1 $2" in
    "-m venv") mkdir -p "$3/bin" && cp "$0" "$3/bin/python" ;;
    "-m pip") echo "PIP $*" >&2; sleep "$FAKE_PIP_SECONDS" ;;
    "-m gearcoupling") echo "gearcoupling ${*:3}" ;;
esac
"""


@pytest.fixture
def fake_checkout(tmp_path):
    """A checkout with the real scripts and a pyproject.toml, and a fake python3 on PATH."""
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    for name in ("setup.sh", "run.sh"):
        shutil.copy(ROOT / "scripts" / name, repo / "scripts" / name)
    (repo / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "python3").write_text(FAKE_PYTHON)
    (bin_dir / "python3").chmod(0o755)
    env = {**os.environ, "PATH": f"{bin_dir}:{os.environ['PATH']}",
           "FAKE_LOG": str(tmp_path / "calls.log")}
    return repo, env


def _script(repo, env, name, *args, pip_s=0.0, beat_s=5.0, **kw):
    env = {**env, "FAKE_PIP_SECONDS": str(pip_s), "GEARCOUPLING_SETUP_HEARTBEAT": str(beat_s)}
    return subprocess.run(["bash", str(repo / "scripts" / name), *args], env=env,
                          capture_output=True, text=True, timeout=60, **kw)


def test_setup_says_what_it_does_before_pip_and_beats_while_it_works(fake_checkout):
    repo, env = fake_checkout
    done = _script(repo, env, "setup.sh", pip_s=1.0, beat_s=0.2)
    assert done.returncode == 0, done.stderr
    err = done.stderr.splitlines()
    assert err[0].startswith("setup: setting up .venv: installing gearcoupling and its "
                             "dependencies")
    first_pip = next(i for i, line in enumerate(err) if line.startswith("PIP"))
    assert first_pip > 0
    beats = [i for i, line in enumerate(err) if line.startswith("setup: still installing")]
    assert beats and first_pip < beats[0] < len(err) - 1, err
    assert done.stdout.splitlines()[-1] == str(repo / ".venv" / "bin" / "python")
    # set up: silent, no pip
    again = _script(repo, env, "setup.sh")
    assert again.returncode == 0 and again.stderr == ""
    assert again.stdout == f"{repo / '.venv' / 'bin' / 'python'}\n"


def test_run_sh_says_it_before_pip_and_leaves_nothing_behind(fake_checkout):
    """run.sh through setup.sh: the line before pip, then the run; its heartbeat does not
    hold the pipe run.sh reads (the whole takes far less than one beat of 5 s)."""
    repo, env = fake_checkout
    t0 = time.monotonic()
    done = _script(repo, env, "run.sh", "renzo-1967", pip_s=0.2, beat_s=5.0)
    assert time.monotonic() - t0 < 4.0
    assert done.returncode == 0, done.stderr
    assert done.stdout == "gearcoupling run renzo-1967\n"
    err = done.stderr
    assert err.index("setup: setting up .venv") < err.index("PIP")
    assert "still installing" not in err


def test_setup_interrupted_exits_130_and_its_heartbeat_ends(fake_checkout, tmp_path):
    """Ctrl-C (SIGINT to the whole process group) during pip: exit 130, and nothing of
    the script left running, the heartbeat included."""
    from fresh_python import session_alive

    repo, env = fake_checkout
    env = {**env, "FAKE_PIP_SECONDS": "30", "GEARCOUPLING_SETUP_HEARTBEAT": "0.2"}
    proc = subprocess.Popen(["bash", str(repo / "scripts" / "setup.sh")], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        log = tmp_path / "calls.log"
        while "-m pip" not in (log.read_text() if log.exists() else ""):
            assert time.monotonic() < deadline and proc.poll() is None
            time.sleep(0.05)
        time.sleep(0.5)  # a beat or two
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=10)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130, err
    assert "still installing" in err
    assert session_alive(proc.pid) == []
