"""Cache entries used only when their key and checksum match.

A cache entry is data gearcoupling computed once and keeps on disk for later runs (the FE
tables, numba's compiled code). Read back, an entry is used only when it is a regular
file, was written for the same key (every input that changes it, the table's version and
the package's) and its content matches the checksum written with it; anything else
(another key, an edited or damaged file, a file of another format, a named pipe, a
folder) is a :class:`CacheMiss`, which the caller turns into one line on stderr
(:func:`note`) and a fresh computation, never a traceback, a hang or a wrong answer.

Two formats: a JSON entry (:func:`write_entry`, :func:`read_entry`), readable by people,
``{"format", "schema", "key", "sha256", "data"}`` with the SHA-256 of the data's canonical
JSON; and sealed bytes (:func:`seal`, :func:`unseal`) for binary payloads, a header line,
a tag line (the key) and the SHA-256 of tag and payload before the payload.
"""

from __future__ import annotations

import hashlib
import importlib
import json
import os
import stat
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from ..errors import ArgumentError, GearCouplingError
from .atomic import write_text
from .files import NOUNS, as_path
from .json import plain

FORMAT = "gearcoupling cache entry"
SCHEMA = 1
MAX_BYTES = 64 * 2**20
"""The largest file read as a cache entry (an FE table is a few kB, a compiled kernel a
few hundred): a larger one is a miss, not read."""
SEAL = b"gearcoupling sealed 1\n"

T = TypeVar("T")


class CacheMiss(GearCouplingError):
    """Why a cache entry is not used (caught by the caller, which computes it again)."""


def cache_key(kind: str, table_version: int, **settings: Any) -> dict:
    """The key of an entry: its ``kind``, the table's version, the package's version and
    ``settings`` (every input that changes the entry, e.g. the spec's hash), as plain JSON
    data."""
    return plain({"kind": kind, "table_version": table_version,
                  "package_version": package_version(), **settings}, "cache key")


def package_version() -> str:
    """gearcoupling's version (part of every cache key)."""
    # looked up, not imported: a static import of the package here puts the compiled
    # kernels (io.numba_cache) in the package stub's import cycle, which confuses mypy
    return str(importlib.import_module("gearcoupling").__version__)


def checksum(data: bytes) -> str:
    """SHA-256 of ``data``, hexadecimal."""
    return hashlib.sha256(data).hexdigest()


def read_regular(path: str | os.PathLike, most_bytes: int = MAX_BYTES) -> bytes | None:
    """The bytes of ``path``; None when nothing is there. A path that is not a regular file
    (a folder, a named pipe, a device, a socket) is refused by its mode before it is opened
    and again after (opened without blocking: a pipe cannot hang the read): a
    :class:`CacheMiss` saying what it is, as is a file over ``most_bytes`` or one that
    cannot be read."""
    try:
        _regular(os.stat(path).st_mode)
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except (FileNotFoundError, NotADirectoryError):
        return None
    except OSError as err:
        raise CacheMiss(f"cannot be read ({err.strerror})") from None
    with os.fdopen(fd, "rb") as f:
        info = os.fstat(fd)
        _regular(info.st_mode)
        if info.st_size > most_bytes:
            raise CacheMiss(f"{info.st_size} bytes, more than a cache entry holds "
                            f"({most_bytes})")
        try:
            return f.read(most_bytes + 1)
        except OSError as err:
            raise CacheMiss(f"cannot be read ({err.strerror})") from None


def _regular(mode: int) -> None:
    for test, noun in NOUNS:
        if test(mode):
            raise CacheMiss(f"{noun}, not a file")
    if not stat.S_ISREG(mode):
        raise CacheMiss("not a regular file")


def seal(payload: bytes, tag: str) -> bytes:
    """``payload`` with a header: :data:`SEAL`, ``tag`` (one line, e.g. the entry's key)
    and the checksum of tag and payload (:func:`unseal` reads it back)."""
    head = tag.encode()
    if b"\n" in head:
        raise ValueError("a seal's tag is one line")
    return SEAL + head + b"\n" + checksum(head + b"\n" + payload).encode() + b"\n" + payload


def unseal(raw: bytes, tag: str) -> bytes:
    """The payload of sealed bytes ``raw`` (:func:`seal`) when their tag is ``tag`` and
    the checksum matches; else :class:`CacheMiss` saying which."""
    if not raw.startswith(SEAL):
        raise CacheMiss("not sealed by gearcoupling (another format, or its header is "
                        "damaged)")
    parts = raw[len(SEAL):].split(b"\n", 2)
    if len(parts) != 3:
        raise CacheMiss("truncated")
    head, digest, payload = parts
    if head != tag.encode():
        raise CacheMiss("written for another key")
    if digest != checksum(head + b"\n" + payload).encode():
        raise CacheMiss("its content does not match its checksum (damaged or edited)")
    return payload


def _canonical(data: Any) -> bytes:
    return json.dumps(data, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()


def write_entry(path: str | os.PathLike, key: dict, data: Any) -> Path:
    """Write ``data`` (JSON data after :func:`~gearcoupling.io.plain`) as the cache entry
    of ``key`` with its checksum, atomically."""
    body = plain(data, Path(path).name)
    entry = {"format": FORMAT, "schema": SCHEMA, "key": plain(key, "cache key"),
             "sha256": checksum(_canonical(body)), "data": body}
    return write_text(path, json.dumps(entry, indent=1, allow_nan=False) + "\n")


def read_entry(path: str | os.PathLike, key: dict) -> Any:
    """The data of the cache entry at ``path`` (:func:`write_entry`); None when nothing is
    there. :class:`CacheMiss` when it is not a regular file (:func:`read_regular`), not an
    entry of this format and schema, was written for another key (saying which parts of
    it differ) or its data do not match its checksum."""
    raw = read_regular(path)
    if raw is None:
        return None
    try:
        entry = json.loads(raw.decode())
    except (UnicodeDecodeError, ValueError, RecursionError):
        raise CacheMiss("not JSON (empty, truncated or damaged)") from None
    if not (isinstance(entry, dict) and entry.get("format") == FORMAT
            and {"key", "sha256", "data"} <= entry.keys()):
        raise CacheMiss("not a gearcoupling cache entry (an older format, or damaged)")
    if entry.get("schema") != SCHEMA:
        raise CacheMiss(f"schema {entry.get('schema')!r}, not {SCHEMA}")
    wanted = plain(key, "cache key")
    if entry["key"] != wanted:
        raise CacheMiss(f"written for another key ({_differences(entry['key'], wanted)})")
    try:
        digest = checksum(_canonical(entry["data"]))
    except (TypeError, ValueError):  # not JSON data after all: NaN, ...
        digest = None
    if digest != entry["sha256"]:
        raise CacheMiss("its data do not match its checksum (damaged or edited)")
    return entry["data"]


def _differences(found: Any, wanted: dict, most: int = 3) -> str:
    """``'nz' is 4, not 3; ...``: the first ``most`` fields of ``wanted`` that differ."""
    if not isinstance(found, dict):
        return f"a key of type {type(found).__name__}"
    diff = [f"{k!r} is {found.get(k)!r}, not {v!r}" for k, v in wanted.items()
            if found.get(k) != v]
    diff += [f"{k!r} is not a key field" for k in found.keys() - wanted.keys()]
    return "; ".join(diff[:most]) + ("; ..." if len(diff) > most else "")


def note(text: str) -> None:
    """One line ``gearcoupling: text`` on stderr (what happened to a cache entry)."""
    print(f"gearcoupling: {text}", file=sys.stderr, flush=True)


def cached(path: Path, key: dict, build: Callable[[Any], T], what: str) -> T | None:
    """``build(data)`` of the cache entry at ``path`` (:func:`read_entry`), or None: when
    nothing is there, and when the entry is not used (a :class:`CacheMiss`, or ``build``
    refusing the data with a :class:`~gearcoupling.errors.GearCouplingError`), then with one
    line on stderr saying why and that ``what`` is computed again."""
    try:
        data = read_entry(path, key)
        return None if data is None else build(data)
    except CacheMiss as miss:
        reason = str(miss)
    except GearCouplingError as err:
        reason = f"not a valid table ({err})"
    note(f"cache entry {str(path)!r} not used: {reason}; computing {what} again"
         + ("" if _storable(path) else ", not stored there"))
    return None


def store(path: Path, key: dict, data: Any) -> Path | None:
    """Write the cache entry (:func:`write_entry`); None, with one line on stderr, when it
    cannot be written (the data are still the caller's to use). A path that is there and
    not a regular file is left alone (:func:`cached` said so already)."""
    if not _storable(path):
        return None
    try:
        return write_entry(path, key, data)
    except (OSError, GearCouplingError) as err:
        note(f"cache entry {str(path)!r} not stored: {getattr(err, 'strerror', None) or err}")
        return None


def _storable(path: Path) -> bool:
    """Whether nothing or a regular file is at ``path`` (an entry may be written there)."""
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except OSError:
        return True  # nothing there (or it cannot be checked: the write says why)


def cache_folder(path: str | os.PathLike, field: str, shown: object = None) -> Path:
    """``path`` as a folder for cache entries, made (with its parents) when missing: checked
    before any work. :class:`~gearcoupling.errors.ArgumentError` naming ``field`` (and
    ``shown``, default ``path``) when it is a file, a device or a pipe, lies under a file,
    or cannot be made or written into. Its entries are not looked at (:func:`cached` checks
    each one)."""
    p = as_path(path, field)
    value = os.fspath(path) if shown is None else shown
    try:
        p.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise ArgumentError(field, value, f"{_kind(p)}, not a folder: give a folder for "
                            "the cache") from None
    except NotADirectoryError:
        raise ArgumentError(field, value, "lies under a file (a part of the path is a file, "
                            "not a folder): give a folder for the cache") from None
    except OSError as err:
        raise ArgumentError(field, value, f"cannot make the cache folder ({err.strerror})"
                            ) from None
    if not p.is_dir():
        raise ArgumentError(field, value, f"{_kind(p)}, not a folder: give a folder for the "
                            "cache")
    if not os.access(p, os.W_OK | os.X_OK):
        raise ArgumentError(field, value, "a folder this process cannot write into: give "
                            "another folder for the cache")
    return p


def _kind(p: Path) -> str:
    try:
        mode = os.stat(p).st_mode
    except OSError as err:
        return f"a path that cannot be checked ({err.strerror})"
    return next((noun for test, noun in NOUNS if test(mode)), "a file")
