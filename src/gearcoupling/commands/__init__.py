"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import capacity, check, generate, load, run, sections, spec, sweep, templates, view

COMMANDS = [spec, sections, run, templates, check, view, generate, sweep]
COMMANDS += [load, capacity]  # loaded contact (issue 10)
