"""The compiled clearance kernel (numba), imported at the first sweep.

:func:`kernels` returns :mod:`._compiled` (its :func:`~._compiled.minimise_rows` does all of
:func:`.kernel.minimise` for a chunk of turning angles), or None where numba cannot be
imported or ``GEARCOUPLING_NUMBA=0``: then the numpy path of :mod:`.kernel` runs (about 3x
slower on a map, 10x on one turning angle). ``import gearcoupling`` does not import numba;
the first sweep in a process loads it and the compiled code from numba's cache (about
0.5 s; after an install, the first sweep compiles for about 10 s and writes the cache:
docs/sweep-speed.md). The two paths agree to rounding (``tests/test_sweep_frozen.py``,
``tests/test_sweep_kernel.py``).
"""

from __future__ import annotations

import os
from functools import lru_cache
from types import ModuleType


@lru_cache(maxsize=1)
def kernels() -> ModuleType | None:
    """The compiled kernel's module, or None without numba (or with ``GEARCOUPLING_NUMBA=0``)."""
    if os.environ.get("GEARCOUPLING_NUMBA", "1") == "0":
        return None
    try:
        from . import _compiled
    except ImportError:
        return None
    return _compiled
