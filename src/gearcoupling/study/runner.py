"""Run a study on dask.distributed: chunks of samples per task, one Parquet part per
finished chunk (written atomically as results arrive), merged into ``study.parquet``.

Resuming: the output folder holds ``study_manifest.json`` (the study's digest) and
``parts/chunk-NNNNNN.parquet``; a rerun skips the chunks whose part exists and says so.
A lost worker's tasks are retried (``retries``) by the scheduler; finished parts stay.
"""

from __future__ import annotations

import json
import logging
import os
import re
import signal
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..arguments import count, flag, real
from ..errors import ArgumentError, BackendError
from ..forked import held_signals
from ..interrupts import reraise as reraise_interrupt
from ..io import atomic_path, output_folder, remove_stale_temporaries, write_json
from ..tables import import_pandas
from .evaluate import evaluate_chunk
from .file import OUTPUTS, TOLERANCE_OUTPUTS, Study, sample_count, samples
from .peer import probe_scheduler

CONNECT_TIMEOUT_S = 10.0
RETRIES = 3
TABLE = "study.parquet"


@dataclass(frozen=True)
class StudyRun:
    """Where a study's table is and what this run did."""

    table: Path
    rows: int
    chunks: int
    skipped_chunks: int
    failed_rows: int

    def to_dataframe(self):
        """The study table (``study.parquet``) as a pandas DataFrame, one row per sample
        (the ``pandas`` extra; pyarrow converts the columns)."""
        import_pandas()
        _, pq = pyarrow_modules()
        return pq.read_table(self.table).to_pandas()


def pyarrow_modules():
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError as err:  # pragma: no cover - depends on the install
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("studies need pyarrow: pip install 'gearcoupling[study]'") from err
    return pa, pq


def _distributed():
    try:
        import distributed
    except ImportError as err:  # pragma: no cover - depends on the install
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("studies need dask.distributed: pip install "
                           "'gearcoupling[study]'") from err
    return distributed


def columns(study: Study) -> list[str]:
    """Column order of the table: sample, inputs, conditions, outputs, provenance."""
    inputs = [q.key for q in study.parameters if q.key not in ("misalignment_deg", "torque_Nm")]
    outs = [k for k in (TOLERANCE_OUTPUTS if study.tolerances else OUTPUTS)
            if k in study.outputs]
    draw = ["draw"] if study.tolerances else []
    return ["sample", "chunk", *inputs, *draw, "misalignment_deg", "torque_Nm", *outs,
            "spec_hash", "version", "error"]


def chunks(study: Study) -> list[list[tuple[int, dict[str, Any]]]]:
    """Samples grouped ``study.chunk`` per task, each sample with its index."""
    items = list(enumerate(samples(study)))
    return [items[k:k + study.chunk] for k in range(0, len(items), study.chunk)]


def _part_path(out: Path, chunk: int) -> Path:
    return out / "parts" / f"chunk-{chunk:06d}.parquet"


def _write_part(rows: list[dict[str, Any]], names: list[str], path: Path) -> None:
    pa, pq = pyarrow_modules()
    table = pa.Table.from_pylist([{k: r.get(k) for k in names} for r in rows])
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp)


def _check_manifest(study: Study, out: Path, fresh: bool) -> None:
    """Refuse a folder holding the parts of another study (unless ``fresh``)."""
    path = out / "study_manifest.json"
    if path.is_file() and not fresh:
        try:
            old = json.loads(path.read_text())
        except (OSError, ValueError):
            old = {}
        if not isinstance(old, dict) or old.get("digest") != study.digest():
            raise ArgumentError("output", str(out), "holds the parts of another study (its file "
                            "changed); use a new --output folder or --fresh")


def _manifest(study: Study, out: Path, fresh: bool) -> None:
    path = out / "study_manifest.json"
    data = {"study": study.name, "source": study.source, "digest": study.digest(),
            "samples": sample_count(study), "chunk": study.chunk}
    if (out / "parts").is_dir():  # temporaries of a killed run; with --fresh every part
        remove_stale_temporaries(out / "parts")
        for part in (out / "parts").glob("chunk-[0-9]*.parquet") if fresh else ():
            part.unlink()
    write_json(path, data)


MAX_WORKERS = 256
_ADDRESS = re.compile(r"(?:tcp://)?(?:\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9._-]+):[0-9]{1,5}")


def scheduler_address(text: object, field: str = "scheduler") -> str:
    """A dask scheduler address ``tcp://HOST:PORT`` (or ``HOST:PORT``); ``tls://`` is
    refused: it needs certificates, which a study does not take."""
    if not (isinstance(text, str) and _ADDRESS.fullmatch(text)
            and 1 <= int(text.rsplit(":", 1)[1]) <= 65535):
        raise ArgumentError(field, text, "a dask scheduler address tcp://HOST:PORT, "
                            "e.g. tcp://127.0.0.1:8786 (tls:// needs certificates, which a "
                            "study does not take: reach a TLS scheduler through a tunnel)")
    return text


def connect(scheduler: str | None, workers: int | None, timeout_s: float = CONNECT_TIMEOUT_S):
    """A dask Client: to ``scheduler`` (``tcp://HOST:PORT``; a peer that is no dask
    scheduler is refused within ``timeout_s``, :func:`.peer.probe_scheduler`) or a new
    LocalCluster with ``workers`` single-threaded worker processes (default: one per
    core)."""
    if scheduler is not None:
        probe_scheduler(scheduler, timeout_s)  # a dask scheduler, else refused in time
    distributed = _distributed()
    if scheduler is not None:
        try:
            return distributed.Client(scheduler, timeout=timeout_s)
        except (OSError, TimeoutError, ValueError) as err:
            raise BackendError(f"cannot reach the dask scheduler at {scheduler} within "
                               f"{timeout_s:g} s ({type(err).__name__}); start one with "
                               "'dask scheduler' or drop --scheduler") from err
    n = workers or os.cpu_count() or 1
    # ":0": the scheduler's HTTP server on a free port (8787 may belong to another cluster);
    # critical logs only: a failed sample is a row's "error" and a lost worker an exception
    # here, while the cluster's teardown after an interruption logs warnings and errors
    # (tasks cancelled, heartbeats to a closed scheduler) that are not the user's business
    return _local_client(distributed, n)


def _local_client(distributed, workers: int):
    """A Client of a new LocalCluster of ``workers`` processes, started with SIGINT
    blocked in this thread: the threads that start the workers are made here and the
    workers inherit the mask, so Ctrl-C in a terminal, which reaches the whole process
    group, stops the study through this process, not each worker on its own.

    A SIGINT or SIGTERM meanwhile is noted (:func:`~gearcoupling.forked.held_signals`)
    and raised once the cluster exists, which is then closed (as on any failure before
    the Client exists). Before, SIGINT was ignored here during the start: a Ctrl-C then
    was lost, and a SIGTERM stopped the start half way. multiprocessing's resource
    tracker is started first: starting it unblocks SIGINT in the thread that does (the
    loop thread, whose mask every worker would then inherit)."""
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()
    cluster = None
    try:
        with held_signals(block={signal.SIGINT}):
            cluster = distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                               processes=True, dashboard_address=":0",
                                               silence_logs=logging.CRITICAL)
        return distributed.Client(cluster)
    except BaseException:
        if cluster is not None:
            cluster.close()
        raise


def _close(client, own_cluster: bool) -> None:
    cluster = client.cluster if own_cluster else None
    client.close()
    if cluster is not None:
        cluster.close()


def run_study(study: Study, out: str | Path, *, scheduler: str | None = None,
              workers: int | None = None, fresh: bool = False, client=None,
              connect_timeout_s: float = CONNECT_TIMEOUT_S,
              progress: Callable[[int, int], None] | None = None) -> StudyRun:
    """Evaluate every sample of ``study`` on dask and write ``<out>/study.parquet``.

    ``progress(done, total)`` counts chunks, those finished by an earlier run first (called
    once with them before any new one). ``client`` reuses a dask Client.
    """
    if not isinstance(study, Study):
        raise ArgumentError("study", study, "a Study (gearcoupling.load_study)")
    output_folder(out, "out", create=False)
    if workers is not None:
        count(workers, "workers", 1, MAX_WORKERS)
    if scheduler is not None:
        scheduler_address(scheduler)
    real(connect_timeout_s, "connect_timeout_s", 0.0, 3600.0, open_lo=True, unit="s")
    flag(fresh, "fresh")
    out = output_folder(out, "out")
    _check_manifest(study, out, fresh)
    names = columns(study)
    groups = chunks(study)
    todo = [c for c in range(len(groups)) if fresh or not _part_path(out, c).is_file()]
    skipped = len(groups) - len(todo)
    own = client is None and bool(todo)
    if own:  # before anything is written: a scheduler that cannot be reached leaves nothing
        client = connect(scheduler, workers, connect_timeout_s)
    try:
        _manifest(study, out, fresh)
        if progress is not None:
            progress(skipped, len(groups))
        if todo:
            _compute(client, study, groups, todo, out, names, progress, skipped)
    finally:
        if own:
            _close(client, scheduler is None)
    return _merge(out, names, len(groups), skipped)


def _compute(client, study, groups, todo, out, names, progress, done: int) -> None:
    distributed = _distributed()
    payload = study.payload()
    futures = {client.submit(evaluate_chunk, payload, c, groups[c], key=f"study-{study.digest()}"
                             f"-{c}", retries=RETRIES, pure=False): c for c in todo}
    for fut in distributed.as_completed(futures):
        c = futures[fut]
        _write_part(fut.result(), names, _part_path(out, c))
        fut.release()
        done += 1
        if progress is not None:
            progress(done, len(groups))


def _merge(out: Path, names: list[str], n_chunks: int, skipped: int) -> StudyRun:
    pa, pq = pyarrow_modules()
    parts = [_part_path(out, c) for c in range(n_chunks)]
    missing = [p.name for p in parts if not p.is_file()]
    if missing:
        raise BackendError(f"study incomplete: {len(missing)} chunk(s) missing ({missing[0]}...)"
                           "; rerun to resume")
    tables = [pq.read_table(p) for p in parts]
    table = pa.concat_tables(tables, promote_options="default").select(names)
    table = table.sort_by("sample")
    with atomic_path(out / TABLE) as tmp:
        pq.write_table(table, tmp)
    failed = int(table.column("error").is_valid().to_numpy(zero_copy_only=False).sum())
    return StudyRun(out / TABLE, table.num_rows, n_chunks, skipped, failed)


def read_table(path: str | Path):
    """A study table as a list of row dicts (pyarrow imported lazily)."""
    _, pq = pyarrow_modules()
    return pq.read_table(path).to_pylist()
