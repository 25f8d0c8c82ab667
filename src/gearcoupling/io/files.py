"""Paths said plainly: what a path is when it is not a readable regular file (input), and
whether a file or folder may be written there (output)."""

from __future__ import annotations

import os
import stat
import tempfile
from collections.abc import Iterable
from pathlib import Path

from ..errors import ArgumentError, GearCouplingError, SpecError

#: what a path is that is not a regular file, by the test of its mode
NOUNS = ((stat.S_ISDIR, "a folder"),
         (stat.S_ISCHR, "a character device (like /dev/null)"),
         (stat.S_ISBLK, "a block device"),
         (stat.S_ISFIFO, "a named pipe (FIFO)"),
         (stat.S_ISSOCK, "a socket"))
KINDS = tuple((test, f"{noun}, not a file" + (" (a pipe can be read only once)"
                                              if test is stat.S_ISFIFO else ""))
              for test, noun in NOUNS)


#: what a writer never replaces and an output folder must not hold
SPECIAL = tuple(noun for _, noun in NOUNS[1:])


def _noun(mode: int) -> str | None:
    """What a path of ``mode`` is when it is not a regular file (``None`` when it is)."""
    return next((noun for test, noun in NOUNS if test(mode)), None)


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


def as_path(path: object, field: str) -> Path:
    """``path`` (a ``str`` or ``os.PathLike``, not empty) as a :class:`Path`; anything
    else is an :class:`ArgumentError` naming ``field``."""
    if isinstance(path, bytes) or not isinstance(path, str | os.PathLike):
        raise ArgumentError(field, path, "give a path (str or os.PathLike)")
    text = os.fspath(path)
    if not isinstance(text, str) or not text.strip():
        raise ArgumentError(field, path, "an empty path: give a file or folder name")
    if "\x00" in text:
        raise ArgumentError(field, path, "a path with a NUL character")
    return Path(text)


def _existing_kind(p: Path) -> str | None:
    """What an existing ``p`` is when it is not a regular file; ``None`` when it is one
    or does not exist."""
    try:
        return _noun(p.stat().st_mode)
    except FileNotFoundError:  # also a dangling link: the write replaces the link
        return None
    except NotADirectoryError:
        return "under a file (a part of the path is a file, not a folder)"
    except OSError as err:
        return f"a path that cannot be checked ({err.strerror})"


def writable_file(path: object, field: str = "path") -> Path:
    """``path`` as a :class:`Path` when a file may be written there: nothing there yet, or
    a regular file (it will be replaced). A folder, a device such as ``/dev/null``, a named
    pipe or a socket is never replaced: :class:`ArgumentError` naming ``field``. Every
    writer calls this before any work (and :func:`~gearcoupling.io.atomic_path` once more
    before the rename). A read-only file is not replaced either: it is refused the same
    way."""
    p = as_path(path, field)
    shown = os.fspath(path)  # type: ignore[call-overload]
    kind = _existing_kind(p)
    if kind is not None:
        raise ArgumentError(field, shown, f"{_not(kind, 'a file')}: give the path of a "
                            "regular file (it is replaced) or of a new one")
    if _read_only(p):
        raise ArgumentError(field, shown, "a read-only file: make it writable to have it "
                            "replaced, or give another path")
    return p


def _read_only(p: Path) -> bool:
    """Whether ``p`` is a file without write permission (no write bit at all, or none for
    this user); False where there is no file."""
    try:
        mode = p.stat().st_mode
    except OSError:
        return False
    return not (mode & 0o222 and os.access(p, os.W_OK))


def own_folder(path: object, field: str = "path") -> Path:
    """``path`` when gearcoupling may make or fill it as a folder of its own files (a
    solver's ``fea_contact/``): nothing there yet, or a folder
    holding writable regular files only. A symbolic link there (the files would go where
    it points), a file, a device or a folder that holds anything else (a folder, a device,
    a read-only file) is refused with :class:`ArgumentError` naming ``field``."""
    p = as_path(path, field)
    shown = os.fspath(path)  # type: ignore[call-overload]
    if p.is_symlink():
        raise ArgumentError(field, shown, "a symbolic link where gearcoupling makes a folder "
                            "of its own files (they would go where it points): remove it")
    kind = _existing_kind(p)
    if kind is not None and kind != "a folder":
        raise ArgumentError(field, shown, f"{_not(kind, 'a folder')}: gearcoupling makes a "
                            "folder of its own files there; remove it")
    for entry in _entries(p, depth=1) if kind else []:
        inner = _existing_kind(entry) or ("a read-only file" if _read_only(entry) else None)
        if inner is not None:
            raise ArgumentError(field, shown, f"holds {entry.name}, {inner}, where "
                                "gearcoupling writes its own files: remove it")
    return p


def writable_targets(folder: str | os.PathLike, files: Iterable[str] = (),
                     folders: Iterable[str] = (), field: str = "-o") -> list[Path]:
    """Every place a command writes in ``folder``, checked before any work: the ``files``
    (names relative to it) by :func:`writable_file` and the ``folders`` it makes for its
    own files by :func:`own_folder`, an error naming ``field`` and the path. Returns the
    paths, files first."""
    base = Path(folder)
    paths = [writable_file(base / name, field) for name in files]
    return paths + [own_folder(base / name, field) for name in folders]


def output_folder(path: object, field: str = "out", *, create: bool = True) -> Path:
    """Create the folder ``path`` (with its parents) and return it; refuse, naming
    ``field``, an empty path, a path that is a file, a device or a pipe, a place that
    cannot be written, and a folder that holds (itself or one level down) a device, a
    named pipe or a socket where a writer would put a file. ``create=False`` checks what
    is there without creating anything (call it again once the other arguments are
    checked)."""
    p = as_path(path, field)
    shown = os.fspath(path)  # type: ignore[call-overload]
    kind = _existing_kind(p)
    if kind is not None and kind != "a folder":
        raise ArgumentError(field, shown, f"{_not(kind, 'a folder')}: give a folder")
    if kind is not None:
        _check_entries(p, field, shown)
    if not create:
        return p
    try:
        p.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise ArgumentError(field, shown, "names an existing file: give a folder") from None
    except OSError as err:
        raise ArgumentError(field, shown, f"cannot create the output folder: "
                            f"{err.strerror}") from None
    if not p.is_dir():
        raise ArgumentError(field, shown, "names an existing file: give a folder")
    try:  # a file and a folder made and removed again: what the writers will do
        probe = Path(tempfile.mkdtemp(prefix=".gearcoupling-probe-", dir=p))
        fd, name = tempfile.mkstemp(dir=probe)
        os.close(fd)
        os.unlink(name)
        probe.rmdir()
    except OSError as err:
        raise ArgumentError(field, shown, f"a folder this process cannot write into "
                            f"({err.strerror})") from None
    return p


def _check_entries(p: Path, field: str, shown: str) -> None:
    for entry in _entries(p):
        kind = _existing_kind(entry)
        if kind in SPECIAL:
            raise ArgumentError(field, shown, f"holds {entry.relative_to(p)}, {kind}, where "
                                "a file may be written: remove it or give another folder")


def _not(kind: str, wanted: str) -> str:
    """``"a socket, not a file"``; a reason that is not a noun as it is."""
    return f"{kind}, not {wanted}" if kind in {n for _, n in NOUNS} else kind


def _entries(folder: Path, depth: int = 2) -> list[Path]:
    """Entries of ``folder`` and of its subfolders, ``depth`` levels in all."""
    found: list[Path] = []
    try:
        children = list(folder.iterdir())
    except OSError:
        return found
    for child in children:
        found.append(child)
        if depth > 1 and child.is_dir() and not child.is_symlink():
            found += _entries(child, depth - 1)
    return found
