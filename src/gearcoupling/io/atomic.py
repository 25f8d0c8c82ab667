"""Atomic file writes: write a temporary file beside the target, then rename it.

A temporary is named ``.<target name>.<pid>.<random><suffix>``; one left behind by a
killed process (``kill -9``) is removed by the next atomic write into the same folder,
once its process is gone (:func:`remove_stale_temporaries`).
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from ..forked import held_signals
from ..interrupts import check as check_interrupt
from .files import writable_file


@contextmanager
def atomic_path(path: str | os.PathLike, field: str = "path") -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path``.

    If the body raises, the temporary file is removed and ``path`` is left untouched, so
    a reader never sees a half-written file. A ``path`` that exists and is not a regular
    file (a folder, a device such as ``/dev/null``, a named pipe, a socket) is refused
    before the body runs and again before the rename
    (:func:`~gearcoupling.io.writable_file`, an error naming ``field``): a rename would
    replace it.
    """
    target = writable_file(path, field)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target.parent)
    tmp_path = None
    try:
        # a SIGINT or SIGTERM between making the temporary and knowing its name would
        # leave it behind: held until then, raised here, where the finally removes it
        with held_signals(block=False):
            fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.{os.getpid()}.",
                                       suffix=target.suffix or ".tmp", dir=target.parent)
            os.close(fd)
            tmp_path = Path(tmp)
        yield tmp_path
        os.chmod(tmp_path, 0o666 & ~_umask())  # mkstemp made it private; use the usual mode
        writable_file(target, field)  # nothing special put there while the body ran
        check_interrupt()  # nothing written after a signal, also one a library dropped
        os.replace(tmp_path, target)
    finally:
        if tmp_path is not None and tmp_path.exists():
            tmp_path.unlink()


_TEMP_NAME = re.compile(r"^\.(?P<target>.+)\.(?P<pid>\d+)\.[A-Za-z0-9_]{8}(?P<suffix>\.[^.]*)$")


def remove_stale_temporaries(folder: str | os.PathLike) -> list[Path]:
    """Remove this module's temporaries in ``folder`` whose writing process has ended.

    Returns the removed paths. Temporaries of live processes (another run writing into
    the same folder) are left alone.
    """
    removed = []
    for entry in Path(folder).glob(".*.*"):
        match = _TEMP_NAME.match(entry.name)
        if not match or _alive(int(match["pid"])):
            continue
        try:
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
