"""``gc.run``: the outputs pipeline that ``gearcoupling run`` wraps."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import gearcoupling as gc
from gearcoupling.outputs import STEPS as ALL_STEPS
from gearcoupling.outputs.pipeline import COST, chains

STEPS = ["spec", "sweep", "viewer"]  # one chain each way, quick


@pytest.mark.slow
def test_two_workers_write_the_same_files_as_one(tmp_path):
    """The forked second chain writes byte-identical files; the summary says two workers
    were used and gives every step's time."""
    one = gc.run(gc.load_spec("industrial-m2"), tmp_path / "one", only=STEPS, workers=1)
    code = (f"import gearcoupling as gc; gc.run(gc.load_spec('industrial-m2'), "
            f"{str(tmp_path / 'two')!r}, only={STEPS!r}, workers=2)")
    subprocess.run([sys.executable, "-c", code], check=True)
    two = json.loads((tmp_path / "two" / "run_summary.json").read_text())
    assert one.workers == 1 and two["workers"] == 2
    assert two["files"] == [p.name for p in one.files[:-1]]
    assert set(two["step_seconds"]) == set(STEPS)
    assert all(s > 0 for s in two["step_seconds"].values())
    for name in ("spec.json", "sweep.csv", "sweep_summary.json"):
        assert (tmp_path / "one" / name).read_bytes() == (tmp_path / "two" / name).read_bytes()


def _longer(split: list[list[str]]) -> float:
    return max(sum(COST[k] for k in chain) for chain in split)


@pytest.mark.parametrize("keys", [list(ALL_STEPS), ["spec", "viewer"],
                                  ["sections", "parts", "step", "load"],
                                  ["parts", "step", "check"], ["load"], []])
def test_the_chains_hold_every_step_once_and_no_move_shortens_the_longer(keys):
    """Each step in one chain, in the order of STEPS, parts and step together; moving any
    step (parts and step as one) to the other chain makes the longer chain no cheaper;
    two steps or more make two chains."""
    split = chains(keys)
    assert sorted(k for chain in split for k in chain) == sorted(keys)
    assert all(chain == [k for k in ALL_STEPS if k in chain] for chain in split)
    assert len(split) == min(len(keys), 2) or {"parts", "step"} == set(keys)
    if {"parts", "step"} <= set(keys):
        assert any({"parts", "step"} <= set(chain) for chain in split)
    if len(split) == 2:
        for i, chain in enumerate(split):
            for k in chain:
                moved = {k, "step"} if k == "parts" else {"parts", k} if k == "step" else {k}
                moved &= set(keys)
                other = [[x for x in split[i] if x not in moved], split[1 - i] + sorted(moved)]
                assert _longer(other) >= _longer(split) - 1e-12


def test_steps_are_checked_before_anything_is_written(tmp_path):
    with pytest.raises(gc.ArgumentError, match="stl"):
        gc.run(gc.load_spec("industrial-m2"), tmp_path / "x", only=["spec", "stl"])
    with pytest.raises(gc.ArgumentError, match="workers"):
        gc.run(gc.load_spec("industrial-m2"), tmp_path / "x", workers=3)
    assert not (tmp_path / "x").exists()


def test_the_cli_forks_beside_its_signal_watcher(tmp_path):
    """``gearcoupling run`` uses two workers on two cores: the CLI's signal-watching thread
    (which only waits on a socket) does not stop the fork (it did: one worker)."""
    code = ("import sys; "
            "from gearcoupling.cli import main; "
            f"sys.exit(main(['run', 'renzo-1967', '--only', 'spec,viewer', '--workers', '2', "
            f"'-o', {str(tmp_path)!r}]))")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True)
    assert json.loads((tmp_path / "run_summary.json").read_text())["workers"] == 2
