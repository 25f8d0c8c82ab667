"""Lazy access to the FE back-ends: gmsh (PyPI, ``fea`` extra) and CalculiX ``ccx``."""

from __future__ import annotations

import os
import shutil
from contextlib import contextmanager

from ..errors import BackendError

CCX_ENV = "GEARCOUPLING_CCX"
"""Environment variable naming the ``ccx`` executable (default: ``ccx`` on the PATH)."""


def gmsh_module():
    """The ``gmsh`` Python module, or :class:`BackendError` saying what to install."""
    try:
        import gmsh
    except ImportError as err:
        raise BackendError("volume meshing needs gmsh: pip install 'gearcoupling[fea]' "
                           "(PyPI package gmsh)") from err
    return gmsh


@contextmanager
def gmsh_session():
    """An initialised, silent gmsh with an empty model; finalised on exit."""
    gmsh = gmsh_module()
    if gmsh.isInitialized():
        gmsh.finalize()
    gmsh.initialize(readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.model.add("gearcoupling")
        yield gmsh
    finally:
        gmsh.finalize()


def ccx_path() -> str:
    """Path of the CalculiX executable, or :class:`BackendError` saying what to install."""
    name = os.environ.get(CCX_ENV, "ccx")
    path = shutil.which(name)
    if path is None:
        raise BackendError(f"the FE solver CalculiX ({name!r}) was not found: install it "
                           "(Debian/Ubuntu: apt-get install calculix-ccx) or set "
                           f"{CCX_ENV} to its path")
    return path
