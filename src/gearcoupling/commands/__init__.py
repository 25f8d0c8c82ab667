"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import check, generate, run, sections, spec, sweep, templates, view

COMMANDS = [spec, sections, run, templates, check, view, generate, sweep]

# fea branch: volume meshes and CalculiX stiffness
from . import fea, stiffness  # noqa: E402

COMMANDS += [fea, stiffness]
