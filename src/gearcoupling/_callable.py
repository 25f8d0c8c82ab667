"""Packages that are also the function they are named for (``gc.sweep(...)``, ``gc.load(...)``).

Importing a subpackage sets it as an attribute of its parent, so ``gearcoupling.sweep`` is
the package once anything imported it; making the package callable keeps
``gc.sweep(spec, ...)`` the function whichever of the two the attribute resolves to.
"""

from __future__ import annotations

import sys
import types
from collections.abc import Callable
from typing import Any, cast


def make_callable(module_name: str, func: Callable[..., Any]) -> None:
    """Calling the module ``module_name`` calls ``func`` (same signature and docstring)."""

    class _CallableModule(types.ModuleType):
        __call__ = staticmethod(func)
        __signature__: None
        __wrapped__: Callable[..., Any]

    module = sys.modules[module_name]
    module.__class__ = _CallableModule
    callable_module = cast(_CallableModule, module)
    callable_module.__signature__ = None  # inspect.signature(module) follows __wrapped__
    callable_module.__wrapped__ = func
