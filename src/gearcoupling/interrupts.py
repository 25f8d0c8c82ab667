"""SIGINT and SIGTERM as one interruption of the command running in this process.

The command line's handler (:func:`handler`) notes the first signal and raises
:class:`Interrupted`. A library can drop that exception (an import that catches
``BaseException``, a ``__del__``, a garbage-collector callback), never the note:
:func:`check`, called where no library sits in between (before an atomic rename, in the
progress callback, when a command returns), raises it again, so the command stops at the
next of these points and writes nothing after the signal. Where the handler is not
installed (a library caller keeps Python's own Ctrl-C) nothing is noted and
:func:`check` does nothing.

Stdlib only: the ``gearcoupling`` program installs its first handler from here before the
package's heavy imports (:func:`at_program_start`).
"""

from __future__ import annotations

import os
import signal
import sys
from collections.abc import Callable
from typing import Any

SIGNALS = (signal.SIGINT, signal.SIGTERM)

_first = 0  # the first signal since reset(), 0 none
#: what a second signal does where the process is the gearcoupling program (set by
#: gearcoupling.cli.console: it ends the process); None: it raises again
last_resort: Callable[[int], Any] | None = None


class Interrupted(KeyboardInterrupt):
    """SIGTERM (or SIGINT) as an exception in the main thread: like Ctrl-C's
    ``KeyboardInterrupt``, it unwinds the command, whose ``finally`` blocks stop its
    workers and remove its temporaries."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def handler(signum: int, _frame: object) -> None:
    """The command's handler of SIGINT and SIGTERM: notes the first signal and raises
    :class:`Interrupted`; a later one calls :data:`last_resort` where set, else raises
    again."""
    global _first
    if _first and last_resort is not None:
        last_resort(signum)
    _first = _first or signum
    raise Interrupted(signum)


def pending() -> int:
    """The number of the signal noted since :func:`reset` (0: none)."""
    return _first


def check() -> None:
    """Raise :class:`Interrupted` if a signal was noted since :func:`reset` (whatever
    dropped the first exception)."""
    if _first:
        raise Interrupted(_first)


def reset() -> None:
    """Forget the noted signal: a new command starts (or the command has answered it)."""
    global _first
    _first = 0


def reraise(err: BaseException) -> None:
    """Raise the interruption ``err`` stands for, if any: a ``KeyboardInterrupt`` in its
    chain of causes (pybind11 turns one raised while a module initialises into
    ``ImportError('initialization failed')``), or a signal noted meanwhile. A back-end's
    import wrapper calls it before reporting the back-end as missing."""
    seen: set[int] = set()
    cause: BaseException | None = err
    while cause is not None and id(cause) not in seen:
        if isinstance(cause, KeyboardInterrupt):
            raise cause
        seen.add(id(cause))
        cause = cause.__cause__ or cause.__context__
    check()


def unraisable_hook(default: Callable[[Any], Any]) -> Callable[[Any], Any]:
    """A :data:`sys.unraisablehook` that keeps quiet about an interruption dropped where
    exceptions cannot propagate (a ``__del__``, a garbage-collector callback: the note
    stands, :func:`check` raises it again) and passes anything else to ``default``."""
    def hook(unraisable: Any) -> None:
        if not isinstance(unraisable.exc_value, KeyboardInterrupt):
            default(unraisable)

    return hook


#: the line of an interruption before the command started (nothing was written)
NOTHING_WRITTEN = "gearcoupling: interrupted; 0 files complete\n"


def _exit_at_once(signum: int, _frame: object) -> None:
    os.write(2, NOTHING_WRITTEN.encode())
    os._exit(128 + signum)


def exit_at_once() -> None:
    """SIGINT and SIGTERM end the process at once with :data:`NOTHING_WRITTEN` and 128 +
    the signal: before a command has started anything there is nothing to clean up."""
    for s in SIGNALS:
        signal.signal(s, _exit_at_once)


def _program_module(argv: list[str]) -> str:
    """The module of ``python [options] -m MODULE ...`` (``""`` for another command line)."""
    for i, arg in enumerate(argv[1:], 1):
        if arg == "-m":
            return argv[i + 1] if i + 1 < len(argv) else ""
        if arg.startswith("-m"):
            return arg[2:]
        if not arg.startswith("-"):
            return ""
    return ""


def is_program() -> bool:
    """Whether this process is being started as the ``gearcoupling`` program: the
    console script (``sys.argv[0]`` names it and is the ``__main__`` file), or
    ``python -m gearcoupling`` while the package is imported to find its ``__main__``."""
    argv0 = sys.argv[0] if sys.argv else ""
    if argv0 == "-m":
        module = _program_module(list(getattr(sys, "orig_argv", ())))
        return module in ("gearcoupling", "gearcoupling.__main__", "gearcoupling.cli")
    main = sys.modules.get("__main__")
    return (os.path.basename(argv0).removesuffix(".exe") == "gearcoupling"
            and getattr(main, "__file__", None) == argv0)


def at_program_start() -> None:
    """:func:`exit_at_once` if this process is the ``gearcoupling`` program
    (:func:`is_program`; the package calls it first): a signal while the program's
    modules load ends it with one line, not a traceback or a silent -15."""
    if is_program():
        try:
            exit_at_once()
        except ValueError:  # pragma: no cover - not the main thread
            pass
