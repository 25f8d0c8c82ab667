"""Registration of a measured hub onto the nominal: coarse (axis, tooth indexing), fine (ICP).

Coarse: the axis is the principal axis of the point cloud (of the three, the one about
which the spec's ``N``-fold tooth pattern is strongest), the centre its centroid, the
midplane the middle of the tooth band's axial extent, and the rotation about the axis
the phase of ``sum (r - R) exp(i N alpha)`` (tooth tips weigh +, roots -), which puts a
tooth centre on ``+x``. ``coarse="none"`` keeps the file's frame (a CMM point file in
the part's coordinates, or a scan of a few teeth whose centroid is not on the axis).

Fine: Gauss-Newton on the point-to-flank distances of the exact nominal (point-to-plane
ICP with the exact surface: the nominal point and normal are re-evaluated at every
iteration; Huber weights, so a few teeth with large pitch errors do not pull the axis),
over at most ``fit_points`` band points, with a uniform normal offset and a
crown-height change as nuisance parameters (size and form are reported, not fitted away
by the placement); a rank-deficient direction (the axial shift of straight teeth) is left
at its coarse value (least-norm step).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError, GearCouplingError
from ..numeric import TINY, divide
from .surface import FlankTable, deviation


@dataclass(frozen=True)
class Registration:
    """Rigid placement ``hub = rotation @ p + translation`` and fit statistics."""

    rotation: NDArray[np.float64]
    translation: NDArray[np.float64]
    rms_mm: float
    iterations: int
    fit_points: int
    outliers: int
    coarse: str
    pattern_strength: float

    def apply(self, points: NDArray[np.float64]) -> NDArray[np.float64]:
        return points @ self.rotation.T + self.translation

    def summary(self) -> dict:
        return {"rotation": self.rotation.tolist(), "translation_mm": self.translation.tolist(),
                "rms_mm": self.rms_mm, "iterations": self.iterations,
                "fit_points": self.fit_points, "outliers": self.outliers,
                "coarse": self.coarse, "pattern_strength": self.pattern_strength}


class RegistrationError(GearCouplingError):
    """The scan cannot be placed on the nominal (wrong part, units, too few points)."""


def _rodrigues(w: NDArray[np.float64]) -> NDArray[np.float64]:
    a = float(np.linalg.norm(w))
    if a < TINY:
        return np.eye(3)
    k = w / a
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * K @ K


def _frame(axis: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation whose third row is ``axis`` (rows: new x, y, z in old coordinates).

    The axis is turned to point along the file's ``+z`` side and the new ``x`` is the
    file's ``x`` projected off the axis, so a scan already near the hub frame keeps its
    tooth numbering.
    """
    a = axis / np.linalg.norm(axis)
    if a[2] < 0:
        a = -a
    helper = np.eye(3)[0] if abs(a[0]) < 0.9 else np.eye(3)[1]
    x = helper - (helper @ a) * a
    x /= np.linalg.norm(x)
    return np.stack([x, np.cross(a, x), a])


def pattern(alpha, r, R: float, N: int) -> complex:
    """Normalised ``sum (r - R) exp(i N alpha) / sum |r - R|`` (1 = perfect N-fold pattern)."""
    w = r - R
    den = float(np.sum(np.abs(w)))
    if den <= 0:
        return 0j
    return complex(np.sum(w * np.exp(1j * N * alpha)) / den)


def _spectrum(alpha, r, R: float, N: int) -> dict[int, float]:
    """Pattern strength for tooth counts ``M`` from ``N/2`` to ``2N``."""
    return {M: abs(pattern(alpha, r, R, M)) for M in range(max(3, N // 2), 2 * N + 1)}


def check_scale(points, tip_radius: float) -> None:
    """Refuse a scan whose size does not match the spec, naming inch/metre files.

    The size is the 99.5th percentile of the radius about the axis (a few stray points
    do not change it); it must be the hub tip radius within -15 / +12 %.
    """
    r_max = float(np.percentile(np.hypot(points[:, 0], points[:, 1]), 99.5))
    ratio = r_max / tip_radius
    for scale, what in ((1 / 25.4, "inches: pass units='in' (--units in)"),
                        (1 / 1000.0, "metres: pass units='m' (--units m)"),
                        (25.4, "a mm file read as inches: pass units='mm'")):
        if abs(ratio / scale - 1.0) < 0.12:
            raise ArgumentError("units", f"scan radius {r_max:.5g} mm", f"the scan is about "
                            f"{ratio:.4g} times the spec's size (hub tip radius "
                            f"{tip_radius:.5g} mm): it looks like {what}")
    if not 0.85 < ratio < 1.12:
        raise RegistrationError(f"scan does not match the spec: its outer radius about the "
                                f"axis is {r_max:.5g} mm, the spec's hub tip radius "
                                f"{tip_radius:.5g} mm (a scan of another part?)")


def coarse_place(points, table: FlankTable, mode: str = "auto", sample: int = 100_000):
    """Coarse rotation and translation (see module docstring); returns ``(Rm, t, strength)``.

    The axis search and the tooth pattern use at most ``sample`` points (every k-th).
    """
    m = table.model
    N = m.teeth
    tip = float(m.tip_radius)
    sub = points[:: max(1, len(points) // sample)]
    if mode == "none":
        Rm, t = np.eye(3), np.zeros(3)
    elif mode == "auto":
        c = points.mean(axis=0)
        q = sub - c
        _, vecs = np.linalg.eigh(q.T @ q)
        best = None
        for k in range(3):  # the axis about which some tooth pattern is strongest
            F = _frame(vecs[:, k])
            p = q[:: max(1, len(q) // 20_000)] @ F.T
            r = np.hypot(p[:, 0], p[:, 1])
            band = (r > m.R - m.dedendum) & (r < 1.05 * tip)
            s = max(_spectrum(np.arctan2(p[band, 1], p[band, 0]), r[band], m.R, N).values(),
                    default=0.0)
            if best is None or s > best[0]:
                best = (s, F)
        if best is None:
            raise RegistrationError("no candidate axis for the scan's tooth pattern")
        Rm, t = best[1], -best[1] @ c
    else:
        raise ArgumentError("coarse", mode, "'auto' (find axis and teeth) or 'none' (keep frame)")
    check_scale(points @ Rm.T + t, tip)
    p = sub @ Rm.T + t
    r = np.hypot(p[:, 0], p[:, 1])
    teeth = r > 0.5 * (table.r_lo + table.r_hi)
    if teeth.sum() < 10:
        raise RegistrationError(f"only {int(teeth.sum())} scan points lie on the tooth band "
                                f"(r > {0.5 * (table.r_lo + table.r_hi):.5g} mm)")
    if mode == "auto":
        zt = p[teeth, 2]
        mid = 0.5 * (zt.min() + zt.max())
        t = t - np.array([0.0, 0.0, mid])
        p[:, 2] -= mid
        width = float(zt.max() - zt.min())
        if abs(width - 2 * m.half_face) > 0.2 * 2 * m.half_face + m.dedendum:
            raise RegistrationError(f"scan does not match the spec: its teeth span {width:.4g} mm"
                                    f" axially, the spec's face width is {2 * m.half_face:.4g} mm")
    band = (r > m.R - m.dedendum) & (r < 1.05 * tip)
    alpha, rr = np.arctan2(p[band, 1], p[band, 0]), r[band]
    z_n = pattern(alpha, rr, m.R, N)
    strength = abs(z_n)
    step = max(1, len(alpha) // 20_000)
    counts = _spectrum(alpha[::step], rr[::step], m.R, N)
    best_M = max(counts, key=counts.__getitem__)
    if best_M != N and strength < 0.5 * counts[best_M]:
        raise RegistrationError(f"scan does not match the spec: its angular tooth pattern "
                                f"repeats {best_M} times per turn (strength {counts[best_M]:.2f})"
                                f", the spec has {N} teeth (strength {strength:.2f})")
    if mode == "auto":
        phase = math.atan2(z_n.imag, z_n.real) / N
        Rz = _rodrigues(np.array([0.0, 0.0, -phase]))
        Rm, t = Rz @ Rm, Rz @ t
    return Rm, t, strength


def fine_register(points, table: FlankTable, Rm, t, *, fit_points: int = 20_000,
                  outlier_mm: float | None = None, max_iter: int = 40, seed: int = 0):
    """Gauss-Newton point-to-flank fit from ``(Rm, t)``; returns the final ``(Rm, t, stats)``."""
    m = table.model
    outlier = 0.2 * m.R / m.teeth if outlier_mm is None else outlier_mm  # 0.1 module
    p = points @ Rm.T + t
    r = np.hypot(p[:, 0], p[:, 1])
    pad = 0.2 * m.dedendum
    cand = np.flatnonzero((np.abs(p[:, 2]) <= table.half_lead + pad)
                          & (r >= table.r_lo - pad) & (r <= table.r_hi + pad))
    rng = np.random.default_rng(seed)
    if len(cand) > fit_points:
        cand = rng.choice(cand, fit_points, replace=False)
    sub = points[cand]
    weight = np.ones(len(sub))
    iterations = 0
    for _ in range(max_iter):
        iterations += 1
        q = sub @ Rm.T + t
        dev = deviation(table, q)
        ok = np.abs(dev.d) <= outlier
        used = int(ok.sum())
        if used < 12:
            raise RegistrationError(f"only {used} scan points lie within {outlier:.3g} mm of "
                                    "the nominal flanks after the coarse placement (wrong part, "
                                    "or pass coarse='none' / --coarse none for a partial scan "
                                    "in the part frame)")
        qi, n, d = q[dev.index[ok]], dev.normal[ok], dev.d[ok]
        # nuisance columns: a uniform plus-material offset (thickness) and a crown change
        # are size/form, not placement; without them they leak into the weakly determined
        # axial shift through the sample's asymmetry
        zn = (dev.z[ok] / table.half_lead)[:, None]
        J = np.concatenate([np.cross(qi, n), n, np.ones_like(zn), zn * zn], axis=1)
        scale = np.array([1.0 / m.R] * 3 + [1.0] * 5)
        sw = np.sqrt(weight[dev.index[ok]])[:, None]
        x_all = np.linalg.lstsq(J * scale * sw, -d * sw[:, 0], rcond=1e-9)[0] * scale
        x = x_all[:6]
        # Huber weights for the next step (robust to a few teeth with large pitch errors)
        res = d + J @ x_all
        k = max(1.345 * 1.4826 * float(np.median(np.abs(res))), 1e-7)
        weight[:] = 1.0
        weight[dev.index[ok]] = np.minimum(1.0, divide(k, np.abs(res)))
        dR = _rodrigues(x[:3])
        Rm, t = dR @ Rm, dR @ t + x[3:]
        if np.linalg.norm(x[:3]) * m.R + np.linalg.norm(x[3:]) < 1e-9 * m.R:
            break
    q = sub @ Rm.T + t
    dev = deviation(table, q)
    ok = np.abs(dev.d) <= outlier
    rms = float(np.sqrt(np.mean(dev.d[ok] ** 2))) if ok.any() else math.inf
    return Rm, t, {"rms_mm": rms, "iterations": iterations, "fit_points": int(ok.sum()),
                   "outliers": int((~ok).sum())}


def register(points, table: FlankTable, *, coarse: str = "auto", fit_points: int = 20_000,
             outlier_mm: float | None = None) -> Registration:
    """Place a scan on the nominal hub: :func:`coarse_place` then :func:`fine_register`.

    ``coarse="auto"`` falls back to the file's own frame when the axis search fails (a
    scan of a few teeth) and the file's frame fits; otherwise the first error is raised.
    """
    if not (isinstance(fit_points, int) and fit_points >= 100):
        raise ArgumentError("fit_points", fit_points, "an integer >= 100")
    try:
        used = coarse
        Rm, t, strength = coarse_place(points, table, coarse)
        Rm, t, stats = fine_register(points, table, Rm, t, fit_points=fit_points,
                                     outlier_mm=outlier_mm)
    except (RegistrationError, ArgumentError) as err:
        if coarse != "auto" or (isinstance(err, ArgumentError) and err.field != "units"):
            raise
        try:
            used = "none (the axis search failed: scan kept in its own frame)"
            Rm, t, strength = coarse_place(points, table, "none")
            Rm, t, stats = fine_register(points, table, Rm, t, fit_points=fit_points,
                                         outlier_mm=outlier_mm)
        except (RegistrationError, ArgumentError):
            raise err from None
    return Registration(Rm, t, stats["rms_mm"], stats["iterations"], stats["fit_points"],
                        stats["outliers"], used, strength)
