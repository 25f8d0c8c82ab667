"""The program touches only what it made (issue 38, items 2, 3 and 11): temporaries only
gearcoupling names, removed by a sweep that leaves look-alikes alone; no write through a
planted symbolic link (FE decks and solver files included); an error names the target,
never its temporary; every target checked before any work; one command at a time in a
folder, and a note of the files an earlier command made there with other settings."""

from __future__ import annotations

import contextlib
import csv
import os
import signal
import string
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.io import lock_folder, remove_stale_temporaries, write_text
from gearcoupling.io.atomic import PREFIX, temporary_mark
from gearcoupling.io.lock import LOCK_NAME, RECORD_NAME

HOB = ["hob", "renzo-1967", "--hob-diameter", "80"]
HOB_FILES = {"hob_path.csv", "hob_program.nc", "hob.json"}
QUICK_RUN = ["run", "renzo-1967", "--only", "spec,sections"]
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
#: the names of the issue: a user's files deleted by ``gearcoupling hob ... -o THAT_FOLDER``
ISSUE_NAMES = (".thesis.4000000.draft_v2.tex", ".bashrc.12.backup01.bak")


def _dead_pid() -> int:
    """The pid of a child that has ended and been reaped."""
    proc = subprocess.Popen([sys.executable, "-c", ""])
    proc.wait()
    return proc.pid


def _temporaries(folder: Path) -> list[Path]:
    return [p for p in folder.rglob(f"{PREFIX}*")]


def _state(folder: Path) -> dict[str, int]:
    """Every entry under ``folder`` with its time: what a command that made, removed or
    wrote anything there would change. (The folder's own time is left out: checking that
    it can be written into, the command makes and removes a probe in it.)"""
    return {str(p.relative_to(folder)): p.lstat().st_mtime_ns for p in folder.rglob("*")}


# ------------------------------------------------------------------ the sweep of temporaries


def test_a_users_files_named_like_old_temporaries_survive_a_command(tmp_path, capsys):
    """Issue 38 item 2: these two files in the output folder were deleted by ``hob``."""
    for name in ISSUE_NAMES:
        (tmp_path / name).write_text(f"the user's {name}")
    assert main([*HOB, "-o", str(tmp_path)]) == 0
    for name in ISSUE_NAMES:
        assert (tmp_path / name).read_text() == f"the user's {name}"
    assert {p.name for p in tmp_path.iterdir()} == {*ISSUE_NAMES, *HOB_FILES, RECORD_NAME}


_CHARS = string.ascii_letters + string.digits + "_"
_DEAD = _dead_pid()
_PIDS = st.one_of(st.just(_DEAD), st.integers(4_194_305, 9_999_999_999))
_SUFFIXES = st.sampled_from(["", ".tex", ".bak", ".json", ".stl", ".tmp", ".d"])
_OLD_FORM = st.builds(lambda x, pid, r, ext: f".{x}.{pid}.{r}{ext}",
                      st.text(_CHARS + ".-", min_size=1, max_size=20), _PIDS,
                      st.text(_CHARS, min_size=8, max_size=8), _SUFFIXES)
_WRONG_MARK = st.builds(lambda pid, mark, r, ext: f"{PREFIX}{pid}-{mark}-{r}{ext}",
                        _PIDS, st.text("0123456789abcdef", min_size=8, max_size=8),
                        st.text(string.ascii_lowercase + string.digits + "_", min_size=8,
                                max_size=8), _SUFFIXES
                        ).filter(lambda n: n.split("-")[2] != temporary_mark(
                            int(n.split("-")[1])))
_ALTERED = st.builds(lambda pid, r, ext, change: change(
    f"{PREFIX}{pid}-{temporary_mark(pid)}-{r}{ext}"), _PIDS,
    st.text(string.ascii_lowercase + string.digits, min_size=8, max_size=8), _SUFFIXES,
    st.sampled_from([str.upper, lambda n: n[1:], lambda n: n + "~", lambda n: "x" + n,
                     lambda n: n.replace("-", ".", 1), lambda n: n.replace("-", "", 1)]))


@settings(max_examples=60, deadline=None)
@given(names=st.lists(st.one_of(_OLD_FORM, _WRONG_MARK, _ALTERED), min_size=1, max_size=6,
                      unique=True))
def test_the_sweep_removes_its_own_stale_temporaries_and_never_a_look_alike(names):
    """Look-alikes of the old and of the new form (another mark, an altered name), all of a
    process that has ended, stay; a real temporary of that process beside them goes."""
    with tempfile.TemporaryDirectory() as folder:
        base = Path(folder)
        for name in names:
            (base / name).write_text("a user's file")
        stale = base / f"{PREFIX}{_DEAD}-{temporary_mark(_DEAD)}-abcd_123.stl"
        stale.write_text("half")
        assert remove_stale_temporaries(base) == [stale]
        assert sorted(p.name for p in base.iterdir()) == sorted(names)


def test_a_temporary_as_a_link_or_of_another_user_is_not_removed(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "kept.txt").write_text("precious")
    folder = tmp_path / "out"
    folder.mkdir()
    name = f"{PREFIX}{_DEAD}-{temporary_mark(_DEAD)}-"
    (folder / f"{name}link0000.stl").symlink_to(outside / "kept.txt")
    (folder / f"{name}link0001.d").symlink_to(outside)
    others = []
    if os.geteuid() == 0:  # a file of another user, the mark as this user's would be
        other = folder / f"{name}other000.stl"
        other.write_text("theirs")
        os.chown(other, 65534, 65534)
        others.append(other.name)
    assert remove_stale_temporaries(folder) == []
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        [f"{name}link0000.stl", f"{name}link0001.d", *others])
    assert (outside / "kept.txt").read_text() == "precious"


def test_a_killed_writer_leaves_a_temporary_that_the_next_write_removes(tmp_path):
    code = ("import sys, time\nfrom gearcoupling.io import atomic_path\n"
            "with atomic_path(sys.argv[1]) as tmp:\n    tmp.write_text('half')\n"
            "    print('ready', flush=True)\n    time.sleep(60)\n")
    proc = subprocess.Popen([sys.executable, "-c", code, str(tmp_path / "hub.stl")],
                            stdout=subprocess.PIPE, env=ENV)
    assert proc.stdout.readline().strip() == b"ready"
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    proc.stdout.close()
    stale = [p.name for p in tmp_path.iterdir()]  # what kill -9 strands
    assert stale == [f"{PREFIX}{proc.pid}-{temporary_mark(proc.pid)}-{stale[0][-12:-4]}.stl"]
    live = tmp_path / f"{PREFIX}{os.getpid()}-{temporary_mark()}-abcdefgh.stl"
    live.write_text("in progress")  # a live writer's: kept
    write_text(tmp_path / "other.txt", "next run")
    assert sorted(p.name for p in tmp_path.iterdir()) == [live.name, "other.txt"]


# ------------------------------------------------------------------ links, solver files


@pytest.mark.parametrize("argv, names", [(HOB, sorted(HOB_FILES)),
                                         (QUICK_RUN, ["spec.json", "run_summary.json"])],
                         ids=["hob", "run"])
def test_a_link_at_an_output_is_replaced_never_written_through(argv, names, tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    for name in names:
        (tmp_path / f"outside-{name}").write_text("precious")
        (out / name).symlink_to(tmp_path / f"outside-{name}")
    assert main([*argv, "-o", str(out)]) == 0
    for name in names:
        assert (tmp_path / f"outside-{name}").read_text() == "precious"
        assert not (out / name).is_symlink() and (out / name).stat().st_size > 100


SOLVER_FILES = [f"cantilever.{ext}" for ext in ("inp", "log", "dat", "frd", "sta", "cvg",
                                                 "12d")] + ["spooles.out"]


@pytest.mark.needs_fea
def test_the_solver_never_writes_through_a_link_planted_in_its_folder(tmp_path):
    """Issue 38 item 3 at its root: the deck, the log and every file ccx writes land in
    the work folder as files of their own; the files the links pointed to are untouched.
    The smallest real solve: a cantilever against Timoshenko's deflection."""
    from gearcoupling.fea.validation import cantilever_tip_deflection

    work, outside = tmp_path / "work", tmp_path / "outside"
    work.mkdir()
    outside.mkdir()
    for name in SOLVER_FILES:
        (outside / name).write_text("precious")
        (work / name).symlink_to(outside / name)
    res = cantilever_tip_deflection(5.0, workdir=work)
    assert res["ratio"] == pytest.approx(1.0, abs=0.02)  # a real solve, read back
    for name in SOLVER_FILES:
        assert (outside / name).read_text() == "precious", name
        assert (work / name).is_file() and not (work / name).is_symlink(), name
    assert _temporaries(tmp_path) == []


@pytest.mark.needs_fea
def test_a_stopped_solve_leaves_no_solver_file(tmp_path):
    """A solve stopped while ccx runs (what the CLI does at a signal) moves nothing into
    the work folder: no deck, no partial printout; its private folder is gone."""
    from gearcoupling.fea import ccx
    from gearcoupling.fea.validation import cantilever_tip_deflection

    def stop_when_running() -> None:
        end = time.monotonic() + 120
        while not ccx.RUNNING and time.monotonic() < end:
            time.sleep(0.005)
        time.sleep(0.2)  # ccx has opened and begun its files
        ccx.stop_solvers()

    stopper = threading.Thread(target=stop_when_running)
    stopper.start()
    try:
        with pytest.raises(gc.BackendError, match="interrupted"):
            cantilever_tip_deflection(2.0, workdir=tmp_path / "work")
    finally:
        stopper.join()
        ccx.allow_solvers()
    assert list((tmp_path / "work").iterdir()) == []


@pytest.mark.needs_fea
def test_a_link_at_the_solver_folder_is_refused_before_any_work(tmp_path, capsys):
    out, elsewhere = tmp_path / "out", tmp_path / "elsewhere"
    out.mkdir()
    elsewhere.mkdir()
    (out / "fea_contact").symlink_to(elsewhere)
    before = _state(out)
    code = main(["fea-contact", "industrial-m2", "--torque", "400", "--size", "1.0",
                 "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "fea_contact" in err and "symbolic link" in err, err
    assert _state(out) == before and list(elsewhere.iterdir()) == []


FC_SMALL = ["fea-contact", "industrial-m2", "--torque", "400", "--size", "1.0",
            "--set", "hub.face_width=8", "--set", "sleeve.face_width=12"]


@pytest.mark.slow
@pytest.mark.needs_fea
def test_fea_contact_never_writes_through_a_planted_deck_or_log(tmp_path, capsys):
    """Issue 38 item 3 as reported: ``fea_contact/fe_contact.inp`` linked to another file
    got the deck. The coarsest mesh of industrial-m2 on half its face (25 s of CPU)."""
    out, outside = tmp_path / "out", tmp_path / "outside"
    (out / "fea_contact").mkdir(parents=True)
    outside.mkdir()
    names = ["fe_contact.inp", "fe_contact.log", "fe_contact.frd", "fe_contact.dat"]
    for name in names:
        (outside / name).write_text("precious")
        (out / "fea_contact" / name).symlink_to(outside / name)
    assert main([*FC_SMALL, "-o", str(out)]) == 0
    for name in names:
        assert (outside / name).read_text() == "precious", name
        path = out / "fea_contact" / name
        assert path.is_file() and not path.is_symlink() and path.stat().st_size > 0, name
    assert _temporaries(out) == []


def _children(pid: int) -> list[str]:
    """Command lines of the processes whose parent is ``pid``."""
    found = []
    for entry in os.listdir("/proc"):
        with contextlib.suppress(OSError, IndexError):
            if entry.isdigit() and int(Path(f"/proc/{entry}/stat").read_text()
                                       .rsplit(")", 1)[1].split()[1]) == pid:
                found.append(Path(f"/proc/{entry}/cmdline").read_bytes().decode())
    return found


@pytest.mark.slow
@pytest.mark.needs_fea
def test_interrupted_fea_contact_counts_no_partial_solver_file(tmp_path):
    """Ctrl-C while CalculiX solves: the one line counts only complete files, and no solver
    file (a 0-byte ``.12d``, a partial ``.frd``) is left for it to count."""
    import re

    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "gearcoupling", *FC_SMALL, "-o", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=ENV,
                            start_new_session=True)
    try:
        end = time.monotonic() + 600
        while not any("ccx" in c for c in _children(proc.pid)):
            assert proc.poll() is None and time.monotonic() < end, "ccx never started"
            time.sleep(0.05)
        time.sleep(1.0)  # the solver has written part of its files
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130, err
    match = re.search(rb"interrupted; (\d+) files? complete", err)
    assert match, err
    left = [p for p in out.rglob("*") if p.is_file()]
    assert left == [] and int(match[1]) == 0, left


# ------------------------------------------------------------------ errors name the target


def test_a_file_size_limit_names_the_target_and_leaves_no_temporary(tmp_path):
    """A write past RLIMIT_FSIZE (EFBIG, as a full disk fails a write): the one line names
    the file being written, not its temporary (the issue's "No space left on device:" had
    no name at all)."""
    code = ("import resource, signal, sys\nsignal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
            "resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))\n"
            "from gearcoupling.cli import main\nsys.exit(main(sys.argv[1:]))\n")
    out = tmp_path / "out"
    res = subprocess.run([sys.executable, "-c", code, *HOB, "-o", str(out)],
                         capture_output=True, text=True, env=ENV, timeout=120)
    assert res.returncode == 2, res.stderr
    assert res.stderr.strip() == f"gearcoupling: error: File too large: {out / 'hob_path.csv'}"
    assert _temporaries(out) == [] and not (out / "hob_path.csv").exists()


@contextlib.contextmanager
def _mounted(tmp_path: Path, options: str):
    """A tmpfs mounted with ``options`` (root only; skipped where it cannot be mounted)."""
    point = tmp_path / "mnt"
    point.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs",
                                            str(point)], capture_output=True).returncode:
        pytest.skip("needs root and tmpfs mounts")
    try:
        yield point
    finally:
        subprocess.run(["umount", "-l", str(point)], check=False)


def test_a_full_disk_names_the_target(tmp_path, capsys):
    with _mounted(tmp_path, "size=16k") as full:
        code = main([*HOB, "-o", str(full)])
        err = capsys.readouterr().err.strip()
        left = sorted(p.name for p in full.iterdir())
    assert code == 2
    assert err == f"gearcoupling: error: No space left on device: {full / 'hob_path.csv'}"
    assert not [n for n in left if n.startswith(PREFIX)], left


def test_a_folder_that_cannot_be_written_names_the_target(tmp_path):
    if os.geteuid() == 0:
        with _mounted(tmp_path, "ro,size=16k") as ro, pytest.raises(OSError) as info:
            write_text(ro / "a.txt", "x")
    else:
        ro = tmp_path / "ro"
        ro.mkdir(mode=0o555)
        with pytest.raises(OSError) as info:
            write_text(ro / "a.txt", "x")
    assert info.value.filename == str(ro / "a.txt")


def test_a_read_only_file_is_not_replaced(tmp_path, capsys):
    target = tmp_path / "hob.json"
    target.write_text("kept")
    target.chmod(0o444)
    assert main([*HOB, "-o", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "hob.json" in err and "read-only" in err and PREFIX not in err, err
    assert target.read_text() == "kept" and [p.name for p in tmp_path.iterdir()] == ["hob.json"]


# ------------------------------------------------------------------ targets checked first


REPORT = ["report", "renzo-1967", "--no-viewer", "--no-datasheet"]


@pytest.mark.parametrize("argv, name", [
    (HOB, "hob.json"),  # the issue: refused only after the two other files were written
    (QUICK_RUN, "run_summary.json"),  # the run's last file
    (REPORT, "report.html"),
    (REPORT, "sweep.csv"),  # a stage's file the report writes
], ids=["hob", "run", "report", "report-stage"])
def test_a_folder_where_a_file_goes_is_refused_before_anything_is_written(argv, name,
                                                                          tmp_path, capsys):
    out = tmp_path / "out"
    (out / name).mkdir(parents=True)
    if argv is REPORT:  # a file of the user's beside
        (out / "notes.txt").write_text("mine")
    before = _state(out)
    assert main([*argv, "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and name.split("/")[0] in err and "a folder" in err, err
    assert _state(out) == before  # not one entry made or removed


# ------------------------------------------------------------------ one command at a time


def test_a_second_command_into_a_folder_in_use_is_refused_at_once(tmp_path, capsys):
    out = tmp_path / "out"
    first = subprocess.Popen([sys.executable, "-m", "gearcoupling", "run", "renzo-1967",
                              "-o", str(out)], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, env=ENV)
    try:
        end = time.monotonic() + 120
        while not (out / "spec.json").exists():
            assert first.poll() is None and time.monotonic() < end, "run never wrote"
            time.sleep(0.02)
        t0 = time.perf_counter()
        code = main([*HOB, "-o", str(out)])
        seconds = time.perf_counter() - t0
        running = first.poll() is None
    finally:
        first.terminate()
        first.wait(timeout=60)
    err = capsys.readouterr().err
    assert running, "the first command ended before the second started: a slower one"
    assert code == 2 and seconds < 5, (code, seconds, err)
    assert str(out) in err and f"pid {first.pid}" in err, err
    assert not HOB_FILES & {p.name for p in out.iterdir()}


def test_a_killed_commands_lock_holds_nobody_back(tmp_path, capsys):
    code = ("import sys, time\nfrom gearcoupling.io import lock_folder\n"
            "lock_folder(sys.argv[1])\nprint('held', flush=True)\ntime.sleep(60)\n")
    holder = subprocess.Popen([sys.executable, "-c", code, str(tmp_path)],
                              stdout=subprocess.PIPE, env=ENV)
    assert holder.stdout.readline().strip() == b"held"
    with pytest.raises(gc.ArgumentError, match=f"pid {holder.pid}"):
        lock_folder(tmp_path).release()
    holder.kill()
    holder.wait(timeout=30)
    holder.stdout.close()
    assert (tmp_path / LOCK_NAME).exists()  # left by kill -9; the lock went with it
    assert main([*HOB, "-o", str(tmp_path)]) == 0
    assert not (tmp_path / LOCK_NAME).exists()


def test_every_command_that_claims_a_folder_lets_it_go():
    """A command that locks its folder (``claim``) is wrapped by ``holds_folders``, which
    releases it: else a second command in the same process would find it held."""
    import inspect

    from gearcoupling.commands import NAMES, command_module
    from gearcoupling.commands.folders import holds_folders

    wrapper = holds_folders(lambda args: 0).__code__
    claiming = [n for n in NAMES if "claim(" in inspect.getsource(command_module(n))]
    assert len(claiming) >= 16, claiming
    for name in claiming:
        assert command_module(name).run.__code__ is wrapper, name


def test_files_of_other_settings_are_named_and_kept(tmp_path, capsys):
    """Two runs with different ``--set`` into one folder: the second names the file of the
    first that it does not replace, and leaves it; a run with the first settings again
    replaces what the second made and has nothing to say."""
    out = str(tmp_path)
    assert main([*QUICK_RUN, "-o", out]) == 0
    sections = (tmp_path / "sections.png").read_bytes()
    capsys.readouterr()
    other = ["run", "renzo-1967", "--only", "spec", "--set", "hub.crowning.radius=3.5"]
    for _ in range(2):  # still there, still of the first settings: said again
        assert main([*other, "-o", out]) == 0
        notes = [ln for ln in capsys.readouterr().err.splitlines() if "note:" in ln]
        assert len(notes) == 1 and "2 files made earlier with other settings" in notes[0]
        assert notes[0].split(": ", 3)[-1].startswith("crown_profile.csv, sections.png"), notes
    assert (tmp_path / "sections.png").read_bytes() == sections
    assert main(["run", "renzo-1967", "--only", "spec", "-o", out]) == 0
    assert "note:" not in capsys.readouterr().err


def test_a_damaged_record_is_read_as_none(tmp_path, capsys):
    from gearcoupling.io import earlier_files

    for text in ("", "null", "[1, 2]", '{"version": 1, "files": {"a": 3}}', "{" * 10_000):
        (tmp_path / RECORD_NAME).write_text(text)
        assert earlier_files(tmp_path, "key") == []
    assert main([*HOB, "-o", str(tmp_path)]) == 0
    assert "note:" not in capsys.readouterr().err


# ------------------------------------------------------------------ the data sheet's bore


@pytest.mark.parametrize("bore, words", [(None, "hub bore (88.9 mm)"), (0.0, "no bore")])
def test_the_data_sheet_says_where_the_bodies_twist(bore, words, tmp_path, capsys):
    """renzo-1967's hub has an 88.9 mm bore: the data sheet said "(none: the hub has no
    bore)" for it."""
    given = [] if bore is None else ["--set", f"hub.body.bore_diameter={bore}"]
    assert main(["datasheet", "renzo-1967", *given, "--model", "compliance", "--rotations",
                 "2", "--angles", "36", "-o", str(tmp_path)]) == 0
    with open(tmp_path / "datasheet.csv", newline="") as fh:
        row = next(r for r in csv.DictReader(fh) if r["quantity"] == "bodies' torsional "
                   "stiffness")
    assert words in row["source"] and float(row["value"]) > 0, row
    assert ("no bore" in row["source"]) == (bore == 0.0)
