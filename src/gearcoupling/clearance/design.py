"""Design quantities from the clearance kernel: contact travel, critical misalignment,
binding angle and the two gear meshes of a double-engagement coupling.

All use the ideal geometry's periodicity: tooth ``k`` at rotation ``psi`` is tooth 0 at
``theta = psi + 2 pi k / N``, so a rotation of one pitch with every tooth covers a turn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..arguments import (
    GAP_TOLERANCE_MM,
    SWEEP_GRID,
    angle_tolerance_deg,
    count,
    real,
    sweep_tolerance_mm,
)
from ..errors import ArgumentError
from ..geometry import sleeve_model
from ..spec import MISALIGNMENT_RANGE_DEG, CouplingSpec, as_spec
from .kernel import FACE_END, minimise
from .result import SweepResult
from .tooth_map import check_misalignment, flank_minima, sweep

ANGLE_TOLERANCE_DEG = 1e-4
DEFAULT_STEPS = 16  # rotations per tooth pitch for the design searches
BINDING_BRACKETS_DEG = (0.5, 1.0, 2.0, 4.0, MISALIGNMENT_RANGE_DEG[1])


def pitch_turning_angles(teeth: int, steps: int = DEFAULT_STEPS) -> np.ndarray:
    """``theta[k, j]`` for ``steps`` rotations over one tooth pitch, ``(N, steps)``."""
    psi = 2.0 * np.pi * np.arange(steps) / (teeth * steps)
    return psi[None, :] + 2.0 * np.pi * np.arange(teeth)[:, None] / teeth


def contact_travel(spec: CouplingSpec,
                   misalignment_deg: float, *, tolerance_mm: float = GAP_TOLERANCE_MM
                   ) -> dict[str, float]:
    """Axial position of the contact on the pivot teeth (theta = 0 and 180°), in mm.

    ``pitch_line_z_mm`` is where the pitch-line clearance of tooth 0's cw flank is smallest
    (Renzo's measure), ``flank_z_mm`` the point of first touch over the whole flank;
    ``renzo_mm`` the small-angle estimate ``R_c cot(phi) i``.
    """
    spec = as_spec(spec)
    i = check_misalignment(misalignment_deg)
    tolerance_mm = sweep_tolerance_mm(tolerance_mm)
    mins, table = flank_minima(spec, i, np.array([0.0, np.pi]), tolerance_mm=tolerance_mm)
    pitch = minimise(table, sleeve_model(spec), i, np.array([0.0, np.pi]),
                     pitch_radius=spec.tooth.pitch_radius,
                     tolerance_mm=tolerance_mm)["pitch_normal"]
    rc = spec.derived["crowning_radius_midplane_mm"]
    return {
        "pitch_line_z_mm": float(pitch.z_mm[0]),
        "pitch_line_z_opposite_mm": float(pitch.z_mm[1]),
        "flank_z_mm": float(mins["z"][0]),
        "renzo_mm": rc / math.tan(spec.tooth.pressure_angle) * i if math.isfinite(rc) else 0.0,
    }


def min_backlash_rad(spec: CouplingSpec, misalignment_deg: float, *, steps: int = DEFAULT_STEPS,
                     tolerance_mm: float = GAP_TOLERANCE_MM) -> float:
    """Smallest backlash (rad) over a full turn at ``misalignment_deg`` (0-6°); negative
    where the teeth bind. ``steps`` rotations per tooth pitch are searched (1-1000)."""
    spec = as_spec(spec)
    i = check_misalignment(misalignment_deg)
    return _min_backlash(spec, i, count(steps, "steps"), sweep_tolerance_mm(tolerance_mm))


def _min_backlash(spec: CouplingSpec, misalignment_rad: float, steps: int = DEFAULT_STEPS,
                  tolerance_mm: float = GAP_TOLERANCE_MM) -> float:
    theta = pitch_turning_angles(spec.tooth.teeth, steps)
    both = np.stack([theta, np.pi - theta])
    mins, _ = flank_minima(spec, misalignment_rad, both, tolerance_mm=tolerance_mm,
                           measures=("normal",))
    gap = mins["normal"] / spec.tooth.base_radius / mins["rate"]
    return float(np.min(np.min(gap[0], axis=0) + np.min(gap[1], axis=0)))


def pivot_on_face_end(spec: CouplingSpec, misalignment_rad: float) -> bool:
    """Whether the pivot teeth (theta = 0 and 180°) touch first at a face end."""
    mins, _ = flank_minima(spec, misalignment_rad, np.array([0.0, np.pi]),
                           tolerance_mm=GAP_TOLERANCE_MM, measures=("normal",))
    return bool(np.any(mins["kind"] == FACE_END))


def critical_misalignment_deg(spec: CouplingSpec, *, tolerance_deg: float = ANGLE_TOLERANCE_DEG
                              ) -> float | None:
    """Smallest misalignment (degrees) at which the contact on the pivot teeth runs onto a
    face end (docs/conventions.md, Tooth geometry: it travels axially by about ``R_c cot(phi)
    i``), by bisection
    to ``tolerance_deg``; below it the contact stays on the flank.

    The pivot teeth carry the largest axial travel. Near the contacting teeth the
    clearance is flat in theta (Renzo's separation grows like theta^2 sin^2 from there), so
    "the" contacting tooth is ill-conditioned while the pivot teeth are not. The profile
    ends (tip, form circle, sleeve tip edge) do not count: the hub profile is conjugate to
    the sleeve's, so the gap is nearly constant along the profile and its minimum sits at a
    profile end after any twist. Returns ``None`` when no face end is reached up to 6°.
    ``tolerance_deg``: 1e-9 to 0.5 degrees.
    """
    spec = as_spec(spec)
    tolerance_deg = angle_tolerance_deg(tolerance_deg)
    top = math.radians(MISALIGNMENT_RANGE_DEG[1])
    if not pivot_on_face_end(spec, top):
        return None
    lo, hi = 0.0, top
    tol = math.radians(tolerance_deg)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if pivot_on_face_end(spec, mid):
            hi = mid
        else:
            lo = mid
    return math.degrees(0.5 * (lo + hi))


def binding_angle_deg(spec: CouplingSpec, *, tolerance_deg: float = ANGLE_TOLERANCE_DEG,
                      steps: int = DEFAULT_STEPS) -> float | None:
    """Misalignment (degrees) at which the smallest backlash over a turn reaches zero
    (Brent's method to ``tolerance_deg``, 1e-9 to 0.5 degrees, searching ``steps``
    rotations per tooth pitch, 1-1000); ``None`` if the coupling does not bind by 6°."""
    from scipy.optimize import brentq  # at the call: importing the sweep stays light

    spec = as_spec(spec)
    tolerance_deg = angle_tolerance_deg(tolerance_deg)
    steps = count(steps, "steps")
    hi = math.radians(MISALIGNMENT_RANGE_DEG[1])
    known: dict[float, float] = {}

    def f(i):  # brentq evaluates the ends again: each value once
        if i not in known:
            known[i] = _min_backlash(spec, i, steps)
        return known[i]

    # bracket from below (small angles are cheap: few rows need deep refinement), so the
    # costly 6° end is evaluated only when nothing smaller binds
    lo = 0.0
    for deg in BINDING_BRACKETS_DEG:
        i = math.radians(deg)
        if f(i) <= 0:
            hi = i
            break
        lo = i
    else:
        return None
    root = brentq(f, lo, hi, xtol=math.radians(tolerance_deg), rtol=1e-12)
    return math.degrees(root)


# ------------------------------------------------------------- double engagement


@dataclass(frozen=True)
class MeshAngles:
    """Misalignment of each gear mesh of a double-engagement coupling (degrees).

    ``a_tilt_axis_deg``, ``b_tilt_axis_deg``: azimuth of each mesh's tilt axis (sleeve axis
    x hub axis) about the sleeve axis, from shaft A's ``x`` carried onto the sleeve by the
    smallest turn; a mesh at the coupling rotation ``psi`` is the single-engagement pose
    ``psi - tilt axis`` (docs/coupling.md). ``sleeve_azimuth_deg``: the direction about
    shaft A toward which the sleeve axis leans; ``centre_b_mm``: hub B's midplane centre.
    """

    a_deg: float
    b_deg: float
    sleeve_tilt_deg: float
    a_tilt_axis_deg: float = 0.0
    b_tilt_axis_deg: float = 0.0
    sleeve_azimuth_deg: float = 0.0
    centre_b_mm: tuple[float, float, float] = (0.0, 0.0, 0.0)


def _direction(angle: float, azimuth: float) -> np.ndarray:
    return np.array([math.sin(angle) * math.cos(azimuth), math.sin(angle) * math.sin(azimuth),
                     math.cos(angle)])


def mesh_angles(offset_mm: float, angle_deg: float, span_mm: float, *,
                offset_azimuth_deg: float = 0.0, angle_azimuth_deg: float = 0.0,
                offset_at: float = 1.0) -> MeshAngles:
    """Angles at the two gear meshes of a double-engagement coupling.

    Shaft A runs along ``z``; hub A's tooth midplane centre ``O_A`` is the origin. Shaft B
    is tilted by ``angle_deg`` (in the plane at ``angle_azimuth_deg``) and crosses the
    plane ``z = offset_at * span_mm`` at the parallel offset ``offset_mm`` (direction
    ``offset_azimuth_deg`` about ``z``); hub B's midplane centre ``O_B`` lies on shaft B,
    the rest of the span beyond that plane (``offset_at`` 1: the offset at hub B's
    midplane; 0.5: at the coupling's centre, where a shaft angle splits evenly). The
    floating sleeve centres on both meshes, so its axis runs through ``O_A`` and ``O_B``;
    each mesh angle is the angle between its shaft and the sleeve axis.
    """
    offset_mm, angle_deg, span_mm, offset_azimuth_deg, angle_azimuth_deg = (
        real(v, name) for v, name in ((offset_mm, "offset_mm"), (angle_deg, "angle_deg"),
                                      (span_mm, "span_mm"),
                                      (offset_azimuth_deg, "offset_azimuth_deg"),
                                      (angle_azimuth_deg, "angle_azimuth_deg")))
    offset_at = real(offset_at, "offset_at", 0.0, 1.0)
    if span_mm <= 0:
        raise ArgumentError("span_mm", span_mm, "distance between the hub midplanes must be > 0 mm")
    if offset_mm < 0 or not 0 <= angle_deg < 90:
        raise ArgumentError("offset_mm/angle_deg", (offset_mm, angle_deg),
                        "offset must be >= 0 mm and the angle 0-90°")
    az = math.radians(offset_azimuth_deg)
    shaft_b = _direction(math.radians(angle_deg), math.radians(angle_azimuth_deg))
    ob = (np.array([offset_mm * math.cos(az), offset_mm * math.sin(az), offset_at * span_mm])
          + (1.0 - offset_at) * span_mm * shaft_b)
    sleeve = ob / np.linalg.norm(ob)
    z = np.array([0.0, 0.0, 1.0])
    k = np.cross(z, sleeve)  # the smallest turn carrying z onto the sleeve axis
    skew = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    ref = np.eye(3) + skew + skew @ skew / (1.0 + float(sleeve[2]))

    def between(u, v):
        return math.degrees(math.atan2(np.linalg.norm(np.cross(u, v)), float(np.dot(u, v))))

    def tilt_axis(hub):  # azimuth of sleeve x hub about the sleeve axis; 0 where aligned
        x = np.cross(sleeve, hub)
        return math.degrees(math.atan2(float(x @ ref[:, 1]), float(x @ ref[:, 0])))

    a = between(z, sleeve)
    return MeshAngles(a, between(shaft_b, sleeve), a, tilt_axis(z), tilt_axis(shaft_b),
                      math.degrees(math.atan2(sleeve[1], sleeve[0])),
                      (float(ob[0]), float(ob[1]), float(ob[2])))


def double_engagement(spec: CouplingSpec, offset_mm: float, angle_deg: float, span_mm: float,
                      angles_deg: ArrayLike, *, offset_azimuth_deg: float = 0.0,
                      angle_azimuth_deg: float = 0.0, tolerance_mm: float = GAP_TOLERANCE_MM,
                      grid: int = SWEEP_GRID, periodic: bool = True
                      ) -> tuple[MeshAngles, SweepResult, SweepResult]:
    """Sweeps of both gear meshes: ``(MeshAngles, result_a, result_b)``.

    Raises :class:`ArgumentError` if a mesh angle exceeds the 6° the sweeps cover.
    ``offset_azimuth_deg``, ``angle_azimuth_deg`` as :func:`mesh_angles`; ``tolerance_mm``,
    ``grid``, ``periodic`` as :func:`~.tooth_map.sweep`.
    """
    spec = as_spec(spec)
    mesh = mesh_angles(offset_mm, angle_deg, span_mm, offset_azimuth_deg=offset_azimuth_deg,
                       angle_azimuth_deg=angle_azimuth_deg)
    for name, value in (("mesh A angle", mesh.a_deg), ("mesh B angle", mesh.b_deg)):
        if value > MISALIGNMENT_RANGE_DEG[1]:
            raise ArgumentError(name, round(value, 6), f"must be at most "
                            f"{MISALIGNMENT_RANGE_DEG[1]}°: reduce the offset or angle, or "
                            "lengthen the span")
    a, b = (sweep(spec, deg, angles_deg, tolerance_mm=tolerance_mm, grid=grid, periodic=periodic)
            for deg in (mesh.a_deg, mesh.b_deg))
    return mesh, a, b


def design_quantities(spec: CouplingSpec, misalignment_deg: float, *,
                      tolerance_deg: float = ANGLE_TOLERANCE_DEG) -> dict:
    """Root-found design angles and the pivot-tooth contact travel, as plain data."""
    spec = as_spec(spec)
    tolerance_deg = angle_tolerance_deg(tolerance_deg)
    travel = contact_travel(spec, misalignment_deg)
    crit = critical_misalignment_deg(spec, tolerance_deg=tolerance_deg)
    bind = binding_angle_deg(spec, tolerance_deg=tolerance_deg)
    return {
        "pivot_contact_z_mm": travel,
        "critical_misalignment_deg": crit,
        "binding_angle_deg": bind,
        "design_angle_tolerance_deg": tolerance_deg,
        "design_rotations_per_pitch": DEFAULT_STEPS,
    }
