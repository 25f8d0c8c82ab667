"""Packages that are also the function they are named for (``gc.sweep(...)``, ``gc.load(...)``).

Importing a subpackage sets it as an attribute of its parent, so ``gearcoupling.sweep`` is
the package once anything imported it; making the package callable keeps
``gc.sweep(spec, ...)`` the function whichever of the two the attribute resolves to.
"""

from __future__ import annotations

import inspect
import sys
import types
from collections.abc import Callable
from typing import Any


def make_callable(module_name: str, func: Callable[..., Any]) -> None:
    """Calling the module ``module_name`` calls ``func`` (``inspect.signature`` and ``help``
    show ``func``'s signature)."""

    class _CallableModule(types.ModuleType):
        __call__ = staticmethod(func)
        __signature__ = inspect.signature(func)

    sys.modules[module_name].__class__ = _CallableModule
