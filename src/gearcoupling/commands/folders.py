"""What a command may write, checked before any work, and its output folder held for it.

A command names every file and folder of its own it writes in its output folder
(:func:`claim`) before its first costly step: each is checked
(:func:`~gearcoupling.io.writable_targets`), the folder is locked against a second command
(:func:`~gearcoupling.io.lock_folder`), and files there that an earlier command made with
other settings are named in one line (they are kept). The command's ``run`` is wrapped by
:func:`holds_folders`, which lets the folders go when it ends and, when it ends normally,
records which settings made the files it wrote.
"""

from __future__ import annotations

import functools
import os
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import GearCouplingError
from ..io import (
    FolderLock,
    earlier_files,
    lock_folder,
    record_files,
    settings_key,
    terminal_text,
    writable_targets,
)

#: names of files made earlier with other settings listed in the note, at most
LISTED = 8


@dataclass(frozen=True)
class _Held:
    lock: FolderLock
    key: str | None
    folders: tuple[str, ...]
    since_ns: int


#: the output folders the running command holds
HELD: dict[Path, _Held] = {}


def claim(out: str | os.PathLike, settings: Any = None, files: Iterable[str] = (),
          folders: Iterable[str] = (), field: str = "-o") -> Path:
    """Hold the output folder ``out`` (made already) for this command and check, before
    any work, every place it writes there: the ``files`` and the ``folders`` of its own
    (names relative to ``out``). ``settings`` (JSON data, e.g. the resolved spec's dict)
    identify what makes the files: files there made with other settings are named in one
    line on stderr. Returns ``out`` as a :class:`~pathlib.Path`."""
    folder = Path(out)
    files, folders = tuple(files), tuple(folders)
    key = None if settings is None else settings_key(settings)
    writable_targets(folder, files, folders, field)  # refused: nothing made in the folder
    if folder not in HELD:
        since = time.time_ns() - 50_000_000  # file times come from a coarser clock
        HELD[folder] = _Held(lock_folder(folder, field), key, folders, since)
    if key is not None:
        _note_earlier(folder, earlier_files(folder, key, [folder / f for f in files]))
    return folder


def _note_earlier(folder: Path, names: list[str]) -> None:
    if not names:
        return
    more = len(names) - LISTED
    listing = ", ".join(names[:LISTED]) + (f" and {more} more" if more > 0 else "")
    print(terminal_text(f"gearcoupling: note: {folder} holds {len(names)} file"
          f"{'' if len(names) == 1 else 's'} made earlier with other settings, left as "
          f"they are: {listing} (give another -o folder to keep runs apart)"),
          file=sys.stderr)


def holds_folders(run: Callable[[Any], int]) -> Callable[[Any], int]:
    """``run`` (a command's) that lets the folders it claimed go when it ends, and records
    which settings made the files it wrote there when it ends without an exception."""
    @functools.wraps(run)
    def holding(args: Any) -> int:
        try:
            status = run(args)
            for folder, held in HELD.items():
                _record(folder, held)
            return status
        finally:
            for held in HELD.values():
                held.lock.release()
            HELD.clear()

    return holding


def _record(folder: Path, held: _Held) -> None:
    """Record the files written into ``folder`` since it was claimed (at its top and in
    its folders of its own); a record that cannot be written is left out (it only serves
    the note of a later command)."""
    if held.key is None:
        return
    made = [p for sub in ("", *held.folders) for p in _new_files(folder / sub, held.since_ns)]
    try:
        record_files(folder, held.key, made)
    except (OSError, GearCouplingError):
        pass


def _new_files(folder: Path, since_ns: int) -> list[Path]:
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return []
    return [Path(e.path) for e in entries if not e.name.startswith(".")
            and e.is_file(follow_symlinks=False)
            and e.stat(follow_symlinks=False).st_mtime_ns >= since_ns]
