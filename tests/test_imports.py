"""One-way imports: the kernels and the package top level load no mesh, CAD or viewer library."""

import subprocess
import sys

import pytest

HEAVY = ("trimesh", "manifold3d", "viser", "OCP", "meshio", "matplotlib", "dask",
         "distributed", "pyarrow", "gmsh", "numba")


@pytest.mark.parametrize("module", [
    "gearcoupling",
    "gearcoupling.geometry",
    "gearcoupling.spec",
    "gearcoupling.cli",
    "gearcoupling.loading",
    "gearcoupling.hob",
    "gearcoupling.inspection",
    "gearcoupling.study",
])
def test_kernels_import_no_heavy_backend(module):
    code = (f"import sys, {module}; "
            f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"{module} imported {out.stdout.strip()}"


def test_later_stages_are_reachable_lazily_from_the_top_level():
    code = ("import sys, gearcoupling as gc; assert 'trimesh' not in sys.modules; "
            "from gearcoupling.parts import build_part; assert gc.build_part is build_part; "
            "assert callable(gc.export_part) and callable(gc.check_interference)")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_import_gearcoupling_loads_no_scipy():
    # issue 14 item 8: scipy.interpolate/optimize (~0.4 s) are imported inside the
    # functions that use them; `import gearcoupling` costs numpy plus our own modules
    code = "import sys, gearcoupling; print(','.join(m for m in sys.modules if 'scipy' in m))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


# the data flow of docs/conventions.md (DESIGN.md §4): each unit may import only these
LAYERS = {
    "errors": set(),
    "atomic": {"errors"},
    "loadspec": {"errors"},
    "geometry": {"errors"},
    "spec": {"errors", "geometry", "loadspec"},
    "plots": {"atomic", "errors", "geometry", "spec"},
    "parts": {"atomic", "errors", "geometry", "spec"},
    "export": {"atomic", "errors", "geometry", "spec", "parts"},
    "clearance": {"atomic", "errors", "geometry", "spec", "plots"},
    "interference": {"atomic", "errors", "geometry", "spec", "plots", "parts", "clearance"},
    "fea": {"atomic", "errors", "geometry", "spec", "parts", "export", "clearance"},
    "loading": {"atomic", "errors", "geometry", "spec", "loadspec", "plots", "clearance",
             "fea"},
    "study": {"__init__", "atomic", "errors", "geometry", "spec", "plots", "clearance", "loading"},
    "hob": {"atomic", "errors", "geometry", "spec", "plots"},
    "inspection": {"atomic", "errors", "geometry", "spec", "plots", "parts", "hob"},
    "viewer": {"atomic", "errors", "geometry", "spec", "parts", "export", "clearance",
               "interference", "loading", "inspection"},
}


def _internal_imports(path, root):
    """Top-level units of gearcoupling that the file at ``path`` imports."""
    import ast

    pkg = list(path.relative_to(root).parts[:-1])
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = pkg[:len(pkg) - (node.level - 1)]
            full = base + (node.module.split(".") if node.module else [])
            if full:
                out.add(full[0])
            else:  # from .. import name
                out.update("__init__" if a.name.startswith("__") else a.name
                           for a in node.names)
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("gearcoupling"):
            parts = node.module.split(".")
            out.add(parts[1] if len(parts) > 1 else "__init__")
        elif isinstance(node, ast.Import):
            out.update(a.name.split(".")[1] for a in node.names
                       if a.name.startswith("gearcoupling."))
    return out


def test_imports_follow_the_data_flow():
    """Every unit imports only the stages before it (lazy imports inside functions count)."""
    from pathlib import Path

    import gearcoupling

    root = Path(gearcoupling.__file__).parent
    wrong = []
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).parts
        unit = rel[0].removesuffix(".py")
        if unit not in LAYERS:  # the top: __init__, cli, commands
            continue
        bad = _internal_imports(path, root) - LAYERS[unit] - {unit}
        wrong += [f"{'/'.join(rel)} imports {b}" for b in sorted(bad)]
    assert not wrong, wrong
