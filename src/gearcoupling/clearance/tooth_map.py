"""``sweep``: the clearance map of every tooth and flank over a set of rotations."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import GAP_TOLERANCE_MM, SWEEP_GRID, angle_list, count, flag, sweep_tolerance_mm
from ..errors import ArgumentError
from ..geometry import sleeve_model, turning_angles
from ..spec import CouplingSpec, as_spec, check_misalignment_deg
from .flank_table import flank_table
from .kernel import MEASURES, minimise
from .result import SweepResult

CHUNK_ANGLES = 1024  # turning angles per kernel call: bounds its memory (~30 kB per angle)
_KEY_SCALE = 1e11  # turning angles closer than 1e-11 rad share one evaluation
_KEYS = {"clearance": "circumferential", "normal": "normal", "pitch": "pitch_circumferential",
         "pitch_normal": "pitch_normal"}
_POINT = (("z", "z_mm"), ("r", "r_mm"), ("kind", "kind"), ("rate", "rate"))  # of the normal


def check_misalignment(misalignment_deg: float) -> float:
    """The misalignment in radians, or :class:`ArgumentError` outside 0-6°."""
    return math.radians(check_misalignment_deg(misalignment_deg, error=ArgumentError))


def check_angles(angles_deg: ArrayLike) -> np.ndarray:
    """Rotation angles as a finite 1-D float array (degrees), at most
    ``MAXIMA["angles"]`` of them (:func:`~gearcoupling.arguments.angle_list`)."""
    return angle_list(angles_deg, "angles_deg")


def flank_minima(spec: CouplingSpec, misalignment_rad: float, theta, *, tolerance_mm: float,
                 grid: int = SWEEP_GRID, periodic: bool = True,
                 measures: tuple[str, ...] = MEASURES):
    """Minima of tooth 0's cw flank at turning angles ``theta`` (any shape), all measures.

    With ``periodic`` (ideal geometry) equal turning angles are evaluated once, and when the
    hub flank is symmetric about the midplane (:attr:`FlankTable.symmetric`) so are
    ``theta`` and ``theta + pi``: mirroring ``z -> -z`` maps ``P(theta)`` to
    ``P(theta - pi)`` (``Mz Rx(i) Mz = Rz(pi) Rx(i) Rz(-pi)``) and the sleeve onto itself,
    so the gaps, ``r``, kind and rate are equal and the contact ``z`` changes sign. Aligned
    (``misalignment_rad == 0``) the pose is the identity at every ``theta``: one evaluation.

    ``measures`` (of :data:`~.clearance.MEASURES`) limits the work to what is wanted.

    Returns
    -------
    dict of name -> array shaped like ``theta``
        ``clearance``, ``normal``, ``pitch``, ``pitch_normal`` (mm), ``z``, ``r`` (mm),
        ``kind`` and ``rate`` of the normal minimum (the point of first touch); only those
        of the ``measures`` found (``z``, ``r``, ``kind``, ``rate`` with ``normal``).
    """
    table = flank_table(spec, min(GAP_TOLERANCE_MM, tolerance_mm))
    sm = sleeve_model(spec)
    theta = np.asarray(theta, dtype=float)
    flat = _turn(theta.ravel())
    mirror = np.zeros(flat.shape, dtype=bool)
    if misalignment_rad == 0.0:  # P(theta) is the identity: every turning angle alike
        th, inverse = flat[:1] * 0.0, np.zeros(flat.size, dtype=np.intp)
    elif periodic:
        if table.symmetric:
            mirror = flat >= np.pi
            flat = np.where(mirror, flat - np.pi, flat)
        _, first, inverse = np.unique(np.round(flat * _KEY_SCALE).astype(np.int64),
                                      return_index=True, return_inverse=True)
        th = flat[first]
    else:  # in turn, so that each minimum is followed from its neighbour's
        order = np.argsort(flat, kind="stable")
        th, inverse = flat[order], np.empty(flat.size, dtype=np.intp)
        inverse[order] = np.arange(flat.size)
    parts = [minimise(table, sm, misalignment_rad, th[j:j + CHUNK_ANGLES],
                      pitch_radius=spec.tooth.pitch_radius, tolerance_mm=tolerance_mm,
                      grid=grid, measures=measures) for j in range(0, th.size, CHUNK_ANGLES)]
    names = [(key, m, "value_mm") for key, m in _KEYS.items() if m in parts[0]]
    if "normal" in parts[0]:
        names += [(key, "normal", f) for key, f in _POINT]
    found = np.empty((len(names), th.size))
    for row, (_, m, f) in zip(found, names, strict=True):
        np.concatenate([getattr(p[m], f) for p in parts], out=row)
    found = found[:, inverse]  # every turning angle from its evaluation
    out = {key: row.reshape(theta.shape) for row, (key, _, _) in zip(found, names, strict=True)}
    if "z" in out:
        out["z"] = np.where(mirror.reshape(theta.shape), -out["z"], out["z"])
        out["kind"] = out["kind"].astype(np.int8)
    return out, table


def _turn(theta: NDArray[np.float64]) -> NDArray[np.float64]:
    """``theta`` modulo 2 pi, in ``[0, 2 pi)`` (as ``np.mod``, in fewer passes)."""
    flat = theta - 2.0 * np.pi * np.floor(theta * (0.5 / np.pi))
    flat[flat < 0.0] += 2.0 * np.pi
    flat[flat >= 2.0 * np.pi] -= 2.0 * np.pi
    return flat


def sweep(spec: CouplingSpec, misalignment_deg: float, angles_deg: ArrayLike, *,
          tolerance_mm: float = GAP_TOLERANCE_MM, grid: int = SWEEP_GRID,
          periodic: bool = True) -> SweepResult:
    """Clearance of every hub tooth and flank at misalignment ``i`` over rotations ``psi``.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
        Misalignment ``i`` in degrees (0-6).
    angles_deg : (n_angle,) float
        Rotations ``psi`` of the coupling in degrees (docs/conventions.md, Frames).
    tolerance_mm : float
        Accuracy of every minimum (mm), 1e-12 to 0.1; also bounds the flank table error.
        The default 1e-7 mm costs about twice 1e-4 mm (see ``benchmarks/bench_sweep.py``).
    grid : int
        Coarse planes over the face width before refinement, 2-1000.
    periodic : bool
        Use the tooth periodicity of the ideal geometry (tooth ``k`` at rotation ``psi`` is
        tooth 0 at ``theta_k = psi + 2 pi k / N``) and evaluate each distinct turning angle
        once; ``False`` evaluates every (tooth, angle) on its own, the path for specs with
        tooth errors.

    Returns
    -------
    SweepResult
        Arrays shaped ``(flank, tooth, angle)`` with flanks ``(cw, ccw)``.
    """
    spec = as_spec(spec)
    i = check_misalignment(misalignment_deg)
    psi = np.radians(check_angles(angles_deg))
    tolerance_mm = sweep_tolerance_mm(tolerance_mm)
    grid = count(grid, "grid", 2)
    periodic = flag(periodic, "periodic")
    N = spec.tooth.teeth
    theta = turning_angles(N, psi)  # (N, M)
    # the ccw flank at theta is the cw flank at pi - theta (mirror y -> -y)
    both = np.stack([theta, np.pi - theta])
    mins, table = flank_minima(spec, i, both, tolerance_mm=tolerance_mm, grid=grid,
                               periodic=periodic)
    r_b = spec.tooth.base_radius
    R = spec.tooth.pitch_radius
    with np.errstate(invalid="ignore"):
        gap_angle = mins["normal"] / r_b / mins["rate"]  # (2, N, M), first order in the gap
    backlash = np.min(gap_angle[0], axis=0) + np.min(gap_angle[1], axis=0)
    derived = spec.derived
    return SweepResult(
        spec=spec,
        misalignment_deg=float(misalignment_deg),
        teeth=N,
        pitch_radius_mm=R,
        base_radius_mm=r_b,
        pressure_angle_deg=math.degrees(spec.tooth.pressure_angle),
        aligned_backlash_mm=derived["aligned_backlash_mm"],
        half_face_mm=0.5 * spec.hub.face_width,
        angles_deg=np.degrees(psi),
        theta_deg=np.mod(np.degrees(theta), 360.0),
        clearance_mm=mins["clearance"],
        normal_clearance_mm=mins["normal"],
        pitch_clearance_mm=mins["pitch"],
        pitch_normal_clearance_mm=mins["pitch_normal"],
        contact_z_mm=mins["z"],
        contact_r_mm=mins["r"],
        contact_kind=mins["kind"],
        backlash_rad=backlash,
        backlash_mm=backlash * R,
        tolerance_mm=tolerance_mm,
        table_error_mm=table.max_error_mm,
        design={"crowning_radius_midplane_mm": derived["crowning_radius_midplane_mm"]},
        gap_angle_rad=np.where(np.isfinite(gap_angle), gap_angle, np.inf),
    )
