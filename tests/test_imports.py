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
    "gearcoupling.rotordynamics",
    "gearcoupling.coupling",
    "gearcoupling.wear",
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
    # scipy.interpolate/optimize (~0.4 s) are imported inside the
    # functions that use them; `import gearcoupling` costs numpy plus our own modules
    code = "import sys, gearcoupling; print(','.join(m for m in sys.modules if 'scipy' in m))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


# the data flow of docs/conventions.md (docs/conventions.md): each unit may import only these
LAYERS = {
    "errors": set(),
    "arguments": {"errors"},
    "numeric": set(),
    "io": {"errors", "forked"},
    "browser": {"errors"},
    "forked": {"errors"},
    "tables": {"errors"},
    "geometry": {"errors"},  # takes spec objects (a protocol): never the spec package
    "spec": {"errors", "io", "geometry"},
    "plots": {"io", "errors", "geometry", "spec"},
    "parts": {"io", "errors", "geometry", "spec"},
    "export": {"io", "errors", "geometry", "spec", "parts"},
    "clearance": {"io", "errors", "geometry", "spec", "plots", "tables"},
    "interference": {"io", "errors", "geometry", "spec", "plots", "parts", "clearance"},
    "fea": {"io", "errors", "forked", "geometry", "spec", "parts", "export", "clearance"},
    "loading": {"io", "errors", "geometry", "spec", "plots", "clearance", "fea", "tables"},
    "study": {"__init__", "io", "forked", "errors", "geometry", "spec", "plots", "clearance",
              "loading", "tables", "wear"},
    "hob": {"io", "errors", "geometry", "spec", "plots"},
    "inspection": {"io", "errors", "geometry", "spec", "plots", "parts", "hob", "tables"},
    "outputs": {"io", "errors", "forked", "geometry", "spec", "plots", "parts", "export",
                "clearance", "interference", "loading", "viewer", "hob", "inspection",
                "rotordynamics", "coupling", "wear"},
    # the report renders the outputs' stage results: it computes nothing of its own
    "reporting": {"__init__", "io", "errors", "browser", "geometry", "spec", "loadspec",
                  "clearance", "loading", "hob", "inspection", "rotordynamics", "outputs",
                  "coupling", "wear"},
    "viewer": {"io", "errors", "browser", "geometry", "spec", "plots", "parts", "export",
               "clearance", "interference", "loading", "inspection", "coupling", "wear"},
    "rotordynamics": {"io", "errors", "forked", "geometry", "spec", "plots", "parts",
                      "clearance", "loading", "tables"},
    "coupling": {"io", "errors", "forked", "geometry", "spec", "plots", "parts", "export",
                 "clearance", "interference", "loading", "rotordynamics", "tables"},
    "wear": {"io", "errors", "geometry", "spec", "plots", "clearance", "loading", "tables"},
}
# the argument checks (numbers, counts, torques, documented maxima) sit beside the errors,
# the numeric guards (numpy only) and the interruption's note (stdlib only) below everything
LAYERS = {k: v | {"arguments", "numeric", "interrupts"}
          if k not in ("errors", "arguments", "numeric") else v for k, v in LAYERS.items()}
LAYERS["interrupts"] = set()


def _type_checking_nodes(tree) -> set[int]:
    """Ids of the nodes under ``if TYPE_CHECKING:`` (annotations only: not imports at run
    time, so they neither break the layering nor make circles)."""
    import ast

    return {id(n) for node in ast.walk(tree) if isinstance(node, ast.If)
            and getattr(node.test, "id", None) == "TYPE_CHECKING"
            for n in ast.walk(node) if n is not node}


def _internal_imports(path, root):
    """Top-level units of gearcoupling that the file at ``path`` imports."""
    import ast

    pkg = list(path.relative_to(root).parts[:-1])
    out = set()
    tree = ast.parse(path.read_text())
    typing_only = _type_checking_nodes(tree)
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
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


def _package_imports():
    """``(file, line, target unit, target module parts, names, inside a function)`` of every
    first-party ``from`` import in the package."""
    import ast
    from pathlib import Path

    import gearcoupling

    root = Path(gearcoupling.__file__).parent
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).parts
        pkg = list(rel[:-1])
        tree = ast.parse(path.read_text())
        typing_only = _type_checking_nodes(tree)
        in_fn = {id(n) for f in ast.walk(tree)
                 if isinstance(f, ast.FunctionDef | ast.AsyncFunctionDef)
                 for n in ast.walk(f) if n is not f}
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or id(node) in typing_only:
                continue
            if node.level:
                base = pkg[:len(pkg) - (node.level - 1)]
                full = base + (node.module.split(".") if node.module else [])
            elif (node.module or "").startswith("gearcoupling"):
                full = node.module.split(".")[1:]
            else:
                continue
            yield (path, "/".join(rel), node.lineno, full, [a.name for a in node.names],
                   id(node) in in_fn)


# a package's module that its ``__init__`` does not load because it imports a heavy
# back-end: the compiled kernels reach it directly (numba's verified on-disk cache)
HEAVY_MODULES = {("io", "numba_cache")}


def test_other_packages_are_reached_only_through_their_public_names():
    """A module imports another package only by the names in that package's ``__all__``
    (no reaching into its modules, but for :data:`HEAVY_MODULES`)."""
    import importlib

    wrong = []
    for _, rel, line, full, names, _ in _package_imports():
        unit = rel.split("/")[0].removesuffix(".py")
        if not full or full[0] == unit or tuple(full) in HEAVY_MODULES:
            continue
        target = importlib.import_module(f"gearcoupling.{full[0]}")
        if not hasattr(target, "__path__"):  # a module, not a package
            continue
        if len(full) > 1:
            wrong.append(f"{rel}:{line} imports gearcoupling.{'.'.join(full)}")
        else:
            wrong += [f"{rel}:{line} imports {n} from {full[0]}, not in its __all__"
                      for n in names if n not in target.__all__]
    assert not wrong, wrong


# the first-party imports made at the call: the compiled kernels import numba (heavy,
# optional) at their top, so importing them is the lazy import of numba
LAZY_FIRST_PARTY = {("clearance/fast.py", "_compiled"),
                    ("loading/kernels/halfspace.py", "_contact_compiled")}


def test_first_party_imports_sit_at_the_top_of_modules():
    inside = [f"{rel}:{line}" for _, rel, line, _, names, in_fn in _package_imports()
              if in_fn and not {(rel, n) for n in names} <= LAZY_FIRST_PARTY]
    assert not inside, inside


def test_no_import_circles_between_modules():
    """The module-level import graph of the package has no cycle (strongly connected
    component of more than one module)."""
    graph: dict[str, set[str]] = {}
    for path, rel, _, full, names, in_fn in _package_imports():
        if in_fn or not full:
            continue
        src = rel.removesuffix(".py").removesuffix("/__init__")
        package = path.parents[len(rel.split("/")) - 1].joinpath(*full)
        for name in names:  # `from . import module` points at that module
            is_module = (package / f"{name}.py").exists() or (package / name).is_dir()
            dst = "/".join([*full, name] if is_module else full)
            graph.setdefault(src, set()).add(dst)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    cycles = []

    def visit(v):  # Tarjan's strongly connected components
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in list(graph):
        if v not in index:
            visit(v)
    assert not cycles, cycles
