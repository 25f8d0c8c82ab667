"""The coupling as a ROSS element (``ross-rotordynamics``, the ``rotordynamics`` extra).

``ross.CouplingElement`` joins two stations (left: the hub, right: the sleeve) by a
diagonal stiffness in SI units: translations ``x, y``, axial ``z``, tilts about ``x, y``
and torsion. It has no cross-coupled terms: the friction's cross-coupled tilt stiffness,
the tilt-torsion coupling and the off-diagonal radial terms of the full matrix
(``stiffness_matrix.csv``) are left out; a program that takes a full matrix should take
that instead (docs/rotordynamics.md).
"""

from __future__ import annotations

import contextlib
import importlib
import os
import sys
import warnings
from pathlib import Path
from typing import Any

from ..errors import ArgumentError, BackendError
from ..interrupts import reraise as reraise_interrupt
from ..io import atomic_path

ROSS_SUFFIXES = (".toml", ".json")


@contextlib.contextmanager
def _quiet():
    """Silence what importing ROSS prints (its compressor package probes for REFPROP on the
    C level and warns when it is absent)."""
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    try:
        saved = [os.dup(1), os.dup(2)]
    except OSError:  # no real descriptors (embedded interpreter)
        saved = []
    with open(os.devnull, "w") as null, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for fd in (1, 2)[:len(saved)]:
            os.dup2(null.fileno(), fd)
        try:
            yield
        finally:
            for fd, keep in zip((1, 2), saved, strict=False):
                os.dup2(keep, fd)
                os.close(keep)


def import_ross() -> Any:
    """``ross``, or :class:`~gearcoupling.errors.BackendError` naming the extra."""
    if "ross" in sys.modules:
        return sys.modules["ross"]
    try:
        with _quiet():
            return importlib.import_module("ross")
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("the ROSS element needs ross-rotordynamics: pip install "
                           "'gearcoupling[rotordynamics]'") from err


def coupling_element(data, *, held_torque: bool = False, axial_N_per_m: float = 0.0,
                     n: int | None = None, tag: str | None = None):
    """A ``ross.CouplingElement`` of :class:`~.data.CouplingData` ``data``.

    Masses, polar and transverse (diametral) inertias of hub (left) and sleeve (right);
    the diagonal of the stiffness matrix (hub bore against sleeve outside diameter).

    Parameters
    ----------
    held_torque : bool
        Tilt and radial stiffness with the torque held and the wind-up free (the matrix
        condensed on torsion) instead of the wind-up held.
    axial_N_per_m : float
        Axial stiffness: the teeth slide axially beyond the slip force and the model gives
        no stick stiffness below it (default 0: free axially).
    n, tag : optional
        ROSS's element number and tag.
    """
    if not (isinstance(axial_N_per_m, int | float) and 0 <= axial_N_per_m < float("inf")):
        raise ArgumentError("axial_N_per_m", axial_N_per_m, "a finite stiffness >= 0 in N/m")
    rs = import_ross()
    K = data.stiffness.matrix
    lateral = data.stiffness.at_constant_torque() if held_torque else K
    hub, sleeve = data.mass["hub"], data.mass["sleeve"]
    spec = data.spec
    return rs.CouplingElement(
        m_l=hub.mass_kg, m_r=sleeve.mass_kg,
        Ip_l=hub.polar_inertia_kg_m2, Ip_r=sleeve.polar_inertia_kg_m2,
        Id_l=hub.transverse_inertia_kg_m2, Id_r=sleeve.transverse_inertia_kg_m2,
        kt_x=float(lateral[0, 0]), kt_y=float(lateral[1, 1]), kt_z=float(axial_N_per_m),
        kr_x=float(lateral[3, 3]), kr_y=float(lateral[4, 4]), kr_z=float(K[5, 5]),
        o_d=spec.sleeve.outer_diameter * 1e-3, L=spec.sleeve.face_width * 1e-3, n=n,
        tag=tag or spec.name)


def write_ross(element, path: str | os.PathLike) -> Path:
    """Save a ROSS element (or a list of them: one entry each, keyed by class and tag) in
    ROSS's own file format (``.toml`` or ``.json``, by ROSS's ``save``), atomically:
    ``ross.CouplingElement.load(path)`` reads the first back."""
    target = Path(path)
    if target.suffix.lower() not in ROSS_SUFFIXES:
        raise ArgumentError("--ross", str(path), "a .toml or .json file (the formats ROSS "
                            "saves and loads)")
    with atomic_path(target) as tmp:
        tmp.unlink()  # ROSS's save adds to an existing file: start from none
        for one in element if isinstance(element, list | tuple) else [element]:
            one.save(tmp)
    return target


__all__ = ["coupling_element", "import_ross", "write_ross"]
