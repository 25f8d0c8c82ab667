"""Command line: ``gearcoupling <command> SPEC [--set KEY=VALUE ...]``.

Each command lives in :mod:`gearcoupling.commands` and registers itself; ``main(argv)``
runs in-process so tests call it directly. Exit status: 0 success, 1 a finding the
command reports (e.g. interference), 2 bad input: a bad argument, a project error
(:class:`~gearcoupling.errors.GearCouplingError`) or a file that cannot be read or
written, each reported on one line ``gearcoupling: error: ...`` without a traceback; 3
an internal error (a defect: one line saying where to report it, the traceback with
``GEARCOUPLING_DEBUG=1``). Interrupted by SIGINT (Ctrl-C) or SIGTERM, a command stops the
worker processes it started, writes nothing more, says ``gearcoupling: interrupted; N
files complete in DIR`` and exits with 130 or 143 (128 + the signal's number); the
program (:func:`console`) does so at any moment of its life, also when a library drops
the interruption, and a second signal ends it at once.
"""

from __future__ import annotations

import argparse
import atexit
import contextlib
import os
import signal
import socket
import sys
import threading
import time
import traceback
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import NoReturn

from . import interrupts
from .commands import CREATED, NAMES, WRITING, command_module
from .errors import GearCouplingError, brief
from .forked import kill_children
from .interrupts import SIGNALS, Interrupted
from .io import remove_stale_temporaries

EXIT_BAD_INPUT = 2
EXIT_INTERNAL = 3
#: set (not "0"), an internal error prints its traceback above its one line
DEBUG_ENV = "GEARCOUPLING_DEBUG"
REPORT_TO = "the gearcoupling issue tracker"
#: seconds the program gives a command to stop after a signal before ending it itself
GRACE_S = 3.0

__all__ = ["EXIT_BAD_INPUT", "EXIT_INTERNAL", "Interrupted", "build_parser", "console",
           "main"]


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


def _internal_error(err: BaseException) -> int:
    """An exception no part of gearcoupling raises on purpose: a defect. One line saying
    where to report it (the traceback above it with :data:`DEBUG_ENV` set)."""
    if os.environ.get(DEBUG_ENV, "0") not in ("", "0"):
        traceback.print_exception(err, file=sys.stderr)
    text = str(err).splitlines()[0] if str(err).strip() else "(no message)"
    print(f"gearcoupling: internal error: {type(err).__name__}: {brief(text, 500)} "
          f"(please report it at {REPORT_TO}, with the command and spec)", file=sys.stderr)
    return EXIT_INTERNAL


@contextmanager
def _signals_raise() -> Iterator[None]:
    """SIGINT and SIGTERM raise :class:`Interrupted` while the command runs (in the main
    thread only; elsewhere Python's handlers stay), noted so that a library that drops
    the exception cannot drop the interruption (:mod:`gearcoupling.interrupts`; such a
    drop is not reported as an error either). A second signal raises again, or, in the
    program, ends it (:func:`_end_now`). FE solvers the command waits on are killed at
    the signal itself (:class:`_Watcher`), even while the main thread is in a library
    call that Python's handler has to wait for (gmsh meshing)."""
    interrupts.reset()
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {}
    hook = sys.unraisablehook
    try:
        sys.unraisablehook = interrupts.unraisable_hook(hook)
        for s in SIGNALS:
            old[s] = signal.signal(s, interrupts.handler)
        if _Watcher.running:  # the program's
            yield
        else:
            with _Watcher(program=False):
                yield
    finally:
        sys.unraisablehook = hook
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


class _Watcher:
    """A thread woken through :func:`signal.set_wakeup_fd` (written by the C-level handler
    the moment a signal arrives, whatever the main thread is doing) that kills the FE
    solvers at once. In the program (``program=True``) a second signal, or
    :data:`GRACE_S` after the first without the process having ended, ends it
    (:func:`_end_now`). A context manager; the program's runs until the process ends."""

    running = False

    def __init__(self, program: bool):
        self.program = program
        self.r, self.w = socket.socketpair()
        self.w.setblocking(False)
        self.old_fd = signal.set_wakeup_fd(self.w.fileno(), warn_on_full_buffer=False)
        self.thread = threading.Thread(target=self._watch, name="gearcoupling-signals",
                                       daemon=True)
        self.thread.fork_safe = True  # type: ignore[attr-defined]  # holds no lock: may fork
        self.thread.start()
        _Watcher.running = True

    def _watch(self) -> None:
        first, end = 0, 0.0
        while True:
            if first:
                self.r.settimeout(max(0.0, end - time.monotonic()))
            try:
                data = self.r.recv(1)
            except TimeoutError:  # the grace after the first signal is over
                _end_now(first)
            except OSError:
                return
            if not data:  # closed
                return
            if data[0] not in SIGNALS:
                continue
            _stop_solvers()
            if self.program:
                if first:
                    _end_now(data[0])
                first, end = data[0], time.monotonic() + GRACE_S

    def __enter__(self) -> _Watcher:
        return self

    def __exit__(self, *exc: object) -> None:
        signal.set_wakeup_fd(self.old_fd)
        self.w.close()
        with contextlib.suppress(OSError):
            self.r.shutdown(socket.SHUT_RDWR)
        self.thread.join(timeout=5.0)
        self.r.close()
        _Watcher.running = False
        _stop_solvers(stop=False)  # the next command in this process may solve again


def _tidy() -> None:
    """Remove the output folders this failed command made, where it left them empty."""
    for folder in reversed(CREATED):
        with contextlib.suppress(OSError):
            folder.rmdir()


_started = 0.0  # when the running command started (time.time(): file times)
_said: list[int] = []  # the exit status of the interruption line, once printed
_ENDING = threading.RLock()  # one interruption line, one ending


def _say_interrupted(signum: int, *, fd: int | None = None) -> int:
    """Once per command (later calls only return the status): remove the temporaries of
    its stopped workers (and, with ``fd``, its own: the process ends next), say what is
    complete in one line on stderr (written straight to the descriptor ``fd`` where
    given), return 128 + the signal."""
    with _ENDING:
        if _said:
            return _said[0]
        folders = list(dict.fromkeys(WRITING))
        complete = []
        for folder in folders:
            with contextlib.suppress(OSError):  # a folder not made yet, or removed
                for sub in (folder, *(p for p in folder.rglob("*") if p.is_dir())):
                    remove_stale_temporaries(sub, own=fd is not None)
                complete += [p for p in folder.rglob("*") if p.is_file()
                             and not p.name.startswith(".") and p.stat().st_mtime >= _started]
        where = f" in {', '.join(map(str, folders))}" if folders else ""
        line = (f"gearcoupling: interrupted; {len(complete)} file"
                f"{'' if len(complete) == 1 else 's'} complete{where}")
        if fd is not None:
            os.write(fd, f"{line}\n".encode())
        else:
            print(line, file=sys.stderr)
        _said.append(128 + int(signum))
        return _said[0]


def _interrupted(stop: KeyboardInterrupt) -> int:
    """After an interruption has unwound the command: its line (:func:`_say_interrupted`)
    and exit status."""
    return _say_interrupted(getattr(stop, "signum", signal.SIGINT))


def _remove_lock_files() -> None:
    """Remove the lock files of the output folders the command holds (the locks go with
    the process)."""
    folders = sys.modules.get("gearcoupling.commands.folders")  # if the command held any
    if folders is not None:
        for held in list(folders.HELD.values()):
            held.lock.remove_file()


def _end_now(signum: int) -> NoReturn:
    """End the program at once, the last resort of a second signal, of a command that did
    not stop within :data:`GRACE_S`, and of a signal before or after the command: kill the
    FE solvers and every child process, remove the files of its output folders' locks,
    then the interruption line (:func:`_say_interrupted`, unless said) and exit 128 + the
    signal."""
    with _ENDING:
        # from here on what this process (its main thread may still run) and what it starts
        # meanwhile write to stderr is not the user's business: only the line goes there
        stderr = os.dup(2)
        os.dup2(os.open(os.devnull, os.O_WRONLY), 2)
        _stop_solvers()
        kill_children()
        _remove_lock_files()
        os._exit(_say_interrupted(signum, fd=stderr))


def _handle(args: argparse.Namespace) -> int:
    """Run the parsed command; its exit status (see the module's docstring)."""
    global _started
    WRITING.clear()
    CREATED.clear()
    _said.clear()
    _started = time.time() - 0.05  # file times come from a coarser clock
    try:
        with _signals_raise():
            try:
                status = int(args.func(args) or 0)
                interrupts.check()  # a signal whose exception a library dropped
                return status
            except KeyboardInterrupt as stop:
                return _interrupted(stop)
            except Exception:
                if interrupts.pending():  # a failure the interruption caused
                    return _interrupted(Interrupted(interrupts.pending()))
                _tidy()
                raise
            except BaseException:
                _tidy()
                raise
    except KeyboardInterrupt as stop:  # at the edge of the handlers' block
        return _interrupted(stop)
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
    except Exception as err:
        return _internal_error(err)


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
    return _handle(args)


def _silence_stdout() -> None:
    """Point stdout at /dev/null so that the interpreter's final flush does not raise."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # in-process stdout without a descriptor
        pass


def _end_at_signal(signum: int, _frame: object) -> None:
    _end_now(signum)


def _program_signals() -> None:
    """The program's signals: outside the command (before it starts, after it returns)
    SIGINT and SIGTERM end the process at once (:func:`_end_now`); while it runs they
    interrupt it (:func:`_signals_raise`), a second one ends it, and so does the grace
    after the first running out (:class:`_Watcher`)."""
    for s in SIGNALS:
        signal.signal(s, _end_at_signal)
    interrupts.last_resort = _end_now
    _Watcher(program=True)


def _other_threads() -> bool:
    return any(t is not threading.main_thread() and not getattr(t, "fork_safe", False)
               for t in threading.enumerate())


def console() -> NoReturn:
    """The ``gearcoupling`` program (and ``python -m gearcoupling``): :func:`main`, then
    exit with its status without tearing the interpreter down.

    Its signal handlers come first (the package installs a first one before its own
    imports, :func:`gearcoupling.interrupts.at_program_start`): a signal at any moment ends
    it with 130 or 143 and one line (:func:`_program_signals`). The exit handlers run and
    the output is flushed as at any exit; the module teardown that follows is left out:
    with matplotlib, numba, trimesh and scipy loaded it keeps the user waiting after the
    work is done (``gearcoupling run``). Where another thread is still alive, or a handler
    or the flush fails, the exit is the ordinary one.
    """
    _program_signals()
    status = main()
    run_handlers = getattr(atexit, "_run_exitfuncs", None)
    if run_handlers is None or _other_threads():
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
