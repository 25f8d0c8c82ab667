"""Signals and exit status (issue 38, items 5 and 9), with real signals to real processes.

The program ends 130 (SIGINT) or 143 (SIGTERM) with one line at any moment: while the
package loads, while the command starts, runs or cleans up, also when a library drops
the interruption or never returns; a second signal ends it at once. An unexpected error
exits 3 with one line saying where to report it. The loops send a signal at seeded random
moments over each command's real duration, two commands at a time."""

from __future__ import annotations

import os
import random
import re
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from fresh_python import session_alive
from gearcoupling.cli import main
from gearcoupling.io.atomic import PREFIX
from test_cli_bad_input import STUDY_28

ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
LINE = re.compile(r"gearcoupling: interrupted; (\d+) files? complete(?: in (.+))?")
WITHIN_S = 5.0  # from the signal to the end of the process and of every process it started
LATE_S = 0.1  # file times run on a coarser clock than time.time()
M2 = "industrial-m2"
STUDY = STUDY_28.replace("steps = 40\n", "steps = 4\n")  # 4 samples

# the cheapest real work of each command; ``{out}`` is the try's own folder
COMMANDS = {
    "run": ["run", M2, "--only", "spec,sections,parts", "--workers", "2", "-o", "{out}"],
    "report": ["report", M2, "--model", "linear", "--angles", "8", "--capacity-count", "2",
               "--check-angles", "1", "--no-viewer", "--no-datasheet", "-o", "{out}"],
    "datasheet": ["datasheet", M2, "--model", "linear", "--rotations", "1", "--angles", "4",
                  "-o", "{out}"],
    "view --html": ["view", M2, "--lod", "coarse", "--html", "{out}/viewer.html"],
    "study": ["study", "study.toml", "--workers", "1", "--no-plots", "-o", "{out}"],
}


def _caught(pid: int, signum: int) -> bool:
    """Whether process ``pid`` has a handler of ``signum`` (``SigCgt`` in /proc)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    caught = int(re.search(r"^SigCgt:\s*([0-9a-f]+)", status, re.M)[1], 16)
    return bool(caught >> (signum - 1) & 1)


@dataclass
class Try:
    """One command started in its own session and signalled ``moment`` s after."""

    argv: list[str]
    out: Path
    moment: float
    sig: int
    group: bool  # to the whole process group, as Ctrl-C in a terminal
    proc: subprocess.Popen = field(init=False)
    started: float = 0.0
    sent: float = 0.0  # time.time() of the signal, 0 before
    sent_mono: float = 0.0
    ended: float = 0.0  # monotonic time of the exit

    def start(self, cwd: Path) -> None:
        self.out.parent.mkdir(parents=True, exist_ok=True)
        argv = [a.replace("{out}", str(self.out)) for a in self.argv]
        with open(f"{self.out}.err", "wb") as err:
            self.proc = subprocess.Popen([sys.executable, "-m", "gearcoupling", *argv],
                                         cwd=cwd, stdout=subprocess.DEVNULL, stderr=err,
                                         env=ENV, start_new_session=True)
        self.started = time.monotonic()

    def step(self) -> bool:
        """Signal when due, note the exit; whether this try is over."""
        now = time.monotonic()
        # not before Python has made its own Ctrl-C handler: no program of ours runs yet
        if not self.sent and self.proc.poll() is None and now >= self.started + self.moment \
                and _caught(self.proc.pid, signal.SIGINT):
            self.sent, self.sent_mono = time.time(), now
            (os.killpg if self.group else os.kill)(self.proc.pid, self.sig)
        if self.proc.poll() is not None and not self.ended:
            self.ended = now
        if self.ended and (not self.sent or not session_alive(self.proc.pid)):
            return True
        if self.sent and now > self.sent_mono + WITHIN_S:  # leave nothing behind
            for pid in session_alive(self.proc.pid):
                os.kill(pid, signal.SIGKILL)
            self.proc.wait()
            self.ended = self.ended or now
            return True
        return False

    @property
    def err(self) -> str:
        return Path(f"{self.out}.err").read_text()

    def check(self) -> None:
        """Ended 128 + the signal within WITHIN_S with one line counting the files in
        ``out``, no process left, no temporary, nothing written after the signal."""
        what = f"{self.sig!r} {'to the group ' if self.group else ''}at {self.moment:.2f} s"
        assert self.ended - self.sent_mono <= WITHIN_S, f"{what}: still running after it"
        assert self.proc.returncode == 128 + self.sig, (what, self.proc.returncode, self.err)
        lines = self.err.strip().splitlines()
        assert len(lines) == 1 and (match := LINE.fullmatch(lines[0])), (what, self.err)
        found = list(self.out.rglob("*")) if self.out.is_dir() else []
        assert not [p for p in found if p.name.startswith(PREFIX)], (what, found)
        files = [p for p in found if p.is_file() and not p.name.startswith(".")]
        assert int(match[1]) == len(files), (what, self.err, files)
        if files:
            assert match[2] is not None and str(self.out) in match[2], (what, self.err)
        late = {p.name: p.stat().st_mtime - self.sent for p in found  # the record's too
                if p.is_file() and p.stat().st_mtime > self.sent + LATE_S}
        assert not late, f"{what}: written after the signal (s after it): {late}"


def _interrupt_at_random_moments(name: str, tmp_path: Path, tries: int = 20,
                                 seed: int = 38) -> None:
    """One run of command ``name`` to its end (exit 0: its duration D), then ``tries``
    runs, two at a time, each sent SIGTERM (to the process) or SIGINT (to the group) at a
    seeded random moment in [0.2 s, D]."""
    (tmp_path / "study.toml").write_text(STUDY)
    argv = COMMANDS[name]
    whole = Try(argv, tmp_path / "whole", 0.0, 0, False)
    whole.start(tmp_path)
    assert whole.proc.wait(timeout=600) == 0, whole.err
    duration = time.monotonic() - whole.started
    rng = random.Random(seed)
    todo = [Try(argv, tmp_path / f"try{k}", rng.uniform(0.2, duration),
                *rng.choice([(signal.SIGTERM, False), (signal.SIGINT, True)]))
            for k in range(tries)]
    running: list[Try] = []
    done: list[Try] = []
    while todo or running:
        while todo and len(running) < 2:
            running.append(todo.pop())
            running[-1].start(tmp_path)
        for t in [t for t in running if t.step()]:
            running.remove(t)
            done.append(t)
        time.sleep(0.005)
    signalled = [t for t in done if t.sent]
    for t in signalled:
        t.check()
    for t in done:
        if not t.sent:  # over before its moment came
            assert t.proc.returncode == 0, t.err
    assert len(signalled) >= tries * 3 // 4, f"{len(signalled)} of {tries} signalled"


@pytest.mark.slow
@pytest.mark.parametrize("name", ["run", "report", "datasheet",
                                  pytest.param("view --html", marks=pytest.mark.needs_viewer),
                                  pytest.param("study", marks=pytest.mark.needs_dask)])
def test_a_signal_at_any_moment_ends_the_command_in_one_line(name, tmp_path):
    _interrupt_at_random_moments(name, tmp_path)


def _wait_for(path: Path, proc: subprocess.Popen, timeout_s: float = 120.0) -> None:
    end = time.monotonic() + timeout_s
    while not path.exists():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < end, f"{path} never appeared"
        time.sleep(0.01)


def _ended(proc: subprocess.Popen, within_s: float) -> tuple[int, str]:
    """The exit status and stderr of ``proc``, which must end within ``within_s``; no
    process of its session may be left."""
    try:
        _, err = proc.communicate(timeout=within_s)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        pytest.fail(f"still running {within_s:g} s after the signal")
    end = time.monotonic() + WITHIN_S
    while session_alive(proc.pid):
        assert time.monotonic() < end, f"left running: {session_alive(proc.pid)}"
        time.sleep(0.05)
    return proc.returncode, err


@pytest.mark.parametrize("how", ["python -m gearcoupling", "the gearcoupling script"])
@pytest.mark.parametrize("sig, group", [(signal.SIGTERM, False), (signal.SIGINT, True)],
                         ids=["SIGTERM", "Ctrl-C"])
def test_a_signal_while_the_package_loads_ends_the_program_in_one_line(how, sig, group,
                                                                        tmp_path):
    """The package's first import after the program's first handler is held up (a
    ``lazy_loader`` that waits): the signal there ends the program with the one line
    at once. Before, SIGTERM ended it silently (-15) and Ctrl-C printed a traceback."""
    shadow = tmp_path / "shadow"
    shadow.mkdir()
    loading = tmp_path / "loading"
    (shadow / "lazy_loader.py").write_text(f"import pathlib, time\n"
                                           f"pathlib.Path({str(loading)!r}).touch()\n"
                                           f"time.sleep(60)\n")
    script = tmp_path / "bin" / "gearcoupling"  # as pip writes it
    script.parent.mkdir()
    script.write_text("import sys\nfrom gearcoupling.cli import console\n"
                      "if __name__ == '__main__':\n    sys.exit(console())\n")
    start = ["-m", "gearcoupling"] if how.startswith("python") else [str(script)]
    proc = subprocess.Popen([sys.executable, *start, "spec", M2], cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            env={**ENV, "PYTHONPATH": f"{shadow}{os.pathsep}{ENV['PYTHONPATH']}"},
                            start_new_session=True)
    _wait_for(loading, proc)
    (os.killpg if group else os.kill)(proc.pid, sig)
    code, err = _ended(proc, WITHIN_S)
    assert (code, err) == (128 + sig, "gearcoupling: interrupted; 0 files complete\n")


# a run whose sections stage meets a library that is given the signal's exception
RUN_WITH = """
import dataclasses, gc, os, pathlib, signal, sys, time
from gearcoupling.outputs import registry
from gearcoupling.outputs.stage import function

out, how = pathlib.Path(sys.argv[1]), sys.argv[2]
stage = registry.STAGES["sections"]
compute = function(stage.compute)


def drop_it(forever):  # a library that catches everything (trimesh's imports do)
    (out.parent / "dropping").touch()
    dropped = False
    while forever or not dropped:
        try:
            time.sleep(0.01)
        except BaseException:
            dropped = True


def in_gc_callback(phase, info):  # dask's: an exception raised there is dropped
    if phase == "start":
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5.0)


def sections_meeting_a_library(inputs):
    if how == "catch-all":
        drop_it(False)
    elif how == "never-returns":
        drop_it(True)
    else:
        gc.callbacks.append(in_gc_callback)
        gc.collect()
        gc.callbacks.remove(in_gc_callback)
    return compute(inputs)


registry.STAGES = dict(registry.STAGES, sections=dataclasses.replace(
    stage, compute=sections_meeting_a_library))
sys.argv = ["gearcoupling", "run", "industrial-m2", "--only", "spec,sections", "--workers",
            "1", "-o", str(out)]
from gearcoupling.cli import console

console()
"""


def _run_with(how: str, tmp_path: Path) -> tuple[subprocess.Popen, Path]:
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-c", RUN_WITH, str(out), how], cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            env=ENV, start_new_session=True)
    return proc, out


def _only_spec_written(code: int, err: str, sig: int, out: Path) -> None:
    assert code == 128 + sig, (code, err)
    assert err.strip() == f"gearcoupling: interrupted; 1 file complete in {out}", err
    assert sorted(p.name for p in out.iterdir()) == ["spec.json"]


@pytest.mark.parametrize("how", ["catch-all", "gc-callback"])
def test_an_interruption_a_library_drops_still_stops_the_command(how, tmp_path):
    """SIGTERM while a library that drops its exception runs: the command stops at its
    next checkpoint (here the atomic rename of sections.png) with the one line (not
    Python's "Exception ignored" report), writing nothing after the signal. Before,
    the run wrote every file and exited 0."""
    proc, out = _run_with(how, tmp_path)
    if how == "catch-all":
        _wait_for(tmp_path / "dropping", proc)
        os.kill(proc.pid, signal.SIGTERM)
    code, err = _ended(proc, 120.0)  # the gc callback sends it itself
    _only_spec_written(code, err, signal.SIGTERM, out)


@pytest.mark.parametrize("second", [None, signal.SIGINT])
def test_a_command_that_never_returns_ends_at_a_second_signal_or_after_the_grace(
        second, tmp_path):
    """A library that drops every exception and never returns: a second signal ends the
    program at once, else it ends within WITHIN_S of the first (the program's grace,
    gearcoupling.cli.GRACE_S), with the one line and the files of before. Before, only
    SIGKILL ended it."""
    proc, out = _run_with("never-returns", tmp_path)
    _wait_for(tmp_path / "dropping", proc)
    os.kill(proc.pid, signal.SIGTERM)
    if second is None:
        code, err = _ended(proc, WITHIN_S)
        _only_spec_written(code, err, signal.SIGTERM, out)
    else:
        time.sleep(0.3)
        os.killpg(proc.pid, second)
        code, err = _ended(proc, 2.0)  # before the grace would end it (2.7 s)
        _only_spec_written(code, err, second, out)


def test_an_internal_error_exits_3_in_one_line(monkeypatch, capsys):
    """An exception no part of gearcoupling raises on purpose (a defect) exits 3, not 1
    (a design finding), with one line naming it and where to report it; the traceback
    only with GEARCOUPLING_DEBUG=1. Before, the traceback went out and the status was 1."""
    from gearcoupling.commands import spec as spec_command

    def defect(args):
        return 1 // 0

    monkeypatch.setattr(spec_command, "run", defect)
    assert main(["spec", M2]) == 3
    err = capsys.readouterr().err
    assert err.startswith("gearcoupling: internal error: ZeroDivisionError: integer "
                          "division or modulo by zero (please report it at "), err
    assert err.endswith(", with the command and spec)\n") and err.count("\n") == 1, err
    monkeypatch.setenv("GEARCOUPLING_DEBUG", "1")
    assert main(["spec", M2]) == 3
    err = capsys.readouterr().err
    assert "Traceback" in err and "1 // 0" in err and err.splitlines()[-1].startswith(
        "gearcoupling: internal error: ZeroDivisionError"), err


class _FailedImport:
    """A meta path finder for module ``name`` that fails as a C++ extension does when a
    signal's exception is raised while it initialises (``interrupted``: pybind11
    reports it as ``ImportError('initialization failed')`` caused by the
    ``KeyboardInterrupt``), else as a module that is not installed."""

    def __init__(self, name: str, interrupted: bool):
        self.name, self.interrupted = name, interrupted

    def find_spec(self, name, path=None, target=None):
        if name != self.name:
            return None
        if self.interrupted:
            raise ImportError("initialization failed") from KeyboardInterrupt()
        raise ModuleNotFoundError(f"No module named {name!r}", name=name)


# (module, function, its arguments, the back-end it imports)
IMPORTERS = [
    ("gearcoupling.parts.solid", "_occ", (), "OCP"),
    ("gearcoupling.export.step", "_step_control", (), "OCP"),
    ("gearcoupling.fea.backends", "gmsh_module", (), "gmsh"),
    ("gearcoupling.plots", "import_matplotlib", (), "matplotlib"),
    ("gearcoupling.viewer.nodes", "import_viser", (), "viser"),
    ("gearcoupling.tables", "import_pandas", (), "pandas"),
    ("gearcoupling.study.runner", "pyarrow_modules", (), "pyarrow"),
    ("gearcoupling.study.runner", "_distributed", (), "distributed"),
    ("gearcoupling.interference.posed", "_fcl", (), "fcl"),
    ("gearcoupling.interference.distance", "_igl", (), "igl"),
    ("gearcoupling.rotordynamics.ross", "import_ross", (), "ross"),
    ("gearcoupling.inspection.io", "_load_mesh", (Path("scan.stl"),), "trimesh"),
    ("gearcoupling.browser", "browser_backend", (sys.executable,), "playwright"),
]


@pytest.mark.parametrize("module, function, args, backend", IMPORTERS,
                         ids=[f"{m.rsplit('.', 1)[1]}.{f}" for m, f, _, _ in IMPORTERS])
def test_a_signal_during_a_backend_import_is_not_a_missing_backend(module, function, args,
                                                                   backend, monkeypatch):
    """Ctrl-C while OpenCASCADE (or another back-end) initialises stays an interruption;
    before, it was reported as "CAD solids need OpenCASCADE: pip install ...". A plain
    ImportError still names the extra."""
    import importlib

    call = getattr(importlib.import_module(module), function)
    for name in [m for m in sys.modules if m == backend or m.startswith(f"{backend}.")]:
        monkeypatch.delitem(sys.modules, name)
    from gearcoupling.errors import BackendError

    finders = sys.meta_path
    monkeypatch.setattr(sys, "meta_path", [_FailedImport(backend, True), *finders])
    with pytest.raises(KeyboardInterrupt):
        call(*args)
    monkeypatch.setattr(sys, "meta_path", [_FailedImport(backend, False), *finders])
    with pytest.raises(BackendError, match="pip install"):
        call(*args)


OCP_INTERRUPTED = """
import os, signal, sys, threading, time
from gearcoupling.cli import _signals_raise
from gearcoupling.errors import BackendError
from gearcoupling.parts.solid import _occ

with _signals_raise():
    threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT)).start()
    try:
        _occ()  # OpenCASCADE's import takes some 0.3-0.6 s
        time.sleep(5.0)
    except KeyboardInterrupt:
        print("interrupted")
    except BackendError as err:
        print(err)
"""


def test_ctrl_c_while_opencascade_loads_is_an_interruption():
    """The real thing: Ctrl-C 50 ms into OpenCASCADE's import (inside its pybind11
    module's initialisation). Before, it was reported as "CAD solids need OpenCASCADE:
    pip install 'gearcoupling[step]'"."""
    import importlib.util

    if importlib.util.find_spec("OCP") is None:
        pytest.skip("OCP not installed: pip install 'gearcoupling[step]'")
    out = subprocess.run([sys.executable, "-c", OCP_INTERRUPTED], capture_output=True,
                         text=True, env=ENV, timeout=120)
    assert out.stdout == "interrupted\n", (out.stdout, out.stderr)
