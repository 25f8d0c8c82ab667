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
    "gearcoupling.load",
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
