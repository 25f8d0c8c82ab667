"""The stages that ``gc.run`` and ``gc.report`` share (gearcoupling.outputs.stages)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.outputs import q_points, stages, study_misalignments, turn_sweep


def test_a_stage_is_computed_once_per_spec_and_arguments():
    spec = gc.load_spec("renzo-1967")
    stages.forget()
    first = turn_sweep(spec, 1.0, 12)
    again = turn_sweep(gc.load_spec("renzo-1967"), 1.0, 12)  # an equal spec, made anew
    assert again is first
    other = turn_sweep(spec.replace(**{"load.friction": 0.05}), 1.0, 12)
    assert other is not first  # another spec: computed for it
    fresh = gc.sweep(spec, 1.0, np.arange(12) * 30.0)
    assert np.array_equal(first.normal_clearance_mm, fresh.normal_clearance_mm)


def test_q_points_are_the_linear_capacity_at_the_study_grid():
    """Each q point is the linear model's tooth-load capacity over the aligned capacity
    (:func:`gearcoupling.capacity` at the same misalignment, 25 rotations per pitch), at
    the study grid; the report's q graph draws the same points (one stage)."""
    spec = gc.load_spec("renzo-1967")
    pts = q_points(spec, spec.design_misalignment_deg)
    assert len(pts) == 7
    assert [p.misalignment_deg for p in pts] == list(study_misalignments(spec))
    for p in pts[::3]:
        c = gc.capacity(spec, p.misalignment_deg, model="linear")
        assert p.q_linear == pytest.approx(c.criteria_Nm["tooth_load"] / c.aligned_capacity_Nm,
                                           rel=1e-12)
    assert q_points(spec, spec.design_misalignment_deg) is pts


@pytest.mark.slow
def test_a_forked_run_hands_its_stages_to_the_parent(tmp_path):
    """``gc.run`` with two workers: the sweep its worker computed is kept in the parent,
    where a report reuses it (the same object, equal to a fresh sweep)."""
    code = f"""
import numpy as np, gearcoupling as gc
from gearcoupling.outputs import stages, turn_sweep
spec = gc.load_spec('renzo-1967')
res = gc.run(spec, {str(tmp_path)!r}, only=['sweep', 'viewer'], workers=2)
assert res.workers == 2, res.workers
kept = [k for k in stages._MEMO if k[0] == 'turn_sweep']
assert len(kept) == 1, kept
sw = turn_sweep(spec, spec.design_misalignment_deg, 360, 1e-7)
assert sw is stages._MEMO[kept[0]]
fresh = gc.sweep(spec, spec.design_misalignment_deg, np.arange(360.0))
assert np.array_equal(sw.normal_clearance_mm, fresh.normal_clearance_mm)
"""
    subprocess.run([sys.executable, "-c", code], check=True)
