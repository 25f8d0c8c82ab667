"""Caches are used only when their key and checksum match (docs/safety.md, Caches).

The FE tooth table: a valid entry, written by the project's writer from the stored table
of industrial-m2 (``tests/golden/fe_table_industrial-m2.json``: ``tooth_compliance_table``
at the default settings, CalculiX 2.20, table version 5), is read back without the solver;
every tampered entry is not used. The solver is made unreachable for these
(``GEARCOUPLING_CCX`` names no program), so "not used" shows as the ``BackendError`` of
the recomputation that would follow, after one line on stderr saying why. One slow test
recomputes a tampered entry with the real solver on the smallest mesh that works.

numba's compiled kernels: the clearance and contact kernels use the verified cache;
seeded bit flips in the cache files of a small kernel compiled the same way, each loaded
by a fresh interpreter, recompile with the same result and one line on stderr (slow).
"""

from __future__ import annotations

import json
import os
import random
import shutil
import stat
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.errors import ArgumentError, BackendError
from gearcoupling.fea import table_entry, tooth_compliance_table
from gearcoupling.io.cache import CacheMiss, read_regular, seal, unseal, write_entry

GOLDEN = Path(__file__).parent / "golden" / "fe_table_industrial-m2.json"
SPEC = "industrial-m2"


@pytest.fixture
def no_solver(monkeypatch):
    """The FE solver made unreachable: a table that is not read from the cache fails with
    a BackendError before any meshing."""
    monkeypatch.setenv("GEARCOUPLING_CCX", "no-such-ccx-for-this-test")


@pytest.fixture
def entry(tmp_path, no_solver):
    """A valid cache entry of industrial-m2's default table in ``tmp_path`` (written by the
    project's writer): ``(path, key, data)``."""
    data = json.loads(GOLDEN.read_text())
    path, key = table_entry(gc.load_spec(SPEC), cache=tmp_path)
    write_entry(path, key, data)
    return path, key, data


def _read_json(path):
    return json.loads(path.read_text())


def _rewrite(path, change):
    """``change(entry)`` on the entry's JSON, written back as it is (checksum unchanged)."""
    e = _read_json(path)
    change(e)
    path.write_text(json.dumps(e))


def _resealed(path, key, change):
    """``change(data)`` on the entry's data, written by the project's writer (a matching
    checksum: the table itself has to be refused)."""
    data = _read_json(path)["data"]
    change(data)
    write_entry(path, key, data)


def _other_settings(path, key):
    """The entry of another setting (nz = 4) copied over this one's file."""
    other, other_key = table_entry(gc.load_spec(SPEC), nz=4, cache=path.parent)
    write_entry(other, other_key, _read_json(path)["data"])
    shutil.copyfile(other, path)


def _times(name, factor):
    def change(data):
        data[name] = (np.asarray(data[name]) * factor).tolist()
    return change


def _fifo(path, key):
    path.unlink()
    os.mkfifo(path)


def _folder(path, key):
    path.unlink()
    path.mkdir()


# (tampering, words the one line on stderr holds)
TAMPERED = {
    "entry of other settings": (_other_settings, "another key ('spec_hash' is"),
    "changed spec_hash": (lambda p, k: _rewrite(p, lambda e: e["key"].update(
        spec_hash="0123456789abcdef")), "another key ('spec_hash' is '0123456789abcdef'"),
    "changed package version": (lambda p, k: _rewrite(p, lambda e: e["key"].update(
        package_version="0.0.1")), "'package_version' is '0.0.1'"),
    "hub compliances x10": (lambda p, k: _rewrite(p, lambda e: _times(
        "hub_mm_per_N", 10)(e["data"])), "do not match its checksum"),
    "compliances negated": (lambda p, k: _rewrite(p, lambda e: _times(
        "sleeve_mm_per_N", -1)(e["data"])), "do not match its checksum"),
    "negated with a matching checksum": (lambda p, k: _resealed(p, k, _times(
        "hub_mm_per_N", -1)), "hub_mm_per_N"),
    "an infinite compliance with a matching checksum": (lambda p, k: _resealed(
        p, k, lambda d: d["sleeve_mm_per_N"][0].__setitem__(0, float("inf"))),
        "sleeve_mm_per_N"),
    "far field below zero with a matching checksum": (lambda p, k: _resealed(
        p, k, _times("near_field_mm_per_N", 100)), "near_field_mm_per_N"),
    "wrong shape with a matching checksum": (lambda p, k: _resealed(
        p, k, lambda d: d["hub_mm_per_N"].pop()), "hub_mm_per_N"),
    "truncated": (lambda p, k: p.write_bytes(p.read_bytes()[:len(p.read_bytes()) // 2]),
                  "not JSON"),
    "empty": (lambda p, k: p.write_text(""), "not JSON"),
    "null": (lambda p, k: p.write_text("null"), "not a gearcoupling cache entry"),
    "the table alone (the old format)": (lambda p, k: p.write_text(
        json.dumps(_read_json(p)["data"])), "not a gearcoupling cache entry"),
    "a named pipe": (_fifo, "a named pipe (FIFO), not a file"),
    "a folder": (_folder, "a folder, not a file"),
}


def test_a_valid_entry_is_used_as_written_without_the_solver(entry, capsys):
    path, _, data = entry
    t = tooth_compliance_table(SPEC, cache=path.parent)
    for name in ("z_mm", "r_mm", "hub_mm_per_N", "sleeve_mm_per_N", "near_field_mm_per_N",
                 "root_stress_MPa_per_N"):
        np.testing.assert_array_equal(getattr(t, name), np.asarray(data[name]))
    assert capsys.readouterr().err == ""


def _unblock_later(path: Path, seconds: float) -> threading.Timer:
    """After ``seconds``, open the pipe ``path`` for writing and close it: a reader blocked
    in ``open`` gets end-of-file, so a hang fails the test instead of stopping the suite."""
    def release():
        try:
            os.close(os.open(path, os.O_WRONLY | os.O_NONBLOCK))
        except OSError:
            pass  # no reader waiting
    timer = threading.Timer(seconds, release)
    timer.start()
    return timer


@pytest.mark.parametrize("tamper", list(TAMPERED))
def test_a_tampered_entry_is_not_used_and_one_line_says_why(tamper, entry, capsys):
    """Every tampering makes the entry a miss: the table is computed again (here: the
    unreachable solver's BackendError) after exactly one line on stderr naming the entry and
    the reason; never the tampered numbers, a traceback or a hang (a named pipe is not
    opened for a blocking read)."""
    path, key, _ = entry
    change, words = TAMPERED[tamper]
    change(path, key)
    capsys.readouterr()
    timer = _unblock_later(path, 20.0) if stat.S_ISFIFO(os.stat(path).st_mode) else None
    try:
        with pytest.raises(BackendError, match="no-such-ccx-for-this-test"):
            tooth_compliance_table(SPEC, cache=path.parent)
    finally:
        if timer is not None:
            timer.cancel()
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"gearcoupling: cache entry {str(path)!r} not used: ")
    assert words in lines[0], lines[0]
    assert lines[0].endswith("computing the FE tooth table of 'industrial-m2' again" + (
        ", not stored there" if tamper in ("a named pipe", "a folder") else ""))


def test_the_load_models_read_the_entry_under_gearcoupling_cache(tmp_path, monkeypatch,
                                                                 no_solver, capsys):
    """``[load] stiffness = "fe"`` reads the table from ``$GEARCOUPLING_CACHE/fea``: the
    valid entry gives the stored table's springs, the same entry with the hub compliances
    x10 is refused (on the old reader it halved the largest tooth load of ``load
    industrial-m2``, exit 0)."""
    from gearcoupling.loading.springs import tooth_compliance

    monkeypatch.setenv("GEARCOUPLING_CACHE", str(tmp_path))
    spec = gc.load_spec(SPEC, **{"load.stiffness": "fe"})
    path, key = table_entry(spec)
    assert path.parent == tmp_path / "fea"
    data = json.loads(GOLDEN.read_text())
    write_entry(path, key, data)
    springs = tooth_compliance(spec)
    z, r = np.asarray(data["z_mm"]), np.asarray(data["r_mm"])
    far = (np.asarray(data["hub_mm_per_N"]) + np.asarray(data["sleeve_mm_per_N"])
           - np.sum(data["near_field_mm_per_N"], axis=0))
    np.testing.assert_allclose(springs.pair_compliance_mm_per_N(z[:3, None], r[None, :]),
                               far[:3], rtol=1e-9)  # rows within the held part of the face
    _rewrite(path, lambda e: _times("hub_mm_per_N", 10)(e["data"]))
    with pytest.raises(BackendError):
        tooth_compliance(spec)
    assert "do not match its checksum" in capsys.readouterr().err


def test_gearcoupling_cache_naming_a_file_is_refused_before_any_work(tmp_path, monkeypatch,
                                                                     no_solver):
    """Checked before the FE run like ``cache=`` (it failed after a 62 s run, throwing the
    table away): an ArgumentError naming the variable and its value, not the solver's."""
    a_file = tmp_path / "a_file"
    a_file.write_text("not a folder")
    monkeypatch.setenv("GEARCOUPLING_CACHE", str(a_file))
    with pytest.raises(ArgumentError, match=r"GEARCOUPLING_CACHE = '.*a_file': a file, not "
                                            r"a folder"):
        tooth_compliance_table(SPEC)
    assert a_file.read_text() == "not a folder"


def test_stiffness_cli_refuses_gearcoupling_cache_naming_a_file_before_work(tmp_path,
                                                                           monkeypatch,
                                                                           no_solver, capsys):
    a_file = tmp_path / "a_file"
    a_file.write_text("not a folder")
    monkeypatch.setenv("GEARCOUPLING_CACHE", str(a_file))
    assert main(["stiffness", SPEC, "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "GEARCOUPLING_CACHE" in err[0] and "not a folder" in err[0], err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("tamper", ["flip", "tag", "truncate", "header"])
def test_sealed_bytes_are_refused_when_anything_changed(tamper):
    """Every single-bit flip anywhere in sealed bytes (header, tag, checksum or payload),
    another tag, a cut and a lost header are refused; the untouched bytes give the
    payload back."""
    payload = bytes(random.Random(1).randrange(256) for _ in range(64))
    raw = seal(payload, "key abc")
    assert unseal(raw, "key abc") == payload
    if tamper == "flip":
        for i in range(len(raw)):
            for b in range(8):
                bad = bytearray(raw)
                bad[i] ^= 1 << b
                with pytest.raises(CacheMiss):
                    unseal(bytes(bad), "key abc")
        return
    bad_raw, tag = {"tag": (raw, "key abd"), "truncate": (raw[:-1], "key abc"),
                    "header": (raw[5:], "key abc")}[tamper]
    with pytest.raises(CacheMiss):
        unseal(bad_raw, tag)


def test_a_named_pipe_is_refused_without_blocking(tmp_path):
    pipe = tmp_path / "pipe"
    os.mkfifo(pipe)
    timer = _unblock_later(pipe, 20.0)
    try:
        with pytest.raises(CacheMiss, match="a named pipe"):
            read_regular(pipe)
    finally:
        timer.cancel()
    assert read_regular(tmp_path / "missing") is None


# numba -----------------------------------------------------------------------------

KERNEL_MODULE = """
import math
from gearcoupling.io.numba_cache import njit

@njit(nogil=True, error_model="numpy", fastmath={"contract"})
def kernel(x):
    s = 0.0
    for v in x:
        s += math.sqrt(v) * 1.5 + math.sin(v)
    return s
"""

KERNEL_RUN = """
import json
import numpy as np
import kernel_module

x = np.linspace(0.0, 10.0, 101)
value = kernel_module.kernel(x)
stats = kernel_module.kernel.stats
print(json.dumps({"value": value.hex(), "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values())}))
"""


def _kernel_env(cache: Path, module_dir: Path) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache),
               PYTHONPATH=os.pathsep.join([str(module_dir), *sys.path]))
    env.pop("GEARCOUPLING_NUMBA", None)
    return env


def _kernel_run(cache: Path, module_dir: Path, timeout_s: float = 120.0
                ) -> tuple[dict, list[str]]:
    """A small kernel compiled with the project's cached ``njit``, called in a fresh
    interpreter with numba's cache in ``cache``: its result and cache figures, and its
    stderr lines (asserting a clean exit: no traceback, no signal)."""
    out = subprocess.run([sys.executable, "-c", KERNEL_RUN], capture_output=True,
                         text=True, timeout=timeout_s, env=_kernel_env(cache, module_dir))
    assert out.returncode == 0, f"exit {out.returncode}: {out.stderr[-2000:]}"
    return json.loads(out.stdout), out.stderr.splitlines()


@pytest.fixture(scope="module")
def numba_cache(tmp_path_factory):
    """A kernel module, its numba cache compiled into a fresh folder, and the figures of
    that first run: ``(cache, module folder, figures)``."""
    module_dir = tmp_path_factory.mktemp("kernel")
    (module_dir / "kernel_module.py").write_text(KERNEL_MODULE)
    cache = tmp_path_factory.mktemp("numba-cache")
    first, err = _kernel_run(cache, module_dir)
    assert first["misses"] == 1 and err == [], err
    return cache, module_dir, first


def test_the_compiled_kernels_use_the_verified_cache():
    """Every cached function of the clearance and contact kernels goes through the sealed
    cache (numba's own cache loads a damaged file)."""
    numba = pytest.importorskip("numba")
    from numba.core.caching import NullCache

    from gearcoupling.clearance import _compiled
    from gearcoupling.io.numba_cache import _SealedCache
    from gearcoupling.loading.kernels import _contact_compiled

    cached = {}
    for module in (_compiled, _contact_compiled):
        for name, obj in vars(module).items():
            if isinstance(obj, numba.core.registry.CPUDispatcher) and \
                    not isinstance(obj._cache, NullCache):
                cached[f"{module.__name__}.{name}"] = type(obj._cache)
    assert "gearcoupling.clearance._compiled.minimise_rows" in cached
    assert "gearcoupling.loading.kernels._contact_compiled.per_grid_cg" in cached
    assert set(cached.values()) == {_SealedCache}, cached


@pytest.mark.slow
def test_bit_flips_in_numba_cache_files_recompile_with_the_same_result(numba_cache,
                                                                      tmp_path):
    """Eight seeded single-bit flips, each in a copy of the cache (index or data file)
    loaded by a fresh interpreter (numba's own cache gave tracebacks, segfaults and an
    LLVM error on such flips of the contact kernel, or silently ran the flipped code):
    each run exits cleanly with the same result, recompiled (a cache miss) after one line
    on stderr naming the file; the cache it writes is then used as it is (a hit, no
    line)."""
    cache, module_dir, first = numba_cache
    files = sorted(p for p in cache.rglob("*") if p.is_file())
    assert {p.suffix for p in files} == {".nbi", ".nbc"}
    rng = random.Random(38)
    for k in range(8):
        copy = tmp_path / f"flip{k}"
        shutil.copytree(cache, copy)
        target = copy / rng.choice(files).relative_to(cache)
        data = bytearray(target.read_bytes())
        data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        target.write_bytes(bytes(data))
        got, err = _kernel_run(copy, module_dir)
        assert got["value"] == first["value"] and got["misses"] == 1, (k, target.name, got)
        assert len(err) == 1 and f"{target.name}' not used: " in err[0] \
            and err[0].endswith("compiling again"), (k, err)
    again, err = _kernel_run(copy, module_dir)
    assert (again["value"], again["hits"], again["misses"], err) == (first["value"], 1, 0, [])


@pytest.mark.slow
def test_two_processes_compiling_at_once_leave_a_cache_both_can_use(numba_cache, tmp_path):
    """Two interpreters compile the kernel into the same empty cache folder at the same
    time (each writes whole files: a temporary renamed into place); a third one then loads
    it from the cache without a line, with the same result."""
    _, module_dir, first = numba_cache
    runs = [subprocess.Popen([sys.executable, "-c", KERNEL_RUN], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True,
                             env=_kernel_env(tmp_path, module_dir)) for _ in range(2)]
    for run in runs:
        out, err = run.communicate(timeout=120)
        assert run.returncode == 0 and err == "", err
        assert json.loads(out)["value"] == first["value"]
    third, err = _kernel_run(tmp_path, module_dir)
    assert (third["value"], third["hits"], third["misses"], err) == (first["value"], 1, 0, [])


# the real solver ---------------------------------------------------------------------

@pytest.mark.slow
@pytest.mark.needs_fea
def test_a_tampered_entry_is_recomputed_by_the_solver_and_stored_again(tmp_path, capsys):
    """On the smallest mesh that gives a valid table (1 mm, 3-tooth sector, 2 x 2 load
    points): an entry of these settings with its hub compliances x10 (the stored default
    table's numbers) is refused, the solver computes the table (its mesh stiffness within
    a factor 1.5 of the default mesh's, where the tampered entry's is 5 times lower) and
    stores it, and that entry is then used as stored, without a line."""
    settings = {"size_mm": 1.0, "sector": 3, "nz": 2, "nr": 2}
    path, key = table_entry(gc.load_spec(SPEC), cache=tmp_path, **settings)
    golden = gc.fea.ComplianceTable.from_dict(json.loads(GOLDEN.read_text()))
    write_entry(path, key, golden.to_dict())
    _rewrite(path, lambda e: _times("hub_mm_per_N", 10)(e["data"]))
    table = tooth_compliance_table(SPEC, cache=tmp_path, **settings)
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "do not match its checksum" in err[0], err
    ratio = table.mesh_stiffness_N_per_mm / golden.mesh_stiffness_N_per_mm
    assert 1 / 1.5 < ratio < 1.5, ratio
    again = tooth_compliance_table(SPEC, cache=tmp_path, **settings)
    np.testing.assert_array_equal(again.hub_mm_per_N, table.hub_mm_per_N)
    assert capsys.readouterr().err == ""
