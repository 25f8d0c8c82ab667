"""numba's on-disk cache of the compiled kernels, used only when its key and checksum match.

:func:`njit` is ``numba.njit(cache=True, ...)`` with numba's cache files (an ``.nbi``
index and ``.nbc`` data files per function, in ``__pycache__`` beside the module or under
``NUMBA_CACHE_DIR``) sealed (:func:`gearcoupling.io.cache.seal`): the index with numba's
version and the source's stamp, each data file with the key it was compiled for (the
signature, the CPU and the function's bytecode), both with a checksum. A file that is not
sealed (numba's own format), fails its checksum, was written for another key, cannot be
loaded or is not a regular file is not used: a regular one is removed, the kernel is
compiled again and its files written anew, and one line on stderr says so (once per
process and cache folder). So a damaged file costs a compilation, never a traceback, a
crash in LLVM or wrong code.

numba writes each file to a temporary name and renames it into place, so two processes
compiling at once (or forked workers) each leave whole files; a data file paired with
another process's index is caught by its key. Where numba's internals are not what this
module expects (another release) or numba finds no cache folder, the kernels are compiled
in every process instead: never loaded unchecked.

Imported only by the compiled kernels (it imports numba).
"""

from __future__ import annotations

import itertools
import os
import pickle
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba

from .cache import CacheMiss, checksum, note, read_regular, seal, unseal

try:
    from numba.core.caching import FunctionCache, IndexDataCacheFile
    from numba.core.serialize import dumps
except ImportError:  # pragma: no cover - another numba layout: no on-disk cache
    FunctionCache = IndexDataCacheFile = None  # type: ignore[assignment,misc]

_REPORTED: set[str] = set()
"""Cache folders this process has reported a discarded file in."""


def njit(**options: Any) -> Callable[[Callable], Any]:
    """``numba.njit(**options)`` with the verified on-disk cache (module docstring)."""
    options.pop("cache", None)

    def wrap(func: Callable) -> Any:
        dispatcher = numba.njit(**options)(func)
        if FunctionCache is not None:
            try:
                dispatcher._cache = _SealedCache(dispatcher.py_func)
            except (AttributeError, TypeError, RuntimeError, OSError):
                pass  # no cache folder, or numba's internals differ: compiled each time
        return dispatcher

    return wrap


if FunctionCache is not None:

    class _SealedFile(IndexDataCacheFile):
        """numba's index and data files, sealed (module docstring)."""

        def _load_index(self) -> dict:
            found = self._read(self._index_path, "index")
            if not (isinstance(found, tuple) and len(found) == 3):
                return {}
            version, stamp, overloads = found
            if version != self._version or stamp != self._source_stamp:
                return {}  # another numba, or the source changed: numba's own rule
            return overloads if isinstance(overloads, dict) else {}

        def _save_index(self, overloads: dict) -> None:
            self._write(self._index_path, (self._version, self._source_stamp, overloads),
                        "index")

        def load(self, key: Any) -> Any:
            name = self._load_index().get(key)
            return None if name is None else self._read(self._data_path(name), _tag(key))

        def save(self, key: Any, data: Any) -> None:
            overloads = self._load_index()
            name = overloads.get(key)
            if name is None:
                taken = set(overloads.values())
                name = next(n for n in map(self._data_name, itertools.count(1))
                            if n not in taken)
                overloads[key] = name
                self._save_index(overloads)
            self._write(self._data_path(name), data, _tag(key))

        def _read(self, path: str, tag: str) -> Any:
            """The object sealed in ``path`` with ``tag``; None when there is none or it is
            not used (then a regular file is removed and the folder reported)."""
            try:
                raw = read_regular(path)
                if raw is None:
                    return None
                return pickle.loads(unseal(raw, tag))
            except CacheMiss as miss:
                reason = str(miss)
            except Exception as err:  # sealed, yet numba cannot load it: recompile
                reason = f"cannot be loaded ({type(err).__name__})"
            _discard(Path(path), reason)
            return None

        def _write(self, path: str, obj: Any, tag: str) -> None:
            if _occupied(path):
                return  # a folder, a pipe or a device is not replaced
            with self._open_for_write(path) as f:
                f.write(seal(dumps(obj), tag))

    class _SealedCache(FunctionCache):
        """numba's per-function cache on :class:`_SealedFile`."""

        def __init__(self, py_func: Callable) -> None:
            super().__init__(py_func)
            self._cache_file = _SealedFile(self._cache_path, self._impl.filename_base,
                                           self._impl.locator.get_source_stamp())


def _tag(key: Any) -> str:
    """A data file's tag: the checksum of its index key (signature, CPU, bytecode)."""
    return "key " + checksum(repr(key).encode())


def _occupied(path: str | os.PathLike) -> bool:
    """Whether something other than a regular file (or nothing) is at ``path``."""
    try:
        return not os.path.isfile(path) and os.path.lexists(path)
    except OSError:
        return True


def _discard(path: Path, reason: str) -> None:
    """Remove the unused cache file ``path`` (a regular file only) and say so, once per
    process and folder."""
    removed = False
    if not _occupied(path):
        try:
            path.unlink()
            removed = True
        except OSError:
            pass
    folder = str(path.parent)
    if folder in _REPORTED:
        return
    _REPORTED.add(folder)
    note(f"compiled-code cache file {str(path)!r} not used: {reason}; "
         f"{'removed, ' if removed else ''}compiling again")
