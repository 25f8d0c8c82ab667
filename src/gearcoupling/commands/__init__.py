"""CLI commands; each module has ``register(subparsers)``. Add new commands to NAMES.

A command's module is imported when the command runs (or for the full ``--help``), so
``gearcoupling run`` loads no report, study or FE code before its work starts.
"""

import importlib
from types import ModuleType

from .common import CREATED, WRITING

#: the commands, in the order ``--help`` lists them (module ``fea_contact`` is
#: ``fea-contact``)
NAMES = ("spec", "sections", "run", "templates", "check", "view", "generate", "sweep",
         "load", "capacity", "wear", "datasheet", "fea", "fea-contact", "stiffness", "study", "hob",
         "charts", "compare", "report")


def command_module(name: str) -> ModuleType:
    """The module of the command ``name`` (one of :data:`NAMES`)."""
    return importlib.import_module(f".{name.replace('-', '_')}", __name__)


__all__ = ["CREATED", "NAMES", "WRITING", "command_module"]
