"""Forked worker processes: when forking is safe, and a map over two of them that leaves no
worker behind (the run's chains, the capacity points of a report)."""

from __future__ import annotations

import contextlib
import multiprocessing
import multiprocessing.connection
import os
import signal
import threading
from collections.abc import Callable, Collection, Iterator, Sequence
from contextlib import contextmanager
from typing import Any, TypeVar, cast

from .errors import BackendError
from .interrupts import check as check_interrupt
from .interrupts import reset as forget_interrupt

T = TypeVar("T")
STOP_SIGNALS = {signal.SIGINT, signal.SIGTERM}  # held while workers fork


def can_fork() -> bool:
    """Forking is safe only from a single-threaded process (no lock held by a thread that
    the child would not have); a thread marked ``fork_safe`` (the CLI's signal watcher,
    which only waits on a socket) does not count."""
    others = [t for t in threading.enumerate()
              if t is not threading.main_thread() and not getattr(t, "fork_safe", False)]
    return "fork" in multiprocessing.get_all_start_methods() and not others


def default_workers() -> int:
    """2 where the machine has two cores or more and forking is safe (:func:`can_fork`),
    else 1."""
    return 2 if (os.cpu_count() or 1) >= 2 and can_fork() else 1


def die_with_parent() -> None:
    """Ask Linux to kill this process when its parent ends, however it ends (a no-op
    elsewhere): a worker never outlives the process that started it. A parent that
    ended before the request (a signal at once after the fork) is not waited for: the
    worker ends at once."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        return
    parent = multiprocessing.parent_process()
    if parent is not None and os.getppid() != parent.pid:  # an orphan already
        os.kill(os.getpid(), signal.SIGKILL)


def worker_signals() -> None:
    """A forked worker leaves signals to its parent: it ignores Ctrl-C (which reaches the
    whole group) and ends at SIGTERM; it dies with the parent (:func:`die_with_parent`)."""
    die_with_parent()
    forget_interrupt()  # the parent's note is the parent's to act on
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)  # blocked over the fork


def _map_worker(func: Callable[..., Any], items: Sequence[Any], indices: Sequence[int],
                ticking: bool, conn) -> None:
    worker_signals()
    try:
        for i in indices:
            if ticking:  # each step of the item's work is told to the parent as it ends
                value = func(items[i], lambda i=i: conn.send(("tick", i, None)))
            else:
                value = func(items[i])
            conn.send(("done", i, value))
    except Exception as err:  # re-raised by the parent
        try:
            conn.send(("error", i, err))
        except Exception:  # an error that does not pickle: its text
            conn.send(("error", i, BackendError(f"{type(err).__name__}: {err}")))
    finally:
        conn.close()


@contextmanager
def held_signals(block: bool | Collection[int] = True) -> Iterator[None]:
    """SIGINT and SIGTERM held over the block, then acted on by their handlers: blocked in
    this thread (and so in the threads made and the processes forked here, until
    :func:`worker_signals`) and, where another thread takes one (a library's, the CLI's
    signal watcher), only noted by the Python handlers meanwhile. Acted on at once, an
    interrupt could raise in code that drops exceptions (an after-fork hook, a
    ``__del__``) and be lost, or in the middle of starting a process, which would then
    run on unknown to the caller. ``block=False``: only noted, for a program started here
    that must not inherit them blocked (exec); a collection of signals: those blocked,
    all noted.

    At the end the handlers of before are back first, then the mask: a signal still
    blocked goes to its handler then, and a noted one is handed to it by a call, every
    time (not raised again: the CLI's watcher counts real signals)."""
    noted: list[int] = []
    main = threading.current_thread() is threading.main_thread()  # where handlers run
    old: dict[int, Callable[[int, Any], Any]] = {
        s: h for s in STOP_SIGNALS if main and callable(h := signal.getsignal(s))}

    def note(signum: int, _frame: Any) -> None:
        noted.append(signum)

    mask = signal.pthread_sigmask(signal.SIG_BLOCK, ())  # kept: the next could raise
    try:
        for s in old:
            signal.signal(s, note)
        blocked = STOP_SIGNALS if block is True else set(block or ())
        if blocked:
            signal.pthread_sigmask(signal.SIG_BLOCK, blocked)
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        for signum in dict.fromkeys(noted):
            old[signum](signum, None)


def kill_children() -> None:
    """Kill every process descended from this one (forked workers, a local dask cluster's,
    FE solvers: found in ``/proc``; a no-op elsewhere) and reap the children: the last
    act of a process that ends at once."""
    me = os.getpid()
    parents: dict[int, list[int]] = {}
    try:
        entries = os.listdir("/proc")
    except OSError:  # pragma: no cover - not Linux
        return
    for entry in entries:
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as fh:
                    ppid = int(fh.read().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            parents.setdefault(ppid, []).append(int(entry))
    found, todo = [], list(parents.get(me, ()))
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo += parents.get(pid, ())
    for pid in found:
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)
    for pid in parents.get(me, ()):
        with contextlib.suppress(OSError):
            os.waitpid(pid, 0)


def start_workers(target: Callable[..., None], args: Sequence[tuple],
                  procs: list[tuple[Any, multiprocessing.connection.Connection]]) -> None:
    """Fork one process per ``args`` entry running ``target(*entry, send)``, appending
    each with the end of its pipe to read to ``procs`` as it starts (the caller's
    ``finally`` stops them: :func:`stop_workers`, also when a signal comes in here).
    SIGINT and SIGTERM are held while they start (:func:`held_signals`): one arriving
    during a fork would reach an after-fork hook, which drops its exception; it is
    raised here once they are started."""
    ctx = multiprocessing.get_context("fork")
    with held_signals():
        for entry in args:
            recv, send = ctx.Pipe(duplex=False)
            proc = ctx.Process(target=target, args=(*entry, send), daemon=True)
            proc.start()
            send.close()
            del send  # its __del__ runs here, where a signal is held, not after
            procs.append((proc, recv))


def messages(procs: Sequence[tuple[Any, multiprocessing.connection.Connection]]
             ) -> Iterator[tuple]:
    """Each message the workers send, as it comes, until every worker has closed its
    pipe; a message ``("error", ..., err)`` raises ``err`` here, and a worker that died
    with an exit code a :class:`BackendError`."""
    waiting = {recv: proc for proc, recv in procs}
    while waiting:
        check_interrupt()  # a signal whose exception a library dropped: no more waiting
        for ready in multiprocessing.connection.wait(list(waiting)):
            conn = cast(multiprocessing.connection.Connection, ready)
            try:
                message = conn.recv()
            except EOFError:  # the worker is finished, or died
                proc = waiting.pop(conn)
                proc.join()
                if proc.exitcode:
                    raise BackendError(f"a worker process ended with exit code "
                                       f"{proc.exitcode}") from None
                continue
            if message[0] == "error":
                raise message[-1]
            yield message


def stop_workers(procs: Sequence[tuple[Any, multiprocessing.connection.Connection]]
                 ) -> None:
    """Kill the workers still running and reap them all, holding SIGINT and SIGTERM
    meanwhile (:func:`held_signals`: a second Ctrl-C does not leave one running)."""
    with held_signals():
        for proc, _ in procs:
            if proc.is_alive():
                proc.kill()
        for proc, recv in procs:
            proc.join()
            recv.close()


def fork_map(func: Callable[[Any], T], items: Sequence[Any], workers: int = 2,
             done: Callable[[int], None] | None = None) -> list[T]:
    """``[func(item) for item in items]``, over ``workers`` forked processes where there are
    two items or more and forking is safe (:func:`can_fork`), else in this process.

    Worker ``k`` takes the items ``k, k + workers, ...`` (costs that grow along the list
    split evenly) and sends each result back (pickled); this process only waits, so it
    answers a signal at once. On any exception here (an error in ``func``, which is raised
    again here, ``KeyboardInterrupt``, the CLI's signal) the workers are killed and reaped
    before it propagates. ``done(n)`` is called after each result with the count so far.
    """
    started = ForkedMap(func, items, workers)
    try:
        return started.results(done)
    finally:
        started.stop()


def _no_tick() -> None:
    pass


class ForkedMap:
    """:func:`fork_map` started now and collected later: the workers run while this
    process does other work. :meth:`results` waits for them (without workers: computes
    the items then); :meth:`stop` kills and reaps those still running, and must follow in
    a ``finally`` (a started map leaves no worker behind).

    ``ticking``: ``func(item, tick)`` is called instead of ``func(item)``; each call of
    ``tick()``, in whichever process runs the item, calls :meth:`results`'s ``tick()`` here
    (a progress bar's step within an item)."""

    def __init__(self, func: Callable[..., T], items: Sequence[Any], workers: int = 2, *,
                 ticking: bool = False):
        self.func, self.items, self.ticking = func, items, ticking
        self.procs: list = []
        self.forked = workers >= 2 and len(items) >= 2 and can_fork()
        if self.forked:
            try:
                start_workers(_map_worker, [(func, items, range(k, len(items), workers),
                                             ticking)
                                            for k in range(min(workers, len(items)))],
                              self.procs)
            except BaseException:
                self.stop()
                raise

    def results(self, done: Callable[[int], None] | None = None,
                tick: Callable[[], None] | None = None) -> list:
        """The items' values in order; ``done(n)`` after each with the count so far,
        ``tick()`` at each step an item tells (``ticking``)."""
        tick = _no_tick if tick is None else tick
        if not self.forked:
            out = []
            for item in self.items:
                out.append(self.func(item, tick) if self.ticking else self.func(item))
                if done is not None:
                    done(len(out))
            return out
        found: dict[int, Any] = {}
        for kind, i, value in messages(self.procs):
            if kind == "tick":
                tick()
                continue
            found[i] = value
            if done is not None:
                done(len(found))
        return [found[i] for i in range(len(self.items))]

    def stop(self) -> None:
        if self.procs:
            stop_workers(self.procs)
            self.procs = []

    __del__ = stop
