"""Optional compiled point work of the clearance kernel (extra ``fast``: numba).

:func:`kernels` returns the numba kernels (:mod:`._compiled`) that fuse what the numpy
path does in ~30 array passes per point - flank ``y`` by Horner's rule, the pose, the
involute and root-fillet gaps - into one loop, and run the searches over the profile
height (:meth:`~.clearance._Planes.cross`, the slope roots of
:meth:`~.clearance._Planes._interior`) in compiled loops; or None when numba is not
installed (then numpy is used). Both perform the same floating-point operations in the
same order: the minima are equal (``tests/test_sweep_frozen.py`` runs both; see
``docs/sweep-speed.md``). ``GEARCOUPLING_NUMBA=0`` forces numpy.
"""

from __future__ import annotations

import os
from functools import lru_cache
from types import ModuleType


@lru_cache(maxsize=1)
def kernels() -> ModuleType | None:
    """The compiled kernels' module, or None without numba (or with ``GEARCOUPLING_NUMBA=0``)."""
    if os.environ.get("GEARCOUPLING_NUMBA", "1") == "0":
        return None
    try:
        from . import _compiled
    except ImportError:
        return None
    return _compiled
