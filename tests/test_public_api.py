"""One public API: what the commands use is reachable from ``import gearcoupling`` by name."""

import inspect
import subprocess
import sys

import pytest

import gearcoupling as gc


@pytest.mark.parametrize("name", gc.__all__)
def test_every_public_name_is_a_documented_function_or_class_of_the_package(name):
    obj = getattr(gc, name)
    assert inspect.isfunction(obj) or inspect.isclass(obj), type(obj)
    assert obj.__module__.startswith("gearcoupling."), obj.__module__
    assert obj.__name__ == name
    assert (obj.__doc__ or "").strip(), f"{name} has no docstring"
    assert name in dir(gc)


def test_the_stub_lists_exactly_the_public_names():
    """``__init__.pyi`` is what type checkers read: it names every public object."""
    import ast
    from pathlib import Path

    stub = Path(gc.__file__).with_suffix(".pyi")
    names = {a.asname or a.name for node in ast.parse(stub.read_text()).body
             if isinstance(node, ast.ImportFrom) for a in node.names}
    assert names == set(gc.__all__)


def test_sweep_and_load_are_plain_functions_before_and_after_their_packages_import():
    # in a fresh interpreter: through the lazy attribute, then after the stage packages
    # were imported (a package must never shadow the function of the same name)
    code = """
import inspect, pickle
import numpy as np
import gearcoupling as gc
spec = gc.load_spec("renzo-1967")
a = gc.sweep(spec, 1.0, [0.0, 90.0])
import gearcoupling.clearance, gearcoupling.loading
assert inspect.isfunction(gc.sweep) and inspect.isfunction(gc.load)
assert pickle.loads(pickle.dumps(gc.sweep)) is gc.sweep
assert list(inspect.signature(gc.sweep).parameters)[:3] == ["spec", "misalignment_deg",
                                                             "angles_deg"]
assert gc.sweep.__doc__.startswith("Clearance of every hub tooth")
b = gc.sweep(spec, 1.0, [0.0, 90.0])
assert np.array_equal(a.clearance_mm, b.clearance_mm)
r = gc.load(spec, 1.0, [0.0], torque_Nm=100.0, model="linear")
assert type(r).__name__ == "LoadResult", type(r)
"""
    subprocess.run([sys.executable, "-c", code], check=True)


def test_unknown_attribute_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no_such_name"):
        gc.no_such_name  # noqa: B018
