"""Lazy access to the FE back-ends: gmsh (PyPI, ``fea`` extra) and CalculiX ``ccx``."""

from __future__ import annotations

import os
import shutil
import signal
import threading
from contextlib import contextmanager

from ..errors import BackendError
from ..interrupts import reraise as reraise_interrupt

CCX_ENV = "GEARCOUPLING_CCX"
"""Environment variable naming the ``ccx`` executable (default: ``ccx`` on the PATH)."""


def gmsh_module():
    """The ``gmsh`` Python module, or :class:`BackendError` saying what to install."""
    try:
        import gmsh
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("volume meshing needs gmsh: pip install 'gearcoupling[fea]' "
                           "(PyPI package gmsh)") from err
    return gmsh


def gmsh_initialize(gmsh, **options) -> None:
    """``gmsh.initialize(**options)`` keeping Python's SIGPIPE disposition.

    gmsh's initialisation resets SIGPIPE to the system default, so a later write to a
    closed socket or pipe (a browser tab closing on the viewer's websocket) kills the
    whole process instead of raising :class:`BrokenPipeError`.
    """
    if not hasattr(signal, "SIGPIPE"):  # Windows
        gmsh.initialize(**options)
        return
    saved = signal.getsignal(signal.SIGPIPE)
    gmsh.initialize(**options)
    if saved is not None and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGPIPE, saved)


@contextmanager
def gmsh_session():
    """An initialised, silent gmsh with an empty model; finalised on exit. The process's
    SIGINT and SIGTERM handlers survive it (gmsh's OpenCASCADE installs its own, which
    end the process without the command's clean-up)."""
    gmsh = gmsh_module()
    saved = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    if gmsh.isInitialized():
        gmsh.finalize()
    gmsh_initialize(gmsh, readConfigFiles=False, interruptible=False)
    _restore_signals(saved)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 1)
        gmsh.model.add("gearcoupling")
        yield gmsh
    finally:
        gmsh.finalize()
        _restore_signals(saved)


def _restore_signals(saved: dict) -> None:
    """Install the Python-level ``saved`` handlers again at the OS level (main thread)."""
    if threading.current_thread() is not threading.main_thread():
        return
    for sig, handler in saved.items():
        if handler is not None:
            signal.signal(sig, handler)


def ccx_path() -> str:
    """Path of the CalculiX executable, or :class:`BackendError` saying what to install."""
    name = os.environ.get(CCX_ENV, "ccx")
    path = shutil.which(name)
    if path is None:
        raise BackendError(f"the FE solver CalculiX ({name!r}) was not found: install it "
                           "(Debian/Ubuntu: apt-get install calculix-ccx) or set "
                           f"{CCX_ENV} to its path")
    return path
