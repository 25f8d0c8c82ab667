"""Atomic file writes: write a temporary file beside the target, then rename it.

A temporary is named ``.<target name>.<pid>.<random><suffix>``; one left behind by a
killed process (``kill -9``) is removed by the next atomic write into the same folder,
once its process is gone (:func:`remove_stale_temporaries`).
"""

from __future__ import annotations

import json
import math
import os
import re
import stat
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from .errors import SpecError


@contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path``.

    If the body raises, the temporary file is removed and ``path`` is left untouched, so
    a reader never sees a half-written file.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target.parent)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.{os.getpid()}.",
                               suffix=target.suffix or ".tmp", dir=target.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    try:
        yield tmp_path
        os.chmod(tmp_path, 0o666 & ~_umask())  # mkstemp made it private; use the usual mode
        os.replace(tmp_path, target)
    finally:
        if tmp_path.exists():
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


def write_json(path: str | os.PathLike, data: Any) -> Path:
    """Write ``data`` as indented JSON atomically; refuses NaN and infinity."""
    return write_text(path, json.dumps(data, indent=2, allow_nan=False, default=_jsonable) + "\n")


def _jsonable(obj: Any) -> Any:
    if hasattr(obj, "tolist"):
        return obj.tolist()
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def write_csv_rows(path: str | os.PathLike, columns, rows) -> Path:
    """A CSV written atomically: floats as ``%.9g``, booleans ``true``/``false``, None empty."""
    import csv

    def cell(v):
        if v is None:
            return ""
        if isinstance(v, bool):
            return str(v).lower()
        return f"{v:.9g}" if isinstance(v, float) else v

    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(columns)
        w.writerows([cell(v) for v in row] for row in rows)
    return Path(path)


def finite_json(data: Any) -> Any:
    """Plain JSON data: numpy scalars to Python, non-finite floats to None."""
    if isinstance(data, dict):
        return {k: finite_json(v) for k, v in data.items()}
    if isinstance(data, list | tuple):
        return [finite_json(v) for v in data]
    if isinstance(data, np.ndarray):
        return finite_json(data.tolist())
    if isinstance(data, np.bool_):
        return bool(data)
    if isinstance(data, np.integer):
        return int(data)
    if isinstance(data, float | np.floating):
        return float(data) if math.isfinite(data) else None
    return data


def not_a_file(path: str | os.PathLike) -> str | None:
    """Why ``path`` is not a readable regular file (``None`` when it is one): a missing
    file, a broken link, a folder, a device such as ``/dev/null``, a named pipe, a socket
    or a file without read permission, each said plainly."""
    p = Path(path)
    try:
        mode = p.stat().st_mode
    except FileNotFoundError:
        return "a broken symbolic link" if p.is_symlink() else "no such file"
    except NotADirectoryError:
        return "no such file (a part of the path is a file, not a folder)"
    except OSError as err:
        return f"cannot be read ({err.strerror})"
    kinds = ((stat.S_ISDIR, "a folder, not a file"),
             (stat.S_ISCHR, "a character device (like /dev/null), not a file"),
             (stat.S_ISBLK, "a block device, not a file"),
             (stat.S_ISFIFO, "a named pipe (FIFO), not a file (a pipe can be read only once)"),
             (stat.S_ISSOCK, "a socket, not a file"))
    for test, text in kinds:
        if test(mode):
            return text
    if not os.access(p, os.R_OK):
        return "a file without read permission"
    return None


def require_file(path: str | os.PathLike, field: str, expected: str) -> Path:
    """``path`` when it is a readable regular file; else a
    :class:`~gearcoupling.errors.SpecError` naming ``field``, what the path is and what is
    ``expected`` (e.g. ``"a TOML spec file"``)."""
    reason = not_a_file(path)
    if reason is not None:
        raise SpecError(field, str(path), f"{reason}: give {expected}")
    return Path(path)
