"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import run, sections, spec

COMMANDS = [spec, sections, run]
