"""Input files said plainly: what a path is when it is not a readable regular file."""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ..errors import GearCouplingError, SpecError

KINDS = ((stat.S_ISDIR, "a folder, not a file"),
         (stat.S_ISCHR, "a character device (like /dev/null), not a file"),
         (stat.S_ISBLK, "a block device, not a file"),
         (stat.S_ISFIFO, "a named pipe (FIFO), not a file (a pipe can be read only once)"),
         (stat.S_ISSOCK, "a socket, not a file"))


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
    for test, text in KINDS:
        if test(mode):
            return text
    if not os.access(p, os.R_OK):
        return "a file without read permission"
    return None


def require_file(path: str | os.PathLike, field: str, expected: str,
                 error: type[GearCouplingError] = SpecError) -> Path:
    """``path`` when it is a readable regular file; else ``error(field, path, reason)``
    saying what the path is and that ``expected`` is wanted (e.g. ``"a TOML spec file"``):
    :class:`SpecError` for files a spec names, :class:`ArgumentError` for arguments."""
    reason = not_a_file(path)
    if reason is not None:
        raise error(field, str(path), f"{reason}: give {expected}")
    return Path(path)
