"""The forked map of the capacity points (gearcoupling/forked.py): the same answers as in one
process, a worker's error raised in the parent, no worker outliving an interrupt. Each
runs in a fresh interpreter: forking needs a process without other threads, and a test
run before may have left one (fork_map then works in this process)."""

import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from fresh_python import run_fresh
from gearcoupling.forked import can_fork

pytestmark = pytest.mark.skipif(not can_fork(), reason="needs the fork start method")


def test_fork_map_keeps_the_order_and_runs_in_two_workers():
    run_fresh("""
        import os
        from gearcoupling.forked import fork_map

        def pid_of(_item):
            return os.getpid()

        seen = []
        pids = fork_map(pid_of, list(range(5)), 2, done=seen.append)
        assert os.getpid() not in pids, pids
        assert len(set(pids)) == 2, pids
        assert pids[0::2] == [pids[0]] * 3 and pids[1::2] == [pids[1]] * 2  # round robin
        assert seen == [1, 2, 3, 4, 5], seen
        assert fork_map(pid_of, [0, 1], 1) == [os.getpid()] * 2  # one worker: this process
    """)


def test_a_workers_error_is_raised_in_the_parent():
    run_fresh("""
        from gearcoupling.errors import ArgumentError
        from gearcoupling.forked import fork_map

        def fails_on_three(x):
            if x == 3:
                raise ArgumentError("x", x, "not 3")
            return x

        try:
            fork_map(fails_on_three, [0, 1, 2, 3], 2)
        except ArgumentError as err:
            assert "not 3" in str(err)
        else:
            raise AssertionError("no error")
    """)


def test_an_interrupt_kills_and_reaps_the_workers(tmp_path):
    """Ctrl-C reaches the parent as soon as both workers run (even while the second is
    still being started: the signals are held over the fork); both are killed and
    reaped."""
    run_fresh("""
        import os, signal, sys, time
        from pathlib import Path
        from gearcoupling.forked import fork_map

        # Python's Ctrl-C handler even where pytest was started with SIGINT ignored (a
        # background job of a script), which Python then leaves ignored
        signal.signal(signal.SIGINT, signal.default_int_handler)
        folder, parent = Path(sys.argv[1]), os.getpid()

        def slow(x):
            (folder / f"{os.getpid()}.pid").touch()
            while len(list(folder.glob("*.pid"))) < 2:
                time.sleep(0.001)
            if x == 1:
                os.kill(parent, signal.SIGINT)
            time.sleep(60.0)

        t0 = time.monotonic()
        try:
            fork_map(slow, [0, 1], 2)
        except KeyboardInterrupt:
            pass
        else:
            raise AssertionError("no KeyboardInterrupt")
        assert time.monotonic() - t0 < 30.0
        pids = [int(p.stem) for p in folder.glob("*.pid")]
        assert len(pids) == 2, pids
        for pid in pids:  # killed and reaped: no such process
            try:
                os.kill(pid, 0)
            except ProcessLookupError:
                continue
            raise AssertionError(f"worker {pid} alive")
    """, str(tmp_path))


def test_an_interrupt_during_a_fork_is_not_lost():
    """Ctrl-C arriving as the parent returns from forking a worker, while a second thread
    runs (the CLI's signal watcher, a library's): that thread takes it (the main one
    holds it) and Python's handler then runs in an after-fork hook (here one that waits
    for it; logging's is another), which drops its exception. It is raised once the
    workers have started, and both are killed and reaped: no child left, not even a
    zombie."""
    run_fresh("""
        import os, select, signal, socket, threading, time
        from gearcoupling.forked import fork_map

        signal.signal(signal.SIGINT, signal.default_int_handler)
        taken, written = socket.socketpair()  # written by the C handler: a thread took it
        written.setblocking(False)
        signal.set_wakeup_fd(written.fileno(), warn_on_full_buffer=False)
        other = threading.Thread(target=threading.Event().wait, daemon=True)
        other.fork_safe = True  # holds no lock: fork_map still forks
        other.start()
        sent = []

        def ctrl_c_at_fork():  # once: the first fork
            if not sent:
                sent.append(signal.SIGINT)
                os.kill(os.getpid(), signal.SIGINT)
                select.select([taken], [], [])

        os.register_at_fork(after_in_parent=ctrl_c_at_fork)
        t0 = time.monotonic()
        try:
            fork_map(time.sleep, [30.0, 30.0], 2)
        except KeyboardInterrupt:
            pass
        else:
            raise AssertionError("the interrupt was lost")
        assert time.monotonic() - t0 < 15.0
        assert_no_child_left("a worker")
    """)


def test_a_signal_held_after_a_dropped_one_is_delivered_every_time():
    """Under the command line's handlers, after a first SIGTERM whose exception a library
    dropped, a SIGINT that comes while signals are held (as over a fork) reaches the
    handler when the hold ends, every time. Before, the first signal left both ignored
    (SIG_IGN): every later one was lost."""
    run_fresh("""
        import os, signal, time
        from gearcoupling.cli import _signals_raise
        from gearcoupling.forked import held_signals

        with _signals_raise():
            try:  # a library that drops the first
                os.kill(os.getpid(), signal.SIGTERM)
                time.sleep(5.0)
            except BaseException:
                pass
            for k in range(20):
                try:
                    with held_signals():
                        os.kill(os.getpid(), signal.SIGINT)
                        time.sleep(0.01)  # held: nothing is raised here
                except KeyboardInterrupt as stop:
                    assert stop.signum == signal.SIGINT, stop
                else:
                    raise AssertionError(f"the held signal {k} was lost")
    """)


def test_a_map_dropped_unstopped_leaves_no_worker():
    """A started map dropped without :meth:`stop` (an interrupt between its start and the
    caller's ``try``) kills and reaps its workers then."""
    run_fresh("""
        import os, time
        from gearcoupling.forked import ForkedMap

        started = ForkedMap(time.sleep, [30.0, 30.0], 2)
        assert len(started.procs) == 2, started.procs
        del started
        assert_no_child_left("a worker")
    """)


def _running(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie has ended: its reaper may be slow)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] not in "ZX"
    except (FileNotFoundError, ProcessLookupError):
        return False


ORPHANED = """
    import os, signal, sys, time
    from pathlib import Path
    from gearcoupling.forked import fork_map

    folder = Path(sys.argv[1])

    def slow_start():
        (folder / f"{os.getpid()}.pid").touch()
        time.sleep(1.0)

    os.register_at_fork(after_in_child=slow_start,
                        after_in_parent=lambda: os.kill(os.getpid(), signal.SIGKILL))
    fork_map(lambda x: (folder / f"item{x}").touch(), [0, 1], 2)
"""


def test_a_worker_whose_parent_ended_before_it_started_ends(tmp_path):
    """The parent killed (SIGKILL: no cleanup) at once after forking a worker that starts
    slowly (a loaded machine), before the worker asked to die with it: the worker ends
    instead of running its item as an orphan."""
    parent = subprocess.run([sys.executable, "-c", textwrap.dedent(ORPHANED), str(tmp_path)],
                            capture_output=True, text=True, timeout=120)
    assert parent.returncode == -9, parent.stderr
    pids = [int(p.stem) for p in tmp_path.glob("*.pid")]
    assert len(pids) == 1, pids
    t0 = time.monotonic()
    while _running(pids[0]):
        assert time.monotonic() - t0 < 60.0, f"the orphaned worker {pids[0]} still runs"
        time.sleep(0.05)
    assert not list(tmp_path.glob("item*")), sorted(p.name for p in tmp_path.iterdir())


def test_forked_capacity_points_equal_those_of_one_process():
    run_fresh("""
        import gearcoupling as gc
        from gearcoupling.errors import ArgumentError

        spec = gc.load_spec("industrial-m2")
        one = gc.compare_capacity([spec], [0.5, 1.0, 2.0], model="compliance", workers=1)
        two = gc.compare_capacity([spec], [0.5, 1.0, 2.0], model="compliance", workers=2)
        assert [c.row() for c in two.curves[spec.name]] == \\
            [c.row() for c in one.curves[spec.name]]
        try:
            gc.compare_capacity([spec], [1.0], workers=3)
        except ArgumentError as err:
            assert "workers" in str(err)
        else:
            raise AssertionError("workers=3 accepted")
    """)
