"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import check, generate, run, sections, spec, sweep, templates, view
from . import fea, stiffness  # fea branch

COMMANDS = [spec, sections, run, templates, check, view, generate, sweep]
COMMANDS += [fea, stiffness]  # fea branch
