"""The examples run, and docs/api.md and the examples cover every public name."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import gearcoupling as gc

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("[0-9][0-9]_*.py"))
HEAVY = {"07_finite_elements.py": "needs_fea", "08_studies.py": "needs_dask",
         "10_viewer_and_report.py": "needs_viewer", "11_rotordynamics.py": "needs_ross"}
SLOW = {"06_outputs_pipeline.py", "13_wear.py", *HEAVY}  # over about 5 s


def _params():
    for path in EXAMPLES:
        marks = [pytest.mark.slow] if path.name in SLOW else []
        if path.name in HEAVY:
            marks.append(getattr(pytest.mark, HEAVY[path.name]))
        yield pytest.param(path, id=path.stem, marks=marks)


@pytest.mark.parametrize("path", list(_params()))
def test_example_runs(path, tmp_path, request):
    env = dict(os.environ)
    if path.name == "07_finite_elements.py":  # its default FE table: the session's, made
        base, _ = request.getfixturevalue("fe_table_industrial")  # by CalculiX (conftest.py)
        env["GEARCOUPLING_CACHE"] = str(base)
        tables = sorted((base / "fea").glob("*.json"))
    out = subprocess.run([sys.executable, str(path)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=900, env=env)
    assert out.returncode == 0, out.stderr[-2000:]
    if path.name == "07_finite_elements.py":  # read from the cache, not a second table
        assert sorted((base / "fea").glob("*.json")) == tables


def test_every_public_name_is_documented_and_used_in_an_example():
    api = (ROOT / "docs" / "api.md").read_text()
    code = "\n".join(p.read_text() for p in EXAMPLES)
    documented = {n for n in gc.__all__ if re.search(rf"`{n}`", api)}
    used = {n for n in gc.__all__ if re.search(rf"gc\.{n}\b", code)}
    assert set(gc.__all__) - documented == set()
    assert set(gc.__all__) - used - {"GearCouplingError", "GeometryError", "BackendError",
                                     "ArgumentError", "CouplingSpec"} == set()
