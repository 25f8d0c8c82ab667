"""Elastic half-space contact on a regular grid: influence coefficients, DC-FFT, CG solver.

Pure numpy/scipy kernel (no mesh, CAD or solver import).

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
  load constraint (given total load) or given. Several independent grids (teeth) may be
  solved together, sharing one approach and one load, each with an optional rank-one
  compliance (a rigid-body spring in series, e.g. tooth bending: the whole grid moves back
  by ``c_k * W_k``), which keeps the operator symmetric positive definite.

Units: lengths in mm, pressures and moduli in MPa (N/mm^2), forces in N.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import fft

from ..errors import GearCouplingError, SpecError

DEFAULT_TOLERANCE = 1e-8  # relative: |dp| summed / |p| summed and gap residual / gap scale
MAX_ITER = 4000
SPRING_EVERY = 10  # iterations between updates of position-dependent springs


def composite_modulus(e1_MPa: float, nu1: float, e2_MPa: float, nu2: float) -> float:
    """Composite (contact) modulus ``E*`` with ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2`` (MPa)."""
    for name, e, nu in (("youngs_modulus_MPa (1)", e1_MPa, nu1),
                        ("youngs_modulus_MPa (2)", e2_MPa, nu2)):
        if not (math.isfinite(e) and e > 0):
            raise SpecError(name, e, "must be a finite modulus > 0 MPa")
        if not (math.isfinite(nu) and -1.0 < nu < 0.5):
            raise SpecError("poisson_ratio", nu, "must be in (-1, 0.5)")
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

    @property
    def cell_area(self) -> float:
        return self.dx * self.dy

    def displacement(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        # 2-D FFT as two 1-D passes that skip the zero padding on the way in and the
        # discarded half on the way out (about 30 % less work than rfft2/irfft2)
        n1, n2 = self.shape
        h = fft.fft(fft.rfft(p, n=2 * n2, axis=-1), n=2 * n1, axis=-2)
        h *= self.kernel_hat
        h = fft.ifft(h, axis=-2)[..., :n1, :]
        return fft.irfft(h, n=2 * n2, axis=-1)[..., :n2]

    def direct(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """The same convolution by the direct double sum (slow; for checks)."""
        n1, n2 = self.shape
        i = np.arange(n1)
        j = np.arange(n2)
        K = influence((i[:, None, None, None] - i[None, None, :, None]) * self.dx,
                      (j[None, :, None, None] - j[None, None, None, :]) * self.dy,
                      self.dx, self.dy, self.e_star_MPa)
        return np.einsum("abcd,...cd->...ab", K, p)


def half_space(shape: tuple[int, int], dx: float, dy: float, e_star_MPa: float) -> HalfSpace:
    """The DC-FFT operator of a grid: coefficients for offsets ``-(n-1)..(n-1)`` wrapped into
    a ``2n1 x 2n2`` array (offset ``k < 0`` at index ``2n + k``; index ``n`` unused)."""
    n1, n2 = (int(v) for v in shape)
    if n1 < 1 or n2 < 1:
        raise SpecError("grid", shape, "needs at least 1 x 1 cells")
    if not (dx > 0 and dy > 0 and math.isfinite(dx) and math.isfinite(dy)):
        raise SpecError("cell size", (dx, dy), "must be finite and > 0 mm")
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
    kernel_hat.setflags(write=False)  # shared by every caller of this grid
    return HalfSpace((n1, n2), dx, dy, e_star_MPa, kernel_hat)


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
    """

    pressure_MPa: NDArray[np.float64]
    gap_mm: NDArray[np.float64]
    approach_mm: float
    load_N: NDArray[np.float64]
    spring_mm: NDArray[np.float64]
    iterations: int
    residual: float


class GridCompliance(Protocol):
    """The compliance behind each grid's surface, in series with the half-space.

    The solver adds ``displacement(q)`` to the half-space displacement of a pressure
    ``q``; it must be linear in ``q`` and symmetric positive semi-definite (the conjugate
    gradients need it) for the current state. A state may depend on the solution (tooth
    bending evaluated where the load sits): the solver calls ``update(p)`` every
    :data:`SPRING_EVERY` iterations and at convergence, and restarts its search whenever it
    returns True (the operator moved), stopping only when it returns False.
    """

    def displacement(self, q: NDArray[np.float64]) -> NDArray[np.float64] | None:
        """Displacement ``(..., n1, n2)`` (mm) of pressure ``q`` (MPa); None: none."""
        ...

    def update(self, p: NDArray[np.float64], tolerance: float) -> bool:
        """Re-evaluate the state at pressure ``p``; True when the operator changed by
        more than ``tolerance`` (relative)."""
        ...

    def deflection_mm(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        """The reported deflection of each grid ``(...,)`` (mm) under ``p``."""
        ...


class RigidSprings:
    """Rank-one compliance: each grid moves back as a rigid body by ``c_k W_k``.

    ``c (...,)`` in mm/N, ``W_k`` the grid's load (pressure times ``cell_area``);
    ``update(p) -> c`` (optional) re-evaluates the compliances for a pressure (springs that
    depend on where the load sits), accepted when one moved by more than ``tolerance``
    (relative).
    """

    def __init__(self, c: ArrayLike, batch: tuple[int, ...], cell_area: float,
                 update: Callable[[NDArray[np.float64]], ArrayLike] | None = None,
                 tolerance: float = 1e-3):
        self.c = _springs(c, batch)
        self.batch = batch
        self.area = cell_area
        self._update = update
        self.tolerance = tolerance

    def displacement(self, q):
        if not np.any(self.c):
            return None
        return (self.c * self.area * np.sum(q, axis=(-2, -1)))[..., None, None]

    def update(self, p, tolerance: float) -> bool:
        if self._update is None:
            return False
        c_new = _springs(self._update(p), self.batch)
        tol = max(tolerance, self.tolerance)
        if np.any(np.abs(c_new - self.c) > tol * np.maximum(self.c, 1e-300)):
            self.c = c_new
            return True
        return False

    def deflection_mm(self, p):
        return self.c * self.area * np.sum(p, axis=(-2, -1))


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
        Starting pressure (warm start: a neighbouring solution; it also gives the first
        split of the load between grids).
    spring_update : callable, optional
        ``spring_update(p) -> (...,)`` compliances of the springs for the current pressure
        (:class:`RigidSprings`), accepted when one moved by more than ``spring_tolerance``.
    compliance : GridCompliance, optional
        Instead of the springs: any compliance operator behind the grids.
    """
    g0 = np.asarray(gap0_mm, dtype=float)
    if g0.shape[-2:] != hs.shape:
        raise SpecError("gap0_mm", g0.shape, f"must end in the grid shape {hs.shape}")
    if (load_N is None) == (approach_mm is None):
        raise SpecError("load_N/approach_mm", (load_N, approach_mm), "give exactly one")
    batch = g0.shape[:-2]
    m = np.ones(g0.shape, bool) if mask is None else np.broadcast_to(
        np.asarray(mask, bool), g0.shape)
    if not np.all(np.isfinite(g0[m])):
        raise SpecError("gap0_mm", "non-finite", "must be finite on contactable cells")
    if compliance is None:
        compliance = RigidSprings(np.zeros(batch) if spring_mm_per_N is None
                                  else spring_mm_per_N, batch, hs.cell_area, spring_update,
                                  spring_tolerance)
    if not (tolerance > 0):
        raise SpecError("tolerance", tolerance, "must be > 0")
    gmin = float(np.min(g0[m])) if np.any(m) else 0.0
    if load_N is not None:
        if not (math.isfinite(load_N) and load_N > 0):
            raise SpecError("load_N", load_N, "must be finite and > 0 N")
    elif approach_mm is not None:
        if not math.isfinite(approach_mm):
            raise SpecError("approach_mm", approach_mm, "must be finite")
        if approach_mm <= gmin or not np.any(m):
            z = np.zeros(g0.shape)
            return ContactSolution(z, np.where(m, g0 - approach_mm, 0.0), approach_mm,
                                   np.zeros(batch), np.zeros(batch), 0, 0.0)
    if not np.any(m):
        raise SpecError("mask", "empty", "no contactable cell carries the load")
    start = None if p0 is None else np.broadcast_to(np.asarray(p0, float), g0.shape)
    # grids as one leading axis
    B = int(np.prod(batch, dtype=int))
    flat = _Grids(hs, g0.reshape(B, *hs.shape), m.reshape(B, *hs.shape), compliance, batch,
                  tolerance, max_iter)
    p_start = None if start is None else start.reshape(B, *hs.shape)
    if load_N is not None:
        p, alpha, it, res = _shared_approach(flat, float(load_N), p_start)
    else:
        p, it, res = _given_approach(flat, float(approach_mm), p_start)
        alpha = float(approach_mm)
    p = p.reshape(g0.shape)
    u = flat.operator(p.reshape(B, *hs.shape)).reshape(g0.shape)
    g = u + g0 - alpha
    load = hs.cell_area * np.sum(p, axis=(-2, -1))
    return ContactSolution(p, np.where(m, g, 0.0), float(alpha), load,
                           compliance.deflection_mm(p), it, res)


class _Grids:
    """The grids of one solve, flattened to ``(B, n1, n2)``, and their operator."""

    def __init__(self, hs: HalfSpace, g0, m, compliance: GridCompliance, batch, tolerance,
                 max_iter):
        self.hs, self.g0, self.m = hs, g0, m
        self.compliance, self.batch = compliance, batch
        self.tolerance, self.max_iter = tolerance, max_iter
        self.area = hs.cell_area
        self.gmin = np.min(np.where(m, g0, np.inf), axis=(1, 2))  # (B,) first touch
        span = np.max(np.where(m, g0, -np.inf), axis=(1, 2)) - self.gmin
        self.scale = np.maximum(np.where(np.isfinite(span), span, 0.0), 1e-12)
        self.tau_self = 1.0 / float(influence(0.0, 0.0, hs.dx, hs.dy, hs.e_star_MPa))

    def operator(self, q):
        """Displacement of pressure ``q (B, n1, n2)``: half-space plus compliance."""
        u = _displacement(self.hs, q)
        shape = (*self.batch, *self.hs.shape)
        v = self.compliance.displacement(q.reshape(shape))
        return u if v is None else u + np.broadcast_to(v, shape).reshape(u.shape)

    def update(self, p, tolerance: float) -> bool:
        return self.compliance.update(p.reshape(*self.batch, *self.hs.shape), tolerance)

    def band_start(self, b):
        """Uniform pressure over the cells of grid ``b`` within the smallest-gap band."""
        g, m = self.g0[b], self.m[b]
        hi = float(np.max(g[m]))
        band = m & (g <= self.gmin[b] + 1e-3 * (hi - self.gmin[b]) + 1e-15)
        return band.astype(float)

    def too_many(self, it: int, res: float):
        return GearCouplingError(
            f"contact solver did not converge in {self.max_iter} iterations (relative "
            f"change {res:.3g} > tolerance {self.tolerance:.3g}): loosen the tolerance or "
            "coarsen the grid")


def _per_grid_loads(grids: _Grids, W: NDArray[np.float64], p: NDArray[np.float64],
                    tolerance: float) -> tuple[NDArray, NDArray, int, float]:
    """Each grid's contact under its own load ``W (B,)`` (0: unloaded), from ``p``.

    Polonsky & Keer's conjugate gradients with one multiplier (approach) per grid; the
    grids are independent, so each has its own step and stops on its own (a converged
    grid is left out of the transforms). Returns the pressure, each loaded grid's
    approach (``nan`` where unloaded), the iterations and the largest final change.
    """
    A, m, g0 = grids.area, grids.m, grids.g0
    B = W.shape[0]
    loaded = W > 0
    p = np.where(loaded[:, None, None] & m, np.maximum(p, 0.0), 0.0)
    for b in np.flatnonzero(loaded & ~np.any(p > 0, axis=(1, 2))):
        p[b] = grids.band_start(b)
    tot = A * np.sum(p, axis=(1, 2))
    p *= np.where(loaded, W / np.where(tot > 0, tot, 1.0), 0.0)[:, None, None]
    u = grids.operator(p)
    exact = np.ones(B, dtype=bool)  # u[b] evaluated afresh, not updated along the steps
    t = np.zeros_like(p)
    G_old = np.ones(B)
    delta = np.zeros(B)
    res = np.zeros(B)
    active = loaded.copy()
    it = 0
    while np.any(active):
        it += 1
        if it > grids.max_iter:
            raise grids.too_many(it, float(np.max(res)))
        ix = np.flatnonzero(active)
        pa, ma, ua = p[ix], m[ix], u[ix]
        on = pa > 0
        n_on = np.maximum(np.count_nonzero(on, axis=(1, 2)), 1)
        g = ua + g0[ix]
        al = np.sum(np.where(on, g, 0.0), axis=(1, 2)) / n_on
        g = np.where(ma, g - al[:, None, None], 0.0)
        G = np.sum(np.where(on, g * g, 0.0), axis=(1, 2))
        go = G_old[ix]
        beta = np.where(go > 0, delta[ix] * G / np.where(go > 0, go, 1.0), 0.0)
        ta = np.where(on, g + beta[:, None, None] * t[ix], 0.0)
        G_old[ix] = G
        full = np.zeros_like(p)
        full[ix] = ta
        r_raw = grids.operator(full)[ix]
        r = r_raw - (np.sum(np.where(on, r_raw, 0.0), axis=(1, 2)) / n_on)[:, None, None]
        den = np.sum(np.where(on, r * ta, 0.0), axis=(1, 2))
        num = np.sum(np.where(on, g * ta, 0.0), axis=(1, 2))
        tau = np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)
        step = pa - tau[:, None, None] * ta
        pn = np.maximum(step, 0.0)
        over = ma & (pn == 0) & (g < 0)
        has_over = np.any(over, axis=(1, 2))
        projected = np.any(step < 0, axis=(1, 2)) | has_over
        # overlapping cells join the contact set (with a self-stiffness step when the CG
        # step is degenerate, e.g. a start on a few cells of equal gap)
        kick = np.where(has_over, np.where(tau > 0, tau, grids.tau_self), 0.0)
        pn = np.where(ma, pn - kick[:, None, None] * np.where(over, g, 0.0), 0.0)
        delta[ix] = np.where(has_over, 0.0, 1.0)
        tot = A * np.sum(pn, axis=(1, 2))
        for k in np.flatnonzero(tot <= 0):
            pn[k] = np.where(ma[k] & (g0[ix[k]] <= grids.gmin[ix[k]] + 1e-15), 1.0, 0.0)
            tot[k] = A * float(np.sum(pn[k]))
            projected[k] = True
        sc = W[ix] / tot
        pn *= sc[:, None, None]
        # no cell left or joined the contact set: the step is linear, so is u
        u[ix] = (ua - tau[:, None, None] * r_raw) * sc[:, None, None]
        exact[ix] = False
        redo = ix[projected]
        if redo.size:
            full = np.zeros_like(p)
            full[redo] = pn[projected]
            u[redo] = grids.operator(full)[redo]
            exact[redo] = True
        res[ix] = np.sum(np.abs(pn - pa), axis=(1, 2)) / np.maximum(np.sum(pn, axis=(1, 2)),
                                                                     1e-300)
        p[ix] = pn
        t[ix] = ta
        gap_err = np.sqrt(G / n_on) / grids.scale[ix]
        done = (res[ix] <= tolerance) & (gap_err <= tolerance) & ~has_over
        active[ix[done]] = False
        if not np.any(active) and grids.update(p, tolerance):
            # the compliance moved with the pressure: every loaded grid starts again
            active = loaded.copy()
            delta[:] = 0.0
            u = grids.operator(p)
            exact[:] = True
    if not np.all(exact):
        u = grids.operator(p)
    on = p > 0
    n_on = np.maximum(np.count_nonzero(on, axis=(1, 2)), 1)
    alpha = np.where(loaded, np.sum(np.where(on, u + g0, 0.0), axis=(1, 2)) / n_on, np.nan)
    return p, alpha, it, float(np.max(res, initial=0.0))


MAX_SPLITS = 60  # load splits between grids sharing one approach
FIRST_SPLIT_TOLERANCE = 1e-3  # the grid solves of the first split (relative, as tolerance)
POWER_LAW = (0.3, 1.5, 0.8)  # bounds and first value of each grid's law exponent


def _shared_approach(grids: _Grids, W: float, p0) -> tuple[NDArray, float, int, float]:
    """Grids under one total load ``W`` sharing one approach: each grid's approach above
    its first touch, ``d_b(W_b)``, increases with its load; the split ``W_b`` is moved
    until the approaches agree (to ``tolerance`` of the gap scale) and no unloaded grid
    is overlapped. Each grid's law is modelled as ``d = k W^e`` through its last solve
    (``e`` the slope between its last two, :data:`POWER_LAW`), the model's equilibrium
    gives the next split (a secant step per grid; grids not yet loaded take the median
    law). Returns the pressure, the approach, the CG iterations and the final change."""
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
    lo_e, hi_e, e0 = POWER_LAW
    expo = np.full(B, e0)
    last_W = np.full(B, np.nan)
    last_d = np.full(B, np.nan)
    iterations = 0
    res = 0.0
    inner = max(tol, FIRST_SPLIT_TOLERANCE)
    for _ in range(MAX_SPLITS):
        p, alpha, it, res = _per_grid_loads(grids, Wb, p, inner)
        iterations += it
        loaded = Wb > 0
        ref = float(np.sum(Wb[loaded] * alpha[loaded]) / W)
        spread = float(np.max(np.abs(alpha[loaded] - ref)))
        overlapped = ~loaded & (grids.gmin < ref - tol * scale)
        if spread <= tol * scale and not np.any(overlapped) and inner <= tol:
            return p, ref, iterations, res
        # inexact steps: each split solved only as well as the split itself is known
        inner = max(tol, min(inner, 0.1 * spread / scale))
        d = np.where(loaded, np.maximum(alpha - grids.gmin, 1e-300), np.nan)
        ok = loaded & (last_W > 0) & (np.abs(Wb / np.where(last_W > 0, last_W, 1.0) - 1)
                                      > 1e-6)
        with np.errstate(invalid="ignore", divide="ignore"):
            slope = np.log(d / last_d) / np.log(Wb / last_W)
        expo = np.where(ok & np.isfinite(slope), np.clip(slope, lo_e, hi_e), expo)
        last_W = np.where(loaded, Wb, last_W)
        last_d = np.where(loaded, d, last_d)
        k = np.where(last_W > 0, last_d / np.where(last_W > 0, last_W, 1.0) ** expo, np.nan)
        known = np.isfinite(k)
        k = np.where(known, k, np.median(k[known]))
        expo = np.where(known, expo, np.median(expo[known]))
        Wb = _model_split(grids.gmin, k, expo, W)
    raise GearCouplingError(f"contact solver: the load split between {B} grids did not "
                            f"settle in {MAX_SPLITS} rounds (approach spread {spread:.3g} mm)")


def _model_split(gmin, k, expo, W: float) -> NDArray[np.float64]:
    """Loads ``W_b = ((a - gmin_b)+ / k_b)^(1/e_b)`` summing to ``W`` (``a`` by Brent)."""
    from scipy.optimize import brentq

    finite = np.isfinite(gmin)

    def split(a):
        x = np.where(finite, np.maximum(a - np.where(finite, gmin, 0.0), 0.0), 0.0)
        return (x / k) ** (1.0 / expo)

    def excess(a):
        return float(np.sum(split(a))) - W

    lo = float(np.min(gmin[finite]))
    hi = float(np.min(np.where(finite, gmin + k * W ** expo, np.inf)))
    a = brentq(excess, lo, hi, xtol=1e-15 * max(abs(hi), 1e-300), rtol=1e-14)
    Wb = split(a)
    return Wb * (W / float(np.sum(Wb)))


def _given_approach(grids: _Grids, approach: float, p0) -> tuple[NDArray, int, float]:
    """Grids at a given approach (independent of each other): Polonsky & Keer."""
    m, g0 = grids.m, grids.g0
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
    u1 = grids.operator(p)
    on = p > 0
    p *= max(approach - gmin, 0.0) / max(float(np.max(u1[on])), 1e-300)
    scale_len = float(np.max(grids.scale))
    delta, G_old = 0.0, 1.0
    t = np.zeros_like(p)
    u = grids.operator(p)
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
        r = grids.operator(t)
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
        u = grids.operator(p)
        res = float(np.sum(np.abs(p - p_old))) / max(float(np.sum(p)), 1e-300)
        gap_err = math.sqrt(G / max(int(np.count_nonzero(on)), 1)) / scale_len
        converged = res <= grids.tolerance and gap_err <= grids.tolerance and not np.any(over)
        if (converged or it % SPRING_EVERY == 0) and grids.update(p, grids.tolerance):
            delta = 0.0
            u = grids.operator(p)
            continue
        if converged:
            return p, it, res


def _displacement(hs: HalfSpace, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """``hs.displacement(q)``, transforming only the grids that carry any pressure."""
    if q.ndim < 3:
        return hs.displacement(q)
    lead = q.shape[:-2]
    flat = q.reshape(-1, *hs.shape)
    busy = np.flatnonzero(np.any(flat != 0.0, axis=(1, 2)))
    if busy.size == flat.shape[0]:
        return hs.displacement(q)
    out = np.zeros(flat.shape)
    if busy.size:
        out[busy] = hs.displacement(flat[busy])
    return out.reshape(*lead, *hs.shape)


def _springs(c, batch) -> NDArray[np.float64]:
    c = np.broadcast_to(np.asarray(c, dtype=float), batch)
    if np.any(~np.isfinite(c)) or np.any(c < 0):
        raise SpecError("spring_mm_per_N", c, "must be finite and >= 0")
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
