"""Studies on a real dask cluster: a `dask scheduler` and two `dask worker` processes on
loopback (subprocesses, bounded waits, always torn down), driven through ``--scheduler``."""

from __future__ import annotations

import itertools
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.study import read_table, spec_hash

pytestmark = [pytest.mark.needs_dask, pytest.mark.slow]

SRC = str(Path(gc.__file__).resolve().parents[1])
STUDY = """\
[study]
base = "renzo-1967"
chunk = 1
outputs = ["critical_misalignment_deg", "min_backlash_mm", "contact_z_max_mm"]
[accuracy]
angle_tolerance_deg = 1e-2
steps = 4
[[vary]]
key = "hub.crowning.radius"
values = [1.5, 2.0, 2.5, 3.0, 3.5, 4.0]
[[vary]]
key = "misalignment_deg"
values = [0.5, 1.0]
"""
WAIT_S = 60.0


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = SRC + os.pathsep + env.get("PYTHONPATH", "")
    return env


def _wait(predicate, what: str, timeout: float = WAIT_S, poll_s: float = 0.05):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if predicate():
            return
        time.sleep(poll_s)
    raise TimeoutError(f"gave up after {timeout:g} s waiting for {what}")


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """``(address, worker processes)`` of a scheduler and two single-threaded workers."""
    from distributed import Client

    tmp = tmp_path_factory.mktemp("dask")
    sched_file = tmp / "scheduler.json"
    log = open(tmp / "dask.log", "w")  # closed in the teardown
    common = dict(env=_env(), stdout=log, stderr=subprocess.STDOUT, cwd=tmp)
    procs = [subprocess.Popen([sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1",
                               "--port", "0", "--no-dashboard", "--scheduler-file",
                               str(sched_file)], **common)]
    try:
        _wait(sched_file.is_file, "the scheduler file")
        _wait(lambda: "address" in json.loads(sched_file.read_text() or "{}"), "its address")
        address = json.loads(sched_file.read_text())["address"]
        workers = [subprocess.Popen([sys.executable, "-m", "dask", "worker", address,
                                     "--nthreads", "1", "--no-nanny", "--no-dashboard",
                                     "--host", "127.0.0.1", "--death-timeout", "60"], **common)
                   for _ in range(2)]
        procs += workers
        with Client(address, timeout=WAIT_S) as client:
            client.wait_for_workers(2, timeout=WAIT_S)
        yield address, workers
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in reversed(procs):
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(timeout=15)
        log.close()


@pytest.fixture(scope="module")
def study_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("study") / "tiny.toml"
    path.write_text(STUDY)
    return path


@pytest.fixture(scope="module")
def uninterrupted(cluster, study_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("full")
    assert main(["study", str(study_file), "-o", str(out), "--scheduler", cluster[0],
                 "--no-plots"]) == 0
    return read_table(out / "study.parquet")


def test_rows_equal_single_spec_runs(uninterrupted):
    from gearcoupling.clearance.design import critical_misalignment_deg, min_backlash_rad

    assert len(uninterrupted) == 12 and [r["sample"] for r in uninterrupted] == list(range(12))
    crit = {}
    for row in uninterrupted:
        rc = row["hub.crowning.radius"]
        spec = gc.load_spec("renzo-1967", **{"hub.crowning.radius": rc})
        if rc not in crit:
            crit[rc] = critical_misalignment_deg(spec, tolerance_deg=1e-2)
        assert row["error"] is None and row["spec_hash"] == spec_hash(spec)
        assert row["critical_misalignment_deg"] == crit[rc]
        assert row["min_backlash_mm"] == min_backlash_rad(
            spec, row["misalignment_deg"], steps=4) * spec.tooth.pitch_radius
    # crowning radius up -> the contact reaches the face end earlier (docs/conventions.md, Tooth
    # geometry)
    values = [crit[rc] for rc in sorted(crit)]
    assert all(a > b for a, b in itertools.pairwise(values))


def test_resume_after_kill_gives_the_same_table(cluster, study_file, uninterrupted, tmp_path,
                                                capsys):
    for attempt in range(3):  # warm workers may finish all 12 between two looks: again
        out = tmp_path / f"killed-{attempt}"
        parts = out / "parts"
        run = subprocess.Popen([sys.executable, "-m", "gearcoupling", "study", str(study_file),
                                "-o", str(out), "--scheduler", cluster[0], "--no-plots"],
                               env=_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            _wait(lambda parts=parts: parts.is_dir() and any(parts.glob("chunk-*.parquet")),
                  "a first part", poll_s=0.002)
        finally:
            run.send_signal(signal.SIGKILL)
            run.wait(timeout=15)
        done = len(list(parts.glob("chunk-*.parquet")))
        if done < 12:
            break
    assert 1 <= done < 12, "the run finished before the kill three times: a slower study"
    assert not (out / "study.parquet").exists()
    for part in parts.glob("chunk-*.parquet"):  # a kill never leaves a half-written part
        assert len(read_table(part)) == 1
    capsys.readouterr()
    assert main(["study", str(study_file), "-o", str(out), "--scheduler", cluster[0],
                 "--no-plots"]) == 0
    said = capsys.readouterr().out
    assert f"resuming: {done} finished chunk(s)" in said and f"{12 - done} to run" in said
    assert read_table(out / "study.parquet") == uninterrupted


def test_unreachable_scheduler_names_the_address(study_file, tmp_path, capsys):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    t0 = time.monotonic()
    assert main(["study", str(study_file), "-o", str(tmp_path), "--scheduler", address,
                 "--connect-timeout", "2"]) == 2
    assert time.monotonic() - t0 < 30
    err = capsys.readouterr().err
    assert address in err and "cannot reach the dask scheduler" in err


def test_worker_killed_mid_study_is_retried(cluster, study_file, uninterrupted, tmp_path):
    """Runs last in this module: it leaves one worker."""
    out = tmp_path / "lost-worker"
    parts = out / "parts"
    run = subprocess.Popen([sys.executable, "-m", "gearcoupling", "study", str(study_file), "-o",
                            str(out), "--scheduler", cluster[0], "--no-plots"], env=_env(),
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        _wait(lambda: parts.is_dir() and any(parts.glob("chunk-*.parquet")), "a first part")
        cluster[1][0].send_signal(signal.SIGKILL)
        _, err = run.communicate(timeout=120)
    finally:
        if run.poll() is None:
            run.kill()
            run.wait(timeout=15)
    assert run.returncode == 0, err
    assert read_table(out / "study.parquet") == uninterrupted


def test_local_cluster_by_default(tmp_path, capsys):
    study = tmp_path / "local.toml"
    study.write_text('[study]\nbase = "renzo-1967"\noutputs = ["min_backlash_mm"]\n'
                     '[accuracy]\nsteps = 2\n[[vary]]\nkey = "misalignment_deg"\n'
                     'values = [0.0, 1.0]\n[[plot]]\nx = "misalignment_deg"\n'
                     'y = "min_backlash_mm"\n')
    assert main(["study", str(study), "-o", str(tmp_path / "out"), "--workers", "1"]) == 0
    rows = read_table(tmp_path / "out" / "study.parquet")
    spec = gc.load_spec("renzo-1967")
    # aligned, the smallest backlash over the turn is the spec's aligned backlash
    assert rows[0]["min_backlash_mm"] == pytest.approx(spec.derived["aligned_backlash_mm"],
                                                       rel=1e-6)
    assert rows[1]["min_backlash_mm"] < rows[0]["min_backlash_mm"]
    assert (tmp_path / "out" / "plot-0-min_backlash_mm.png").stat().st_size > 1000
