"""Command line: ``gearcoupling <command> SPEC [--set KEY=VALUE ...]``.

Each command lives in :mod:`gearcoupling.commands` and registers itself; ``main(argv)``
runs in-process so tests call it directly. Exit status: 0 success, 1 a finding the
command reports (e.g. interference), 2 bad input: a bad argument, a project error
(:class:`~gearcoupling.errors.GearCouplingError`) or a file that cannot be read or
written, each reported on one line ``gearcoupling: error: ...`` without a traceback.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from typing import NoReturn

from .commands import COMMANDS
from .errors import GearCouplingError

EXIT_BAD_INPUT = 2


class _Parser(argparse.ArgumentParser):
    """Argument errors on one line (argparse prints the usage first by default)."""

    def error(self, message: str) -> NoReturn:
        # one "gearcoupling:" prefix: a subcommand's prog is "gearcoupling load"
        command = self.prog.removeprefix("gearcoupling").strip()
        where = f"{command}: " if command else ""
        self.exit(EXIT_BAD_INPUT, f"gearcoupling: error: {where}{message} "
                  f"(see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="gearcoupling",
        description="Crowned-tooth gear couplings: exact geometry, parts, sweeps and viewer.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in COMMANDS:
        module.register(sub)
    return parser


def _error(text: str) -> int:
    print(f"gearcoupling: error: {text}", file=sys.stderr)
    return EXIT_BAD_INPUT


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as stop:  # --help, or an argument error already printed on one line
        return stop.code if isinstance(stop.code, int) else EXIT_BAD_INPUT
    try:
        return int(args.func(args) or 0)
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


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
