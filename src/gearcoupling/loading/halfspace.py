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
from dataclasses import dataclass

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
    i = np.arange(2 * n1)
    j = np.arange(2 * n2)
    oi = np.where(i < n1, i, i - 2 * n1).astype(float)
    oj = np.where(j < n2, j, j - 2 * n2).astype(float)
    K = influence(oi[:, None] * dx, oj[None, :] * dy, dx, dy, e_star_MPa)
    K[n1, :] = 0.0
    K[:, n2] = 0.0
    return HalfSpace((n1, n2), float(dx), float(dy), float(e_star_MPa), fft.rfft2(K))


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
        Rigid-body spring deflection of each grid ``c_k W_k``.
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


def solve_contact(hs: HalfSpace, gap0_mm: ArrayLike, *, load_N: float | None = None,
                  approach_mm: float | None = None, mask: ArrayLike | None = None,
                  spring_mm_per_N: ArrayLike | None = None,
                  tolerance: float = DEFAULT_TOLERANCE, max_iter: int = MAX_ITER,
                  p0: ArrayLike | None = None, spring_update=None,
                  spring_tolerance: float = 1e-3) -> ContactSolution:
    """Solve ``p >= 0``, ``g >= 0``, ``p g = 0`` on one or several grids (Polonsky & Keer).

    ``g = gap0 + u(p) + c_k W_k - approach`` where ``u`` is the half-space displacement of
    each grid, ``W_k`` its load and ``c_k`` its spring compliance.

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
        error on the contact set (relative to the approach scale) are both below it.
    max_iter : int
    p0 : (..., n1, n2) float, optional
        Starting pressure (warm start).
    spring_update : callable, optional
        ``spring_update(p) -> (...,)`` compliances for the current pressure (springs that
        depend on where the load sits, e.g. tooth bending at the load centre): evaluated
        every few iterations and at convergence; the iteration restarts from steepest
        descent whenever a compliance moved by more than ``spring_tolerance`` (relative),
        and stops only when none did.
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
    c = np.zeros(batch) if spring_mm_per_N is None else _springs(spring_mm_per_N, batch)
    if not (tolerance > 0):
        raise SpecError("tolerance", tolerance, "must be > 0")
    A = hs.cell_area
    g_w = np.where(m, g0, np.inf)
    gmin = float(np.min(g_w)) if np.any(m) else 0.0
    given_load = load_N is not None
    W = approach = 0.0  # exactly one is given (checked above) and used
    if load_N is not None:
        if not (math.isfinite(load_N) and load_N > 0):
            raise SpecError("load_N", load_N, "must be finite and > 0 N")
        W = float(load_N)
    elif approach_mm is not None:
        if not math.isfinite(approach_mm):
            raise SpecError("approach_mm", approach_mm, "must be finite")
        if approach_mm <= gmin or not np.any(m):
            z = np.zeros(g0.shape)
            return ContactSolution(z, np.where(m, g0 - approach_mm, 0.0), approach_mm,
                                   np.zeros(batch), np.zeros(batch), 0, 0.0)
        approach = float(approach_mm)
    if not np.any(m):
        raise SpecError("mask", "empty", "no contactable cell carries the load")

    def operator(q):
        u = hs.displacement(q)
        if np.any(c):
            wk = A * np.sum(q, axis=(-2, -1))
            u = u + (c * wk)[..., None, None]
        return u

    # start: uniform pressure over the cells within the smallest-gap band
    if p0 is not None:
        p = np.where(m, np.maximum(np.asarray(p0, float), 0.0), 0.0)
    else:
        band = m & (g_w <= gmin + 1e-3 * (np.max(g0[m]) - gmin) + 1e-15)
        p = band.astype(float)
    if not np.any(p > 0):
        p = m.astype(float)
    if given_load:
        p *= W / (A * np.sum(p))
    else:
        # scale a first guess so the gap at the start cells roughly closes
        u1 = operator(p)
        on = p > 0
        s = max(approach - gmin, 0.0) / max(float(np.max(u1[on])), 1e-300)
        p *= s
    scale_len = max(float(np.max(np.abs(g0[m] - gmin))), 1e-12)
    delta, G_old = 0.0, 1.0
    tau_self = 1.0 / float(influence(0.0, 0.0, hs.dx, hs.dy, hs.e_star_MPa))
    t = np.zeros_like(p)
    u = operator(p)
    res = math.inf
    alpha = approach if not given_load else 0.0
    it = 0
    while True:
        it += 1
        if it > max_iter:
            raise GearCouplingError(
                f"contact solver did not converge in {max_iter} iterations (relative "
                f"change {res:.3g} > tolerance {tolerance:.3g}): loosen the tolerance or "
                "coarsen the grid")
        on = p > 0
        g = u + g0
        if given_load:
            alpha = float(np.mean(g[on]))
        else:
            alpha = approach
        g = np.where(m, g - alpha, 0.0)
        G = float(np.sum(g[on] ** 2))
        t = np.where(on, g + (delta * G / G_old if G_old > 0 else 0.0) * t, 0.0)
        G_old = G
        r = operator(t)
        if given_load:
            r = r - float(np.mean(r[on]))
        den = float(np.sum(r[on] * t[on]))
        tau = float(np.sum(g[on] * t[on])) / den if den > 0 else 0.0
        p_old = p
        p = p - tau * t
        p = np.maximum(p, 0.0)
        over = m & (p == 0) & (g < 0)
        if np.any(over):
            # overlapping cells join the contact set (with a self-stiffness step when the
            # CG step is degenerate, e.g. a start on a few cells of equal gap)
            delta = 0.0
            p = p - (tau if tau > 0 else tau_self) * np.where(over, g, 0.0)
        else:
            delta = 1.0
        p = np.where(m, p, 0.0)
        if given_load:
            total = A * float(np.sum(p))
            if total <= 0:
                p = np.where(m & (g0 <= gmin + 1e-15), 1.0, 0.0)
                total = A * float(np.sum(p))
            p *= W / total
        u = operator(p)
        res = float(np.sum(np.abs(p - p_old))) / max(float(np.sum(p)), 1e-300)
        gap_err = math.sqrt(G / max(int(np.count_nonzero(on)), 1)) / scale_len
        converged = res <= tolerance and gap_err <= tolerance and not np.any(over)
        if spring_update is not None and (converged or it % SPRING_EVERY == 0):
            c_new = _springs(spring_update(p), batch)
            if np.any(np.abs(c_new - c) > spring_tolerance * np.maximum(c, 1e-300)):
                c, delta = c_new, 0.0
                u = operator(p)
                continue
        if converged:
            break
    g = u + g0 - alpha
    load = A * np.sum(p, axis=(-2, -1))
    return ContactSolution(p, np.where(m, g, 0.0), float(alpha), load, c * load, it, res)


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
