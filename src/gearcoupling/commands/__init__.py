"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import check, generate, run, sections, spec, sweep, templates, view

# manufacturing and inspection (issue 13)
from . import charts, compare, hob  # isort: skip

COMMANDS = [spec, sections, run, templates, check, view, generate, sweep]

# fea branch: volume meshes and CalculiX stiffness
from . import fea, stiffness  # noqa: E402

COMMANDS += [fea, stiffness]
COMMANDS += [hob, charts, compare]  # issue 13
