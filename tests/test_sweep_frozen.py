"""The sweep kernel against its frozen outputs (``tests/golden_sweep_kernel.py``): a
speed-up must not move any minimum by more than 1e-9 mm."""

from __future__ import annotations

import numpy as np
import pytest

from golden_sweep_kernel import FILE, MISALIGNMENTS_DEG, TEMPLATES, minima

VALUES = ("clearance", "normal", "pitch", "pitch_normal")


@pytest.fixture(scope="module")
def frozen():
    with np.load(FILE) as data:
        return dict(data)


@pytest.fixture(params=["numba", "numpy"])
def backend(request, monkeypatch):
    """Both point evaluations of :mod:`gearcoupling.sweep.fast`: compiled and numpy."""
    from gearcoupling.sweep import clearance

    if request.param == "numba":
        pytest.importorskip("numba", reason="extra 'fast' not installed")
        if clearance.kernels() is None:
            pytest.skip("GEARCOUPLING_NUMBA=0")
    else:
        monkeypatch.setattr(clearance, "kernels", lambda: None)
    return request.param


@pytest.mark.parametrize("deg", MISALIGNMENTS_DEG)
@pytest.mark.parametrize("name", TEMPLATES)
def test_minima_equal_frozen_kernel(frozen, name, deg, backend):
    got = minima(name, deg)
    for key in VALUES:
        ref = frozen[f"{name}|{deg:g}|{key}"]
        assert np.array_equal(np.isfinite(got[key]), np.isfinite(ref)), key
        fin = np.isfinite(ref)
        assert np.max(np.abs(got[key][fin] - ref[fin]), initial=0.0) <= 1e-9, key
    # where the minimum lies: same point (a flat valley could move it; none does here)
    for key in ("z", "r"):
        ref = frozen[f"{name}|{deg:g}|{key}"]
        fin = np.isfinite(ref)
        assert np.max(np.abs(got[key][fin] - ref[fin]), initial=0.0) <= 1e-6, key
