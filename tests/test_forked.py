"""The forked map of the report's capacity points (outputs/forked.py): the same answers as
in one process, a worker's error raised in the parent, no worker outliving an interrupt."""

import os
import signal
import time

import pytest

import gearcoupling as gc
from gearcoupling.errors import ArgumentError
from gearcoupling.outputs.forked import can_fork, fork_map

pytestmark = pytest.mark.skipif(not can_fork(), reason="needs the fork start method")


def _pid_of(_item):
    return os.getpid()


def test_fork_map_keeps_the_order_and_runs_in_two_workers():
    seen = []
    pids = fork_map(_pid_of, list(range(5)), 2, done=seen.append)
    assert os.getpid() not in pids
    assert len(set(pids)) == 2
    assert pids[0::2] == [pids[0]] * 3 and pids[1::2] == [pids[1]] * 2  # round robin
    assert seen == [1, 2, 3, 4, 5]
    assert fork_map(_pid_of, [0, 1], 1) == [os.getpid()] * 2  # one worker: this process


def _fails_on_three(x):
    if x == 3:
        raise ArgumentError("x", x, "not 3")
    return x


def test_a_workers_error_is_raised_in_the_parent():
    with pytest.raises(ArgumentError, match="not 3"):
        fork_map(_fails_on_three, [0, 1, 2, 3], 2)


def test_an_interrupt_kills_and_reaps_the_workers(tmp_path):
    parent = os.getpid()

    def slow(x):
        (tmp_path / f"{os.getpid()}.pid").touch()
        while len(list(tmp_path.glob("*.pid"))) < 2:
            time.sleep(0.01)
        if x == 1:
            os.kill(parent, signal.SIGINT)
        time.sleep(60.0)

    # Python's own Ctrl-C handler (a CLI test run before may have left its own)
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    t0 = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            fork_map(slow, [0, 1], 2)
    finally:
        signal.signal(signal.SIGINT, before)
    assert time.monotonic() - t0 < 30.0
    pids = [int(p.stem) for p in tmp_path.glob("*.pid")]
    assert len(pids) == 2
    for pid in pids:  # killed and reaped: no such process
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)


def test_forked_capacity_points_equal_those_of_one_process():
    spec = gc.load_spec("industrial-m2")
    one = gc.compare_capacity([spec], [0.5, 1.0, 2.0], model="compliance", workers=1)
    two = gc.compare_capacity([spec], [0.5, 1.0, 2.0], model="compliance", workers=2)
    assert [c.row() for c in two.curves[spec.name]] == [c.row() for c in one.curves[spec.name]]
    with pytest.raises(ArgumentError, match="workers"):
        gc.compare_capacity([spec], [1.0], workers=3)
