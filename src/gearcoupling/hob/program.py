"""Hob feed program: the hob centre path in the hub's axial section (pure numpy).

The hob's pitch point follows the feed path ``q(s)`` (docs/conventions.md, Tooth geometry) with
outward unit
normal ``n(s) = (cos e, sin e)`` in ``(v, z)``; its pitch cylinder touches the rack's
pitch line there, so the hob centre (its axis, seen in the axial section) is the offset
curve ``c(s) = q(s) + r_h n(s)``, ``r_h`` the hob pitch radius. A circular path of
radius ``R_c`` about the crowning axis ``C`` gives a concentric circle of radius
``R_c + r_h``; arcs stay arcs (G2/G3), straight segments lines, and smooth segments
(Vari-Crown, tables) are replaced by chords whose deviation from ``c(s)`` is measured and
kept within the tolerance.

Machine axes: ``X`` = hob centre distance from the hub axis (radial infeed), ``Z`` = hob
centre axial position, hub midplane at ``Z = 0``; both mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import pairwise

import numpy as np
from numpy.typing import NDArray

from ..arguments import MAXIMA, count, is_real, real
from ..errors import ArgumentError
from ..geometry import HubModel, hub_model, plane_rack, tip_radius
from ..io import gcode_comment
from ..numeric import TINY
from ..spec import CouplingSpec, as_spec

_DENSE = 65  # exact-curve samples per move when its chordal deviation is measured
MAX_HOB_DIAMETER_MM = 1000.0  # hobs are made up to a few hundred mm (module 40: about 500)
#: axial feed per workpiece revolution a hobbing machine takes (mm/rev): roughing feeds
#: reach a few mm, finishing ones tenths; controllers refuse numbers far beyond
FEED_RANGE_MM_PER_REV = (0.001, 50.0)


def check_hob_diameter(spec: CouplingSpec,
                       hob_diameter_mm, field: str = "hob_diameter_mm") -> float:
    """The hob outside diameter (mm) if a hob of that size can cut the spec's hub; else a
    :class:`ArgumentError` naming ``field`` that says which bound and why: the hob must carry
    teeth of the hub's whole depth on a body (above ``2 (dedendum + module)``), and no hob
    is made larger than :data:`MAX_HOB_DIAMETER_MM` (its approach travel ``sqrt(H (D - H))``
    would grow without end)."""
    D = hob_diameter_mm
    if not (is_real(D) and math.isfinite(D)):
        raise ArgumentError(field, D, "a finite hob outside diameter in mm")
    depth = hub_model(spec).dedendum + spec.tooth.module
    if D <= 2.0 * depth:
        raise ArgumentError(field, D, f"too small to carry teeth {depth:.4g} mm deep around a "
                        f"body: a hob for this hub is larger than 2 (dedendum + module) = "
                        f"{2.0 * depth:.4g} mm")
    if D > MAX_HOB_DIAMETER_MM:
        raise ArgumentError(field, D, f"larger than any hob made (up to {MAX_HOB_DIAMETER_MM:g} mm"
                        " outside diameter); its approach travel alone would be "
                        f"{math.sqrt(depth * (D - depth)):.4g} mm")
    return float(D)


@dataclass(frozen=True)
class Move:
    """One program move in the ``(Z, X)`` plane.

    ``kind`` is ``"line"`` or ``"arc"``; ``start``/``end``/``centre`` are ``(Z, X)`` mm;
    ``s`` the feed-path arc lengths at its ends; ``clockwise`` for arcs drawn with ``Z``
    to the right and ``X`` up (the ``G18`` view from ``+Y``: ``G2``).
    """

    kind: str
    start: tuple[float, float]
    end: tuple[float, float]
    s: tuple[float, float]
    centre: tuple[float, float] | None = None
    clockwise: bool = False


@dataclass(frozen=True)
class HobProgram:
    """A hob feed program; see :func:`hob_program`.

    Attributes
    ----------
    moves : list of Move
        Approach, feed path and overtravel moves, in order.
    table : dict of (n,) float arrays
        Exact hob centre path sampled over the program: ``s_mm, z_mm, x_mm, infeed_mm,
        path_z_mm, crown_drop_mm, e_deg``.
    """

    spec_name: str
    hob_diameter_mm: float
    hob_pitch_radius_mm: float
    tolerance_mm: float
    max_deviation_mm: float
    s_generate_mm: float
    approach_mm: float
    whole_depth_mm: float
    z_start_mm: float
    z_end_mm: float
    x_mid_mm: float
    crown_drop_end_mm: float
    crown_kind: str
    moves: list[Move] = field(repr=False)
    table: dict[str, NDArray[np.float64]] = field(repr=False)
    notes: tuple[str, ...] = ()

    def summary(self) -> dict:
        """Scalars of the program (``hob.json``)."""
        counts = {k: sum(m.kind == k for m in self.moves) for k in ("line", "arc")}
        return {
            "spec": self.spec_name, "crowning": self.crown_kind,
            "hob_diameter_mm": self.hob_diameter_mm,
            "hob_pitch_radius_mm": self.hob_pitch_radius_mm,
            "tolerance_mm": self.tolerance_mm, "max_deviation_mm": self.max_deviation_mm,
            "line_moves": counts["line"], "arc_moves": counts["arc"],
            "feed_path_s_generate_mm": self.s_generate_mm,
            "approach_mm": self.approach_mm, "whole_depth_mm": self.whole_depth_mm,
            "z_start_mm": self.z_start_mm, "z_end_mm": self.z_end_mm,
            "x_mid_mm": self.x_mid_mm, "crown_drop_end_mm": self.crown_drop_end_mm,
            "notes": list(self.notes),
        }

    def rows(self) -> list[dict[str, float]]:
        """The sampled hob centre path as CSV rows (``hob_path.csv``)."""
        keys = list(self.table)
        return [dict(zip(keys, vals, strict=True)) for vals in zip(*self.table.values(),
                                                                    strict=True)]

    def gcode(self, feed_mm_per_rev: float = 1.0, retract_mm: float | None = None) -> str:
        """The program as ISO G-code (``G18`` ZX plane, ``G95`` feed per workpiece turn;
        every number fixed-point, as controllers read them; the spec name only inside a
        comment, :func:`~gearcoupling.io.gcode_comment`). ``feed_mm_per_rev`` in
        :data:`FEED_RANGE_MM_PER_REV`; ``retract_mm`` from 0 to the hob diameter (default
        the whole depth)."""
        feed = real(feed_mm_per_rev, "feed_mm_per_rev", *FEED_RANGE_MM_PER_REV, unit="mm/rev")
        retract = self.whole_depth_mm if retract_mm is None else real(
            retract_mm, "retract_mm", 0.0, self.hob_diameter_mm, unit="mm")
        first = self.moves[0].start
        comments = [
            f"gearcoupling hob program: spec {self.spec_name}, crowning {self.crown_kind}",
            "X = hob centre distance from the hub axis, Z = hob centre axial position, mm, "
            "hub midplane Z0",
            f"hob outside diameter {self.hob_diameter_mm:.4f}, pitch radius "
            f"{self.hob_pitch_radius_mm:.4f}, chordal tolerance {self.tolerance_mm:.2e}, "
            f"max deviation {self.max_deviation_mm:.2e}",
            f"approach/overtravel {self.approach_mm:.4f}, crown drop at the tooth ends "
            f"{self.crown_drop_end_mm:.5f}",
        ]
        lines = [
            "%",
            *map(gcode_comment, comments),
            "G21 G90 G18 G95",
            f"G0 X{first[1] + retract:.5f} Z{first[0]:.5f}",
            f"G1 X{first[1]:.5f} F{feed:.4f}",
        ]
        for m in self.moves:
            z, x = m.end
            if m.kind == "line":
                lines.append(f"G1 X{x:.5f} Z{z:.5f}")
            else:
                if m.centre is None:
                    raise ArgumentError("moves", m, "an arc move with a centre")
                cz, cx = m.centre
                code = "G2" if m.clockwise else "G3"
                lines.append(f"{code} X{x:.5f} Z{z:.5f} I{cx - m.start[1]:.5f} "
                             f"K{cz - m.start[0]:.5f}")
        last = self.moves[-1].end
        lines += [f"G0 X{last[1] + retract:.5f}", "M30", "%"]
        return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------ kernels


def hob_centre(m: HubModel, r_h: float, s) -> NDArray[np.float64]:
    """Exact hob centre ``(Z, X)`` at feed-path arc lengths ``s``.

    Parameters
    ----------
    s : (...) float
    Returns
    -------
    (..., 2) float
    """
    _, e, qv, qz = m.path.evaluate(s)
    return np.stack([qz + r_h * np.sin(e), qv + r_h * np.cos(e)], axis=-1)


def chord_deviation(curve: NDArray[np.float64], a: NDArray[np.float64],
                    b: NDArray[np.float64]) -> NDArray[np.float64]:
    """Distance of points to the segment ``a``-``b``.

    Parameters
    ----------
    curve : (..., k, 2) float
    a, b : (..., 2) float
    Returns
    -------
    (...) float
        Largest distance of the ``k`` points to the segment.
    """
    d = b - a
    L2 = np.maximum(np.einsum("...i,...i->...", d, d), TINY)
    t = np.einsum("...ki,...i->...k", curve - a[..., None, :], d) / L2[..., None]
    foot = a[..., None, :] + np.clip(t, 0.0, 1.0)[..., None] * d[..., None, :]
    return np.max(np.linalg.norm(curve - foot, axis=-1), axis=-1)


def _chords(m: HubModel, r_h: float, s0: float, s1: float, tol: float) -> list[float]:
    """Arc lengths of chord ends on ``[s0, s1]`` whose deviation is within ``tol``."""
    knots = [s0]
    s = s0
    frac = np.linspace(0.0, 1.0, _DENSE)
    while s < s1:
        kap = float(np.max(np.abs(m.path.evaluate(np.array([s, min(s1, s + 1e-3)]))[0])))
        kc = kap / (1.0 + r_h * kap)
        ds = min(s1 - s, math.sqrt(8.0 * 0.9 * tol / kc) if kc > 0 else s1 - s)
        while True:
            nxt = min(s1, s + ds)
            pts = hob_centre(m, r_h, s + (nxt - s) * frac)
            if chord_deviation(pts, pts[0], pts[-1]) <= 0.95 * tol or ds < 1e-9:
                break
            ds *= 0.7
        knots.append(nxt)
        s = nxt
    return knots


def _pieces(m: HubModel, s_gen: float) -> list[tuple[float, float, float]]:
    """``(s0, s1, kappa)`` pieces of the path on ``[-s_gen, s_gen]`` (nan: smooth; runs of
    smooth segments merged)."""
    inner = [b for b in m.path.breaks[1:] if 0.0 < b < s_gen]
    edges = [-s_gen, *(-b for b in reversed(inner)), *inner, s_gen]
    out: list[tuple[float, float, float]] = []
    for a, b in pairwise(edges):
        mid = 0.5 * abs(a + b)
        k = int(np.clip(np.searchsorted(m.path.breaks, mid, side="right") - 1, 0,
                        len(m.path.seg_kappa) - 1))
        kap = float(m.path.seg_kappa[k])
        if out and math.isnan(kap) and math.isnan(out[-1][2]):
            out[-1] = (out[-1][0], b, kap)  # one chord run over consecutive smooth segments
        else:
            out.append((a, b, kap))
    return out


def _path_moves(m: HubModel, r_h: float, s_gen: float, tol: float):
    moves: list[Move] = []
    worst = 0.0
    for a, b, kap in _pieces(m, s_gen):
        ends = hob_centre(m, r_h, np.array([a, b]))
        if math.isfinite(kap) and kap > 0:
            _, e, qv, qz = m.path.evaluate(a)
            centre = (float(qz - math.sin(e) / kap), float(qv - math.cos(e) / kap))
            va, vb = ends[0] - centre, ends[1] - centre
            cw = va[0] * vb[1] - va[1] * vb[0] < 0
            moves.append(Move("arc", tuple(ends[0]), tuple(ends[1]), (a, b), centre, bool(cw)))
            continue
        knots = [a, b] if math.isfinite(kap) else _chords(m, r_h, a, b, tol)
        pts = hob_centre(m, r_h, np.array(knots))
        for i in range(len(knots) - 1):
            dense = hob_centre(m, r_h, np.linspace(knots[i], knots[i + 1], _DENSE))
            worst = max(worst, float(chord_deviation(dense, pts[i], pts[i + 1])))
            moves.append(Move("line", tuple(pts[i]), tuple(pts[i + 1]),
                              (knots[i], knots[i + 1])))
    return moves, worst


def hob_program(spec: CouplingSpec, hob_diameter_mm: float, *,
                tolerance_mm: float | None = None, table_points: int = 201) -> HobProgram:
    """The hob centre path and a two-axis (X infeed, Z feed) program for a spec's hub.

    Parameters
    ----------
    spec : CouplingSpec
    hob_diameter_mm : float
        Hob outside diameter; its pitch radius is ``D/2 - dedendum`` (the hob addendum
        cuts the hub root).
    tolerance_mm : float, optional
        Largest chordal deviation of the program from the exact hob centre path
        (default module / 1000).
    table_points : int
        Samples of the exact path in :attr:`HobProgram.table`.

    Returns
    -------
    HobProgram
        Moves from the approach point (hob tip just touching the blank before the first
        face end) along the path over the feed range that generates the whole face
        (every rack depth down to the root reaches both face-end planes), to the
        overtravel point; straight run-outs at constant infeed.
    """
    spec = as_spec(spec)
    m = hub_model(spec)
    module = spec.tooth.module
    tol = module / 1000.0 if tolerance_mm is None else tolerance_mm
    if not (is_real(tol) and math.isfinite(tol) and module * 1e-6 <= tol <= module * 0.1):
        raise ArgumentError("tolerance_mm", tolerance_mm,
                        f"a chordal tolerance from {module * 1e-6:.3g} to {module * 0.1:.3g} mm "
                        "(1e-6 to 0.1 module)")
    D = check_hob_diameter(spec, hob_diameter_mm)
    count(table_points, "table_points", 3, MAXIMA["points"])
    r_h = 0.5 * D - m.dedendum
    s_gen = float(m.path.solve_plane(m.half_face, m.dedendum)[0])
    z_end = m.half_face
    root = float(plane_rack(m, z_end, m.dedendum)[0])
    H = float(tip_radius(m, z_end)) - root
    approach = math.sqrt(max(H, 0.0) * (D - max(H, 0.0)))
    moves, worst = _path_moves(m, r_h, s_gen, tol)
    first, last = moves[0].start, moves[-1].end
    a0 = (first[0] - approach, first[1])
    a1 = (last[0] + approach, last[1])
    moves = [Move("line", a0, first, (-s_gen, -s_gen)), *moves,
             Move("line", last, a1, (s_gen, s_gen))]
    s = np.linspace(-s_gen, s_gen, table_points)
    _, e, _, qz = m.path.evaluate(s)
    c = hob_centre(m, r_h, s)
    x_mid = m.R + r_h
    notes: tuple[str, ...] = ()
    if m.revolved:
        notes = ("the spec's crowning.generation is 'revolved', which a hob does not cut: "
                 "this program cuts the enveloped crown of the same feed path",)
    return HobProgram(
        spec_name=spec.name, hob_diameter_mm=float(D), hob_pitch_radius_mm=r_h,
        tolerance_mm=float(tol), max_deviation_mm=worst, s_generate_mm=s_gen,
        approach_mm=approach, whole_depth_mm=H, z_start_mm=float(a0[0]), z_end_mm=float(a1[0]),
        x_mid_mm=x_mid, crown_drop_end_mm=float(m.path.drop(m.half_face)),
        crown_kind=m.path.kind, moves=moves,
        table={"s_mm": s, "z_mm": c[:, 0], "x_mm": c[:, 1], "infeed_mm": x_mid - c[:, 1],
               "path_z_mm": qz, "crown_drop_mm": m.R - m.path.evaluate(s)[2],
               "e_deg": np.degrees(e)},
        notes=notes,
    )
