"""Atomic file writes: write a temporary file beside the target, then rename it.

A temporary is named ``.gctmp-<pid>-<mark>-<random><suffix>``: the writing process's id, a
mark only this module gives that process (:func:`temporary_mark`: eight hex digits of a
keyed hash of the pid and the user id) and the target's suffix. One left behind by a killed
process (``kill -9``) is removed by the next atomic write into the same folder once its
process is gone (:func:`remove_stale_temporaries`); a file or folder that only looks like
one (another mark, another owner, a symbolic link) is never touched. Private working
folders (:func:`temporary_folder`, a solver's scratch) are named the same way.
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import stat
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..forked import held_signals
from ..interrupts import check as check_interrupt
from .files import writable_file

#: how every temporary name of this module starts
PREFIX = ".gctmp-"
_SUFFIX = r"\.[A-Za-z0-9_]{1,16}"
_TEMP_NAME = re.compile(r"\.gctmp-(?P<pid>[1-9][0-9]{0,9})-(?P<mark>[0-9a-f]{8})-"
                        rf"[a-z0-9_]{{8}}{_SUFFIX}")


def temporary_mark(pid: int | None = None) -> str:
    """The mark in the temporary names of process ``pid`` (default this one) of this user:
    eight hex digits that a name copied by hand or by another program does not carry."""
    pid = os.getpid() if pid is None else pid
    text = f"gearcoupling temporary: pid {pid}, uid {os.getuid()}"
    return hashlib.blake2s(text.encode(), digest_size=4).hexdigest()


def _prefix() -> str:
    return f"{PREFIX}{os.getpid()}-{temporary_mark()}-"


def _suffix(target: Path) -> str:
    """The target's suffix when it is short and plain (a writer may pick its format by
    it), else ``.tmp``."""
    suffix = target.suffix
    return suffix if re.fullmatch(_SUFFIX, suffix) else ".tmp"


def _about_temporary(err: OSError) -> bool:
    """Whether ``err`` is about a temporary of this module (named, or a write without a
    name: a full disk, a file size limit)."""
    return err.filename is None or os.path.basename(os.fspath(err.filename)).startswith(PREFIX)


@contextmanager
def atomic_path(path: str | os.PathLike, field: str = "path") -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path``.

    If the body raises, the temporary file is removed and ``path`` is left untouched, so
    a reader never sees a half-written file. A ``path`` that exists and is not a writable
    regular file (a folder, a device such as ``/dev/null``, a named pipe, a socket, a
    read-only file) is refused before the body runs and again before the rename
    (:func:`~gearcoupling.io.writable_file`, an error naming ``field``): a rename would
    replace it. A symbolic link at ``path`` is replaced, never written through. An
    :class:`OSError` of the temporary (a full disk, a folder that cannot be written) is
    raised naming ``path``.
    """
    target = writable_file(path, field)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target.parent)
    tmp_path = None
    try:
        # a SIGINT or SIGTERM between making the temporary and knowing its name would
        # leave it behind: held until then, raised here, where the finally removes it
        with held_signals(block=False):
            fd, tmp = tempfile.mkstemp(prefix=_prefix(), suffix=_suffix(target),
                                       dir=target.parent)
            os.close(fd)
            tmp_path = Path(tmp)
        yield tmp_path
        os.chmod(tmp_path, 0o666 & ~_umask())  # mkstemp made it private; use the usual mode
        writable_file(target, field)  # nothing special put there while the body ran
        check_interrupt()  # nothing written after a signal, also one a library dropped
        os.replace(tmp_path, target)
    except OSError as err:
        if not _about_temporary(err):
            raise
        raise OSError(err.errno, err.strerror, os.fspath(target)) from None
    finally:
        if tmp_path is not None and tmp_path.exists():
            tmp_path.unlink()


@contextmanager
def temporary_folder(parent: str | os.PathLike) -> Iterator[Path]:
    """A new private folder in ``parent`` (made with it), named as this module's
    temporaries; removed with what it holds when the block ends, however it ends: move
    what is to be kept out of it first (:func:`move_into`)."""
    folder = Path(parent)
    folder.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(folder)
    made = None
    try:
        with held_signals(block=False):  # as in atomic_path: never made and not known
            made = Path(tempfile.mkdtemp(prefix=_prefix(), suffix=".d", dir=folder))
        yield made
    finally:
        if made is not None:
            shutil.rmtree(made, ignore_errors=True)


def move_into(source: str | os.PathLike, target: str | os.PathLike,
              field: str = "path") -> Path:
    """Rename the complete file ``source`` onto ``target`` (same file system) as
    :func:`atomic_path` does: a target that is not a writable regular file is refused, a
    symbolic link there is replaced, not followed."""
    dest = writable_file(target, field)
    check_interrupt()  # nothing moved in after a signal
    try:
        os.replace(source, dest)
    except OSError as err:
        raise OSError(err.errno, err.strerror, os.fspath(dest)) from None
    return dest


def is_stale_temporary(path: str | os.PathLike) -> bool:
    """Whether ``path`` is a temporary file or folder of this module, made by this user,
    whose process has ended: its name has this module's form and the mark of the pid in
    it, it is a regular file or a folder (not a link) owned by this user, and no process
    of that pid exists."""
    p = Path(path)
    match = _TEMP_NAME.fullmatch(p.name)
    if not match or match["mark"] != temporary_mark(int(match["pid"])):
        return False
    try:
        st = p.lstat()
    except OSError:
        return False
    if st.st_uid != os.getuid() or not (stat.S_ISREG(st.st_mode) or stat.S_ISDIR(st.st_mode)):
        return False
    return not _alive(int(match["pid"]))


def remove_stale_temporaries(folder: str | os.PathLike, *, own: bool = False) -> list[Path]:
    """Remove the temporaries in ``folder`` whose writing process has ended
    (:func:`is_stale_temporary`), with ``own`` also this process's (the last act of a
    process that ends at once); returns the removed paths. Temporaries of other live
    processes (another run writing into the same folder) and files that only look like
    temporaries are left alone."""
    removed = []
    for entry in Path(folder).glob(f"{PREFIX}*"):
        if not (is_stale_temporary(entry) or (own and entry.name.startswith(_prefix()))):
            continue
        try:
            if entry.is_dir() and not entry.is_symlink():
                shutil.rmtree(entry)
            else:
                entry.unlink()
            removed.append(entry)
        except FileNotFoundError:  # another run cleaned it first
            pass
    return removed


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    except OverflowError:  # not a pid this system can have
        return False
    return True


_UNSAFE = re.compile(r"[^A-Za-z0-9._+-]+")


def safe_name(name: str) -> str:
    """``name`` as a single safe folder name: characters other than letters, digits and
    ``._+-`` become ``_``, leading dots are dropped (no ``..``, no hidden folder, no path
    separator, no absolute path); empty -> ``custom``; at most 100 characters."""
    cleaned = _UNSAFE.sub("_", str(name)).lstrip(".")[:100]
    return cleaned or "custom"


def default_output_dir(name: str) -> Path:
    """``outputs/<safe_name(name)>``: where commands write when ``-o`` is not given."""
    return Path("outputs") / safe_name(name)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)
