"""Hob feed paths in the hub's axial section (docs/conventions.md, Tooth geometry).

A feed path is the locus ``q(s) = (v, z)`` of the hob's pitch point, parametrised by arc
length ``s`` from the midplane, with even curvature ``kappa(s)``, tangent angle
``e(s) = ∫ kappa`` and unit normal ``n(s) = (cos e, sin e)``; ``q(0) = (R, 0)`` and
``dq/ds = (-sin e, cos e)``.

A path is a chain of segments on ``s >= 0`` (mirrored for ``s < 0``): circular arcs of
constant curvature, evaluated in closed form (stable as ``kappa -> 0``), and smooth
segments with a given ``kappa(s)`` and ``e(s)``, whose position is integrated by
16-point Gauss-Legendre quadrature (exact to rounding for the polynomial and spline
curvatures used here).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import pairwise
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import real
from ..errors import ArgumentError, GeometryError

SmoothFn = Callable[[NDArray[np.float64]], tuple[NDArray[np.float64], NDArray[np.float64]]]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)


class FeedPath:
    """A feed path built from segments; see the module docstring.

    Parameters
    ----------
    pitch_radius : float
        ``R``, radial position of the path at the midplane.
    segments : sequence of (length, kappa)
        Consecutive segments from ``s = 0``; ``kappa`` is a float for an arc or ``None``
        for a smooth segment evaluated by ``smooth``. The last length may be ``inf``.
    smooth : callable, optional
        ``smooth(s) -> (kappa, e)`` for ``s`` inside the smooth segments.
    """

    def __init__(
        self,
        pitch_radius: float,
        segments: Sequence[tuple[float, float | None]],
        smooth: SmoothFn | None = None,
        kind: str = "custom",
    ):
        self.R = float(pitch_radius)
        self.kind = kind
        self.smooth = smooth
        lengths = np.array([seg[0] for seg in segments], dtype=float)
        self.seg_kappa = np.array(
            [np.nan if seg[1] is None else float(seg[1]) for seg in segments], dtype=float
        )
        self.breaks = np.concatenate([[0.0], np.cumsum(lengths)])
        n = len(segments)
        self.e_break = np.zeros(n + 1)
        self.qv_break = np.full(n + 1, self.R)
        self.qz_break = np.zeros(n + 1)
        for k in range(n - 1):
            _, e, qv, qz = self._segment(np.array([k]), np.array([lengths[k]]))
            self.e_break[k + 1], self.qv_break[k + 1], self.qz_break[k + 1] = e[0], qv[0], qz[0]

    def _segment(self, k: NDArray[np.intp], ds: NDArray[np.float64]):
        """Evaluate segment ``k`` at distance ``ds`` past its start (``ds >= 0``)."""
        e0, qv0, qz0 = self.e_break[k], self.qv_break[k], self.qz_break[k]
        kap_seg = self.seg_kappa[k]
        arc = np.isfinite(kap_seg)
        kap = np.where(arc, kap_seg, 0.0)
        half = 0.5 * kap * ds
        sinc = np.sinc(half / np.pi)
        mid = e0 + half
        e = e0 + 2.0 * half
        qv = qv0 - ds * np.sin(mid) * sinc
        qz = qz0 + ds * np.cos(mid) * sinc
        if not np.all(arc):
            smooth = self.smooth
            if smooth is None:
                raise ArgumentError("smooth", None, "a smooth curvature: FeedPath segments "
                                    "with kappa None need it")
            sm = ~arc
            s0 = self.breaks[k][sm]
            a = s0 + ds[sm]
            kap[sm], e[sm] = smooth(a)
            nodes = s0[:, None] + ds[sm][:, None] * (0.5 * (_GL_X + 1.0))
            _, en = smooth(nodes)
            qv[sm] = qv0[sm] - 0.5 * ds[sm] * (np.sin(en) @ _GL_W)
            qz[sm] = qz0[sm] + 0.5 * ds[sm] * (np.cos(en) @ _GL_W)
        return kap, e, qv, qz

    def evaluate(self, s: ArrayLike):
        """Curvature, tangent angle and position at arc length ``s``.

        Parameters
        ----------
        s : (...) float
            Arc length from the midplane, mm (negative on the ``z < 0`` side).

        Returns
        -------
        kappa, e, qv, qz : (...) float
            Curvature (1/mm), tangent angle (rad), radial and axial position (mm).
        """
        s = np.asarray(s, dtype=float)
        shape = s.shape
        s = s.ravel()
        sgn = np.where(s < 0, -1.0, 1.0)
        a = np.abs(s)
        k = np.clip(np.searchsorted(self.breaks, a, side="right") - 1, 0, len(self.seg_kappa) - 1)
        kap, e, qv, qz = self._segment(k, a - self.breaks[k])
        return (
            kap.reshape(shape),
            (sgn * e).reshape(shape),
            qv.reshape(shape),
            (sgn * qz).reshape(shape),
        )

    def solve_plane(self, z: ArrayLike, h: ArrayLike, *, max_iter: int = 50):
        """Arc length ``s`` of the rack point at depth ``h`` that lies in the plane ``z``.

        Solves ``qz(s) - h sin e(s) = z`` by Newton's method; the left side increases
        monotonically with slope ``(1 - h kappa) cos e > 0`` wherever the spec is valid.

        Parameters
        ----------
        z, h : (...) float
            Axial position and rack depth below the path (mm), broadcast together.

        Returns
        -------
        s, kappa, e, qv, qz : (...) float
        """
        z, h = np.broadcast_arrays(np.asarray(z, dtype=float), np.asarray(h, dtype=float))
        s = z.copy()
        scale = self.R + np.abs(z) + np.abs(h)
        for _ in range(max_iter):
            kap, e, qv, qz = self.evaluate(s)
            c = np.cos(e)
            f = qz - h * np.sin(e) - z
            slope = (1.0 - h * kap) * c
            if np.any(slope <= 0):
                raise GeometryError(
                    "rack depth beyond the feed path's centre of curvature or tangent past 90°"
                )
            step = f / slope
            s = s - step
            if np.all(np.abs(step) <= 1e-15 * scale):
                break
        else:
            raise GeometryError("feed path plane solve did not converge")
        kap, e, qv, qz = self.evaluate(s)
        return s, kap, e, qv, qz

    def drop(self, z: ArrayLike) -> NDArray[np.float64]:
        """Crown drop ``R - qv`` of the path at axial position ``z``."""
        _, _, _, qv, _ = self.solve_plane(z, 0.0)
        return self.R - qv


def arc_path(R: float, radius: float, kind: str) -> FeedPath:
    """A circular feed path of ``radius`` (``inf``: straight)."""
    return FeedPath(R, [(np.inf, 1.0 / radius)], kind=kind)


def end_round_path(R: float, radius: float, end_radius: float, start_z: float,
                   kind: str) -> FeedPath:
    """A circular path of ``radius`` up to the axial position ``start_z``, then of
    ``end_radius``, tangent-continuous."""
    s0 = start_z if np.isinf(radius) else radius * np.arcsin(start_z / radius)
    return FeedPath(R, [(s0, 1.0 / radius), (np.inf, 1.0 / end_radius)], kind=kind)


def vari_crown_path(R: float, radius: float, end_radius: float, face_width: float,
                    kind: str) -> FeedPath:
    """Curvature ``1/radius`` at the midplane blending quadratically in arc length to
    ``1/end_radius`` at half the face width, constant beyond."""
    km, ke = 1.0 / radius, 1.0 / end_radius
    se = 0.5 * face_width

    def smooth(s):
        x = s / se
        return km + (ke - km) * x * x, s * (km + (ke - km) * x * x / 3.0)

    return FeedPath(R, [(se, None), (np.inf, ke)], smooth, kind=kind)


def curvature_table_path(R: float, s_knots, kappa_knots, kind: str) -> FeedPath:
    """A path whose curvature is splined through ``(s, kappa)`` samples (slope 0 at the
    midplane), constant past the last sample."""
    from scipy.interpolate import CubicSpline  # lazy: keeps `import gearcoupling` fast

    s_knots, kappa_knots = np.asarray(s_knots, dtype=float), np.asarray(kappa_knots, dtype=float)
    spline = CubicSpline(s_knots, kappa_knots, bc_type=((1, 0.0), "not-a-knot"))
    anti = spline.antiderivative()

    def smooth(s):
        return spline(s), anti(s)

    segments: list[tuple[float, float | None]] = [
        (float(b - a), None) for a, b in pairwise(s_knots)
    ]
    segments.append((np.inf, float(kappa_knots[-1])))
    return FeedPath(R, segments, smooth, kind=kind)


def drop_table_to_curvature(z_knots, drop_knots, n: int = 400):
    """Convert crown-drop samples ``(z, drop)`` into curvature samples ``(s, kappa)``.

    The drop is splined (clamped slope 0 at ``z = 0``, natural at the end); the path
    ``v = R - drop(z)`` then has ``tan e = drop'``, ``kappa = drop'' / (1 + drop'^2)^1.5``
    and arc length ``s = ∫ sqrt(1 + drop'^2) dz``, sampled at ``n`` points.
    """
    from scipy.interpolate import CubicSpline

    d = CubicSpline(z_knots, drop_knots, bc_type=((1, 0.0), "not-a-knot"))
    z = np.linspace(0.0, float(z_knots[-1]), n)
    d1, d2 = d(z, 1), d(z, 2)
    kappa = d2 / (1.0 + d1**2) ** 1.5
    seg = np.diff(z)
    nodes = z[:-1, None] + seg[:, None] * (0.5 * (_GL_X + 1.0))
    ds = 0.5 * seg * (np.sqrt(1.0 + d(nodes, 1) ** 2) @ _GL_W)
    s = np.concatenate([[0.0], np.cumsum(ds)])
    return s, kappa


def drop_table_path(R: float, z_knots, drop_knots, kind: str) -> FeedPath:
    """A path through splined crown-drop samples ``(z, drop)``
    (:func:`drop_table_to_curvature`)."""
    s, kappa = drop_table_to_curvature(np.asarray(z_knots, dtype=float),
                                       np.asarray(drop_knots, dtype=float))
    return curvature_table_path(R, s, kappa, kind)


class CrowningLike(Protocol):
    """A hub crowning as the geometry sees it (:class:`gearcoupling.spec.Crowning` is one):
    its kind and the feed path it stands for (built by its kind's entry of
    ``gearcoupling.spec.CROWN_KINDS``)."""

    @property
    def kind(self) -> str: ...

    def feed_path(self, pitch_radius: float, face_width: float) -> FeedPath: ...


def feed_path(crowning: CrowningLike, pitch_radius: float, face_width: float) -> FeedPath:
    """The feed path of a hub crowning (``spec.hub.crowning``) at pitch radius
    ``pitch_radius`` over the face width ``face_width`` (mm)."""
    if not callable(getattr(crowning, "feed_path", None)):
        raise ArgumentError("crowning", crowning, "a Crowning of a spec "
                            "(spec.hub.crowning)")
    R = real(pitch_radius, "pitch_radius", 0.0, open_lo=True, unit="mm")
    b = real(face_width, "face_width", 0.0, open_lo=True, unit="mm")
    return crowning.feed_path(R, b)
