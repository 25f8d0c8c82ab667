"""Shared fixtures: templates and small helpers for the geometry tests; the markers of
tests that need an optional back-end skip, with the reason, where it is missing.

Markers (``pyproject.toml``): ``slow`` (over about 5 s; ``scripts/test.sh --fast`` leaves
them out), ``needs_fea`` (gmsh, OpenCASCADE and CalculiX ``ccx``), ``needs_fcl``
(python-fcl), ``needs_dask`` (dask.distributed, pyarrow), ``needs_browser`` (playwright and
Debian's chromium), ``needs_viewer`` (viser), ``needs_ross`` (ross-rotordynamics).

``scripts/test.sh`` runs the suite on two pytest-xdist workers (``-n 2 --dist loadgroup``):
the tests of a module with module-scoped fixtures go to one worker (``xdist_group``, so the
fixture is made once), every other test to whichever worker is free, and the session's FE
table is made once for all workers (:func:`fe_table_industrial`).
"""

from __future__ import annotations

import fcntl
import importlib.util
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc

from golden_values import engagement_templates

# marker -> (Python modules, executable, what to install)
REQUIRES = {
    "needs_fea": (("gmsh", "OCP"), "ccx", "pip install 'gearcoupling[fea]'; "
                  "apt-get install calculix-ccx"),
    "needs_fcl": (("fcl",), None, "pip install 'gearcoupling[interference]'"),
    "needs_dask": (("distributed", "pyarrow"), None, "pip install 'gearcoupling[study]'"),
    "needs_browser": (("playwright",), "/usr/bin/chromium", "pip install playwright; "
                      "apt-get install chromium"),
    "needs_viewer": (("viser",), None, "pip install 'gearcoupling[viewer]'"),
    "needs_ross": (("ross",), None, "pip install 'gearcoupling[rotordynamics]'"),
}


def _missing(modules, executable) -> list[str]:
    gone = [m for m in modules if importlib.util.find_spec(m) is None]
    if executable and not (Path(executable).is_file() or shutil.which(executable)):
        gone.append(executable)
    return gone


def _uses_module_fixture(item) -> bool:
    """Whether a test uses a fixture made once per module or class (pytest's fixture
    closure; False where a pytest release no longer has it: then the fixture is only made
    once more on the other worker)."""
    defs = getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {})
    return any(getattr(d, "scope", None) in ("module", "class", "package")
               for found in defs.values() for d in found)


def pytest_collection_modifyitems(config, items):
    """Skip, with the reason, a test whose marked back-end is not installed; put the tests
    of a module with module-scoped fixtures in one xdist group (module docstring)."""
    checked: dict[str, list[str]] = {}
    for item in items:
        if item.get_closest_marker("xdist_group") is None and _uses_module_fixture(item):
            item.add_marker(pytest.mark.xdist_group(item.nodeid.split("::")[0]))
        for name, (modules, exe, install) in REQUIRES.items():
            if item.get_closest_marker(name) is None:
                continue
            if name not in checked:
                checked[name] = _missing(modules, exe)
            if checked[name]:
                item.add_marker(pytest.mark.skip(reason=f"{', '.join(checked[name])} not "
                                                        f"installed: {install}"))


@pytest.fixture(scope="session")
def renzo():
    return gc.load_spec("renzo-1967")


@pytest.fixture(scope="session", params=engagement_templates())
def template(request):
    return gc.load_spec(request.param)


def flank_grid(model, nz: int = 9, nr: int = 7, margin: float = 0.02):
    """(z, r) grid strictly inside the flank of a hub model: face, form radius and tip."""
    from gearcoupling.geometry.hub import form_radius, tip_radius

    z = np.linspace(-model.half_face, model.half_face, nz) * (1 - margin)
    lo, hi = form_radius(model, z), tip_radius(model, z)
    f = np.linspace(margin, 1 - margin, nr)
    r = lo[:, None] + (hi - lo)[:, None] * f[None, :]
    return np.broadcast_to(z[:, None], r.shape).copy(), r


@pytest.fixture(scope="session")
def fe_table_industrial(tmp_path_factory):
    """industrial-m2's FE tooth-spring table at the default settings, in a fresh cache
    (``(cache base, table)``; the table is ``<base>/fea/industrial-m2-<hash>.json``).

    One per session for every FE test that needs a table: the end-to-end check against
    the CalculiX contact reference needs the default mesh (its accuracy is what it
    asserts), and the table's physics, cache and protocol tests hold on it as well as on
    a coarser one, so they share it instead of paying for a second table (half a minute
    of CPU each); so does examples/07_finite_elements.py. Under pytest-xdist the workers
    share one cache folder of the run: the first to get its lock runs the solver, the
    others read the table it wrote."""
    from gearcoupling.fea import tooth_compliance_table

    if os.environ.get("PYTEST_XDIST_WORKER"):  # the run's folder, above the worker's own
        base = tmp_path_factory.getbasetemp().parent / "fe-cache"
        base.mkdir(exist_ok=True)
    else:
        base = tmp_path_factory.mktemp("fe-cache")
    with open(base / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        return base, tooth_compliance_table(gc.load_spec("industrial-m2"), cache=base / "fea")
