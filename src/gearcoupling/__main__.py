"""``python -m gearcoupling``: the command line."""

from .cli import console

console()
