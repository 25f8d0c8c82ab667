"""Command line: ``gearcoupling <command> SPEC [--set KEY=VALUE ...]``.

Each command lives in :mod:`gearcoupling.commands` and registers itself; ``main(argv)``
runs in-process so tests call it directly. Exit status: 0 success, 1 a finding the
command reports (e.g. interference), 2 bad input: a bad argument, a project error
(:class:`~gearcoupling.errors.GearCouplingError`) or a file that cannot be read or
written, each reported on one line ``gearcoupling: error: ...`` without a traceback.
Interrupted by SIGINT (Ctrl-C) or SIGTERM, a command stops the worker processes it
started, writes nothing more, says ``gearcoupling: interrupted; N files complete in DIR``
and exits with 130 or 143 (128 + the signal's number).
"""

from __future__ import annotations

import argparse
import atexit
import contextlib
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import NoReturn

from .commands import CREATED, NAMES, WRITING, command_module
from .errors import GearCouplingError, brief
from .io import remove_stale_temporaries

EXIT_BAD_INPUT = 2
SIGNALS = (signal.SIGINT, signal.SIGTERM)


class _Parser(argparse.ArgumentParser):
    """Argument errors on one line (argparse prints the usage first by default)."""

    def error(self, message: str) -> NoReturn:
        # one "gearcoupling:" prefix: a subcommand's prog is "gearcoupling load"
        command = self.prog.removeprefix("gearcoupling").strip()
        where = f"{command}: " if command else ""
        self.exit(EXIT_BAD_INPUT, f"gearcoupling: error: {where}{message} "
                  f"(see {self.prog} --help)\n")


def build_parser(commands: Sequence[str] = NAMES) -> argparse.ArgumentParser:
    """The parser of ``commands`` (default every command: the full help)."""
    parser = _Parser(
        prog="gearcoupling",
        description="Crowned-tooth gear couplings: exact geometry, parts, sweeps and viewer.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in commands:
        command_module(name).register(sub)
    return parser


def _error(text: str) -> int:
    print(f"gearcoupling: error: {brief(text, 2000)}", file=sys.stderr)
    return EXIT_BAD_INPUT


class Interrupted(KeyboardInterrupt):
    """SIGTERM (or SIGINT) as an exception in the main thread: like Ctrl-C's
    ``KeyboardInterrupt``, it unwinds the command, whose ``finally`` blocks stop its
    workers and remove its temporaries."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


@contextmanager
def _signals_raise() -> Iterator[None]:
    """SIGINT and SIGTERM raise :class:`Interrupted` while the command runs (in the main
    thread only; elsewhere Python's handlers stay). The first one does: further ones are
    ignored until the command has cleaned up. FE solvers the command waits on are killed
    at the signal itself (:func:`_kill_solvers_at_signal`), even while the main thread is
    in a library call that Python's handler has to wait for (gmsh meshing)."""
    def handler(signum: int, _frame: object) -> None:
        for s in SIGNALS:
            signal.signal(s, signal.SIG_IGN)
        raise Interrupted(signum)  # the solvers went already (_kill_solvers_at_signal)

    try:
        old = {s: signal.signal(s, handler) for s in SIGNALS}
    except ValueError:  # not the main thread
        yield
        return
    try:
        with _kill_solvers_at_signal():
            yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)


def _stop_solvers(stop: bool = True) -> None:
    """Stop the FE solvers and refuse new ones (``stop=False``: allow them again)."""
    ccx = sys.modules.get("gearcoupling.fea.ccx")  # only if this command ran an FE solver
    if ccx is not None:
        if stop:
            ccx.stop_solvers()
        else:
            ccx.allow_solvers()


@contextmanager
def _kill_solvers_at_signal() -> Iterator[None]:
    """A thread woken through :func:`signal.set_wakeup_fd` (written by the C-level handler
    the moment a signal arrives) that kills the FE solvers at once."""
    import socket
    import threading

    r, w = socket.socketpair()
    w.setblocking(False)

    def watch() -> None:
        with contextlib.suppress(OSError):
            if r.recv(1):
                _stop_solvers()

    old_fd = signal.set_wakeup_fd(w.fileno(), warn_on_full_buffer=False)
    watcher = threading.Thread(target=watch, name="gearcoupling-signals", daemon=True)
    watcher.fork_safe = True  # type: ignore[attr-defined]  # holds no lock: gc.run may fork
    watcher.start()
    try:
        yield
    finally:
        signal.set_wakeup_fd(old_fd)
        w.close()
        with contextlib.suppress(OSError):
            r.shutdown(socket.SHUT_RDWR)
        watcher.join(timeout=5.0)
        r.close()
        _stop_solvers(stop=False)  # the next command in this process may solve again


def _tidy() -> None:
    """Remove the output folders this failed command made, where it left them empty."""
    for folder in reversed(CREATED):
        with contextlib.suppress(OSError):
            folder.rmdir()


def _interrupted(stop: KeyboardInterrupt, started: float) -> int:
    """After an interruption has unwound the command: remove the temporaries of its
    stopped workers, say what is complete in one line, return 128 + the signal."""
    signum = getattr(stop, "signum", signal.SIGINT)
    folders = list(dict.fromkeys(WRITING))
    complete = []
    for folder in folders:
        for sub in (folder, *(p for p in folder.rglob("*") if p.is_dir())):
            remove_stale_temporaries(sub)
        complete += [p for p in folder.rglob("*") if p.is_file()
                     and not p.name.startswith(".") and p.stat().st_mtime >= started]
    where = f" in {', '.join(map(str, folders))}" if folders else ""
    print(f"gearcoupling: interrupted; {len(complete)} file{'' if len(complete) == 1 else 's'}"
          f" complete{where}", file=sys.stderr)
    return 128 + int(signum)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    # a command's own parser (its module alone is imported); any other start (--help, a
    # misspelt command) the full one
    parser = build_parser([argv[0]] if argv and argv[0] in NAMES else NAMES)
    try:
        args = parser.parse_args(argv)
    except SystemExit as stop:  # --help, or an argument error already printed on one line
        return stop.code if isinstance(stop.code, int) else EXIT_BAD_INPUT
    WRITING.clear()
    CREATED.clear()
    started = time.time() - 0.05  # file times come from a coarser clock
    try:
        with _signals_raise():
            try:
                return int(args.func(args) or 0)
            except KeyboardInterrupt as stop:
                return _interrupted(stop, started)
            except BaseException:
                _tidy()
                raise
    except GearCouplingError as err:
        return _error(str(err).splitlines()[0] if str(err) else type(err).__name__)
    except BrokenPipeError:  # e.g. ``gearcoupling spec --json | head``: the reader left
        _silence_stdout()
        return 0
    except OSError as err:  # a file that cannot be read or written
        where = f" {err.filename!s}" if err.filename else ""
        return _error(f"{err.strerror or err}:{where}")
    except MemoryError:
        return _error("out of memory: use fewer angles, teeth or a coarser tolerance")


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush does not raise."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # in-process stdout without a descriptor
        pass


def console() -> NoReturn:
    """The ``gearcoupling`` program (and ``python -m gearcoupling``): :func:`main`, then
    exit with its status without tearing the interpreter down.

    The exit handlers run and the output is flushed as at any exit; the module teardown
    that follows is left out: with matplotlib, numba, trimesh and scipy loaded it took
    0.15-0.5 s after the work was done (``gearcoupling run``). Where another thread is
    still alive, or a handler or the flush fails, the exit is the ordinary one.
    """
    status = main()
    run_handlers = getattr(atexit, "_run_exitfuncs", None)
    if run_handlers is None or threading.active_count() > 1:
        sys.exit(status)
    try:
        run_handlers()
        for stream in (sys.stdout, sys.stderr):
            stream.flush()
    except (OSError, ValueError):
        sys.exit(status)
    os._exit(status)


if __name__ == "__main__":  # pragma: no cover
    console()
