"""A hub flank as a smooth table: ``y(z, t) = r sin(alpha)`` in Chebyshev form.

The exact flank (:func:`~gearcoupling.geometry.hub.hub_flank_model`) costs a Newton solve
per point; a sweep evaluates it millions of times. Tooth 0's cw flank is fully described by
its polar angle ``alpha`` (or ``y = r sin(alpha)``, which spares the sweep two sines) as a
function of the axial position ``z`` and the normalised height ``t`` in ``[0, 1]``, with
``r = r_form(z) + t (r_tip(z) - r_form(z))``; both are analytic, so a tensor Chebyshev
interpolant on ``nz x nt`` nodes converges geometrically (paths with a curvature jump,
``end_round``, converge only algebraically).
:func:`flank_table` builds it once per spec (cached) and records the interpolation error
measured at the cell centres between the nodes (``max_error_mm``, arc length at ``r``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache
from itertools import pairwise

import numpy as np
from numpy.polynomial import chebyshev as C
from numpy.typing import NDArray

from ..arguments import GAP_TOLERANCE_MM
from ..errors import ArgumentError, GeometryError
from ..geometry import HubModel, form_radius, hub_flank_model, hub_model, tip_radius
from ..spec import CouplingSpec

DEFAULT_NODES = (24, 12)  # (nz, nt): interpolation error ~1e-8 mm on renzo-1967
NODE_LADDER = ((16, 8), (24, 12), (32, 16), (32, 32), (48, 48), (64, 64))


@dataclass(frozen=True, eq=False)
class FlankTable:
    """Chebyshev tables of one hub flank (tooth 0, cw side, hub frame), piecewise in ``z``.

    The face width is cut into pieces at the feed path's curvature jumps
    (:func:`kink_edges`: ``end_round``'s start, as a narrow band where the enveloped flank
    carries the jump along a slanted line), so that each piece is analytic and its table
    converges geometrically; smooth paths have one piece.

    Attributes
    ----------
    half_face : float
        Hub half face width (mm); ``z`` spans ``[-half_face, half_face]``.
    y : (pieces, nz, nt) float
        Chebyshev coefficients of ``y(z, t) = r sin(alpha)`` (mm) in the piece's own
        ``x in [-1, 1]`` and ``2 t - 1``.
    form : (pieces, nz) float
        Chebyshev coefficients of the form radius ``r_form(z)`` (mm) in ``x``.
    tip_kind, tip_radius : str, float
        The tip surface (sphere about O or cylinder), evaluated in closed form.
    max_error_mm : float
        Largest interpolation error of ``y`` found between the nodes and on the edges of
        every piece (mm).
    edges : (pieces + 1,) float
        Axial ends of the pieces, from ``-half_face`` to ``half_face``.
    """

    half_face: float
    y: NDArray[np.float64]
    form: NDArray[np.float64]
    tip_kind: str
    tip_radius: float
    max_error_mm: float
    edges: NDArray[np.float64]

    def _local(self, z):
        """Piece index and local coordinate of flat ``z``: ``(k (n,) int, x (n,) float)``."""
        e = self.edges
        k = np.clip(np.searchsorted(e, z, side="right") - 1, 0, e.size - 2)
        lo, hi = e[k], e[k + 1]
        return k, (2.0 * z - (lo + hi)) / (hi - lo)

    def _by_piece(self, z, matrices, out_rows: int):
        """``matrices[k] @ T(x)`` per point (``(out_rows, n)``) for flat ``z``, one matrix
        product per piece (Chebyshev polynomials by an in-place recurrence)."""
        k, x = self._local(z)
        nz = self.y.shape[1]
        v = np.empty((nz, x.size))  # T_j(x), j along axis 0
        v[0] = 1.0
        v[1] = x
        x2 = 2.0 * x
        for j in range(2, nz):
            np.multiply(x2, v[j - 1], out=v[j])
            v[j] -= v[j - 2]
        if len(matrices) == 1:
            return _product(matrices[0], v)
        out = np.empty((out_rows, x.size))
        for p, mat in enumerate(matrices):
            sel = np.flatnonzero(k == p)
            if sel.size:
                out[:, sel] = _product(mat, v[:, sel])
        return out

    def radii(self, z: NDArray[np.float64]):
        """``(r_form(z), r_tip(z))`` in mm."""
        z = np.asarray(z, dtype=float)
        form = self._by_piece(z.ravel(), self.form[:, None, :], 1)[0]
        return form.reshape(z.shape), self._tip(z)

    def _tip(self, z):
        if self.tip_kind == "cylinder":
            return np.full(np.shape(z), self.tip_radius)
        return np.sqrt(np.maximum(self.tip_radius**2 - z * z, 0.0))

    def z_coefficients(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        """Chebyshev coefficients in ``2 t - 1`` of ``y`` in the planes ``z``: ``(..., nt)``."""
        z = np.asarray(z, dtype=float)
        nt = self.y.shape[2]
        out = self._by_piece(z.ravel(), np.swapaxes(self.y, 1, 2), nt)
        return out.T.reshape(*z.shape, nt)

    def y_at(self, kz: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray[np.float64]:
        """``y`` at heights ``t`` for per-plane coefficients ``kz`` (``(..., nt)``)."""
        return clenshaw(np.moveaxis(kz, -1, 0), t)

    @cached_property
    def _power(self) -> NDArray[np.float64] | None:
        """``y``'s coefficients in powers of ``s = 2 t - 1`` (Chebyshev in ``z``),
        ``(pieces, nz, nt)``, or None where that form could lose more than 1e-12 mm to
        rounding: Horner's rule ``2 nt eps sum |a|`` plus the conversion
        ``eps sum |c| |M|`` (``|T_i(x)| <= 1``; about 1e-14 mm on the templates, 1e-15
        measured; the (64, 64) table keeps Clenshaw)."""
        nt = self.y.shape[2]
        to_power = np.zeros((nt, nt))
        for j in range(nt):
            p = C.cheb2poly(np.eye(nt)[j])
            to_power[: p.size, j] = p
        yp = self.y @ to_power.T
        eps = np.finfo(float).eps
        bound = eps * (2 * nt * float(np.max(np.sum(np.abs(yp), axis=(1, 2))))
                       + float(np.max(np.sum(np.abs(self.y) @ np.abs(to_power).T,
                                             axis=(1, 2)))))
        return yp if bound <= 1e-12 else None

    @cached_property
    def _plane_matrices(self) -> NDArray[np.float64]:
        """``(pieces, nt + 1, nz)``: the ``t`` coefficients of ``y`` (:attr:`_power` or
        Chebyshev) and the form radius, against the Chebyshev polynomials in ``x``."""
        yp = self._power
        coef = self.y if yp is None else yp
        return np.ascontiguousarray(
            np.concatenate([coef, self.form[:, :, None]], axis=2).transpose(0, 2, 1))

    def plane_coefficients(self, z: NDArray[np.float64]):
        """The planes ``z`` (``(n,)``) for :meth:`plane_y`, in one matrix product per piece.

        Returns
        -------
        coef : (nt, n) float
            Coefficients in ``t`` of ``y``: in powers of ``2 t - 1`` where that is safe
            (:attr:`_power`), else Chebyshev.
        r_form, r_tip : (n,) float
            As :meth:`radii`.
        """
        out = self._by_piece(z, self._plane_matrices, self.y.shape[2] + 1)
        return out[:-1], out[-1], self._tip(z)

    def plane_y(self, coef: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray[np.float64]:
        """``y`` at heights ``t`` (``(..., n)``) from :meth:`plane_coefficients` ``(nt, n)``.

        Horner's rule in powers of ``s = 2 t - 1``: 2 operations per coefficient against
        Clenshaw's 3 (the values agree to 1e-15 mm on the templates).
        """
        if self._power is None:
            return clenshaw(coef, t)
        s = 2.0 * t - 1.0
        b = coef[-1] * s  # in place below: the same operations, fewer temporaries
        for k in range(coef.shape[0] - 2, 0, -1):
            b += coef[k]
            b *= s
        b += coef[0]
        return b

    @cached_property
    def symmetric(self) -> bool:
        """:meth:`even_in_z` at its default tolerance (once per table)."""
        return self.even_in_z()

    def even_in_z(self, rel: float = 1e-12) -> bool:
        """Whether the flank is symmetric about the midplane: pieces mirror each other and
        ``y``, ``r_form`` at mirrored sample points agree within ``rel`` of ``|y|``."""
        hf = self.half_face
        if not np.allclose(self.edges, -self.edges[::-1], rtol=0.0, atol=1e-12 * hf):
            return False
        z = np.linspace(0.0, hf, 9)
        t = np.linspace(0.0, 1.0, 5)
        zz, tt = np.meshgrid(np.concatenate([z, -z]), t, indexing="ij")
        r, a = self.evaluate(zz, tt)
        y = r * np.sin(a)
        n = z.size
        scale = np.max(np.abs(y))
        return bool(np.max(np.abs(y[:n] - y[n:])) <= rel * scale
                    and np.max(np.abs(r[:n] - r[n:])) <= rel * np.max(np.abs(r)))

    def evaluate(self, z, t):
        """``(r, alpha)`` at ``(z, t)`` (broadcast)."""
        z, t = np.broadcast_arrays(np.asarray(z, float), np.asarray(t, float))
        lo, hi = self.radii(z)
        r = lo + t * (hi - lo)
        return r, np.arcsin(self.y_at(self.z_coefficients(z), t) / r)


BLAS_BLOCK = 250_000  # multiply-adds per BLAS call: below OpenBLAS's threading threshold


def _product(mat: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    """``mat @ v`` for a small ``mat`` (``(rows, nz)``): numpy's own loop below 20000
    columns, BLAS above in blocks of columns small enough to run in the calling thread. A
    threaded BLAS wakes its threads for each product, which on a loaded machine costs
    more than the product itself, and the sweep makes hundreds of them."""
    n = v.shape[1]
    if n <= 20000:
        return np.einsum("ij,jn->in", mat, v)
    out = np.empty((mat.shape[0], n))
    step = max(BLAS_BLOCK // max(mat.shape[0] * mat.shape[1], 1), 64)
    for i in range(0, n, step):
        np.matmul(mat, v[:, i:i + step], out=out[:, i:i + step])
    return out


def clenshaw(coef: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Chebyshev series in ``2 t - 1`` with coefficients along the first axis.

    ``coef : (nt, ...)``, ``t : (...)``; Clenshaw's recurrence, no Vandermonde matrix (the
    sweep's hot loop: less work than ``chebvander`` + ``einsum``, the same values to
    1e-14 mm).
    """
    x = 2.0 * t - 1.0
    x2 = 2.0 * x
    b1, b2 = coef[-1], 0.0
    for k in range(coef.shape[0] - 2, 0, -1):
        b1, b2 = coef[k] + x2 * b1 - b2, b1
    return coef[0] + x * b1 - b2


def _nodes(n: int) -> NDArray[np.float64]:
    return np.cos(np.pi * (np.arange(n) + 0.5) / n)[::-1]


def exact_alpha(m: HubModel, z, t):
    """Exact ``(r, alpha)`` of tooth 0's cw flank at ``(z, t)`` (slow reference)."""
    z, t = np.broadcast_arrays(np.asarray(z, float), np.asarray(t, float))
    lo, hi = form_radius(m, z), tip_radius(m, z)
    r = lo + np.clip(t, 0.0, 1.0) * (hi - lo)
    pts, _, _ = hub_flank_model(m, "cw", z, r, check=False)
    return r, np.arctan2(pts[..., 1], pts[..., 0])


def kink_edges(m: HubModel) -> NDArray[np.float64]:
    """Axial edges of the table pieces: ``[-hf, ..., hf]``, cut where the feed path's
    curvature jumps inside the face (``end_round``'s start ``s0``).

    The revolved flank carries the jump in the plane ``z = qz(s0)``; the enveloped one
    along ``z = qz(s0) - h sin e(s0)`` over the rack depths ``h`` of the flank
    (docs/conventions.md, Tooth geometry), so there the jump gets a piece of its own, that band (a
    narrow piece converges
    fast although it is not smooth).
    """
    hf = m.half_face
    p = m.path
    cuts: list[float] = []
    for k in range(1, p.breaks.size - 1):
        s0 = p.breaks[k]
        if not np.isfinite(s0):
            continue
        before, after = p.seg_kappa[k - 1], p.seg_kappa[k]
        if np.isnan(before) or np.isnan(after):
            continue  # smooth segments join with continuous curvature
        if abs(after - before) <= 1e-12 * max(abs(after), abs(before)):
            continue
        zb, e0 = float(p.qz_break[k]), float(p.e_break[k])
        if m.revolved or e0 == 0.0:
            band = [zb]
        else:  # rack depths from above the hub tip to the form (margin 10 %)
            h_lo, h_hi = -1.1 * (m.tip_radius - m.R), 1.1 * m.dedendum
            band = sorted([zb - h_hi * math.sin(e0), zb - h_lo * math.sin(e0)])
        cuts += [c for c in band if 1e-6 * hf < c < hf * (1 - 1e-6)]
        if any(abs(c) <= 1e-6 * hf for c in band):
            cuts.append(0.0)
    half = sorted(set(cuts))
    edges = sorted({*(-c for c in half), *half, -hf, hf})
    return np.array(edges, dtype=float)


def _fit_piece(m: HubModel, lo: float, hi: float, nz: int, nt: int):
    """Chebyshev coefficients ``(nz, nt)`` of ``y`` and ``(nz,)`` of ``r_form`` on
    ``z in [lo, hi]``."""
    xz, yt = _nodes(nz), _nodes(nt)
    z = 0.5 * (lo + hi) + 0.5 * (hi - lo) * xz
    t = 0.5 * (yt + 1.0)
    r, a = exact_alpha(m, z[:, None], t[None, :])
    vz, vt = C.chebvander(xz, nz - 1), C.chebvander(yt, nt - 1)
    coef = np.linalg.solve(vz, np.linalg.solve(vt, (r * np.sin(a)).T).T)
    return coef, np.linalg.solve(vz, form_radius(m, z))


def _check_points(edges, nz: int, nt: int):
    """Where the table error is measured: the cell centres between the nodes of every
    piece, the profile ends ``t = 0, 1`` at those planes and the piece edges in ``z``
    (the kernel's minima often lie on the edges, where an interpolant is weakest)."""
    xz, yt = _nodes(nz), _nodes(nt)
    xc = np.concatenate([[-1.0], 0.5 * (xz[1:] + xz[:-1]), [1.0]])
    tc = np.concatenate([[0.0], 0.5 * (0.5 * (yt[1:] + yt[:-1]) + 1.0), [1.0]])
    z = np.concatenate([0.5 * (lo + hi) + 0.5 * (hi - lo) * xc for lo, hi in pairwise(edges)])
    return np.meshgrid(z, tc, indexing="ij")


def build_flank_table(m: HubModel, nodes: tuple[int, int] = DEFAULT_NODES) -> FlankTable:
    """Fit the Chebyshev tables of ``m``'s flank on ``nodes = (nz, nt)`` nodes per piece
    (pieces from :func:`kink_edges`)."""
    nz, nt = nodes
    if nz < 4 or nt < 3:
        raise ArgumentError("nodes", nodes, "flank table nodes (nz, nt) of at least (4, 3)")
    edges = kink_edges(m)
    fits = [_fit_piece(m, lo, hi, nz, nt) for lo, hi in pairwise(edges)]
    coef = np.stack([f[0] for f in fits])
    form = np.stack([f[1] for f in fits])
    table = FlankTable(m.half_face, coef, form, m.tip_kind, m.tip_radius, 0.0, edges)
    zc, tc = _check_points(edges, nz, nt)
    r_ex, a_ex = exact_alpha(m, zc, tc)
    r_in, a_in = table.evaluate(zc, tc)
    err = float(np.max(np.abs(r_ex * np.sin(a_ex) - r_in * np.sin(a_in))))
    if not np.isfinite(err):
        raise GeometryError("hub flank table is not finite")
    return FlankTable(m.half_face, coef, form, m.tip_kind, m.tip_radius, err, edges)


def adaptive_flank_table(m: HubModel, tolerance_mm: float = GAP_TOLERANCE_MM
                         ) -> FlankTable:
    """The smallest table of :data:`NODE_LADDER` whose measured error is within tolerance.

    Smooth feed paths (circular, none, vari_crown, table) reach 1e-7 mm with (24, 12) to
    (32, 32) nodes; ``end_round``'s curvature jump gets pieces of its own
    (:func:`kink_edges`), but on the enveloped flank the jump runs slanted through its
    band piece, which converges slowly: the ladder stops when a rung no longer halves the
    error; read ``max_error_mm``.
    """
    if not (tolerance_mm > 0):
        raise ArgumentError("tolerance_mm", tolerance_mm, "a table tolerance > 0 mm")
    table = build_flank_table(m, NODE_LADDER[0])
    for nodes in NODE_LADDER[1:]:
        if table.max_error_mm <= tolerance_mm:
            break
        trial = build_flank_table(m, nodes)
        if trial.max_error_mm > 0.5 * table.max_error_mm:
            break  # stalled (a jump the pieces do not isolate): more nodes buy nothing
        table = trial
    return table


@lru_cache(maxsize=64)
def flank_table(spec: CouplingSpec, tolerance_mm: float = GAP_TOLERANCE_MM) -> FlankTable:
    """The cached adaptive :class:`FlankTable` of a spec's hub flank."""
    return adaptive_flank_table(hub_model(spec), tolerance_mm)
