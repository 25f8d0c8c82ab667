"""Bad command lines exit with status 2 and one line naming what is wrong: a table of bad
inputs, plus the output-folder, pipe, temporary-file and viewer
address cases that need more than one call."""

import contextlib
import os
import signal
import socket
import subprocess
import sys
import time

import pytest

import gearcoupling as gc
from fresh_python import session_alive as _session_alive
from gearcoupling.cli import main

T = "renzo-1967"
M2 = "industrial-m2"


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad")
    (d / "latin1.toml").write_bytes("# Kupplung für Walzwerk\n[tooth]\nteeth = 38\n"
                                    .encode("latin-1"))
    (d / "broken.toml").write_text("[tooth\nteeth = 38\n")
    (d / "misspelt.toml").write_text("[tooth]\nteth = 38\nmodule = 2.0\n"
                                     "[hub]\nface_width = 16.0\n")
    (d / "crowing.toml").write_text("[tooth]\nteeth = 38\nmodule = 2.0\n"
                                    "[hub]\nface_width = 16.0\n[hub.crowing]\nkind = 'none'\n")
    (d / "a_file").write_text("not a folder")
    (d / "folder.toml").mkdir()
    (d / "html_folder").mkdir()
    os.mkfifo(d / "pipe")  # never opened: a reader would block
    (d / "dangling").symlink_to(d / "gone.toml")
    study = '[study]\nbase = "industrial-m2"\n[[vary]]\nkey = "hub.crowning.radius"\n'
    (d / "billion.toml").write_text(study + "range = [40.0, 200.0]\nsteps = 1000000000\n")
    (d / "tiny-tolerance.toml").write_text(study + "values = [40.0]\n[accuracy]\n"
                                           "tolerance_mm = 1e-300\n")
    (d / "huge-torque.toml").write_text(study.replace("hub.crowning.radius", "torque_Nm")
                                        + "values = [1e30]\n")
    template = (gc.io.bundled_dir("templates") / "industrial-m2.toml").read_text()
    (d / "long-name.toml").write_text(f'name = "{"x" * 300}"\n{template}')
    return d


# (argv with {d} for the fixture folder, words the one-line message must contain)
BAD = [
    (["spec", "nope"], "templates"),
    (["spec", "{d}/missing.toml"], "no such file: give a spec file"),
    (["spec", "{d}/folder.toml"], "a folder, not a file: give a spec file"),
    (["spec", "/dev/null"], "a character device (like /dev/null), not a file"),
    (["spec", "{d}/pipe"], "a named pipe (FIFO), not a file"),
    (["spec", "{d}/dangling"], "a broken symbolic link"),
    (["spec", "{d}/latin1.toml"], "UTF-8"),
    (["spec", "{d}/broken.toml"], "not valid TOML"),
    (["spec", "{d}/misspelt.toml"], "tooth.teth"),
    (["spec", "{d}/crowing.toml"], "hub.crowing"),
    (["spec", T, "--set", "oops"], "KEY=VALUE"),
    (["spec", T, "--set", "hub.face_width=-1"], "hub.face_width"),
    (["spec", T, "--set", "hub.backlash=nan"], "hub.backlash"),
    (["spec", T, "--set", "hub.backlash=inf"], "hub.backlash"),
    (["spec", T, "--set", "tooth.teeth=5"], "tooth.teeth"),
    (["spec", T, "--set", "tooth.teeth=12.5"], "tooth.teeth"),
    (["spec", T, "--set", "tooth.teth=40"], "did you mean 'teeth'"),
    (["spec", T, "--set", "hub.crowing.kind=none"], "did you mean 'crowning'"),
    (["spec", T, "--set", "design_misalignment_deg=6.001"], "design_misalignment_deg"),
    (["spec", T, "--set", "units=cm"], "units"),
    (["spec", "industrial-m2", "--set", "tooth.module=two"], "tooth.module"),
    (["spec", T, "--set", "hub.crowning.kind=none", "--set", "hub.crowning.radius=-3"],
     "hub.crowning.radius"),
    (["spec", T, "--set", "hub.crowning.kind=table"], "hub.crowning"),
    (["spec", T, "--set", "hub.crowning.radius=0.01"], "hub.crowning.radius"),
    (["sections", T, "--tolerance", "-1"], "--tolerance"),
    (["sections", T, "--tolerance", "0"], "--tolerance"),
    (["sections", T, "--tolerance", "nan"], "--tolerance"),
    (["sections", T, "-o", "{d}/a_file"], "-o"),
    (["sections", T, "-o", "{d}/a_file/sub"], "-o"),
    (["sections", T, "-o", "/proc/gearcoupling-cannot-write-here"], "-o"),
    (["sweep", T, "--tolerance", "0"], "--tolerance"),
    (["sweep", T, "--tolerance", "-1"], "--tolerance"),
    (["sweep", T, "--tolerance", "nan"], "--tolerance"),
    (["sweep", T, "--angles", "0"], "--angles"),
    (["sweep", T, "--angles", "3000000"], "--angles"),
    (["sweep", T, "--angles", "ten"], "--angles"),
    (["sweep", T, "--misalignment", "7"], "--misalignment"),
    (["sweep", T, "--misalignment", "-0.5"], "--misalignment"),
    (["sweep", T, "--misalignment", "nan"], "--misalignment"),
    (["view", T, "--html", "{d}/html_folder"], "--html"),
    (["view", T, "--port", "0"], "--port"),
    (["view", T, "--port", "70000"], "--port"),
    (["view", T, "--tolerance", "0"], "--tolerance"),
    (["view", T, "--angle", "nan"], "--angle"),
    (["view", T, "--cutaway", "most"], "--cutaway"),
    (["view", T, "--host", "no.such.host.invalid"], "host"),
    (["generate", T, "--teeth", "0-99999999999"], "--teeth"),
    (["generate", T, "--teeth", "x"], "--teeth"),
    (["generate", T, "--format", "xyz"], "--format"),
    (["generate", T, "--parts", "wheel"], "--parts"),
    (["run", T, "--only", "spec,stl"], "--only"),
    (["run", T, "--skip", "nope"], "--skip"),
    (["check", T, "--angles", "0"], "--angles"),
    (["check", T, "--tolerance", "nan"], "--tolerance"),
    (["check", T, "--teeth", "foo"], "--teeth"),
    # commands added with the load, FE, study, hob and inspection work: every error comes
    # from the argument types or the first checks, before any heavy work
    (["load", T, "--angles", "3000000"], "--angles"),
    (["load", T, "--angles", "0"], "--angles"),
    (["load", T, "--torque", "nan"], "--torque"),
    (["load", T, "--torque=-inf"], "--torque"),
    (["load", T, "--torque", "1e300"], "--torque"),
    (["load", T, "--tolerance", "0"], "--tolerance"),
    (["load", T, "--misalignment", "7"], "--misalignment"),
    (["load", T, "-o", "{d}/a_file"], "-o"),
    (["capacity", T, "--max", "7"], "--max"),
    (["capacity", T, "--max", "0"], "--max"),
    (["capacity", T, "--count", "1"], "--count"),
    (["capacity", T, "--count", "100000"], "--count"),
    (["capacity", T, "--compare", "nope"], "--compare"),
    (["capacity", T, "--compare", "{d}/missing.toml"], "--compare"),
    (["capacity", T, "-o", "{d}/a_file"], "-o"),
    (["fea", T, "--size", "0"], "--size"),
    (["fea", T, "--size", "nan"], "--size"),
    (["fea", T, "--sector", "0"], "--sector"),
    (["fea", T, "--sector", "100000"], "--sector"),
    (["fea", T, "--format", "stl"], "--format"),
    (["fea-contact", T, "--torque", "0"], "--torque"),
    (["fea-contact", T, "--size", "-1"], "--size"),
    (["fea-contact", T, "--contact-size", "50"], "--contact-size"),
    (["fea-contact", T, "--misalignment", "7"], "--misalignment"),
    (["fea-contact", T, "--misalignment", "1", "--sector", "3"], "--sector"),
    (["fea-contact", T, "--misalignment", "1", "--rotation", "400"], "--rotation"),
    (["fea-contact", T, "--misalignment", "1", "--contact-size", "0.5"], "--contact-size"),
    (["stiffness", T, "--size", "-1"], "--size"),
    (["stiffness", T, "--nz", "1"], "--nz"),
    (["stiffness", T, "--nr", "10"], "--nr"),
    (["stiffness", T, "--sector", "2"], "--sector"),
    (["stiffness", T, "--cache", "{d}/a_file"], "--cache"),
    (["study", "{d}/missing.toml"], "no such file"),
    (["study", "/dev/null"], "a character device (like /dev/null), not a file: give a study"),
    (["study", "{d}/html_folder"], "a folder, not a file: give a study"),
    (["study", "renzo-tolerances", "--connect-timeout", "0"], "--connect-timeout"),
    (["study", "renzo-tolerances", "--connect-timeout", "nan"], "--connect-timeout"),
    (["study", "renzo-tolerances", "--workers", "0"], "--workers"),
    (["study", "renzo-tolerances", "-o", "{d}/a_file"], "-o"),
    (["hob", T], "--hob-diameter"),
    (["hob", T, "--hob-diameter", "0"], "--hob-diameter"),
    (["hob", T, "--hob-diameter", "inf"], "--hob-diameter"),
    (["hob", T, "--hob-diameter", "1e9"], "larger than any hob made"),
    (["hob", T, "--hob-diameter", "10"], "too small to carry"),
    (["hob", T, "--hob-diameter", "80", "--tolerance", "-1"], "--tolerance"),
    (["hob", T, "--hob-diameter", "80", "--feed", "0"], "--feed"),
    (["charts", T, "--points", "2"], "--points"),
    (["charts", T, "--points", "100000000"], "--points"),
    (["charts", T, "--tip-exclusion", "0.9"], "--tip-exclusion"),
    (["charts", T, "--tip-exclusion", "nan"], "--tip-exclusion"),
    (["compare", T, "{d}/missing.stl"], "no such file: give a scan or mesh file"),
    (["compare", T, "{d}/html_folder"], "a folder, not a file: give a scan or mesh file"),
    (["compare", T, "/dev/null"], "a character device (like /dev/null), not a file"),
    (["compare", T, "{d}/pipe"], "a named pipe (FIFO), not a file"),
    (["compare", T, "{d}/a_file", "--grade", "12"], "--grade"),
    (["compare", T, "{d}/a_file", "{d}/a_file", "{d}/a_file"], "FILE"),
    (["compare", T, "{d}/a_file", "--limit", "fpt=abc"], "--limit"),
    (["compare", T, "{d}/a_file", "--limit", "bogus=0.1"], "--limit"),
    (["compare", T, "{d}/a_file", "--limit", "fpt"], "--limit"),
    (["compare", T, "{d}/a_file", "--fit-points", "0"], "--fit-points"),
    (["check", T, "--angles", "3000000"], "--angles"),
    (["check", T, "--hub-rotation", "nan"], "--hub-rotation"),
    (["check", T, "--hub-rotation", "1000"], "--hub-rotation"),
    (["check", T, "--teeth", "999"], "--teeth"),
    (["check", T, "--worst", "0"], "--worst"),
    (["generate", T, "--tolerance", "0"], "--tolerance"),
    (["generate", T, "--tolerance", "nan"], "--tolerance"),
    (["templates", "extra"], "unrecognized arguments"),
    ([], "required"),
    (["frobnicate", T], "invalid choice"),
    (["report", T, "--angles", "3"], "--angles"),
    (["report", T, "--capacity-count", "1"], "--capacity-count"),
    (["report", T, "--hob-diameter", "1e9"], "larger than any hob made"),
    (["report", T, "--scan", "/dev/null"], "a character device (like /dev/null), not a file"),
    (["report", T, "--grade", "0"], "--grade"),
    (["report", T, "--misalignment", "7"], "--misalignment"),
    (["report", T, "--limit", "fpt"], "--limit"),
    (["capacity", T, "--misalignments", "1"], "--misalignments"),
    (["capacity", T, "--misalignments", "0,1", "--max", "2"], "--misalignments"),
    (["datasheet", T, "--torque", "0"], "torque_Nm = 0.0"),
    (["datasheet", T, "--rotations", "0"], "--rotations"),
    (["datasheet", T, "--ross", "coupling.xml"], ".toml or .json"),
    # issue 28: numbers a person would not write (Python's float() reads 0_5 as 5)
    (["sweep", M2, "--misalignment", "0_5"], "--misalignment"),
    (["sweep", M2, "--tolerance", "1_0e-7"], "--tolerance"),
    (["sweep", M2, "--angles", "3_6"], "--angles"),
    (["sweep", M2, "--misalignment", "0x1"], "--misalignment"),
    (["sweep", M2, "--misalignment", "\u0661"], "--misalignment"),
    (["sweep", M2, "--misalignment", "1,5"], "--misalignment"),
    (["load", M2, "--torque", "1_000"], "--torque"),
    (["capacity", M2, "--misalignments", "0_5,1"], "--misalignments"),
    (["hob", M2, "--hob-diameter", "6_0"], "--hob-diameter"),
    (["run", M2, "--workers", "0_2"], "--workers"),
    (["spec", M2, "--set", "tooth.teeth=3_8"], "tooth.teeth"),
    (["spec", M2, "--set", "hub.face_width=0x10"], "hub.face_width"),
    (["spec", M2, "--set", "hub.backlash=nan"], "hub.backlash"),
    (["compare", T, "{d}/a_file", "--limit", "fpt=0_5"], "--limit"),
    (["generate", T, "--teeth", "1_0"], "--teeth"),
    # sizes with documented maxima, empty paths, duplicates: refused before any work
    (["capacity", M2, "--misalignments", ",".join(["1"] * 5000)], "--misalignments"),
    (["report", T, "-o", ""], "-o"),
    (["run", M2, "-o", ""], "-o"),
    (["view", M2, "--html", ""], "--html"),
    (["capacity", M2, "--compare", M2, M2], "--compare"),
    (["capacity", M2, "--compare", M2], "--compare"),
    (["study", "{d}/billion.toml"], "steps"),
    (["study", "{d}/tiny-tolerance.toml"], "accuracy.tolerance_mm"),
    # one torque range everywhere, with its ends
    (["report", T, "--torque=1e30"], "--torque"),
    (["report", T, "--set", "load.torque_Nm=1e300"], "load.torque_Nm"),
    (["load", M2, "--torque=1.7e308"], "--torque"),
    (["load", M2, "--torque=1e-300"], "--torque"),
    (["load", M2, "--torque=5e-324"], "--torque"),
    (["load", M2, "--torque=-1e-300"], "'-1e-300'"),
    (["load", M2, "--set", "load.torque_Nm=2e9"], "load.torque_Nm"),
    (["fea-contact", T, "--torque=2e9"], "--torque"),
    (["study", "{d}/huge-torque.toml"], "torque_Nm"),
    # messages that name what the user gave
    (["spec", T, "--set", "tooth.module=3"], "tooth.module = 3"),
    (["fea-contact", M2, "--set", "load.torque_Nm=0"], "load.torque_Nm = 0"),
    (["fea-contact", T, "--size=1e-9"], "choose a larger size"),
    (["fea-contact", T, "--size=1e-9"], "--size"),
    (["fea-contact", T, "--contact-size", "1e6"], "--contact-size"),
    (["view", M2, "--serve-seconds=-1"], " s "),
    (["capacity", M2, "--misalignments", ""], "2 to 200 different angles"),
    (["report", T, "-o", "/sys/kernel/gearcoupling"], "-o"),
    (["report", T, "-o", "/sys/kernel"], "cannot write"),
    (["spec", "{d}/long-name.toml"], "at most 200 characters"),
    (["hob", M2, "--hob-diameter", "60", "--feed", "1e300"], "--feed"),
    (["study", "renzo-tolerances", "--scheduler", "not a url"], "--scheduler"),
    (["study", "renzo-tolerances", "--scheduler", "tcp://127.0.0.1"], "--scheduler"),
    (["study", "renzo-tolerances", "--scheduler", "http://x.invalid:80"], "--scheduler"),
    (["view", M2, "--angle", "2e6"], "--angle"),
    (["wear", T, "--hours", "10"], "--speed"),
    (["wear", T, "--hours", "10", "--speed", "1800", "--coefficient", "-1"], "--coefficient"),
    (["wear", T, "--point", "1,2000,1800,10", "--speed", "1800"], "--speed"),
    # an inch template: the value as typed, in inches, with the mm value beside it
    (["spec", T, "--set", "hub.crowning.radius=0.1"], "hub.crowning.radius = 0.1 in (2.54 mm)"),
]


@pytest.mark.parametrize("argv, words", BAD, ids=[" ".join(a) or "(none)" for a, _ in BAD])
def test_bad_input_exits_2_with_one_line_naming_the_field(argv, words, files, capsys,
                                                          tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # anything written by mistake lands here
    code = main([a.replace("{d}", str(files)) for a in argv])
    err = capsys.readouterr().err
    assert code == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("gearcoupling: error:") and words in lines[0], err
    assert lines[0].count("gearcoupling:") == 1, err  # one prefix, not one per parser
    assert not (tmp_path / "outputs").exists() or not any((tmp_path / "outputs").rglob("*.*"))


def test_there_are_at_least_40_bad_inputs():
    assert len(BAD) >= 40


def test_every_command_with_options_has_bad_inputs():
    import argparse

    from gearcoupling.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    per_command = {name: sum(1 for argv, _ in BAD if argv[:1] == [name]) for name in sub.choices}
    assert {n: k for n, k in per_command.items() if k < 2 and n != "templates"} == {}


@pytest.mark.parametrize("name", ["../../escape", "/tmp/absolute-escape", "..", "a/b\\c", ""])
def test_a_spec_name_never_chooses_where_files_go(name, tmp_path, monkeypatch, capsys):
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    assert main(["run", T, "--only", "spec", "--set", f"name={name!r}".replace("'", '"')]) == 0
    written = [p for p in tmp_path.rglob("spec.json")]
    assert len(written) == 1
    out = written[0].parent
    assert out.parent == work / "outputs" and not out.name.startswith(".")
    assert not os.path.exists("/tmp/absolute-escape")


def test_spec_json_into_a_closed_pipe_is_quiet():
    # `gearcoupling spec --json | head` with the reader gone before the write
    proc = subprocess.Popen([sys.executable, "-m", "gearcoupling", "spec", T, "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()
    _, err = proc.communicate(timeout=120)
    assert b"Traceback" not in err and b"BrokenPipe" not in err, err.decode()
    assert proc.returncode == 0


def test_a_signal_while_the_temporary_is_made_leaves_none_behind(tmp_path, monkeypatch):
    """A SIGTERM that lands just after the temporary file exists, before the writer knows
    its name, is held until it does and then raised where the writer removes it: the study
    interrupted on CI left ``.chunk-000003.parquet.<pid>.<random>.parquet`` (0 bytes)."""
    import tempfile

    from gearcoupling.io import atomic_path

    made = tempfile.mkstemp

    def mkstemp(*args, **kwargs):
        out = made(*args, **kwargs)
        signal.raise_signal(signal.SIGTERM)
        return out

    class Stopped(Exception):
        pass

    def stop(signum, frame):
        raise Stopped

    monkeypatch.setattr(tempfile, "mkstemp", mkstemp)
    old = signal.signal(signal.SIGTERM, stop)
    try:
        with pytest.raises(Stopped), atomic_path(tmp_path / "chunk.parquet") as tmp:
            tmp.write_text("never written")
    finally:
        signal.signal(signal.SIGTERM, old)
    assert list(tmp_path.iterdir()) == []


def test_viewer_ports_are_tried_a_bounded_number_of_times():
    from gearcoupling.viewer.server import free_port

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        t0 = time.perf_counter()
        with pytest.raises(gc.ArgumentError, match="taken") as info:
            free_port("127.0.0.1", port, tries=1)
        assert info.value.field == "port" and time.perf_counter() - t0 < 5
        assert free_port("127.0.0.1", port, tries=50) > port
    with pytest.raises(gc.ArgumentError, match="cannot be resolved"):
        free_port("no.such.host.invalid", 8080)


def test_the_last_port_is_not_exceeded():
    from gearcoupling.viewer.server import free_port

    with socket.socket() as taken:
        try:
            taken.bind(("127.0.0.1", 65535))
        except OSError:
            pytest.skip("port 65535 is in use on this machine")
        taken.listen()
        with pytest.raises(gc.ArgumentError, match="65535-65535"):
            free_port("127.0.0.1", 65535)


def test_serving_beyond_this_machine_warns():
    from gearcoupling.viewer.server import exposure_warning

    assert exposure_warning("127.0.0.1") is None and exposure_warning("localhost") is None
    assert "Save static HTML" in exposure_warning("0.0.0.0")


# --- issue 28, items 1-3: a target that is not a regular file; interruptions -------------

def _special_targets(d):
    """``{kind: path}`` of existing targets that are not regular files: a link to
    /dev/null (replacing the link would be the bug, /dev/null itself is never at risk),
    a named pipe, a socket and a folder."""
    d.mkdir(exist_ok=True)
    paths = {"device": d / "devnull-link", "fifo": d / "fifo", "socket": d / "sock",
             "folder": d / "folder"}
    paths["device"].symlink_to(os.devnull)
    os.mkfifo(paths["fifo"])
    sock = socket.socket(socket.AF_UNIX)
    sock.bind(str(paths["socket"]))
    sock.close()  # the socket file stays
    paths["folder"].mkdir()
    return paths


def _unchanged(paths) -> bool:
    import stat as st

    return (os.readlink(paths["device"]) == os.devnull
            and st.S_ISFIFO(os.lstat(paths["fifo"]).st_mode)
            and st.S_ISSOCK(os.lstat(paths["socket"]).st_mode)
            and paths["folder"].is_dir() and not any(paths["folder"].iterdir()))


WORDS = {"device": "character device", "fifo": "named pipe", "socket": "socket",
         "folder": "folder"}


@pytest.mark.parametrize("kind", list(WORDS))
def test_view_html_refuses_a_target_that_is_not_a_regular_file(kind, tmp_path, capsys):
    targets = _special_targets(tmp_path / "t")
    code = main(["view", "industrial-m2", "--html", str(targets[kind])])
    err = capsys.readouterr().err
    assert code == 2 and "--html" in err and WORDS[kind] in err, err
    assert len(err.strip().splitlines()) == 1, err
    assert _unchanged(targets)


@pytest.mark.parametrize("kind", list(WORDS))
def test_every_file_writer_refuses_a_special_target_before_any_work(kind, tmp_path):
    from gearcoupling.io import write_text
    from gearcoupling.plots import save_figure

    targets = _special_targets(tmp_path / "t")
    spec = gc.load_spec("industrial-m2")
    path = targets[kind]
    # a bad tolerance that the work would refuse: the target is refused first
    calls = [lambda: gc.write_html(spec, path, tolerance_mm=-1.0),
             lambda: gc.export_part(spec, "hub", path, tolerance_mm=-1.0),
             lambda: write_text(path, "x"),
             lambda: save_figure(None, path)]
    for call in calls:
        with pytest.raises(gc.ArgumentError, match=WORDS[kind]):
            call()
    assert _unchanged(targets)


@pytest.mark.parametrize("kind", ["device", "fifo", "socket"])
def test_folder_writers_refuse_a_special_file_in_the_folder_before_any_work(kind, tmp_path,
                                                                            capsys):
    targets = _special_targets(tmp_path / "t")
    out = tmp_path / "out"
    out.mkdir()
    os.rename(targets[kind], out / "spec.json")  # where `run` writes the resolved spec
    code = main(["run", "industrial-m2", "--only", "sections,spec", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "spec.json" in err and WORDS[kind] in err, err
    assert sorted(p.name for p in out.iterdir()) == ["spec.json"]  # no sections.png either
    spec = gc.load_spec("industrial-m2")
    for call in (lambda: gc.run(spec, out, only=["sections", "spec"]),
                 lambda: gc.report(spec, out, angles=-1)):
        with pytest.raises(gc.ArgumentError, match=WORDS[kind]):
            call()
    for kind2 in ("device", "fifo", "socket"):  # the folder itself is not a folder
        if kind2 != kind:
            with pytest.raises(gc.ArgumentError, match=WORDS[kind2]):
                gc.run(spec, targets[kind2], only=["spec"])


def _snapshot(folder):
    return {p.relative_to(folder): (p.stat().st_mtime, p.stat().st_size)
            for p in folder.rglob("*") if p.is_file()}


def _interrupt(argv, cwd, sig, ready, *, group=False, started=None):
    """Start ``gearcoupling ARGV`` in its own session, wait for ``ready()``, send ``sig``
    (to the whole process group with ``group``, as Ctrl-C in a terminal does). Returns
    ``(exit status, stderr, time sent)`` once no process of the session is left (at most
    30 s after the command's exit)."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-m", "gearcoupling", *argv], cwd=cwd,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                            start_new_session=True)
    if started is not None:  # the caller's ready() may look at the process group
        started.append(proc.pid)
    try:
        end = time.monotonic() + 180
        while not ready():
            assert proc.poll() is None, proc.communicate()[1].decode()
            assert time.monotonic() < end, "the command never got ready"
            time.sleep(0.02)
        sent = time.time()
        (os.killpg if group else os.kill)(proc.pid, sig)
        try:
            _, err = proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            pytest.fail("still running 60 s after the signal, or a worker holds its output open")
        end = time.monotonic() + 30
        while _session_alive(proc.pid):
            assert time.monotonic() < end, f"workers outlived the signal: " \
                                           f"{_session_alive(proc.pid)}"
            time.sleep(0.1)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        for pid in _session_alive(proc.pid):  # leave nothing behind on a failure
            os.kill(pid, signal.SIGKILL)
    return proc.returncode, err.decode(), sent


def _check_interrupted(code, err, sig, out, sent, files_before):
    import re

    assert "Traceback" not in err, err
    assert code == 128 + sig, (code, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    match = re.fullmatch(r"gearcoupling: interrupted; (\d+) files? complete in (.+)", lines[0])
    assert match, err
    assert os.path.samefile(match[2], out)
    now = _snapshot(out)
    assert not any(p.name.startswith(".") for p in now), now  # no temporaries
    assert int(match[1]) == len(set(now) - set(files_before))
    time.sleep(3.0)  # a surviving writer would add or change files now
    assert _snapshot(out) == now
    late = {p: t for p, (t, _) in now.items() if t > sent + 0.5}
    assert not late, f"written after the signal: {late}"


@pytest.mark.slow
@pytest.mark.parametrize("sig, group", [(signal.SIGTERM, False), (signal.SIGINT, True)],
                         ids=["SIGTERM", "Ctrl-C"])
def test_run_interrupted_stops_its_workers_and_writes_nothing_after(sig, group, tmp_path):
    out = tmp_path / "out"
    code, err, sent = _interrupt(["run", "industrial-m2", "--workers", "2", "-o", str(out)],
                                 tmp_path, sig, lambda: (out / "hub.stl").exists(),
                                 group=group)
    _check_interrupted(code, err, sig, out, sent, {})


@pytest.mark.slow
def test_capacity_interrupted_by_ctrl_c_says_so_in_one_line(tmp_path):
    out = tmp_path / "out"
    code, err, sent = _interrupt(["capacity", "industrial-m2", "-o", str(out)], tmp_path,
                                 signal.SIGINT, out.exists, group=True)
    _check_interrupted(code, err, signal.SIGINT, out, sent, {})


def _solver_running(pgid: int) -> bool:
    """A ccx process in the process group ``pgid``."""
    for pid in _session_alive(pgid):
        with contextlib.suppress(OSError), open(f"/proc/{pid}/comm") as fh:
            if fh.read().strip() == "ccx":
                return True
    return False


@pytest.mark.slow
@pytest.mark.needs_fea
def test_stiffness_interrupted_kills_its_solvers(tmp_path):
    """SIGTERM while a ccx run of the FE table waits in a thread (and the main thread meshes
    the other part in gmsh): the solver is killed at the signal, the command exits 143 with
    its one line, and no table reaches the cache. Before, gmsh's OpenCASCADE handler ended
    the process at once (-15) and left the solver running. The coarsest mesh (module / 2):
    the signal goes at the solver's start, and its solves still take seconds after it
    (with the solvers left running the test fails: they outlive the signal by 3 s)."""
    out, cache = tmp_path / "out", tmp_path / "cache"
    box: list[int] = []
    seen: list[float] = []

    def ready() -> bool:
        return bool(box) and _solver_running(box[0])

    def watch() -> None:  # when the last solver of the group went
        while _solver_running(box[0]):
            time.sleep(0.05)
        seen.append(time.time())

    import threading

    watcher = threading.Thread(target=watch, daemon=True)

    def start() -> bool:
        if ready():
            watcher.start()
            return True
        return False

    code, err, sent = _interrupt(["stiffness", "industrial-m2", "--size", "1.0", "--cache",
                                  str(cache), "-o", str(out)], tmp_path, signal.SIGTERM, start,
                                 started=box)
    # the watcher polls every 50 ms and may not have run yet (a loaded machine): wait for it
    # up to the limit, no longer
    if watcher.ident is not None:
        watcher.join(timeout=max(0.0, sent + 3.0 - time.time()))
    assert seen and seen[0] - sent < 3.0, "a solver outlived the signal by 3 s"
    assert code == 128 + signal.SIGTERM and "Traceback" not in err, err
    assert "interrupted" in err and len(err.strip().splitlines()) == 1, err
    assert not list(cache.rglob("*.json"))  # no table from after the signal


STUDY_28 = """\
[study]
base = "industrial-m2"
chunk = 1
outputs = ["critical_misalignment_deg"]
[accuracy]
angle_tolerance_deg = 1e-2
steps = 4
[[vary]]
key = "hub.crowning.radius"
range = [40.0, 200.0]
steps = 40
"""


@pytest.mark.slow
@pytest.mark.needs_dask
@pytest.mark.parametrize("sig, group", [(signal.SIGTERM, False), (signal.SIGINT, True)],
                         ids=["SIGTERM", "Ctrl-C"])
def test_study_interrupted_stops_its_scheduler_and_workers(sig, group, tmp_path):
    (tmp_path / "s.toml").write_text(STUDY_28)
    out = tmp_path / "out"
    parts = out / "parts"
    code, err, sent = _interrupt(["study", "s.toml", "--workers", "2", "-o", str(out)],
                                 tmp_path, sig, lambda: parts.is_dir() and any(
                                     parts.glob("chunk-*.parquet")), group=group)
    _check_interrupted(code, err, sig, out, sent, {})


@pytest.mark.slow
@pytest.mark.needs_dask
@pytest.mark.parametrize("sig, group", [(signal.SIGTERM, False), (signal.SIGINT, True)],
                         ids=["SIGTERM", "Ctrl-C"])
def test_study_interrupted_while_its_cluster_starts_stops(sig, group, tmp_path):
    """The signal goes when the first worker process exists and the manifest does not
    (the cluster is starting). Before, SIGINT was ignored in that window (so that the
    workers inherited it ignored): a Ctrl-C was lost and the whole study ran (exit 0).
    Now it is noted, raised once the cluster exists, and the cluster closed; the workers
    inherit it blocked instead."""
    (tmp_path / "s.toml").write_text(STUDY_28)
    out = tmp_path / "out"
    box: list[int] = []

    def starting() -> bool:
        return bool(box) and len(_session_alive(box[0])) > 1 and out.is_dir() and not (
            out / "study_manifest.json").exists()

    code, err, sent = _interrupt(["study", "s.toml", "--workers", "2", "-o", str(out)],
                                 tmp_path, sig, starting, group=group, started=box)
    _check_interrupted(code, err, sig, out, sent, {})
    assert not (out / "study_manifest.json").exists()


# --- issue 28, items 6, 8, 12, 14: inputs read before any work, nothing left on failure --

SCANS = {"empty.stl": b"", "binary.stl": bytes(range(256)) * 40,
         "malformed.stl": b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2\nendsolid\n",
         "malformed.ply": b"ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n",
         "nan.csv": b"x,y,z\n1,2,3\nnan,1,2\n"}


@pytest.mark.parametrize("name", list(SCANS))
def test_report_reads_the_scan_before_any_work_and_leaves_no_folder(name, tmp_path, capsys):
    scan = tmp_path / name
    scan.write_bytes(SCANS[name])
    out = tmp_path / "report"
    code = main(["report", T, "--scan", str(scan), "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "--scan" in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()  # none of the stages' files


def test_report_pdf_without_playwright_is_refused_before_any_work(tmp_path, capsys,
                                                                 monkeypatch):
    monkeypatch.setitem(sys.modules, "playwright.sync_api", None)  # the extra not installed
    out = tmp_path / "report"
    assert main(["report", T, "--pdf", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "playwright" in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


def test_a_huge_spec_gives_a_short_message(tmp_path, capsys):
    # an unknown table of 100 000 keys: the message quotes a bounded part of it
    spec = tmp_path / "huge.toml"
    spec.write_text("[tooth]\nteeth = 38\nmodule = 2.0\n[hub]\nface_width = 16.0\n[junk]\n"
                    + "".join(f"k{i} = {i}\n" for i in range(100_000)))
    assert main(["spec", str(spec)]) == 2
    err = capsys.readouterr().err
    assert "junk" in err and len(err) < 2500, len(err)


@pytest.mark.needs_dask
def test_an_unreachable_scheduler_leaves_no_manifest(tmp_path, capsys):
    (tmp_path / "s.toml").write_text(STUDY_28)
    out = tmp_path / "out"
    with socket.socket() as free:  # a port nobody listens on
        free.bind(("127.0.0.1", 0))
        port = free.getsockname()[1]
    code = main(["study", str(tmp_path / "s.toml"), "--scheduler", f"tcp://127.0.0.1:{port}",
                 "--connect-timeout", "1", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "scheduler" in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists() or not any(out.rglob("*"))


@pytest.mark.needs_fea
def test_a_stopped_process_starts_no_new_solver(tmp_path):
    """After an interruption's stop_solvers a thread that reaches run_ccx does not start
    ccx (no log is written: nothing ran); allow_solvers lets the next command solve."""
    from gearcoupling.errors import BackendError
    from gearcoupling.fea import ccx

    ccx.stop_solvers()
    try:
        with pytest.raises(BackendError, match="interrupted"):
            ccx.run_ccx("*HEADING\n", tmp_path / "stopped")
        assert not (tmp_path / "stopped" / "job.log").exists()
    finally:
        ccx.allow_solvers()
    with contextlib.suppress(BackendError):  # an empty model: whatever ccx makes of it
        ccx.run_ccx("*HEADING\n", tmp_path / "allowed")
    assert (tmp_path / "allowed" / "job.log").exists()  # it ran


def test_an_output_folder_is_named_before_it_is_made(tmp_path, monkeypatch):
    """An interruption while the folder is being made still knows where the command was
    writing (the one-line summary names it)."""
    from gearcoupling.commands import WRITING, common

    def interrupted(path, field="out", *, create=True):
        if create:
            raise KeyboardInterrupt
        return path

    monkeypatch.setattr(common, "output_folder", interrupted)
    WRITING.clear()
    with pytest.raises(KeyboardInterrupt):
        common.writing_into(tmp_path / "new")
    assert WRITING == [tmp_path / "new"]
    WRITING.clear()
