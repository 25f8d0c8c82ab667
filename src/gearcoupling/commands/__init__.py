"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import check, generate, run, sections, spec, study, sweep, templates, view

COMMANDS = [spec, sections, run, templates, check, view, generate, sweep, study]
