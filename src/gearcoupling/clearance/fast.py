"""The compiled clearance kernel (numba), imported at the first sweep.

:func:`kernels` returns :mod:`._compiled` (its :func:`~._compiled.minimise_rows` does all
of :func:`.kernel.minimise` for a chunk of turning angles). ``import gearcoupling`` does not
import numba; the first sweep in a process loads it and the compiled code from numba's
cache (about 0.5 s; after an install, the first sweep compiles and writes the cache:
docs/sweep-speed.md).
"""

from __future__ import annotations

from functools import lru_cache
from types import ModuleType


@lru_cache(maxsize=1)
def kernels() -> ModuleType:
    """The compiled kernel's module."""
    from . import _compiled

    return _compiled
