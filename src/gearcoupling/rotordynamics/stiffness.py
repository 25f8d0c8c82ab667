"""The 6 x 6 stiffness matrix of hub against sleeve at the operating point.

Central differences of the pose (:mod:`.pose`) through the load model, the torque held
(the load models are torque driven), then turned into the matrix at a held wind-up:

    K_uu = -dQ/du + K_cc (dQ/dT) (dchi/du)^T,   K_uc = -K_cc dQ/dT,
    K_cu = -K_cc dchi/du,                        K_cc = dT/dchi,

with ``Q`` the generalized forces on the hub (:func:`.pose.generalized_forces`), ``chi``
the wind-up and ``u`` the five other coordinates; ``K = -dQ/dq``. Each rotation of one
tooth pitch is differenced on its own and the matrices averaged (the matrix repeats every
pitch); the tilt about ``y`` at a misalignment follows exactly from turning the operating
point's mean forces (the tilt axis turns by ``b / i``). The bodies' torsion is added in
series on the torsion coordinate. Method, conventions and step convergence:
docs/rotordynamics.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..clearance import SweepResult, sweep
from ..errors import ArgumentError
from ..loading import (
    body_windup_rad,
    load_from_sweep,
    load_model,
    resolve_model,
    resolve_torque_Nm,
    springs_name,
    start_from,
)
from ..spec import MISALIGNMENT_RANGE_DEG, as_spec
from .pose import generalized_forces, translation_gap_offsets
from .torsion import windup_beyond_touch
from .wrench import hub_wrench

DOFS = ("x", "y", "z", "tilt_x", "tilt_y", "torsion")
FORCE_UNITS = ("N", "N", "N", "N·m", "N·m", "N·m")
DISPLACEMENT_UNITS = ("m", "m", "m", "rad", "rad", "rad")
DEFAULT_ROTATIONS = 8
#: difference schemes and their default steps: ``central`` (two solves per column, second
#: order) and ``forward`` (one solve per column from the operating point, first order, so
#: a smaller step; central where aligned); docs/rotordynamics.md, "Step sizes"
DEFAULT_STEPS = {"central": 0.02, "forward": 0.0025}
DIFFERENCES = tuple(DEFAULT_STEPS)
#: models differenced forward unless told: those whose poses are costly and whose forces
#: are smooth in the pose (the others' tooth springs switch on and off within a step)
FORWARD_MODELS = ("surface",)


def default_rotations(model: str) -> int:
    """Rotations over one tooth pitch the data are averaged over unless given: the model's
    load-study rotations where it has them (surface: 3; on renzo-1967 and industrial-m2 at
    1° the stiffness diagonal is within 0.42 % of 16 rotations, 0.07 % at 4, the near-zero
    axial entry aside), else :data:`DEFAULT_ROTATIONS`."""
    study = load_model(model).study
    return study[0] if study else DEFAULT_ROTATIONS


def default_differences(model: str) -> str:
    """The difference scheme unless given: ``forward`` for :data:`FORWARD_MODELS` (on
    renzo-1967 and industrial-m2 at their design points within 0.12 % of ``central`` on the
    diagonal, 0.2 % of ``sqrt(K_ii K_jj)`` elsewhere, with 15 pose solves against 33),
    else ``central``."""
    return "forward" if model in FORWARD_MODELS else "central"


_TRANSLATIONS = 3
_SHIFTS = (0, 1)  # x and y: the translations that change gaps
_TILT_X, _TILT_Y, _TORSION = 3, 4, 5


@dataclass(frozen=True, eq=False)
class StiffnessMatrix:
    """The coupling's stiffness at one operating point (docs/rotordynamics.md).

    Attributes
    ----------
    mesh_matrix : (6, 6) float
        ``K = -dQ/dq`` of the teeth alone (the wind-up ``chi`` held), SI units: rows
        ``FORCE_UNITS``, columns per ``DISPLACEMENT_UNITS``, order :data:`DOFS`.
    body_torsional_Nm_per_rad : float
        The bodies' torsional stiffness in series (``inf`` for a hub without a bore).
    axial_slip_force_N : float
        ``mu`` times the sum of the normal tooth loads: the thrust at which the teeth slide.
    operating_forces : (5,) float
        Pitch-mean force on the hub (N, sleeve frame) and tilt moments (N·m) at the point.
    rotation_spread : dict
        Per diagonal entry differenced at each rotation: its (min, max) over the pitch.
    steps : dict
        ``translation_mm``, ``tilt_rad``, ``torque_Nm``, ``relative_step``, ``rotations``,
        ``differences`` (the scheme used: central where aligned).
    friction : float
        The Coulomb coefficient used (0 at zero misalignment, where the teeth do not slide).
    operating_windup_rad : float
        The teeth's wind-up beyond first touch at the point, mean over the rotations
        (:func:`.torsion.windup_beyond_touch`; the wind-up curve's point at the torque).
    """

    misalignment_deg: float
    torque_Nm: float
    model: str
    springs: str
    mesh_matrix: NDArray[np.float64]
    body_torsional_Nm_per_rad: float
    axial_slip_force_N: float
    operating_forces: NDArray[np.float64]
    rotation_spread: dict[str, tuple[float, float]]
    steps: dict[str, Any]
    friction: float
    notes: tuple[str, ...] = field(default=())
    operating_windup_rad: float = math.nan

    @property
    def matrix(self) -> NDArray[np.float64]:
        """Hub bore against sleeve outside diameter: :attr:`mesh_matrix` with the bodies'
        torsion in series on the torsion coordinate."""
        return series_torsion(self.mesh_matrix, self.body_torsional_Nm_per_rad)

    def at_constant_torque(self) -> NDArray[np.float64]:
        """``(5, 5)``: the matrix of ``x, y, z, tilt_x, tilt_y`` with the torque held (the
        wind-up free), ``K_uu - K_uc K_cu / K_cc``."""
        K = self.mesh_matrix
        return K[:5, :5] - np.outer(K[:5, 5], K[5, :5]) / K[5, 5]

    def cross_coupled(self) -> dict[str, float]:
        """The tilt terms across the axes (N·m/rad), held wind-up and held torque:
        ``k_xy`` the moment about ``-x`` on the hub per tilt about ``y``, ``k_yx`` the moment
        about ``-y`` per tilt about ``x``, and the antisymmetric part ``(k_xy - k_yx) / 2``
        that feeds a whirl."""
        out = {}
        for name, K in (("held_windup", self.matrix), ("held_torque",
                                                         self.at_constant_torque())):
            kxy, kyx = float(K[_TILT_X, _TILT_Y]), float(K[_TILT_Y, _TILT_X])
            out.update({f"k_xy_{name}_Nm_per_rad": kxy, f"k_yx_{name}_Nm_per_rad": kyx,
                        f"antisymmetric_{name}_Nm_per_rad": 0.5 * (kxy - kyx)})
        return out

    def as_dict(self) -> dict[str, Any]:
        return {"dofs": list(DOFS), "force_units": list(FORCE_UNITS),
                "displacement_units": list(DISPLACEMENT_UNITS),
                "matrix": self.matrix.tolist(), "mesh_matrix": self.mesh_matrix.tolist(),
                "at_constant_torque": self.at_constant_torque().tolist(),
                "cross_coupled": self.cross_coupled(),
                "body_torsional_Nm_per_rad": _finite_or_none(self.body_torsional_Nm_per_rad),
                "axial_slip_force_N": self.axial_slip_force_N,
                "operating_force_N": self.operating_forces[:3].tolist(),
                "operating_tilt_moment_Nm": self.operating_forces[3:].tolist(),
                "rotation_spread": {k: list(v) for k, v in self.rotation_spread.items()},
                "steps": self.steps, "friction": self.friction, "model": self.model,
                "springs": self.springs, "notes": list(self.notes)}


def _finite_or_none(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def series_torsion(K: NDArray, k_body: float) -> NDArray[np.float64]:
    """``K`` with a torsion spring ``k_body`` in series on its last coordinate (the
    teeth's wind-up condensed out)."""
    if not math.isfinite(k_body):
        return K.copy()
    d = K[5, 5] + k_body
    out = K - np.outer(K[:, 5], K[5, :]) / d
    out[:5, 5] = K[:5, 5] * k_body / d
    out[5, :5] = K[5, :5] * k_body / d
    out[5, 5] = K[5, 5] * k_body / d
    return out


def pitch_rotations(spec, rotations: int) -> NDArray[np.float64]:
    """``rotations`` coupling rotations (degrees) evenly over one tooth pitch."""
    if isinstance(rotations, bool) or not isinstance(rotations, int) or rotations < 1:
        raise ArgumentError("rotations", rotations, "a whole number >= 1 (rotations per pitch)")
    return np.arange(rotations) * 360.0 / spec.tooth.teeth / rotations


@dataclass(frozen=True)
class _Case:
    """What a pose evaluation needs: the spec, torque, model, friction and tolerance."""

    spec: Any
    torque_Nm: float
    model: str | None
    friction: float
    tolerance_mm: float

    def solve(self, sw: SweepResult, torque: float | None = None, offsets=None):
        """Hub-frame force and moment ``(M, 3)``, wind-up ``(M,)`` and the load result."""
        T = self.torque_Nm if torque is None else torque
        res = load_from_sweep(sw, torque_Nm=T, model=self.model, gap_offset_rad=offsets)
        F, M = hub_wrench(res, self.friction)
        return F, M, np.asarray(res.windup_rad, float), res

    def state(self, sw: SweepResult, phi: float = 0.0, torque: float | None = None,
              offsets=None) -> tuple[NDArray, NDArray, Any]:
        """Generalized forces ``(M, 5)``, wind-up ``(M,)`` and the load result of ``sw``,
        whose tilt axis lies at ``phi`` from the operating one."""
        F, M, chi, res = self.solve(sw, torque, offsets)
        return generalized_forces(F, M, math.radians(sw.misalignment_deg), phi), chi, res

    def sweep(self, misalignment_rad: float, angles_deg) -> SweepResult:
        return sweep(self.spec, math.degrees(misalignment_rad), angles_deg,
                     tolerance_mm=self.tolerance_mm)


def stiffness_from_sweep(sw: SweepResult, torque_Nm: float, *, model: str | None = None,
                         friction: float | None = None,
                         relative_step: float | None = None,
                         differences: str | None = None) -> StiffnessMatrix:
    """The stiffness matrix at the operating point of ``sw``, a sweep over rotations of one
    tooth pitch (:func:`pitch_rotations`), at ``torque_Nm`` (signed, not zero).

    ``relative_step``: the translation step as a share of the largest tooth deflection
    at the point (the tilt step is it over the pitch radius, the torque step this share
    of the torque; default :data:`DEFAULT_STEPS` of the scheme); the accuracy knob with
    ``rotations`` and ``differences`` (:data:`DIFFERENCES`, default
    :func:`default_differences`; docs/rotordynamics.md).
    """
    spec = sw.spec
    model = resolve_model(spec, model)
    differences = default_differences(model) if differences is None else differences
    if differences not in DIFFERENCES:
        raise ArgumentError("differences", differences, f"one of {DIFFERENCES}")
    if relative_step is None:
        relative_step = DEFAULT_STEPS[differences]
    if not (isinstance(relative_step, int | float) and 1e-4 <= relative_step <= 0.2):
        raise ArgumentError("relative_step", relative_step, "a share from 1e-4 to 0.2 of the "
                            "largest tooth deflection")
    alpha = math.radians(sw.misalignment_deg)
    mu = spec.load.friction if friction is None else float(friction)
    notes = []
    if alpha == 0.0 and mu > 0:
        notes.append("aligned: the teeth do not slide, so friction adds no stiffness (a "
                     "Coulomb force has no linear part at zero sliding); the slip force holds")
        mu = 0.0
    case = _Case(spec, float(torque_Nm), model, mu, sw.tolerance_mm)
    Q0, c0, res0 = case.state(sw)
    deflection = float(np.mean(np.max(res0.deflection_mm, axis=0)))
    if not deflection > 0:
        raise ArgumentError("torque_Nm", torque_Nm, "a torque that loads the teeth: the "
                            "stiffness is that of loaded teeth (at zero torque the coupling "
                            "turns freely within its backlash)")
    h_t = relative_step * deflection
    h_a = h_t / spec.tooth.pitch_radius
    if alpha > 0:
        h_a = min(h_a, 0.25 * alpha)
    h_T = relative_step * abs(case.torque_Nm)
    n = sw.angles_deg.size
    if alpha == 0:  # aligned, the wind-up is even in the tilts and translations
        differences = "central"
    forward = differences == "forward"
    dQdu, dcdu = np.zeros((n, 5, 5)), np.zeros((n, 5))
    _translations(case, sw, res0.loaded_flank, h_t, dQdu, dcdu, (Q0, c0) if forward else None)
    _tilts(case, sw, res0.loaded_flank, h_a, (Q0, c0), dQdu, dcdu, forward)
    dQdT, dcdT = _difference(lambda t: case.state(sw, torque=t)[:2], case.torque_Nm, h_T,
                             (Q0, c0) if forward else None)
    per_rotation = np.array([_held_windup(dQdu[j], dcdu[j], dQdT[j], dcdT[j])
                             for j in range(n)])
    per_rotation[:, :, :_TRANSLATIONS] *= 1e3  # per mm -> per m
    K = per_rotation.mean(axis=0)
    Qbar = Q0.mean(axis=0)
    if alpha > 0:  # the tilt axis turned by b / i: the mean forces turn with it
        K[:5, _TILT_Y] = -np.array([-Qbar[1], Qbar[0], 0.0, -Qbar[4], Qbar[3]]) / alpha
        K[5, _TILT_Y] = 0.0
    k_body = _body_stiffness(spec, case.torque_Nm)
    diag = np.array([np.diag(series_torsion(k, k_body)) for k in per_rotation])
    spread = {DOFS[i]: (float(diag[:, i].min()), float(diag[:, i].max()))
              for i in range(6) if alpha == 0.0 or i != _TILT_Y}
    slip = spec.load.friction * float(np.mean(np.sum(res0.normal_force_N, axis=0)))
    steps = {"translation_mm": h_t, "tilt_rad": h_a, "torque_Nm": h_T,
             "relative_step": float(relative_step), "rotations": n,
             "differences": differences}
    return StiffnessMatrix(float(sw.misalignment_deg), case.torque_Nm, res0.model,
                           springs_name(spec, res0.model), _round_off(K), k_body, slip, Qbar,
                           spread, steps, mu, tuple(notes), windup_beyond_touch(res0))


def _difference(f, x: float, h: float, base: tuple | None) -> tuple:
    """The derivative of ``f(x) -> (Q, chi)`` at ``x``: central over ``x +- h``, or forward
    from ``base`` = ``f(x)`` where given."""
    Qp, cp = f(x + h)
    if base is not None:
        return (Qp - base[0]) / h, (cp - base[1]) / h
    Qm, cm = f(x - h)
    return (Qp - Qm) / (2 * h), (cp - cm) / (2 * h)


def _translations(case: _Case, sw: SweepResult, flank: str, h: float, dQdu: NDArray,
                  dcdu: NDArray, base: tuple[NDArray, NDArray] | None) -> None:
    """Fill the translation columns: each rotation on its own, the loaded flanks moved by
    their gap offsets (:func:`.pose.translation_gap_offsets`); central differences, or
    forward from the operating point ``base`` = (Q, chi) per rotation where given. The
    axial column stays zero: the sleeve's teeth are straight, so an axial shift changes no
    gap and the model no force (solved, it gave only the solver's rounding)."""
    alpha = math.radians(sw.misalignment_deg)
    for j, psi in enumerate(np.asarray(sw.angles_deg, float)):
        one = case.sweep(alpha, [psi])
        start_from(one, sw, j, flank)  # the shifted poses start from the operating one
        for e in _SHIFTS:
            def moved(x, e=e, one=one):
                d = np.zeros(3)
                d[e] = x
                Q, c, _ = case.state(one, offsets=translation_gap_offsets(case.spec, one,
                                                                            flank, 0, d))
                return Q[0], c[0]
            dQdu[j, :, e], dcdu[j, e] = _difference(
                moved, 0.0, h, None if base is None else (base[0][j], base[1][j]))


def _tilts(case: _Case, sw: SweepResult, flank: str, h: float,
           base: tuple[NDArray, NDArray], dQdu: NDArray, dcdu: NDArray, forward: bool) -> None:
    """Fill the tilt columns from sweeps at the neighbouring tilt vectors, turned back onto
    the operating tilt axis: about ``x`` at a misalignment (central, or backward from the
    operating point ``base`` = (Q, chi) within ``h`` of 6°; ``forward``: one-sided from
    ``base``, backward within ``h`` of 6°; the ``y`` column follows from the mean forces),
    about ``x`` and ``y`` aligned (vectors of length ``h`` along +-x and +-y, one sweep)."""
    alpha = math.radians(sw.misalignment_deg)
    psi = np.asarray(sw.angles_deg, float)
    n = psi.size
    backward = alpha + h > math.radians(MISALIGNMENT_RANGE_DEG[1])
    if alpha == 0:
        poses = [(h, p) for p in (0.0, math.pi, 0.5 * math.pi, -0.5 * math.pi)]
    elif forward:
        poses = [(alpha - h if backward else alpha + h, 0.0)]
    else:
        poses = [(alpha + s * h, 0.0) for s in ((-1.0, -2.0) if backward else (1.0, -1.0))]
    found = {}
    for A in sorted({A for A, _ in poses}):
        same = [k for k, (Ak, _) in enumerate(poses) if Ak == A]
        tilted = case.sweep(A, np.concatenate([psi - math.degrees(poses[k][1]) for k in same]))
        start_from(tilted, sw, 0, flank)  # its first pose, rotation 0, next to the operating one
        F, M, chi, _ = case.solve(tilted)
        for m, k in enumerate(same):
            part = slice(m * n, (m + 1) * n)
            found[k] = (generalized_forces(F[part], M[part], A, poses[k][1]), chi[part])
    if forward:  # one-sided from the operating point, toward 6° where there is room
        s = -1.0 if backward else 1.0
        dQdu[:, :, _TILT_X] = s * (found[0][0] - base[0]) / h
        dcdu[:, _TILT_X] = s * (found[0][1] - base[1]) / h
        return
    if backward:  # (3 f(i) - 4 f(i - h) + f(i - 2h)) / 2h, second order as the central one
        (Q1, c1), (Q2, c2) = found[0], found[1]
        dQdu[:, :, _TILT_X] = (3 * base[0] - 4 * Q1 + Q2) / (2 * h)
        dcdu[:, _TILT_X] = (3 * base[1] - 4 * c1 + c2) / (2 * h)
        return
    pairs = {_TILT_X: (0, 1), _TILT_Y: (2, 3)} if alpha == 0 else {_TILT_X: (0, 1)}
    for col, (plus, minus) in pairs.items():
        dQdu[:, :, col] = (found[plus][0] - found[minus][0]) / (2 * h)
        dcdu[:, col] = (found[plus][1] - found[minus][1]) / (2 * h)


def _round_off(K: NDArray) -> NDArray[np.float64]:
    """``K`` with the entries below 1e-9 of their block's scale set to 0: round-off where
    symmetry makes them vanish (translations and rotations are scaled apart)."""
    d = np.abs(np.diag(K))
    scale = np.where(np.arange(6) < _TRANSLATIONS, d[:_TRANSLATIONS].max(), d[3:].max())
    return np.where(np.abs(K) < 1e-9 * np.sqrt(np.outer(scale, scale)), 0.0, K)


def _held_windup(dQdu: NDArray, dcdu: NDArray, dQdT: NDArray, dcdT: float) -> NDArray:
    """The 6 x 6 matrix at a held wind-up from the torque-driven derivatives."""
    kcc = 1.0 / dcdT
    K = np.zeros((6, 6))
    K[:5, :5] = -dQdu + kcc * np.outer(dQdT, dcdu)
    K[:5, 5] = -kcc * dQdT
    K[5, :5] = -kcc * dcdu
    K[5, 5] = kcc
    return K


def _body_stiffness(spec, torque_Nm: float) -> float:
    """The bodies' torsional stiffness (N·m/rad, linear); ``inf`` when they do not twist."""
    twist = body_windup_rad(spec, abs(torque_Nm))["body_rad"]
    return abs(torque_Nm) / twist if twist > 0 else math.inf


def stiffness_matrix(spec, misalignment_deg: float, torque_Nm: float | None = None, *,
                     model: str | None = None, friction: float | None = None,
                     rotations: int | None = None,
                     relative_step: float | None = None,
                     differences: str | None = None,
                     tolerance_mm: float | None = None) -> StiffnessMatrix:
    """The 6 x 6 stiffness matrix of hub against sleeve (module docstring).

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
        0-6 degrees.
    torque_Nm : float, optional
        Signed, not zero; default the spec's ``[load]`` torque.
    model : str, optional
        Load model; default the spec's ``[load] model``.
    friction : float, optional
        Coulomb coefficient; default the spec's ``[load] friction``.
    rotations : int, optional
        Rotations over one tooth pitch the matrix is averaged over (accuracy knob); default
        :func:`default_rotations`.
    relative_step : float, optional
        Difference step as a share of the largest tooth deflection (default
        :data:`DEFAULT_STEPS` of the scheme).
    differences : {"central", "forward"}, optional
        Difference scheme (accuracy knob); default :func:`default_differences`.
    tolerance_mm : float, optional
        Sweep accuracy of every gap (default the sweep's).
    """
    spec = as_spec(spec)
    T = resolve_torque_Nm(spec, torque_Nm)
    model = resolve_model(spec, model)
    angles = pitch_rotations(spec, default_rotations(model) if rotations is None else rotations)
    sw = (sweep(spec, misalignment_deg, angles) if tolerance_mm is None else
          sweep(spec, misalignment_deg, angles, tolerance_mm=tolerance_mm))
    return stiffness_from_sweep(sw, T, model=model, friction=friction,
                                relative_step=relative_step, differences=differences)


__all__ = ["DEFAULT_STEPS", "DIFFERENCES", "DISPLACEMENT_UNITS", "DOFS", "FORCE_UNITS",
           "FORWARD_MODELS", "StiffnessMatrix", "default_differences", "default_rotations",
           "pitch_rotations",
           "series_torsion", "stiffness_from_sweep", "stiffness_matrix"]
