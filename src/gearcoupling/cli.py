"""Command line: ``gearcoupling <command> SPEC [--set KEY=VALUE ...]``.

Each command lives in :mod:`gearcoupling.commands` and registers itself; ``main(argv)``
runs in-process so tests call it directly. Exit status: 0 success, 1 a finding the
command reports (e.g. interference), 2 bad input.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .errors import GearCouplingError, GeometryError, SpecError


def build_parser() -> argparse.ArgumentParser:
    from .commands import COMMANDS

    parser = argparse.ArgumentParser(
        prog="gearcoupling",
        description="Crowned-tooth gear couplings: exact geometry, parts, sweeps and viewer.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in COMMANDS:
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except (SpecError, GeometryError) as err:
        print(f"gearcoupling: error: {err}", file=sys.stderr)
        return 2
    except GearCouplingError as err:
        print(f"gearcoupling: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
