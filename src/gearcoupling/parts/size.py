"""A part's size before it is built, and the memory budget it has to fit.

The triangle count comes from the layout's grid sizes (:func:`.hub.hub_triangles`,
:func:`.sleeve.sleeve_triangles`: the count the builder makes); the memory is that count
times :data:`BYTES_PER_TRIANGLE`, the peak per triangle of the heaviest command that
meshes a part. The budget is ``GEARCOUPLING_MEMORY_MB`` (megabytes, 10^6 bytes) where it
is set, else :data:`MEMORY_SHARE` of the memory this process can still use: the
``MemAvailable`` of ``/proc/meminfo``, lowered by a cgroup's ``memory.max`` and an
address-space limit (``ulimit -v``) where one is set. Where none of these can be read
there is no budget.
"""

from __future__ import annotations

import math
import os
import resource
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ..arguments import parse_number
from ..errors import ArgumentError

#: peak memory per triangle of a part: ``check --teeth all`` (both parts and their
#: interference trees) 1.25 kB, ``generate`` (build, validity check, STL) 0.96 kB, ``view``
#: 0.33 kB, the build alone 0.09 kB (industrial-m2, 0.2-0.7 M triangles)
BYTES_PER_TRIANGLE = 1300
#: share of the available memory a part may take when no budget is set
MEMORY_SHARE = 0.75
#: the environment variable that sets the budget in MB
MEMORY_ENV = "GEARCOUPLING_MEMORY_MB"


@dataclass(frozen=True)
class PartSize:
    """The size of a part mesh before it is built: ``triangles`` at ``tolerance_mm``."""

    part: str
    tolerance_mm: float
    triangles: int

    @property
    def bytes(self) -> int:
        """Peak memory of the part's heaviest use (:data:`BYTES_PER_TRIANGLE` each)."""
        return self.triangles * BYTES_PER_TRIANGLE


def _read_kb(path: str, key: str) -> int | None:
    """The ``key: N kB`` line of a ``/proc`` file in bytes, or None."""
    try:
        for line in Path(path).read_text().splitlines():
            name, _, rest = line.partition(":")
            if name == key:
                return int(rest.split()[0]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def _read_int(path: str) -> int | None:
    try:
        return int(Path(path).read_text().split()[0])
    except (OSError, ValueError, IndexError):  # absent, or "max"
        return None


def available_memory_bytes() -> int | None:
    """Memory this process can still use: ``MemAvailable``, a cgroup's headroom under
    ``memory.max`` and the headroom under ``RLIMIT_AS``, the smallest that is known."""
    known = [_read_kb("/proc/meminfo", "MemAvailable")]
    limit = _read_int("/sys/fs/cgroup/memory.max")
    if limit is not None:
        known.append(limit - (_read_int("/sys/fs/cgroup/memory.current") or 0))
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft != resource.RLIM_INFINITY:
        known.append(soft - (_read_kb("/proc/self/status", "VmSize") or 0))
    found = [max(k, 0) for k in known if k is not None]
    return min(found) if found else None


def memory_budget() -> tuple[int | None, str]:
    """``(bytes, where it comes from)``: ``GEARCOUPLING_MEMORY_MB`` or
    :data:`MEMORY_SHARE` of :func:`available_memory_bytes`; ``None`` if neither is known."""
    text = os.environ.get(MEMORY_ENV, "").strip()
    if text:
        mb = parse_number(text, MEMORY_ENV)
        if not mb > 0:
            raise ArgumentError(MEMORY_ENV, text, "a memory budget in MB, > 0")
        return int(mb * 1e6), f"{MEMORY_ENV}={text}"
    available = available_memory_bytes()
    if available is None:
        return None, "no budget: the available memory is unknown"
    return int(MEMORY_SHARE * available), (f"{MEMORY_SHARE:.0%} of the {_gb(available)} "
                                           f"available; {MEMORY_ENV} sets it")


def _gb(n: float) -> str:
    return f"{n / 1e9:.3g} GB"


def _round_up(value: float) -> float:
    """``value`` rounded up to two significant digits."""
    exp = math.floor(math.log10(value)) - 1
    return float(f"{math.ceil(value / 10.0 ** exp - 1e-9)}e{exp}")


def fitting_tolerance(triangles_at: Callable[[float], int], tol: float, most: int,
                      coarsest: float) -> float | None:
    """The finest tolerance of two significant digits, from ``tol`` to ``coarsest``, at
    which ``triangles_at`` gives at most ``most`` triangles (to within the last of four
    bisections); None if even ``coarsest`` gives more.

    The count goes about as ``1 / tolerance`` but in steps (the grids are refined by
    bisection): a first guess from that rule is stepped up until it fits, then bisected
    against the coarsest tolerance known not to fit."""
    bad, n = tol, triangles_at(tol)
    if n <= most:
        return tol
    fit = None
    for _ in range(8):
        t = min(_round_up(bad * 1.02 * n / most), coarsest)
        n = triangles_at(t)
        if n <= most:
            fit = t
            break
        if t >= coarsest:
            return None
        bad = t
    if fit is None:
        return None
    for _ in range(4):
        t = _round_up(math.sqrt(bad * fit))
        if not bad < t < fit:
            break
        if triangles_at(t) <= most:
            fit = t
        else:
            bad = t
    return fit


def check_memory(size: PartSize, triangles_at: Callable[[float], int],
                 coarsest: float) -> None:
    """Refuse a part whose memory exceeds the budget (:func:`memory_budget`), naming its
    triangles, their memory and a tolerance that fits (:func:`fitting_tolerance`, at most
    ``coarsest``): an :class:`~gearcoupling.errors.ArgumentError` on ``tolerance_mm``."""
    budget, source = memory_budget()
    if budget is None or size.bytes <= budget:
        return
    fit = fitting_tolerance(triangles_at, size.tolerance_mm, budget // BYTES_PER_TRIANGLE,
                            coarsest)
    advice = (f"use a tolerance of {fit:g} mm or coarser, or mesh fewer teeth"
              if fit is not None else "no tolerance fits it: mesh fewer teeth")
    raise ArgumentError("tolerance_mm", size.tolerance_mm,
                        f"the {size.part} would have {size.triangles:,} triangles, about "
                        f"{_gb(size.bytes)} to build, check and write ({BYTES_PER_TRIANGLE} "
                        f"bytes each), over the memory budget of {_gb(budget)} ({source}): "
                        f"{advice}")
