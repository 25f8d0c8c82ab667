"""Elastic half-space contact on a regular grid: influence coefficients, DC-FFT, CG solver.

Pure numpy/scipy kernel, numba for small grids (no mesh, CAD or solver import).

- **Influence coefficients** (Love 1929; Johnson, *Contact Mechanics*, eq. 3.25): the normal
  surface displacement of two elastic bodies at offset ``(x, y)`` from the centre of a
  rectangular cell ``2a x 2b`` under unit uniform pressure is
  ``(1 / (pi E*)) * [F(x + a, y + b) - F(x + a, y - b) - F(x - a, y + b) + F(x - a, y - b)]``
  with ``F(X, Y) = X asinh(Y / |X|) + Y asinh(X / |Y|)`` (the integral of ``1 / rho`` over
  the rectangle from the origin to ``(X, Y)``, odd in each argument) and the composite
  modulus ``1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2``.
- **DC-FFT** (Liu, Wang & Liu, Wear 243, 2000): the linear (non-periodic) convolution of
  the pressure with the influence coefficients by FFT on a grid doubled in each direction,
  the coefficients wrapped to negative offsets and the pressure zero-padded, so no
  wrap-around error remains (exact to rounding against the direct sum).
- **Contact solver** (Polonsky & Keer, Wear 231, 1999): conjugate gradients on the contact
  set with ``p >= 0`` and gap ``>= 0``, the rigid approach as the Lagrange multiplier of the
  load constraint (given total load) or given. Several grids (teeth) may be solved
  together, sharing one approach and one load, each with a compliance behind it in series
  (:class:`GridCompliance`; :class:`RigidSprings`: tooth bending as the whole grid moving
  back by ``c_k * W_k``). Under a shared load the grids are solved by decomposition
  (:func:`_shared_approach`): each grid under its own load (well conditioned: a few
  iterations), the loads moved between the grids until their approaches agree, each
  grid's approach modelled as ``k W^e + c W`` through its last solves.
- **Precision**: searches to a tolerance of 1e-6 or looser run their transforms in single
  precision (five times faster; relative error 5e-7 of a displacement) and end with every
  grid checked, and carried on where needed, in double precision.
- **Small grids** (at most :data:`COMPILED_MAX_CELLS` cells) take the same per-grid search
  compiled with numba (:func:`compiled`, :mod:`._contact_compiled`), in double precision.

Units: lengths in mm, pressures and moduli in MPa (N/mm^2), forces in N.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from types import ModuleType
from typing import Protocol, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import fft

from ...errors import ArgumentError, GearCouplingError
from ...numeric import TINY, divide

#: the gap scale of a flat grid (a span below it: straight teeth at no misalignment, where
#: every contactable cell has the same gap): its gap residual is measured against this
GAP_SCALE_FLOOR_MM = 1e-7
DEFAULT_TOLERANCE = 1e-8  # relative: |dp| summed / |p| summed and gap residual / gap scale
MAX_ITER = 4000
FFT_BLOCK_BYTES = 210_000  # spectra per transform call (4 grids of 48 x 32 in double)
SINGLE_PRECISION_TOLERANCE = 1e-6  # solves to this or looser search in single precision
SINGLE_PRECISION_NOISE = 5e-7  # transform error in single precision / largest displacement
SINGLE_PRECISION_ITER = 200  # iterations of one grid solve before it goes on in double
EXACT_BELOW = 1e-5  # solves to this or tighter end on double-precision displacements
SPRING_EVERY = 10  # iterations between updates of position-dependent springs
COMPILED_MAX_ITER = 200  # a compiled grid search longer than this hands over to the batched one
COMPILED_MAX_CELLS = 200  # grids up to this many cells take the compiled search (compiled(),
# docs/load-surface.md: the studies' 12 x 8 grids 1.3x faster; 24 x 16 and up slower)


def composite_modulus(e1_MPa: float, nu1: float, e2_MPa: float, nu2: float) -> float:
    """Composite (contact) modulus ``E*`` with ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2`` (MPa)."""
    for name, e, nu in (("youngs_modulus_MPa (1)", e1_MPa, nu1),
                        ("youngs_modulus_MPa (2)", e2_MPa, nu2)):
        if not (math.isfinite(e) and e > 0):
            raise ArgumentError(name, e, "must be a finite modulus > 0 MPa")
        if not (math.isfinite(nu) and -1.0 < nu < 0.5):
            raise ArgumentError(name.replace("youngs_modulus_MPa", "poisson_ratio"), nu,
                                "must be in (-1, 0.5)")
    return 1.0 / ((1.0 - nu1 * nu1) / e1_MPa + (1.0 - nu2 * nu2) / e2_MPa)


def _f(X: NDArray[np.float64], Y: NDArray[np.float64]) -> NDArray[np.float64]:
    """``X asinh(Y/|X|) + Y asinh(X/|Y|)``, 0 where an argument is 0 (its limit)."""
    ax, ay = np.abs(X), np.abs(Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(ax > 0, X * np.arcsinh(Y / np.where(ax > 0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0, Y * np.arcsinh(X / np.where(ay > 0, ay, 1.0)), 0.0)
    return t1 + t2


def influence(x: ArrayLike, y: ArrayLike, dx: float, dy: float, e_star_MPa: float
              ) -> NDArray[np.float64]:
    """Normal displacement (mm) at offsets ``(x, y)`` (mm, broadcast) from the centre of a
    ``dx x dy`` cell under unit pressure (1 MPa), both bodies together (Love's formula)."""
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    a, b = 0.5 * dx, 0.5 * dy
    s = _f(x + a, y + b) - _f(x + a, y - b) - _f(x - a, y + b) + _f(x - a, y - b)
    return s / (math.pi * e_star_MPa)


@dataclass(frozen=True, eq=False)
class HalfSpace:
    """Influence operator of an ``n1 x n2`` grid of ``dx x dy`` cells (DC-FFT).

    ``displacement(p)`` maps pressures ``(..., n1, n2)`` (MPa) to normal displacements
    (mm) of the same shape; leading axes are independent grids (batched FFT).
    """

    shape: tuple[int, int]
    dx: float
    dy: float
    e_star_MPa: float
    kernel_hat: NDArray[np.complex128]
    kernel_hat_single: NDArray[np.complex64]

    @property
    def cell_area(self) -> float:
        return self.dx * self.dy

    def displacement(self, p: NDArray[np.float64], single: bool = False
                     ) -> NDArray[np.float64]:
        """The displacement of ``p``; ``single``: transforms in single precision (relative
        error about 5e-7 of the largest displacement, 5x faster; measured)."""
        # 2-D FFT as two 1-D passes that skip the zero padding on the way in and the
        # discarded half on the way out (14-30 % less work than rfft2/irfft2)
        n1, n2 = self.shape
        kernel: NDArray[np.complexfloating] = self.kernel_hat
        if single:
            p, kernel = p.astype(np.float32), self.kernel_hat_single
        # double precision in blocks of a few grids: its batched transforms slow down 3x
        # per grid beyond about 200 kB of spectra (measured: 28 against 76 us per 48 x 32
        # grid; single precision keeps 15 us per grid to 50 grids)
        block = max(1, FFT_BLOCK_BYTES // (2 * n1 * (n2 + 1) * 16))
        if single or p.ndim < 3 or p.shape[0] <= block:
            return self._transform(p, kernel)
        out = np.empty(p.shape)
        for i in range(0, p.shape[0], block):
            out[i:i + block] = self._transform(p[i:i + block], kernel)
        return out

    def _transform(self, p, kernel) -> NDArray[np.float64]:
        n1, n2 = self.shape
        h = fft.fft(fft.rfft(p, n=2 * n2, axis=-1), n=2 * n1, axis=-2)
        h *= kernel
        h = fft.ifft(h, axis=-2)[..., :n1, :]
        return fft.irfft(h, n=2 * n2, axis=-1)[..., :n2].astype(float, copy=False)

    def direct(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """The same convolution by the direct double sum (slow; for checks)."""
        n1, n2 = self.shape
        i = np.arange(n1)
        j = np.arange(n2)
        K = influence((i[:, None, None, None] - i[None, None, :, None]) * self.dx,
                      (j[None, :, None, None] - j[None, None, None, :]) * self.dy,
                      self.dx, self.dy, self.e_star_MPa)
        return np.einsum("abcd,...cd->...ab", K, p)


@lru_cache(maxsize=1)
def compiled() -> ModuleType:
    """The compiled per-grid solver (:mod:`._contact_compiled`), imported at its first use."""
    from . import _contact_compiled

    return _contact_compiled


def offset_influence(hs: HalfSpace) -> NDArray[np.float64]:
    """The influence coefficients of ``hs`` by offset: ``(2 n1 - 1, 2 n2 - 1)``, offset
    ``(d1, d2)`` at ``(d1 + n1 - 1, d2 + n2 - 1)`` (read only, kept per grid)."""
    return _offset_influence(*hs.shape, hs.dx, hs.dy, hs.e_star_MPa)


@lru_cache(maxsize=32)
def _offset_influence(n1: int, n2: int, dx: float, dy: float, e_star_MPa: float
                      ) -> NDArray[np.float64]:
    d1 = np.arange(-(n1 - 1), n1, dtype=float)
    d2 = np.arange(-(n2 - 1), n2, dtype=float)
    K = influence(d1[:, None] * dx, d2[None, :] * dy, dx, dy, e_star_MPa)
    K.setflags(write=False)
    return K


def half_space(shape: tuple[int, int], dx: float, dy: float, e_star_MPa: float) -> HalfSpace:
    """The DC-FFT operator of a grid: coefficients for offsets ``-(n-1)..(n-1)`` wrapped into
    a ``2n1 x 2n2`` array (offset ``k < 0`` at index ``2n + k``; index ``n`` unused)."""
    n1, n2 = (int(v) for v in shape)
    if n1 < 1 or n2 < 1:
        raise ArgumentError("grid", shape, "needs at least 1 x 1 cells")
    if not (dx > 0 and dy > 0 and math.isfinite(dx) and math.isfinite(dy)):
        raise ArgumentError("cell size", (dx, dy), "must be finite and > 0 mm")
    return _half_space(n1, n2, float(dx), float(dy), float(e_star_MPa))


@lru_cache(maxsize=32)
def _half_space(n1: int, n2: int, dx: float, dy: float, e_star_MPa: float) -> HalfSpace:
    """:func:`half_space`, kept per grid: the poses of a turn share a few grids."""
    i = np.arange(2 * n1)
    j = np.arange(2 * n2)
    oi = np.where(i < n1, i, i - 2 * n1).astype(float)
    oj = np.where(j < n2, j, j - 2 * n2).astype(float)
    K = influence(oi[:, None] * dx, oj[None, :] * dy, dx, dy, e_star_MPa)
    K[n1, :] = 0.0
    K[:, n2] = 0.0
    kernel_hat = fft.rfft2(K)
    single = kernel_hat.astype(np.complex64)
    for a in (kernel_hat, single):
        a.setflags(write=False)  # shared by every caller of this grid
    return HalfSpace((n1, n2), dx, dy, e_star_MPa, kernel_hat, single)


@dataclass(frozen=True, eq=False)
class ContactSolution:
    """Result of :func:`solve_contact`.

    Attributes
    ----------
    pressure_MPa : (..., n1, n2) float
        Contact pressure (>= 0, 0 on masked cells).
    gap_mm : (..., n1, n2) float
        Loaded gap (>= 0 to the tolerance; 0 in contact).
    approach_mm : float
        Rigid approach (the multiplier of the load constraint, or the given one).
    load_N : (...,) float
        Total load of each grid (pressure times cell area).
    spring_mm : (...,) float
        Deflection of each grid behind its surface (the compliance's ``deflection_mm``;
        ``c_k W_k`` for rigid-body springs).
    iterations : int
    residual : float
        Final relative pressure change (the convergence measure).
    law : (3, ...) float or None
        Shared approach: each grid's law ``(k, e, c)``, its approach above its first touch
        (smallest cell gap) ``k W^e + c W`` (:func:`_shared_approach`; nan where never
        loaded): :func:`load_split` predicts a neighbouring problem's split from it.
    """

    pressure_MPa: NDArray[np.float64]
    gap_mm: NDArray[np.float64]
    approach_mm: float
    load_N: NDArray[np.float64]
    spring_mm: NDArray[np.float64]
    iterations: int
    residual: float
    law: NDArray[np.float64] | None = None


class GridCompliance(Protocol):
    """The compliance behind each grid's surface, in series with the half-space.

    Grids are numbered along the flattened batch axes (``B`` grids). The solver adds
    ``displacement(q, grids)`` to the half-space displacement of the pressure ``q`` on the
    grids ``grids``; it must act on each grid alone (block diagonal), be linear in ``q``
    and symmetric positive semi-definite for the current state (the conjugate gradients
    need it). A state may depend on the solution (tooth bending evaluated where the load
    sits): the solver calls ``update(p, tolerance)`` when its search has converged and
    searches again while it returns True (the operator moved), unless ``uniform``: a
    displacement uniform over each grid (a rigid-body spring) does not change the contact
    of a grid under a given load, only its approach.
    """

    uniform: bool

    def displacement(self, q: NDArray[np.float64], grids: NDArray[np.intp]
                     ) -> NDArray[np.float64] | None:
        """Displacement ``(k, n1, n2)`` (mm) of the pressure ``q (k, n1, n2)`` (MPa) on
        the grids ``grids (k,)``; None: none."""
        ...

    def update(self, p: NDArray[np.float64], tolerance: float) -> bool:
        """Re-evaluate the state at the pressure ``p (B, n1, n2)``; True when the operator
        changed by more than ``tolerance`` (relative)."""
        ...

    def deflection_mm(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """The reported deflection of each grid ``(B,)`` (mm) under ``p (B, n1, n2)``."""
        ...


class RigidSprings:
    """Rank-one compliance: each grid moves back as a rigid body by ``c_k W_k``.

    ``c (B,)`` in mm/N, ``W_k`` the grid's load (pressure times ``cell_area``);
    ``update(p) -> c`` (optional) re-evaluates the compliances for a pressure (springs that
    depend on where the load sits), accepted when one moved by more than the solver's
    tolerance or ``tolerance`` (relative), the larger.
    """

    uniform = True

    def __init__(self, c: ArrayLike, cell_area: float,
                 update: Callable[[NDArray[np.float64]], ArrayLike] | None = None,
                 tolerance: float = 0.0):
        self.c = _springs(c)
        self.area = cell_area
        self._update = update
        self.tolerance = tolerance

    def displacement(self, q, grids):
        c = self.c[grids]
        if not np.any(c):
            return None
        return (c * self.area * np.sum(q, axis=(1, 2)))[:, None, None]

    def update(self, p, tolerance: float) -> bool:
        if self._update is None:
            return False
        c_new = np.broadcast_to(_springs(self._update(p)), self.c.shape)
        tol = max(tolerance, self.tolerance)
        if np.any(np.abs(c_new - self.c) > tol * np.maximum(self.c, TINY)):
            self.c = c_new
            return True
        return False

    def deflection_mm(self, p):
        return self.c * self.area * np.sum(p, axis=(1, 2))


class LocalCompliance:
    """``inner`` (a :class:`GridCompliance`) plus a compliance of each cell of its own,
    ``c (B, n1, n2)`` mm/MPa: the displacement ``c q`` (a Winkler layer; diagonal, so
    linear and symmetric). ``deflection_mm`` is ``inner``'s."""

    def __init__(self, inner: GridCompliance, c: ArrayLike):
        self.inner = inner
        self.c = np.asarray(c, dtype=float)
        self.uniform = bool(inner.uniform and not np.any(self.c))

    def displacement(self, q, grids):
        v = self.inner.displacement(q, grids)
        local = self.c.reshape(-1, *q.shape[1:])[grids] * q
        return local if v is None else v + local

    def update(self, p, tolerance: float) -> bool:
        return self.inner.update(p, tolerance)

    def deflection_mm(self, p):
        return self.inner.deflection_mm(p)


def solve_contact(hs: HalfSpace, gap0_mm: ArrayLike, *, load_N: float | None = None,
                  approach_mm: float | None = None, mask: ArrayLike | None = None,
                  spring_mm_per_N: ArrayLike | None = None,
                  tolerance: float = DEFAULT_TOLERANCE, max_iter: int = MAX_ITER,
                  p0: ArrayLike | None = None, spring_update=None,
                  spring_tolerance: float = 1e-3,
                  compliance: GridCompliance | None = None) -> ContactSolution:
    """Solve ``p >= 0``, ``g >= 0``, ``p g = 0`` on one or several grids (Polonsky & Keer).

    ``g = gap0 + u(p) + v(p) - approach`` where ``u`` is the half-space displacement of
    each grid and ``v`` the compliance behind it (``compliance``, or rigid-body springs
    ``v_k = c_k W_k`` with ``W_k`` the grid's load).

    Several grids under one total load share the approach; they are solved by
    decomposition (:func:`_shared_approach`): each grid's contact under its own load by
    conjugate gradients (well conditioned, few iterations), the loads moved between the
    grids until the approaches agree.

    Parameters
    ----------
    hs : HalfSpace
    gap0_mm : (..., n1, n2) float
        Initial gap (mm) at zero approach; leading axes are independent grids that share
        the approach.
    load_N, approach_mm : float
        Exactly one: the total load over all grids (N, > 0) or the rigid approach (mm).
    mask : (..., n1, n2) bool, optional
        Cells that may carry pressure (default all).
    spring_mm_per_N : (...,) float, optional
        Rigid-body compliance of each grid in series with the half-space (>= 0).
    tolerance : float
        Stop when the relative change of the pressure field in one iteration and the gap
        error on the contact set (relative to the gap scale) are both below it, on every
        grid, and (shared approach) the grids' approaches agree to it.
    max_iter : int
        Conjugate-gradient iterations of one grid solve.
    p0 : (..., n1, n2) float, optional
        Starting pressure (warm start: a neighbouring solution); its load on each grid is
        the first split of a shared load (:func:`load_split` predicts one).
    spring_update : callable, optional
        ``spring_update(p) -> (...,)`` compliances of the springs for the current pressure
        (:class:`RigidSprings`), accepted when one moved by more than ``spring_tolerance``.
    compliance : GridCompliance, optional
        Instead of the springs: any compliance operator behind the grids.
    """
    g0 = np.asarray(gap0_mm, dtype=float)
    if g0.shape[-2:] != hs.shape:
        raise ArgumentError("gap0_mm", g0.shape, f"must end in the grid shape {hs.shape}")
    if (load_N is None) == (approach_mm is None):
        raise ArgumentError("load_N/approach_mm", (load_N, approach_mm), "give exactly one")
    batch = g0.shape[:-2]
    m = np.ones(g0.shape, bool) if mask is None else np.broadcast_to(
        np.asarray(mask, bool), g0.shape)
    if not np.all(np.isfinite(g0[m])):
        raise ArgumentError("gap0_mm", "non-finite", "must be finite on contactable cells")
    if compliance is None:
        compliance = _rigid_springs(hs, g0.shape, spring_mm_per_N, spring_update,
                                    spring_tolerance)
    if not (tolerance > 0):
        raise ArgumentError("tolerance", tolerance, "must be > 0")
    if load_N is not None:
        if not (math.isfinite(load_N) and load_N > 0):
            raise ArgumentError("load_N", load_N, "must be finite and > 0 N")
    elif approach_mm is not None:
        if not math.isfinite(approach_mm):
            raise ArgumentError("approach_mm", approach_mm, "must be finite")
        gmin = float(np.min(g0[m])) if np.any(m) else 0.0
        if approach_mm <= gmin or not np.any(m):
            z = np.zeros(g0.shape)
            return ContactSolution(z, np.where(m, g0 - approach_mm, 0.0), approach_mm,
                                   np.zeros(batch), np.zeros(batch), 0, 0.0)
    if not np.any(m):
        raise ArgumentError("mask", "empty", "no contactable cell carries the load")
    return _solve_grids(hs, g0, m, compliance, tolerance, max_iter, load_N, approach_mm, p0)


def _solve_grids(hs: HalfSpace, g0: NDArray[np.float64], m: NDArray[np.bool_],
                 compliance: GridCompliance, tolerance: float, max_iter: int,
                 load_N: float | None, approach_mm: float | None,
                 p0: ArrayLike | None) -> ContactSolution:
    """:func:`solve_contact` on checked arguments: gaps ``g0 (..., n1, n2)`` and mask
    ``m``, exactly one of ``load_N`` (shared approach) and ``approach_mm`` (given)."""
    batch = g0.shape[:-2]
    B = int(np.prod(batch, dtype=int))
    start = None if p0 is None else np.broadcast_to(np.asarray(p0, float), g0.shape)
    # grids as one leading axis
    flat = _Grids(hs, g0.reshape(B, *hs.shape), m.reshape(B, *hs.shape), compliance,
                  tolerance, max_iter)
    p_start = None if start is None else start.reshape(B, *hs.shape)
    laws = None
    if load_N is not None:
        p, alpha, it, res, laws = _shared_approach(flat, float(load_N), p_start)
        laws = laws.reshape(3, *batch)
    else:
        alpha = float(cast(float, approach_mm))  # exactly one of the two is given
        p, it, res = _given_approach(flat, alpha, p_start)
    u = flat.operator(p, np.arange(B)).reshape(g0.shape)
    deflection = np.asarray(compliance.deflection_mm(p), float).reshape(batch)
    p = p.reshape(g0.shape)
    g = u + g0 - alpha
    load = hs.cell_area * np.sum(p, axis=(-2, -1))
    return ContactSolution(p, np.where(m, g, 0.0), float(alpha), load, deflection, it, res,
                           laws)


def _rigid_springs(hs: HalfSpace, shape: tuple[int, ...], spring_mm_per_N: ArrayLike | None,
                   spring_update, spring_tolerance: float) -> RigidSprings:
    """:class:`RigidSprings` of the grids of ``shape (..., n1, n2)`` (flattened to one
    leading axis), ``spring_update`` called with the pressure in that shape."""
    batch = shape[:-2]
    B = int(np.prod(batch, dtype=int))
    c = np.zeros(batch) if spring_mm_per_N is None else np.broadcast_to(
        np.asarray(spring_mm_per_N, dtype=float), batch)
    update = None if spring_update is None else (
        lambda p: np.broadcast_to(np.asarray(spring_update(p.reshape(shape)), float),
                                  batch).reshape(B))
    return RigidSprings(c.reshape(B), hs.cell_area, update, spring_tolerance)


class _Grids:
    """The grids of one solve, flattened to ``(B, n1, n2)``, and their operator."""

    def __init__(self, hs: HalfSpace, g0, m, compliance: GridCompliance, tolerance,
                 max_iter):
        # contiguous once: the compiled search takes them as they are, split after split
        self.hs, self.g0, self.m = hs, np.ascontiguousarray(g0), np.ascontiguousarray(m)
        self.compliance = compliance
        self.tolerance, self.max_iter = tolerance, max_iter
        self.area = hs.cell_area
        self.gmin = np.min(np.where(m, g0, np.inf), axis=(1, 2))  # (B,) first touch
        span = np.max(np.where(m, g0, -np.inf), axis=(1, 2)) - self.gmin
        self.scale = np.maximum(np.where(np.isfinite(span), span, 0.0), GAP_SCALE_FLOOR_MM)
        self.tau_self = 1.0 / float(influence(0.0, 0.0, hs.dx, hs.dy, hs.e_star_MPa))

    def operator(self, q, grids, single: bool = False):
        """Displacement of the pressure ``q (k, n1, n2)`` on the grids ``grids (k,)``:
        half-space (``single``: in single precision) plus compliance."""
        u = _displacement(self.hs, q, single)
        v = self.compliance.displacement(q, grids)
        return u if v is None else u + v

    def update(self, p, tolerance: float) -> bool:
        return self.compliance.update(p, tolerance)

    def band_start(self, b):
        """Uniform pressure over the cells of grid ``b`` within the smallest-gap band."""
        g, m = self.g0[b], self.m[b]
        hi = float(np.max(g[m]))
        band = m & (g <= self.gmin[b] + 1e-3 * (hi - self.gmin[b]) + 1e-15)
        return band.astype(float)

    def too_many(self, it: int, res: float, gap: float | None = None):
        left = f"relative change {res:.3g}" + (
            "" if gap is None else f", gap residual {gap:.3g} of the gap scale")
        return GearCouplingError(
            f"contact solver did not converge in {self.max_iter} iterations ({left}; "
            f"tolerance {self.tolerance:.3g}): loosen the tolerance or coarsen the grid")


def _per_grid_loads(grids: _Grids, W: NDArray[np.float64], p: NDArray[np.float64],
                    tolerance: float, u_hs: NDArray[np.float64] | None = None
                    ) -> tuple[NDArray, NDArray, int, float, NDArray]:
    """Each grid's contact under its own load ``W (B,)`` (0: unloaded), from ``p`` (and
    its half-space displacement ``u_hs``, if known: rescaled with ``p``, not transformed).

    Polonsky & Keer's conjugate gradients with one multiplier (approach) per grid; the
    grids are independent, so each has its own step and stops on its own (a converged
    grid is left out). Solves to :data:`SINGLE_PRECISION_TOLERANCE` or looser transform in
    single precision; those to at most :data:`EXACT_BELOW` are then checked (and carried
    on where needed) in double. Returns the pressure, each loaded grid's approach (``nan``
    where unloaded), the iterations, the largest final change and the half-space
    displacement of the pressure.
    """
    if grids.compliance.uniform and np.prod(grids.hs.shape) <= COMPILED_MAX_CELLS:
        out = _per_grid_loads_compiled(compiled(), grids, W, p, tolerance)
        if out is not None:
            return out
    A, m, g0 = grids.area, grids.m, grids.g0
    B = W.shape[0]
    loaded = W > 0
    p, u = _scaled_start(grids, W, p, u_hs)
    every = np.flatnonzero(loaded)
    # single-precision transforms while their rounding stays below the tolerance (checked
    # in double precision at the end)
    noise = SINGLE_PRECISION_NOISE * np.max(np.abs(u[every]), axis=(1, 2), initial=0.0)
    single = tolerance >= SINGLE_PRECISION_TOLERANCE and bool(
        np.all(noise <= tolerance * grids.scale[every]))
    exact = tolerance <= EXACT_BELOW
    behind = grids.compliance.displacement(p[every], every)
    if behind is not None:
        u[every] += behind
    stale = np.zeros(B, dtype=bool)  # u[b] updated along the steps, not evaluated afresh
    t = np.zeros_like(p)
    G_old = np.ones(B)
    delta = np.zeros(B)
    res = np.zeros(B)
    gap_worst = 0.0
    active = loaded.copy()
    it = 0
    while np.any(active):
        it += 1
        if it > grids.max_iter:
            raise grids.too_many(it, float(np.max(res)), gap_worst)
        ix = np.flatnonzero(active)
        every_grid = ix.size == B  # views, not copies, while every grid iterates
        pa, ma, ua, ta = (p, m, u, t) if every_grid else (p[ix], m[ix], u[ix], t[ix])
        on = pa > 0
        n_on = np.maximum(np.count_nonzero(on, axis=(1, 2)), 1)
        g = ua + (g0 if every_grid else g0[ix])
        al = np.sum(g, axis=(1, 2), where=on) / n_on
        g -= al[:, None, None]
        g *= ma
        gon = g * on
        G = np.einsum("kij,kij->k", gon, gon)
        go = G_old[ix]
        beta = np.where(go > 0, delta[ix] * G / np.where(go > 0, go, 1.0), 0.0)
        ta *= on
        ta *= beta[:, None, None]
        ta += gon
        G_old[ix] = G
        r_raw = grids.operator(ta, ix, single)
        r = r_raw - (np.sum(r_raw, axis=(1, 2), where=on) / n_on)[:, None, None]
        den = np.einsum("kij,kij->k", r, ta)
        num = np.einsum("kij,kij->k", gon, ta)
        tau = np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)
        step = pa - tau[:, None, None] * ta
        pn = np.maximum(step, 0.0)
        over = (pn == 0) & (g < 0)  # g is 0 off the contactable cells
        has_over = np.any(over, axis=(1, 2))
        projected = np.any(step < 0, axis=(1, 2)) | has_over
        if np.any(has_over):
            # overlapping cells join the contact set (with a self-stiffness step when the
            # CG step is degenerate, e.g. a start on a few cells of equal gap)
            kick = np.where(has_over, np.where(tau > 0, tau, grids.tau_self), 0.0)
            pn -= kick[:, None, None] * (g * over)
        delta[ix] = np.where(has_over, 0.0, 1.0)
        tot = A * np.sum(pn, axis=(1, 2))
        for k in np.flatnonzero(tot <= 0):
            pn[k] = np.where(ma[k] & (g0[ix[k]] <= grids.gmin[ix[k]] + 1e-15), 1.0, 0.0)
            tot[k] = A * float(np.sum(pn[k]))
            projected[k] = True
        sc = W[ix] / tot
        pn *= sc[:, None, None]
        # where no cell left or joined the contact set the step is linear, and so is u
        ua -= tau[:, None, None] * r_raw
        ua *= sc[:, None, None]
        if np.any(projected):
            redo = np.flatnonzero(projected)
            ua[redo] = grids.operator(pn[redo], ix[redo], single)
        stale[ix] = ~projected
        res[ix] = np.sum(np.abs(pn - pa), axis=(1, 2)) / (tot * sc / A)
        if every_grid:
            p = pn
        else:
            u[ix], p[ix], t[ix] = ua, pn, ta
        gap_err = np.sqrt(G / n_on) / grids.scale[ix]
        gap_worst = float(np.max(gap_err, initial=0.0))
        done = (res[ix] <= tolerance) & (gap_err <= tolerance) & ~has_over
        active[ix[done]] = False
        if single and it >= SINGLE_PRECISION_ITER:  # stalled on rounding: on in double
            active[:] = False
        if np.any(active):
            continue
        if single and exact:  # converged in single precision: each grid checked in double
            single = False
            u[every] = grids.operator(p[every], every)
            stale[:] = False
            active[every] = _gap_errors(grids, u[every], p[every], every) > tolerance
            delta[:] = 0.0
        if not np.any(active) and grids.update(p, tolerance):
            # the compliance moved with the pressure: every loaded grid searches again
            # (a uniform one only moves each grid's approach)
            u[every] = grids.operator(p[every], every)
            stale[:] = False
            if not grids.compliance.uniform:
                active = loaded.copy()
                delta[:] = 0.0
    if exact and np.any(stale):
        redo = np.flatnonzero(stale)
        u[redo] = grids.operator(p[redo], redo)
    alpha = _approaches(grids, p, u, loaded)
    return p, alpha, it, float(np.max(res, initial=0.0)), u


def _scaled_start(grids: _Grids, W: NDArray[np.float64], p: NDArray[np.float64],
                  u_hs: NDArray[np.float64] | None
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The start of :func:`_per_grid_loads`: ``p (B, n1, n2)`` kept >= 0 on the
    contactable cells of the loaded grids (a band start where it carries nothing), scaled to
    the loads ``W (B,)``, and its half-space displacement (``u_hs`` rescaled where given).
    """
    loaded = W > 0
    p, scale, fresh = _start_pressure(grids, W, p)
    every = np.flatnonzero(loaded)
    u = np.zeros_like(p)
    if u_hs is None:
        fresh = loaded
    else:
        u[every] = u_hs[every] * scale[every, None, None]
    redo = np.flatnonzero(fresh)
    if redo.size:
        u[redo] = _displacement(grids.hs, p[redo])
    return p, u


def _start_pressure(grids: _Grids, W: NDArray[np.float64], p: NDArray[np.float64]
                    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """The pressure of :func:`_scaled_start`, the factor ``(B,)`` it was scaled by and the
    grids that started afresh (a band start)."""
    loaded = W > 0
    p = np.where(loaded[:, None, None] & grids.m, np.maximum(p, 0.0), 0.0)
    fresh = loaded & ~np.any(p > 0, axis=(1, 2))
    for b in np.flatnonzero(fresh):
        p[b] = grids.band_start(b)
    tot = grids.area * np.sum(p, axis=(1, 2))
    scale = np.where(loaded, W / np.where(tot > 0, tot, 1.0), 0.0)
    p *= scale[:, None, None]
    return p, scale, fresh


def _per_grid_loads_compiled(kern, grids: _Grids, W: NDArray[np.float64],
                             p: NDArray[np.float64], tolerance: float
                             ) -> tuple[NDArray, NDArray, int, float, NDArray] | None:
    """:func:`_per_grid_loads` by the compiled kernel (:func:`compiled`), for a uniform
    compliance on a small grid: each grid's search in double precision, the displacement
    by the direct sum over the contact (module :mod:`._contact_compiled`). None where a
    grid has not converged in :data:`COMPILED_MAX_ITER` iterations (a cell going in and
    out of contact at the tolerance: the batched search, which ends on rounding, takes it)."""
    loaded = W > 0
    p = np.ascontiguousarray(_start_pressure(grids, W, p)[0])
    limit = min(int(grids.max_iter), COMPILED_MAX_ITER)
    u, its, res = kern.per_grid_cg(
        offset_influence(grids.hs), grids.g0, grids.m, np.ascontiguousarray(W, dtype=float), p,
        grids.scale, grids.gmin, float(tolerance), limit, grids.area, grids.tau_self)
    if np.any(its > limit):
        return None
    grids.update(p, tolerance)  # uniform: the springs move the approaches, not the contact
    every = np.flatnonzero(loaded)
    behind = grids.compliance.displacement(p[every], every)
    if behind is not None:
        u[every] += behind
    alpha = _approaches(grids, p, u, loaded)
    return p, alpha, int(np.max(its, initial=0)), float(np.max(res, initial=0.0)), u


def _approaches(grids: _Grids, p: NDArray[np.float64], u: NDArray[np.float64],
                loaded: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Each loaded grid's approach, the mean of ``u + g0`` over its contact set (``nan``
    where unloaded); the compliance behind is then taken out of ``u`` (in place), which
    leaves the half-space displacement."""
    on = p > 0
    n_on = np.maximum(np.count_nonzero(on, axis=(1, 2)), 1)
    alpha = np.where(loaded, np.sum(u + grids.g0, axis=(1, 2), where=on) / n_on, np.nan)
    every = np.flatnonzero(loaded)
    behind = grids.compliance.displacement(p[every], every)
    if behind is not None:
        u[every] -= behind
    return alpha


MAX_SPLITS = 60  # load splits between grids sharing one approach
FIRST_SPLIT_TOLERANCE = 1e-3  # the grid solves of the first split (relative, as tolerance)
FORCING = 0.1  # later splits: grid solves to this share of the approaches' spread
CONTACT_EXPONENT = (0.5, 1.0, 0.9)  # bounds and first value of each grid's contact law


def _gap_errors(grids: _Grids, u, p, ix) -> NDArray[np.float64]:
    """Gap error of the grids ``ix`` on their contact sets, relative to their gap scale."""
    on = p > 0
    n_on = np.maximum(np.count_nonzero(on, axis=(1, 2)), 1)
    g = u + grids.g0[ix]
    g -= (np.sum(g, axis=(1, 2), where=on) / n_on)[:, None, None]
    return np.sqrt(np.sum(g * g, axis=(1, 2), where=on) / n_on) / grids.scale[ix]


def _shared_approach(grids: _Grids, W: float, p0
                     ) -> tuple[NDArray, float, int, float, NDArray]:
    """Grids under one total load ``W`` sharing one approach.

    Each grid's approach above its first touch, ``d_b(W_b)``, increases with its load;
    the split ``W_b`` is moved until the approaches agree (to ``tolerance`` of the gap
    scale) and no unloaded grid is overlapped. A grid's law is modelled through its last
    solve as ``d = k W^e + c W``: ``c W`` the compliance behind it (its deflection over
    its load), ``k W^e`` the contact (``e`` the slope between its last two solves, within
    :data:`CONTACT_EXPONENT`: Hertz 2/3, a line contact about 1); the model's equilibrium
    gives the next split (grids not yet loaded take the median law). Early splits are
    solved only as well as the split is known (inexact Newton). Returns the pressure, the
    approach, the CG iterations, the final change and the laws ``(3, B)``.
    """
    B = grids.g0.shape[0]
    A = grids.area
    tol = grids.tolerance
    scale = float(np.max(grids.scale))
    if p0 is not None and np.any(p0 > 0):
        p = np.where(grids.m, np.maximum(p0, 0.0), 0.0)
        Wb = A * np.sum(p, axis=(1, 2))
        Wb *= W / float(np.sum(Wb))
    else:  # cold: all on the grid that touches first
        p = np.zeros(grids.g0.shape)
        Wb = np.zeros(B)
        Wb[int(np.argmin(grids.gmin))] = W
    lo_e, hi_e, e0 = CONTACT_EXPONENT
    expo = np.full(B, e0)
    last_W = np.full(B, np.nan)
    last_a = np.full(B, np.nan)
    c = np.zeros(B)
    iterations = 0
    res = 0.0
    spread = math.inf
    inner = max(tol, FIRST_SPLIT_TOLERANCE)
    u_hs = None
    for _ in range(MAX_SPLITS):
        p, alpha, it, res, u_hs = _per_grid_loads(grids, Wb, p, inner, u_hs)
        iterations += it
        loaded = Wb > 0
        ref = float(np.sum(Wb[loaded] * alpha[loaded]) / W)
        spread = float(np.max(np.abs(alpha[loaded] - ref)))
        overlapped = ~loaded & (grids.gmin < ref - tol * scale)
        settled = spread <= tol * scale and not np.any(overlapped) and inner <= tol
        # inexact steps: each split solved only as well as the split itself is known; a
        # split solved more loosely than that is solved again before the laws learn from it
        wanted = max(tol, min(inner, FORCING * spread / scale))
        again = wanted < 0.5 * inner and not np.any(overlapped)
        inner = wanted
        if again and not settled:
            continue
        # each loaded grid's law through this solve
        defl = np.asarray(grids.compliance.deflection_mm(p), float).reshape(B)
        c = np.where(loaded, np.maximum(defl, 0.0) / np.where(loaded, Wb, 1.0), c)
        a = np.where(loaded, np.maximum(alpha - grids.gmin - c * Wb, TINY), np.nan)
        moved = loaded & (last_W > 0) & (np.abs(Wb / np.where(last_W > 0, last_W, 1.0) - 1)
                                         > 1e-6)
        with np.errstate(invalid="ignore", divide="ignore"):
            slope = np.log(a / last_a) / np.log(Wb / last_W)
        expo = np.where(moved & np.isfinite(slope), np.clip(slope, lo_e, hi_e), expo)
        last_W = np.where(loaded, Wb, last_W)
        last_a = np.where(loaded, a, last_a)
        known = last_W > 0
        k = np.where(known, last_a / np.where(known, last_W, 1.0) ** expo, np.nan)
        if settled:
            return p, ref, iterations, res, np.stack([k, np.where(known, expo, np.nan),
                                                      np.where(known, c, np.nan)])
        Wb = _model_split(grids.gmin, np.where(known, k, np.median(k[known])),
                          np.where(known, expo, np.median(expo[known])),
                          np.where(known, c, np.median(c[known])), W)
    raise GearCouplingError(f"contact solver: the load split between {B} grids did not "
                            f"settle in {MAX_SPLITS} rounds (approach spread {spread:.3g} mm)")


def load_split(first_touch_mm: ArrayLike, law: ArrayLike, load_N: float
               ) -> NDArray[np.float64]:
    """Loads ``(B,)`` of grids sharing one approach under ``load_N``, each from its law
    ``(k, e, c)`` (``law (3, B)``, :attr:`ContactSolution.law`; nan: the median law) above
    its first touch ``first_touch_mm (B,)`` (inf: never touches): a first split for a
    neighbouring problem."""
    g = np.asarray(first_touch_mm, dtype=float)
    k, e, c = np.asarray(law, dtype=float)
    known = np.isfinite(k) & np.isfinite(e) & np.isfinite(c)
    if not np.any(known):
        raise ArgumentError("law", "no known law", "load_split needs a grid with a known law")
    lo_e, hi_e, _ = CONTACT_EXPONENT
    fill = [np.where(known, v, np.median(v[known])) for v in (k, e, c)]
    return _model_split(g, np.maximum(fill[0], TINY), np.clip(fill[1], lo_e, hi_e),
                        np.maximum(fill[2], 0.0), float(load_N))


def _law_loads(x, k, e, c):
    """Loads ``w >= 0`` with ``k w^e + c w = x`` (``x >= 0``, ``0 < e <= 1``: concave, so
    Newton from a lower bound climbs monotonically) and ``dw/dx``."""
    pos = x > 0
    xs = np.where(pos, x, 1.0)
    with np.errstate(over="ignore"):  # a power past the float range: the linear bound wins
        w = np.minimum((0.5 * xs / k) ** (1.0 / e), np.where(c > 0, 0.5 * xs / np.where(
            c > 0, c, 1.0), np.inf))
    for _ in range(30):
        f = k * w**e + c * w - xs
        fp = e * k * w ** (e - 1.0) + c
        step = f / fp
        w = w - step
        if np.all(np.abs(step) <= 1e-14 * w):
            break
    fp = e * k * w ** (e - 1.0) + c
    return np.where(pos, w, 0.0), np.where(pos, 1.0 / fp, 0.0)


def _model_split(gmin, k, e, c, W: float) -> NDArray[np.float64]:
    """Loads ``W_b`` summing to ``W`` under a common approach ``a``, each grid's load from
    its law ``k W^e + c W = a - gmin_b`` (:func:`_law_loads`; ``a`` by Newton from above:
    the total load is convex in ``a``, so Newton falls monotonically to the root)."""
    finite = np.isfinite(gmin)
    g = np.where(finite, gmin, 0.0)
    # from above: the approach at which the first-touching grid alone carries W
    a = float(np.min(np.where(finite, g + k * W**e + c * W, np.inf)))
    for _ in range(100):
        w, dw = _law_loads(np.where(finite, np.maximum(a - g, 0.0), 0.0), k, e, c)
        excess = float(np.sum(w)) - W
        slope = float(np.sum(dw))
        if excess <= 1e-13 * W or slope <= 0:
            break
        a -= excess / slope
    total = float(np.sum(w))
    if total > 0:
        return w * (W / total)
    # a load so small that every law's load underflows: the first-touching grids share it
    first = finite & (g <= np.min(np.where(finite, g, np.inf)))
    return np.where(first, W / max(int(np.sum(first)), 1), 0.0)


def _given_approach(grids: _Grids, approach: float, p0) -> tuple[NDArray, int, float]:
    """Grids at a given approach (independent of each other): Polonsky & Keer."""
    m, g0 = grids.m, grids.g0
    every = np.arange(g0.shape[0])
    gmin = float(np.min(grids.gmin))
    if p0 is not None:
        p = np.where(m, np.maximum(p0, 0.0), 0.0)
    else:
        p = np.zeros(g0.shape)
    if not np.any(p > 0):
        p = np.stack([grids.band_start(b) for b in range(g0.shape[0])])
    if not np.any(p > 0):
        p = m.astype(float)
    # scale a first guess so the gap at the start cells roughly closes
    u1 = grids.operator(p, every)
    on = p > 0
    p *= divide(max(approach - gmin, 0.0), float(np.max(u1[on])))
    scale_len = float(np.max(grids.scale))
    delta, G_old = 0.0, 1.0
    t = np.zeros_like(p)
    u = grids.operator(p, every)
    res = math.inf
    it = 0
    while True:
        it += 1
        if it > grids.max_iter:
            raise grids.too_many(it, res)
        on = p > 0
        g = np.where(m, u + g0 - approach, 0.0)
        G = float(np.sum(g[on] ** 2))
        t = np.where(on, g + (delta * G / G_old if G_old > 0 else 0.0) * t, 0.0)
        G_old = G
        r = grids.operator(t, every)
        den = float(np.sum(r[on] * t[on]))
        tau = float(np.sum(g[on] * t[on])) / den if den > 0 else 0.0
        p_old = p
        p = np.maximum(p - tau * t, 0.0)
        over = m & (p == 0) & (g < 0)
        if np.any(over):
            delta = 0.0
            p = p - (tau if tau > 0 else grids.tau_self) * np.where(over, g, 0.0)
        else:
            delta = 1.0
        p = np.where(m, p, 0.0)
        u = grids.operator(p, every)
        res = divide(float(np.sum(np.abs(p - p_old))), float(np.sum(p)))
        gap_err = math.sqrt(G / max(int(np.count_nonzero(on)), 1)) / scale_len
        converged = res <= grids.tolerance and gap_err <= grids.tolerance and not np.any(over)
        if (converged or it % SPRING_EVERY == 0) and grids.update(p, grids.tolerance):
            delta = 0.0
            u = grids.operator(p, every)
            continue
        if converged:
            return p, it, res


def _displacement(hs: HalfSpace, q: NDArray[np.float64], single: bool = False
                  ) -> NDArray[np.float64]:
    """``hs.displacement(q)``, transforming only the grids that carry any pressure."""
    if q.ndim < 3:
        return hs.displacement(q, single)
    lead = q.shape[:-2]
    flat = q.reshape(-1, *hs.shape)
    busy = np.flatnonzero(np.any(flat != 0.0, axis=(1, 2)))
    if busy.size == flat.shape[0]:
        return hs.displacement(q, single)
    out = np.zeros(flat.shape)
    if busy.size:
        out[busy] = hs.displacement(flat[busy], single)
    return out.reshape(*lead, *hs.shape)


def _springs(c) -> NDArray[np.float64]:
    c = np.asarray(c, dtype=float)
    if np.any(~np.isfinite(c)) or np.any(c < 0):
        raise ArgumentError("spring_mm_per_N", c, "must be finite and >= 0")
    return c


def hertz_ellipse(load_N: float, rx_mm: float, ry_mm: float, e_star_MPa: float
                  ) -> dict[str, float]:
    """Hertz's elliptic contact of the gap ``x^2/(2 rx) + y^2/(2 ry)`` under ``load_N``.

    Returns ``a_mm`` (semi-axis along x), ``b_mm`` (along y), ``p0_MPa`` and the approach
    ``delta_mm`` (Johnson, *Contact Mechanics*, §3.5: eccentricity from
    ``B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e))``).
    """
    from scipy.optimize import brentq
    from scipy.special import ellipe, ellipk

    A, B = 0.5 / rx_mm, 0.5 / ry_mm
    swap = A > B
    if swap:
        A, B = B, A

    def ratio(e2):
        K, E = ellipk(e2), ellipe(e2)
        return (E / (1.0 - e2) - K) / (K - E)

    if B / A - 1.0 < 1e-12:
        e2 = 0.0
        kme = math.pi / 4.0  # (K - E) / e^2 as e -> 0
        K = E = math.pi / 2.0
    else:
        e2 = brentq(lambda v: ratio(v) - B / A, 1e-12, 1.0 - 1e-15, xtol=1e-15, rtol=1e-15)
        K, E = float(ellipk(e2)), float(ellipe(e2))
        kme = (K - E) / e2
    a = (3.0 * load_N * kme / (2.0 * math.pi * A * e_star_MPa)) ** (1.0 / 3.0)
    b = a * math.sqrt(1.0 - e2)
    p0 = 3.0 * load_N / (2.0 * math.pi * a * b)
    delta = p0 * b * K / e_star_MPa
    if swap:
        a, b = b, a
    return {"a_mm": a, "b_mm": b, "p0_MPa": p0, "delta_mm": delta}
