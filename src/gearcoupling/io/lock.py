"""One command at a time in an output folder, and a record of which settings made its files.

:func:`lock_folder` takes an advisory lock (``fcntl.flock``) on ``.gearcoupling.lock`` in
the folder: a second command into the same folder is refused at once, naming the process
that holds it; the lock goes with the process, also when it is killed. ``.gearcoupling.json``
records, file by file, the settings key of the command that made it (:func:`settings_key`)
with the file's size and time, so that a later command with other settings can name the
files it will not replace (:func:`earlier_files`); it never removes them.
"""

from __future__ import annotations

import errno
import fcntl
import hashlib
import json
import os
import stat
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ArgumentError
from .json import write_json

LOCK_NAME = ".gearcoupling.lock"
RECORD_NAME = ".gearcoupling.json"
_RECORD_VERSION = 1
_RECORD_MAX_BYTES = 16 << 20  # a record of a million files; a larger one is not ours


@dataclass(frozen=True)
class FolderLock:
    """An output folder held by this process: ``fd`` is the open, locked lock file."""

    folder: Path
    path: Path
    fd: int

    def release(self) -> None:
        """Remove the lock file (still ours: the same file) and let the lock go."""
        try:
            self.remove_file()
        finally:
            os.close(self.fd)

    def remove_file(self) -> None:
        """Remove the lock file if it is still ours (the same file); the lock goes with the
        descriptor (at the latest when the process ends)."""
        try:
            now = os.lstat(self.path)
            held = os.fstat(self.fd)
            if (now.st_dev, now.st_ino) == (held.st_dev, held.st_ino):
                os.unlink(self.path)
        except OSError:  # removed, or the folder gone: nothing to tidy
            pass


def lock_folder(folder: str | os.PathLike, field: str = "-o") -> FolderLock:
    """Hold ``folder`` (an existing folder) for this process until
    :meth:`FolderLock.release` or its end. Another process holding it is an
    :class:`ArgumentError` naming ``field``, the folder and that process's id, at once
    (no wait); a symbolic link or anything but a regular file at the lock's place is
    refused too."""
    base = Path(folder)
    path = base / LOCK_NAME
    while True:
        fd = _open_lock(path, base, field)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = _holder(fd)
            os.close(fd)
            raise ArgumentError(field, os.fspath(base), f"another gearcoupling command "
                                f"({holder}) is writing into this folder: wait for it to "
                                "end, or give another folder") from None
        if _same_file(fd, path):
            break
        os.close(fd)  # its holder removed it after we opened it: lock the new one
    os.ftruncate(fd, 0)
    os.write(fd, f"{os.getpid()}\n".encode())
    return FolderLock(base, path, fd)


def _open_lock(path: Path, base: Path, field: str) -> int:
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC
                     | os.O_NONBLOCK, 0o644)
    except OSError as err:
        if err.errno == errno.ELOOP:
            raise ArgumentError(field, os.fspath(base), f"holds {LOCK_NAME}, a symbolic "
                                "link where gearcoupling keeps its lock: remove it") from None
        raise OSError(err.errno, err.strerror, os.fspath(path)) from None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise ArgumentError(field, os.fspath(base), f"holds {LOCK_NAME}, not a regular "
                            "file, where gearcoupling keeps its lock: remove it")
    return fd


def _same_file(fd: int, path: Path) -> bool:
    try:
        now = os.lstat(path)
    except FileNotFoundError:
        return False
    held = os.fstat(fd)
    return (now.st_dev, now.st_ino) == (held.st_dev, held.st_ino)


def _holder(fd: int) -> str:
    """``pid N`` as the holder wrote it in the lock file."""
    text = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
    return f"pid {text}" if text.isdigit() else "pid not yet written"


def settings_key(settings: Any) -> str:
    """A short hash of ``settings`` (JSON data: a resolved spec's dict, options)."""
    text = json.dumps(settings, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _read_record(folder: Path) -> dict[str, dict[str, Any]]:
    """The files of the folder's record, ``{relative name: {"key", "size", "mtime_ns"}}``;
    empty when there is none or it is not one this module wrote (a link, another kind of
    file, another layout)."""
    path = folder / RECORD_NAME
    try:
        st = path.lstat()
        if not stat.S_ISREG(st.st_mode) or st.st_size > _RECORD_MAX_BYTES:
            return {}
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    if not isinstance(data, dict) or data.get("version") != _RECORD_VERSION:
        return {}
    files = data.get("files")
    if not isinstance(files, dict):
        return {}
    return {k: v for k, v in files.items() if isinstance(k, str) and isinstance(v, dict)
            and not os.path.isabs(k) and ".." not in Path(k).parts}


def _unchanged(folder: Path, name: str, entry: dict[str, Any]) -> bool:
    """Whether the file ``name`` is still as the record says (size and time)."""
    try:
        st = (folder / name).lstat()
    except (OSError, ValueError):
        return False
    return (stat.S_ISREG(st.st_mode) and st.st_size == entry.get("size")
            and st.st_mtime_ns == entry.get("mtime_ns"))


def earlier_files(folder: str | os.PathLike, key: str,
                  replaced: Iterable[str | os.PathLike] = ()) -> list[str]:
    """Files of ``folder`` (relative names, sorted) that its record says a command with
    settings other than ``key`` made and that are still as it left them, less those in
    ``replaced`` (paths this command writes)."""
    base = Path(folder)
    skip = {os.path.relpath(p, base) for p in replaced}
    return sorted(name for name, entry in _read_record(base).items()
                  if entry.get("key") != key and name not in skip
                  and _unchanged(base, name, entry))


def record_files(folder: str | os.PathLike, key: str,
                 made: Iterable[str | os.PathLike]) -> Path:
    """Record in ``folder`` that a command of settings ``key`` made the files ``made``
    (paths in the folder), keeping the entries of the other files that are still as
    recorded (a file of ``made`` still as recorded was not written again: an earlier
    command's file of the same moment); written atomically."""
    base = Path(folder)
    files = {name: entry for name, entry in _read_record(base).items()
             if _unchanged(base, name, entry)}
    for path in map(Path, made):
        name = os.path.relpath(path, base)
        try:
            st = path.lstat()
        except OSError:
            continue
        if name not in files:
            files[name] = {"key": key, "size": st.st_size, "mtime_ns": st.st_mtime_ns}
    return write_json(base / RECORD_NAME, {"version": _RECORD_VERSION,
                                           "files": dict(sorted(files.items()))})
