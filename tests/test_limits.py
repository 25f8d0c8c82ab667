"""Studies, schedulers and resources at their limits (issue 38, items 8-10): a scheduler
address where no dask scheduler answers, study files asking for too many samples, TOML
nested without end, scans with absurd coordinates, and parts over the memory budget. Each
is refused with exit 2 and one line naming what is wrong, in bounded time."""

from __future__ import annotations

import http.server
import os
import resource
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.errors import ArgumentError, SpecError
from gearcoupling.io import MAX_NESTING
from gearcoupling.parts import build_part, check_tolerance, part_size
from gearcoupling.parts.size import BYTES_PER_TRIANGLE, MEMORY_ENV
from gearcoupling.study import load_study
from random_specs import STRATA, random_spec_data

SRC = str(Path(gc.__file__).resolve().parents[1])
STUDY = """\
[study]
base = "renzo-1967"
outputs = ["critical_misalignment_deg"]
[[vary]]
key = "hub.crowning.radius"
values = [2.0, 2.5]
"""
# 300 teeth, module 60, face 600 mm: the top of the documented range (issue 38, item 10)
BIG = """\
units = "mm"
[tooth]
teeth = 300
module = 60.0
[hub]
face_width = 600.0
backlash = 7.5
[hub.tip]
diameter = 18120.0
[hub.root]
dedendum = 75.0
fillet_radius = 18.0
[hub.crowning]
kind = "circular"
radius = 9000.0
[hub.body]
bore_diameter = 17000.0
length = 1200.0
[sleeve]
face_width = 900.0
minor_diameter = 17920.0
major_diameter = 18150.0
tip_chamfer = 6.0
root_fillet_radius = 15.0
outer_diameter = 19000.0
"""
CONNECT_S = 1.0
MARGIN_S = 4.0  # of a refused peer over --connect-timeout: reading the study, on a busy machine


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != MEMORY_ENV}
    env["PYTHONPATH"] = SRC + os.pathsep + env.get("PYTHONPATH", "")
    return {**env, **extra}


def _one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("gearcoupling: error: "), err
    return lines[0]


def _in_thread(call, timeout_s: float):
    """``call()``'s result, or None if it is still running after ``timeout_s`` (a daemon
    thread: a hang fails the test instead of stopping the suite)."""
    box: list = []
    worker = threading.Thread(target=lambda: box.append(call()), daemon=True)
    worker.start()
    worker.join(timeout_s)
    return box[0] if box else None


# ------------------------------------------------------------------ scheduler peers


class _Peer:
    """A TCP server on loopback that is no dask scheduler: ``http`` (python's
    http.server, which waits for a request), ``http400`` (answers ``HTTP/1.0 400`` at once
    and closes) or ``silent`` (accepts and never answers)."""

    def __init__(self, kind: str):
        self.conns: list[socket.socket] = []
        if kind == "http":
            self.server = http.server.ThreadingHTTPServer(
                ("127.0.0.1", 0), http.server.BaseHTTPRequestHandler)
            self.port = self.server.server_address[1]
            threading.Thread(target=self.server.serve_forever, daemon=True).start()
            return
        self.server = None
        self.sock = socket.create_server(("127.0.0.1", 0))
        self.port = self.sock.getsockname()[1]
        threading.Thread(target=self._serve, args=(kind,), daemon=True).start()

    def _serve(self, kind: str) -> None:
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            if kind == "http400":
                conn.sendall(b"HTTP/1.0 400 Bad Request\r\n\r\n")
                conn.close()
            else:
                self.conns.append(conn)

    def close(self) -> None:
        if self.server is not None:
            self.server.shutdown()
            self.server.server_close()
        else:
            self.sock.close()
        for c in self.conns:
            c.close()


@pytest.fixture
def study_file(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(STUDY)
    load_study(path)  # warm: the refusal is timed, not the first spec build
    return path


@pytest.mark.parametrize("kind, found", [
    ("http", f"sent nothing in {CONNECT_S:g} s"),
    ("http400", r"sent b'HTTP/1.0 400 Bad Request\r\n\r\n' (an HTTP server)"),
    ("silent", f"sent nothing in {CONNECT_S:g} s"),
])
def test_a_peer_that_is_no_dask_scheduler_is_refused_within_the_connect_timeout(
        kind, found, study_file, tmp_path, capsys):
    """Before: the HTTP server and the silent one hung the study past 300 s with
    --connect-timeout 5; the 400 answer, read as a frame length, gave "out of memory"."""
    peer = _Peer(kind)
    out = tmp_path / "out"
    try:
        t0 = time.monotonic()
        code = _in_thread(lambda: main(["study", str(study_file), "-o", str(out), "--scheduler",
                                        f"tcp://127.0.0.1:{peer.port}", "--connect-timeout",
                                        f"{CONNECT_S:g}"]), CONNECT_S + MARGIN_S + 30)
        took = time.monotonic() - t0
    finally:
        peer.close()
    assert code == 2, f"exit {code} after {took:.1f} s"
    assert took < CONNECT_S + MARGIN_S, took
    line = _one_line(capsys.readouterr().err)
    assert "--scheduler" in line and "is not a dask scheduler" in line and found in line, line
    assert not out.exists() or not any(out.rglob("*"))


def test_tls_scheduler_is_refused_up_front_naming_the_allowed_scheme(study_file, capsys):
    """Before: a TypeError traceback from dask (TLS without a security context)."""
    assert main(["study", str(study_file), "--scheduler", "tls://127.0.0.1:8786"]) == 2
    line = _one_line(capsys.readouterr().err)
    assert "--scheduler" in line and "tcp://HOST:PORT" in line and "tls://" in line, line


@pytest.mark.needs_dask
def test_a_real_dask_scheduler_passes_the_probe():
    """The probe reads a real scheduler's handshake (dask's framing) and lets it through."""
    from distributed import LocalCluster

    from gearcoupling.study.peer import probe_scheduler

    with LocalCluster(n_workers=0, processes=False, protocol="tcp", host="127.0.0.1",
                      dashboard_address=None) as cluster:
        t0 = time.monotonic()
        probe_scheduler(cluster.scheduler_address, 5.0)
        assert time.monotonic() - t0 < 5.0


# ------------------------------------------------------------------ study sample counts


def test_a_list_of_two_million_values_is_refused_before_it_is_parsed(tmp_path):
    """Before: every value built a spec before the count was checked (not refused after
    400 s). The list is counted from the text's commas: refused well before tomllib has
    parsed it (about 3 s here)."""
    path = tmp_path / "two-million.toml"
    path.write_text(STUDY.replace("values = [2.0, 2.5]",
                                  "values = [" + "2.0, " * 1_999_999 + "2.0]"))
    t0 = time.monotonic()
    outcome = _in_thread(lambda: _refusal(path), 30.0)
    took = time.monotonic() - t0
    assert outcome is not None, "not refused within 30 s"
    assert isinstance(outcome, SpecError), outcome
    assert f"{path}:6 values" in str(outcome) and "1999999 values" in str(outcome), outcome
    assert took < 3.0, took


def _refusal(path: Path) -> Exception | None:
    try:
        load_study(path)
    except Exception as err:  # the test looks at the type
        return err
    return None


def test_the_sample_count_is_checked_before_any_value_builds_a_spec(tmp_path):
    """A grid of 1000 x 1000 x 3 samples whose last value the spec refuses: the count
    (from the lists' lengths and steps) is refused first. Before, every value built a spec
    first, so the value was refused and a long list took minutes."""
    path = tmp_path / "grid.toml"
    path.write_text(STUDY.replace("values = [2.0, 2.5]", "values = [2.0, 2.5, -1.0]")
                    + '[[vary]]\nkey = "tooth.pressure_angle_deg"\nrange = [15.0, 25.0]\n'
                    "steps = 1000\n[[vary]]\nkey = \"misalignment_deg\"\n"
                    "range = [0.1, 1.0]\nsteps = 1000\n")
    with pytest.raises(SpecError) as err:
        load_study(path)
    assert err.value.value == 3_000_000, err.value
    assert "3 x 1000 x 1000" in str(err.value) and "1 to 1000000" in str(err.value)


# ------------------------------------------------------------------ nesting


def _nested(form: str, depth: int) -> str:
    if form == "array":
        return "extra = " + "[" * depth + "]" * depth
    if form == "table":
        return "extra = " + "{a = " * depth + "1" + "}" * depth
    return ".".join(["extra"] * depth) + " = 1"  # a dotted key


@pytest.mark.parametrize("form", ["array", "table", "dotted"])
@pytest.mark.parametrize("depth", [10, 1000, 100_000])
def test_deeply_nested_spec_files_are_refused_naming_file_and_limit(form, depth, tmp_path,
                                                                    capsys):
    """Before: a RecursionError with a 3000-line traceback (arrays and inline tables from
    about 400 levels; a dotted key of 1000 parts when its value was quoted in the error),
    and a dotted key of 100 000 parts took minutes to parse."""
    path = tmp_path / "deep.toml"
    template = (gc.io.bundled_dir("templates") / "industrial-m2.toml").read_text()
    path.write_text(template.replace("[hub]\n", f"[hub]\n{_nested(form, depth)}\n", 1))
    t0 = time.monotonic()
    assert main(["spec", str(path)]) == 2
    line = _one_line(capsys.readouterr().err)
    if depth <= MAX_NESTING:  # the ordinary refusal of a key the spec does not have
        assert "hub.extra" in line and "unknown key" in line, line
    else:
        assert f"{path}:" in line and f"at most {MAX_NESTING} levels" in line, line
    assert time.monotonic() - t0 < 5.0


def test_nesting_of_headers_and_dotted_keys_together_is_counted_after_parsing(tmp_path,
                                                                            capsys):
    """The header nests 21 levels (the root and 20 tables), the key 20 tables more: each
    line passes the text's check, the parsed data (41 levels) is refused."""
    path = tmp_path / "deep.toml"
    path.write_text("[" + ".".join(["a"] * 20) + "]\n" + ".".join(["b"] * 21) + " = 1\n")
    assert main(["spec", str(path)]) == 2
    line = _one_line(capsys.readouterr().err)
    assert f"{path} = nested 41 levels deep" in line and f"at most {MAX_NESTING}" in line, line


@pytest.mark.parametrize("where", ["study", "set"])
def test_deep_nesting_in_a_study_file_or_a_set_value_is_refused(where, tmp_path, capsys):
    """Before: RecursionError tracebacks (the study file's value, ``--set``'s TOML)."""
    deep = "[" * 1000 + "]" * 1000
    if where == "study":
        path = tmp_path / "deep-study.toml"
        path.write_text(STUDY.replace("values = [2.0, 2.5]", f"values = [2.0, {deep}]"))
        argv = ["study", str(path), "-o", str(tmp_path / "out")]
        named = f"{path}:6"
    else:
        argv = ["spec", "industrial-m2", "--set", f"hub.face_width={deep}"]
        named = "--set hub.face_width"
    assert main(argv) == 2
    line = _one_line(capsys.readouterr().err)
    assert named in line and f"at most {MAX_NESTING} levels" in line, line


# ------------------------------------------------------------------ scan magnitudes


@pytest.fixture(scope="module")
def far_scan(tmp_path_factory):
    """A CSV scan of 200 points about the industrial-m2 hub, one at 1e300 mm (finite)."""
    rng = np.random.default_rng(0)
    pts = rng.normal(size=(200, 3)) * 30.0
    pts[5, 1] = 1e300
    path = tmp_path_factory.mktemp("scan") / "far.csv"
    np.savetxt(path, pts, delimiter=",")
    return path


@pytest.mark.parametrize("command", ["compare", "report"])
def test_a_scan_with_coordinates_near_1e300_is_refused_naming_row_and_column(
        command, far_scan, tmp_path, capsys):
    """Before: numpy's LinAlgError ("Eigenvalues did not converge") in the registration,
    exit 1 with a traceback."""
    argv = (["compare", "industrial-m2", str(far_scan)] if command == "compare"
            else ["report", "industrial-m2", "--scan", str(far_scan)])
    assert main([*argv, "-o", str(tmp_path / "out")]) == 2
    line = _one_line(capsys.readouterr().err)
    assert str(far_scan) in line and "row 5, column y = 1e+300 mm" in line, line
    assert "within ±1e+06 mm" in line, line


def test_an_array_scan_with_huge_coordinates_is_refused_by_the_api():
    pts = np.random.default_rng(1).normal(size=(100, 3)) * 30.0
    pts[7, 2] = -2e6
    with pytest.raises(ArgumentError) as err:
        gc.compare_part("industrial-m2", pts)
    assert err.value.field == "points" and "row 7, column z = -2e+06 mm" in str(err.value)


# ------------------------------------------------------------------ parts and memory


def _specs():
    """The templates and a seeded random spec per crown kind."""
    specs = [gc.load_spec(n) for n in gc.template_names()]
    for i, stratum in enumerate(STRATA[::4]):
        data = random_spec_data(np.random.default_rng([i, 38]), *stratum)
        specs.append(gc.spec_from_dict(data))
    return specs


@pytest.mark.slow
def test_the_triangle_estimate_is_the_built_count():
    """The estimate from the layout's grid sizes equals the built mesh's triangle count
    (factor 1, not an approximation) for whole parts and sectors, with and without
    bore and shoulder (measured: equal on all 5 templates, 12 random specs and the
    bore/shoulder variants)."""
    for spec in _specs():
        n = spec.tooth.teeth
        for part in ("hub", "sleeve"):
            for teeth in (None, [0, 1, n - 1]):
                built = len(build_part(spec, part, teeth=teeth).faces)
                assert part_size(spec, part, teeth=teeth).triangles == built, (
                    spec.name, part, teeth)


def test_the_estimate_covers_bore_and_shoulder_variants():
    spec = gc.load_spec("industrial-m2", **{"hub.body.bore_diameter": 0.0,
                                            "hub.body.length": 16.0})
    for teeth in (None, [4, 5]):
        built = len(build_part(spec, "hub", teeth=teeth).faces)
        assert part_size(spec, "hub", teeth=teeth).triangles == built


@pytest.fixture(scope="module")
def big_spec(tmp_path_factory):
    path = tmp_path_factory.mktemp("big") / "big.toml"
    path.write_text(BIG)
    return path


def test_the_documented_minimum_tolerance_is_accepted(big_spec):
    """0.0006 mm is 1e-5 module at module 60; 60 * 1e-5 rounds to 0.0006000000000000001,
    which refused it before."""
    spec = gc.load_spec(big_spec)
    assert check_tolerance(spec, 0.0006) == 0.0006
    assert check_tolerance(spec, 6.0) == 6.0
    for bad in (0.0006 * (1 - 1e-6), 6.0 * (1 + 1e-6)):
        with pytest.raises(ArgumentError):
            check_tolerance(spec, bad)


def test_a_part_over_the_memory_budget_is_refused_with_a_tolerance_that_fits(
        big_spec, tmp_path, capsys, monkeypatch):
    """Before: 66 M triangles (5.7 GB) were built with no estimate; a memory limit
    segfaulted and left an empty folder. The refusal names the count, its memory and a
    tolerance that fits the budget and is not needlessly coarse."""
    monkeypatch.setenv(MEMORY_ENV, "2000")
    out = tmp_path / "out"
    assert main(["generate", str(big_spec), "--tolerance", "0.0006", "-o", str(out)]) == 2
    line = _one_line(capsys.readouterr().err)
    assert "the hub would have 66,127,800 triangles, about 86 GB" in line, line
    assert f"budget of 2 GB ({MEMORY_ENV}=2000)" in line, line
    fit = float(line.split("use a tolerance of ")[1].split(" mm")[0])
    spec = gc.load_spec(big_spec)
    most = 2e9 / BYTES_PER_TRIANGLE
    assert part_size(spec, "hub", tolerance_mm=fit).triangles <= most
    assert part_size(spec, "hub", tolerance_mm=fit / 1.5).triangles > most
    assert not out.exists()


@pytest.mark.slow
def test_under_an_address_space_limit_the_budget_follows_it(big_spec, tmp_path):
    """With ``ulimit -v`` 4 GB and no budget set, the default budget is 75 % of what the
    limit leaves: the part is refused up front (before: a crash under the limit, and an
    empty folder left behind)."""
    out = tmp_path / "out"

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (4 * 2**30, resource.RLIM_INFINITY))

    proc = subprocess.run([sys.executable, "-m", "gearcoupling", "generate", str(big_spec),
                           "--tolerance", "0.00061", "-o", str(out)], env=_env(),
                          preexec_fn=limit, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2, proc.stderr[-2000:]
    line = _one_line(proc.stderr)
    assert "65,506,800 triangles" in line and "75% of the" in line, line
    assert "or coarser" in line, line
    assert not out.exists()


def test_a_bad_memory_budget_is_refused_naming_the_variable(monkeypatch):
    monkeypatch.setenv(MEMORY_ENV, "lots")
    with pytest.raises(ArgumentError) as err:
        build_part("industrial-m2", "sleeve")
    assert err.value.field == MEMORY_ENV
