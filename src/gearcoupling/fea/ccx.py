"""Run CalculiX ``ccx`` on a deck and read its ``.dat`` printout."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import BackendError
from ..forked import held_signals
from ..io import move_into, temporary_folder
from .backends import ccx_path


@dataclass(frozen=True)
class CcxResult:
    """Printout of a ccx run: ``blocks`` in file order, each ``(kind, set, time, rows)``
    with ``kind`` e.g. ``"displacements"`` or ``"stresses"`` and ``rows (k, c)`` float
    (first column the node or element number)."""

    job: Path
    blocks: list[tuple[str, str, float, NDArray[np.float64]]]
    seconds: float

    def get(self, kind: str, name: str) -> list[NDArray[np.float64]]:
        """Rows of every block of a kind and set, one per step, in order."""
        return [rows for k, s, _, rows in self.blocks if k == kind and s == name.upper()]

    def last(self, kind: str) -> NDArray[np.float64] | None:
        """Rows of the last block whose kind starts with ``kind`` (``None`` if none)."""
        found = [rows for k, _, _, rows in self.blocks if k.startswith(kind)]
        return found[-1] if found else None


@contextmanager
def solver_dir(workdir=None) -> Iterator[Path]:
    """The folder of a solver run: ``workdir`` (kept), or a new temporary folder that is
    removed after a successful run and kept (with the deck and log) after a failure."""
    if workdir is not None:
        path = Path(workdir)
        path.mkdir(parents=True, exist_ok=True)
        yield path
        return
    path = Path(tempfile.mkdtemp(prefix="gearcoupling-ccx-"))
    yield path
    shutil.rmtree(path, ignore_errors=True)


RUNNING: set[subprocess.Popen] = set()
"""The ccx processes :func:`run_ccx` is waiting on, in any thread."""
_LOCK = threading.Lock()
_STOPPED = threading.Event()  # set by stop_solvers: no new solver starts until allowed


def stop_solvers() -> int:
    """Kill every ccx process this process is running, and refuse new ones until
    :func:`allow_solvers` (an interruption: the threads that wait on them then fail at
    once instead of holding the process, or starting the next solve, until they finish);
    returns how many were killed."""
    with _LOCK:
        _STOPPED.set()
        running = list(RUNNING)
    for proc in running:
        proc.kill()
    return len(running)


def allow_solvers() -> None:
    """Let :func:`run_ccx` start solvers again after :func:`stop_solvers`."""
    _STOPPED.clear()


def _stopped() -> BackendError:
    return BackendError("ccx not run: the command was interrupted (stop_solvers)")


@contextmanager
def _started(args: list[str], cwd: Path, env: dict[str, str]) -> Iterator[subprocess.Popen]:
    """``Popen(args)`` registered in :data:`RUNNING` while the block runs (and killed at
    once if the solvers are stopped meanwhile). A SIGINT or SIGTERM while it starts is held
    until it is registered (:func:`~gearcoupling.forked.held_signals`; noted, not blocked:
    ccx would inherit the mask) and then kills it: raised inside ``Popen``, it would leave
    the solver running unknown to anyone."""
    proc = None
    try:
        with held_signals(block=False):
            proc = subprocess.Popen(args, cwd=cwd, stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True, env=env)
            with _LOCK:
                RUNNING.add(proc)
                if _STOPPED.is_set():  # stopped while it started: it goes at once
                    proc.kill()
    except BaseException:  # a signal held while it started
        if proc is not None:
            proc.kill()
            proc.communicate()
            with _LOCK:
                RUNNING.discard(proc)
        raise
    try:
        with proc:
            yield proc
    finally:
        with _LOCK:
            RUNNING.discard(proc)


def run_ccx(deck: str, workdir: str | Path, job: str = "job", *,
            timeout_s: float = 3600.0, threads: int = 2) -> CcxResult:
    """Write ``<workdir>/<job>.inp`` and run ``ccx`` on it.

    ``ccx`` runs in a private folder made for it in ``workdir``
    (:func:`~gearcoupling.io.temporary_folder`); when it has ended, the deck, its output
    files and ``<job>.log`` (its printout) are moved into ``workdir``, each replacing what
    is there as an atomic write does (a symbolic link there is replaced, not written
    through). A run that is interrupted or stopped (:func:`stop_solvers`) moves nothing:
    no partial solver file is left. A failed run raises :class:`BackendError` naming the
    log and the deck; one that timed out keeps only those two.
    """
    exe = ccx_path()
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads),
               CCX_NPROC_EQUATION_SOLVER=str(threads))
    if _STOPPED.is_set():
        raise _stopped()
    with temporary_folder(work) as scratch:
        (scratch / f"{job}.inp").write_text(deck)
        t0 = time.perf_counter()
        returncode, stdout, timed_out = _solve([exe, "-i", job], scratch, env, timeout_s)
        if _STOPPED.is_set():
            raise _stopped()
        seconds = time.perf_counter() - t0
        (scratch / f"{job}.log").write_text(stdout if not timed_out else
                                            f"{stdout}\ntimed out after {timeout_s} s\n")
        kept = [f"{job}.inp", f"{job}.log"] if timed_out else sorted(
            p.name for p in scratch.iterdir() if p.is_file() and not p.is_symlink())
        for name in kept:
            move_into(scratch / name, work / name)
    log = work / f"{job}.log"
    if timed_out:
        raise BackendError(f"ccx timed out after {timeout_s:.0f} s; its log is {log}")
    dat = work / f"{job}.dat"
    if returncode != 0 or "*ERROR" in stdout or f"{job}.dat" not in kept:
        first = next((ln.strip() for ln in stdout.splitlines() if "*ERROR" in ln), "")
        raise BackendError(f"ccx failed (exit {returncode}) {first}; its log is {log} "
                           f"and the deck {work / f'{job}.inp'}")
    return CcxResult(work / job, parse_dat(dat.read_text()), seconds)


def _solve(args: list[str], cwd: Path, env: dict[str, str],
           timeout_s: float) -> tuple[int, str, bool]:
    """Run the solver ``args`` in ``cwd``: its exit status, its printout (stdout, then
    stderr) and whether it was killed for running past ``timeout_s``. An interruption
    kills it and propagates."""
    with _started(args, cwd, env) as proc:
        try:
            stdout, stderr = proc.communicate(timeout=timeout_s)
            timed_out = False
        except subprocess.TimeoutExpired:
            proc.kill()
            stdout, stderr = proc.communicate()
            timed_out = True
        except BaseException:  # an interruption: the solver goes with the caller
            proc.kill()
            raise
    return proc.returncode, f"{stdout}\n{stderr}", timed_out


_HEADER = re.compile(r"^\s*([a-z][\w ]*?)\s*\(.*\)\s*for (.*?)\s+and time\s+(\S+)", re.I)


def _set_name(text: str) -> str:
    """``set X`` -> ``X``; ``slave set A and master set B`` -> ``A``; else the text."""
    m = re.search(r"set\s+(\S+)", text, re.I)
    return (m.group(1) if m else text).upper()


_STATS = re.compile(r"^\s*statistics for slave set\s+([^,\s]+).*and time\s+(\S+)", re.I)


def parse_dat(text: str) -> list[tuple[str, str, float, NDArray[np.float64]]]:
    """Blocks of a ccx ``.dat`` file (see :class:`CcxResult`); rows of unequal length
    (contact statistics) are padded with NaN."""
    blocks: list[tuple[str, str, float, NDArray[np.float64]]] = []
    current: tuple[str, str, float] | None = None
    rows: list[list[float]] = []

    def close() -> None:
        if current is not None:
            width = max((len(r) for r in rows), default=0)
            arr = np.full((len(rows), width), np.nan)
            for i, r in enumerate(rows):
                arr[i, :len(r)] = r
            blocks.append((*current, arr))

    for line in text.splitlines():
        head, stats = _HEADER.match(line), _STATS.match(line)
        if head or stats:
            close()
            if stats:
                current = ("statistics", stats.group(1).upper(), float(stats.group(2)))
            elif head:
                current = (head.group(1).strip().lower(), _set_name(head.group(2)),
                           float(head.group(3)))
            rows = []
            continue
        parts = line.split()
        if current is not None and parts:
            try:
                rows.append([float(x) for x in parts])
            except ValueError:
                continue
    close()
    return blocks
