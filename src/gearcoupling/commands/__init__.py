"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import run, sections, spec, templates

COMMANDS = [spec, sections, run, templates]
