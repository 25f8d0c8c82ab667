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


def _annotation_names(annotation) -> set[str]:
    """The names (``x`` or ``module.x``) a string annotation mentions."""
    import ast

    if not isinstance(annotation, str):
        return set()
    names, qualifiers = set(), set()
    for node in ast.walk(ast.parse(annotation, mode="eval")):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            names.add(f"{node.value.id}.{node.attr}")
            qualifiers.add(id(node.value))
        elif isinstance(node, ast.Name) and id(node) not in qualifiers:
            names.add(node.id)
    return names


def _public_callables(obj):
    """``(qualified name, function)`` of a public function, or of a class's public methods
    and properties."""
    if inspect.isfunction(obj):
        yield obj.__name__, obj
        return
    for name, member in vars(obj).items():
        member = member.fget if isinstance(member, property) else member
        member = getattr(member, "__func__", member)  # static and class methods
        if not name.startswith("_") and inspect.isfunction(member):
            yield f"{obj.__name__}.{name}", member


def _returned_classes(fn) -> list[tuple[str, object]]:
    """The classes of gearcoupling a function's return annotation names, resolved in its
    module; a name that is not a third-party ``module.Class`` must resolve there."""
    import builtins

    out = []
    for name in _annotation_names(inspect.signature(fn).return_annotation):
        root, _, attr = name.partition(".")
        if root not in fn.__globals__ and not hasattr(builtins, root):
            assert attr and root != "gearcoupling", f"{fn.__qualname__} returns {name}, " \
                "which is not importable where it is defined"
            continue  # a third-party type (trimesh.Trimesh, imported for type checking)
        obj = fn.__globals__.get(root, getattr(builtins, root, None))
        obj = getattr(obj, attr, None) if attr else obj
        if inspect.isclass(obj) and obj.__module__.startswith("gearcoupling"):
            out.append((name, obj))
    return out


@pytest.mark.parametrize("name", [n for n in gc.__all__ if inspect.isfunction(getattr(gc, n))])
def test_every_public_function_has_a_return_annotation(name):
    fn = getattr(gc, name)
    assert inspect.signature(fn).return_annotation is not inspect.Signature.empty, name


def test_every_returned_type_is_importable_from_gearcoupling():
    """What a public function or a public method of a returned type returns is a public
    name too (``gc.capacity`` returns ``gc.Capacity``, whose methods return public types)."""
    todo = [getattr(gc, n) for n in gc.__all__]
    seen: set[int] = set()
    missing = []
    while todo:
        obj = todo.pop()
        if id(obj) in seen:
            continue
        seen.add(id(obj))
        for where, fn in _public_callables(obj):
            for name, cls in _returned_classes(fn):
                if getattr(gc, cls.__name__, None) is not cls:
                    missing.append(f"{where} returns {name}")
                todo.append(cls)
    assert not missing, missing
    assert len(seen) > len(gc.__all__) // 2  # the walk saw the public API
