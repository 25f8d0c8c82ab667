"""The command line, called in-process."""

import json

import pytest

from gearcoupling.cli import main
from gearcoupling.io.lock import RECORD_NAME
from gearcoupling.outputs import run_files


def test_spec_json_has_derived_values(capsys):
    assert main(["spec", "renzo-1967", "--json", "--set", "hub.crowning.radius=3.0"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["hub"]["crowning"]["radius"] == pytest.approx(76.2)
    d = data["derived"]
    assert d["pitch_radius_mm"] == pytest.approx(63.5)
    assert d["base_radius_mm"] == pytest.approx(63.5 * 0.9396926207859084)
    # Renzo eq. 4 with R_c = 3 in, i = 1 deg
    tan_i, tan_phi = 0.017455064928217585, 0.36397023426620234
    assert d["renzo_z0_mm"] == pytest.approx(0.5 * 76.2 * tan_i**2 / tan_phi)


def test_spec_table_output(capsys):
    assert main(["spec", "industrial-m2"]) == 0
    out = capsys.readouterr().out
    assert "aligned_backlash_mm" in out and "renzo_z0_mm" in out


def test_spec_tables_piped_keep_the_files_order_and_say_not_set(capsys):
    """Piped (capsys: not a terminal, 80 columns): every heading on one line, the
    sections in the spec's order (a table before its sub-tables), unset inspection limits
    as "not set", never "inf"."""
    assert main(["spec", "renzo-1967", "--set", "inspection.fpt=0.02"]) == 0
    lines = capsys.readouterr().out.splitlines()
    heads = [line for line in lines if line.startswith("[")]
    assert heads == ["[renzo-1967]", "[tooth]", "[hub]", "[hub.tip]", "[hub.root]",
                     "[hub.crowning]", "[hub.body]", "[sleeve]", "[inspection]", "[load]",
                     "[material.hub]", "[material.sleeve]", "[derived]"]
    start = lines.index("[inspection]")
    block = lines[start:lines.index("[load]")]
    assert any("fpt" in line and "0.508" in line for line in block)  # 0.02 in, in mm
    assert sum("not set" in line for line in block) == 6
    assert not any(" inf " in line for line in block)


@pytest.mark.slow
def test_sections_and_run_write_files(tmp_path, capsys):
    assert main(["sections", "industrial-m2", "-o", str(tmp_path / "s")]) == 0
    png = tmp_path / "s" / "sections.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["run", "industrial-m2", "-o", str(tmp_path / "r")]) == 0
    spec = json.loads((tmp_path / "r" / "spec.json").read_text())
    assert spec["name"] == "industrial-m2" and spec["tooth"]["teeth"] == 38
    written = {p.name for p in (tmp_path / "r").iterdir()}
    assert {"sections.png", "hub.stl", "sleeve.stl", "hub.step", "sleeve.step", "sweep.csv",
            "sweep_summary.json", "interference.json", "viewer.html"} <= written
    # no temporary files left behind: the one hidden file is the record of the settings
    assert [n for n in written if n.startswith(".")] == [RECORD_NAME]
    assert written - {RECORD_NAME} <= set(run_files())  # each checked before any work


def test_run_only_and_skip_choose_steps(tmp_path):
    assert main(["run", "renzo-1967", "-o", str(tmp_path), "--only", "spec,sections,parts",
                 "--skip", "parts"]) == 0
    assert {p.name for p in tmp_path.iterdir()} == {"spec.json", "sections.png",
                                                    "crown_profile.csv", "run_summary.json",
                                                    RECORD_NAME}
    summary = json.loads((tmp_path / "run_summary.json").read_text())
    assert set(summary["step_seconds"]) == {"spec", "sections"}
    assert summary["files"] == ["spec.json", "crown_profile.csv", "sections.png"]


@pytest.mark.parametrize("argv, words", [
    (["spec", "renzo-1967", "--set", "hub.face_width=-1"], "hub.face_width = -1.0 in (-25.4 mm)"),
    (["spec", "renzo-1967", "--set", "hub.crowning.radius=0.01"], "hub.crowning.radius"),
    (["spec", "nope"], "templates"),
    (["spec", "renzo-1967", "--set", "oops"], "KEY=VALUE"),
    (["run", "renzo-1967", "--only", "spec,stl"], "--only = 'stl'"),
])
def test_bad_input_exits_2_with_a_clear_message(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_sections_shows_a_progress_bar(tmp_path, capsys):
    assert main(["sections", "industrial-m2", "-o", str(tmp_path)]) == 0
    got = capsys.readouterr()
    assert "sections industrial-m2" in got.err and "1/1" in got.err
    assert got.out.strip() == str(tmp_path / "sections.png")


@pytest.mark.parametrize("where", ["starting", "running"])
def test_an_interruption_leaves_no_bar_behind(where, monkeypatch, capsys):
    """A Ctrl-C that lands while the progress bar starts (before its first update) or
    while it runs: stderr (a pipe here) gets no frame of the bar, only the command's one
    line (a finished bar stays: test_sections_shows_a_progress_bar). Before, one landing
    while it started left the bar's last frame beside that line (seen once in the suite:
    ``capacity  0/13 0:00:00 -:--:--``)."""
    from rich.progress import Progress

    from gearcoupling.commands.common import progress

    original = Progress.add_task

    def added_then_interrupted(self, *args, **kwargs):
        original(self, *args, **kwargs)
        raise KeyboardInterrupt  # the signal lands just after the bar's task exists

    if where == "starting":
        monkeypatch.setattr(Progress, "add_task", added_then_interrupted)
    with pytest.raises(KeyboardInterrupt), progress("work", 3) as update:
        update(1, 3)
        raise KeyboardInterrupt
    assert capsys.readouterr().err.strip() == ""  # rich ends a transient bar with a newline


def test_templates_lists_every_template(capsys):
    import gearcoupling as gc

    assert main(["templates"]) == 0
    out = capsys.readouterr().out
    assert all(name in out for name in gc.template_names())
    # each description is the header's whole first sentence, not cut at the line's end
    from gearcoupling.commands.templates import description
    from gearcoupling.io import bundled_dir

    joined = " ".join(out.split())
    for name in gc.template_names():
        text = description((bundled_dir("templates") / f"{name}.toml").read_text())
        assert text.endswith(".") and len(text) > 60, text
        assert f"{name} {text}" in joined


def test_atomic_writes_leave_the_old_file_on_failure_and_use_the_usual_mode(tmp_path):
    import os

    from gearcoupling.io import atomic_path, write_text

    target = tmp_path / "a.txt"
    write_text(target, "old")
    assert oct(target.stat().st_mode & 0o777) == oct(0o666 & ~_umask())
    with pytest.raises(RuntimeError), atomic_path(target) as tmp:
        tmp.write_text("half")
        raise RuntimeError("writer failed")
    assert target.read_text() == "old" and os.listdir(tmp_path) == ["a.txt"]


def _umask() -> int:
    import os

    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_plots_return_figures_draw_on_given_axes_and_never_switch_the_backend(tmp_path):
    import subprocess
    import sys

    # a user's interactive back-end survives importing and using the plot functions
    code = ("import matplotlib; matplotlib.use('svg'); import matplotlib.pyplot as plt\n"
            "import gearcoupling as gc\n"
            "from gearcoupling.plots import sections_figure, plot_sections\n"
            "spec = gc.load_spec('industrial-m2')\n"
            "fig = sections_figure(spec, 0.01)\n"
            f"plot_sections(spec, {str(tmp_path / 's.png')!r}, 0.01)\n"
            "print(matplotlib.get_backend(), type(fig).__name__, len(plt.get_fignums()))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["svg", "Figure", "0"]  # backend kept, a Figure, nothing left in pyplot
    assert (tmp_path / "s.png").read_bytes()[:4] == b"\x89PNG"

    from matplotlib.figure import Figure

    from gearcoupling.plots import sections_figure

    fig = Figure()
    axes = fig.subplots(1, 3)
    assert sections_figure(gc_spec(), 0.01, ax=axes) is fig
    assert all(a.has_data() for a in axes)
    assert all(a.get_xlabel() and a.get_ylabel() for a in axes)  # the sections' axis too
    with pytest.raises(ValueError, match="3 axes"):
        sections_figure(gc_spec(), 0.01, ax=axes[:2])


def gc_spec():
    import gearcoupling as gc

    return gc.load_spec("industrial-m2")


def test_the_program_exits_with_the_status_its_handlers_run_and_its_output_is_whole():
    """``console`` (the installed program, ``python -m gearcoupling``) leaves out the
    interpreter's teardown: the status, the exit handlers and the piped output stay."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}

    def program(*argv: str) -> subprocess.CompletedProcess:
        code = ("import atexit, sys\n"
                "atexit.register(lambda: print('handler ran', flush=True))\n"
                f"sys.argv = ['gearcoupling', *{list(argv)!r}]\n"
                "from gearcoupling.cli import console\nconsole()\n")
        return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              env=env, timeout=300)

    ok = program("spec", "renzo-1967", "--json")
    assert ok.returncode == 0, ok.stderr
    text, handler = ok.stdout.rsplit("}", 1)
    assert json.loads(text + "}")["derived"]["pitch_radius_mm"] == pytest.approx(63.5)
    assert handler.strip() == "handler ran"
    bad = program("spec", "no-such-template")
    assert bad.returncode == 2 and "gearcoupling: error:" in bad.stderr
    assert bad.stdout.strip() == "handler ran"
    module = subprocess.run([sys.executable, "-m", "gearcoupling", "templates"],
                            capture_output=True, text=True, env=env, timeout=300)
    assert module.returncode == 0 and "renzo-1967" in module.stdout.split()
