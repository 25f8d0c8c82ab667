"""One public API: what the commands use is reachable from ``import gearcoupling`` by name."""

import subprocess
import sys

import pytest

import gearcoupling as gc


@pytest.mark.parametrize("name", gc.__all__)
def test_every_public_name_resolves(name):
    assert getattr(gc, name) is not None
    assert name in dir(gc)


def test_sweep_and_load_are_functions_whether_or_not_their_packages_were_imported():
    # in a fresh interpreter: first through the lazy attribute, then after the subpackage
    # import has replaced the attribute by the (callable) package
    code = """
import numpy as np
import gearcoupling as gc
spec = gc.load_spec("renzo-1967")
a = gc.sweep(spec, 1.0, [0.0, 90.0])
import gearcoupling.sweep
import gearcoupling.load
b = gc.sweep(spec, 1.0, [0.0, 90.0])
assert type(a).__name__ == type(b).__name__ == "SweepResult"
assert np.array_equal(a.clearance_mm, b.clearance_mm)
r = gc.load(spec, 1.0, [0.0], torque_Nm=100.0, model="linear")
assert type(r).__name__ == "LoadResult", type(r)
assert abs(gc.min_backlash_rad(spec, 0.0) * spec.tooth.pitch_radius
           - spec.derived["aligned_backlash_mm"]) < 1e-6
"""
    subprocess.run([sys.executable, "-c", code], check=True)


def test_callable_packages_show_their_functions_signature():
    import inspect

    import gearcoupling.load
    import gearcoupling.sweep

    for package, func in ((gearcoupling.sweep, gearcoupling.sweep.sweep),
                          (gearcoupling.load, gearcoupling.load.load)):
        assert inspect.signature(package) == inspect.signature(func)
        assert next(iter(inspect.signature(package).parameters)) == "spec"


def test_unknown_attribute_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no_such_name"):
        gc.no_such_name  # noqa: B018
