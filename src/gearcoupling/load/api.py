"""Entry points: ``load`` (sweep + load sharing) and ``load_from_sweep``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SpecError
from ..loadspec import LOAD_MODELS
from .result import LoadResult

FLANK_NAMES = ("cw", "ccw")


def resolve_torque_Nm(spec, torque_Nm: float | None) -> float:
    """The torque to apply: the argument, else ``[load] torque_Nm``; finite or SpecError."""
    t = spec.load.torque_Nm if torque_Nm is None else torque_Nm
    if t is None:
        raise SpecError("load.torque_Nm", None, "no torque: give [load] torque_Nm (or "
                        "torque_lbf_in) in the spec or torque_Nm= / --torque")
    try:
        t = float(t)
    except (TypeError, ValueError) as err:
        raise SpecError("torque_Nm", t, "must be a number (N·m)") from err
    if not math.isfinite(t):
        raise SpecError("torque_Nm", t, "must be a finite torque in N·m")
    return t


def resolve_model(spec, model: str | None) -> str:
    m = spec.load.model if model is None else model
    if m not in LOAD_MODELS:
        raise SpecError("model", m, f"one of {LOAD_MODELS}")
    return m


def loaded_gaps(sweep_result, flank: int, gap_offset_rad: ArrayLike | None) -> NDArray:
    """Gap angles ``(N, M)`` of the loaded flank plus the per-tooth offsets."""
    g = sweep_result.gap_angle_rad
    if g is None:
        raise SpecError("sweep_result", None, "has no gap angles (made by an older sweep); "
                        "run gearcoupling.sweep.sweep again")
    g = g[flank]
    if gap_offset_rad is None:
        return g
    off = np.asarray(gap_offset_rad, dtype=float)
    N = g.shape[0]
    if off.shape == (2, N):
        off = off[flank]
    if off.shape != (N,) or not np.all(np.isfinite(off)):
        raise SpecError("gap_offset_rad", off.shape, f"must be finite, shaped ({N},) or (2, {N})")
    return g + off[:, None]


def contact_points(spec, sweep_result, flank: int) -> tuple[NDArray, NDArray]:
    """First-touch ``(z, r)`` of the loaded flank, ``(N, M)``; where nothing faces the sleeve
    (no finite point) the midplane pitch point stands in (those teeth carry no load)."""
    z = sweep_result.contact_z_mm[flank]
    r = sweep_result.contact_r_mm[flank]
    ok = np.isfinite(z) & np.isfinite(r)
    return np.where(ok, z, 0.0), np.where(ok, r, spec.tooth.pitch_radius)


def tooth_compliance(spec):
    """The compliance object of ``[load] stiffness``: cantilever, or the FE table."""
    if spec.load.stiffness == "fe":
        try:
            from ..fea import tooth_compliance_table
        except ImportError as err:
            from ..errors import BackendError

            raise BackendError("[load] stiffness = \"fe\" needs gearcoupling.fea."
                               "tooth_compliance_table (the FE tooth-stiffness branch), which "
                               "this installation lacks; use stiffness = \"cantilever\"") from err
        return tooth_compliance_table(spec)
    from .cantilever import CantileverCompliance

    return _cached_cantilever(spec, CantileverCompliance)


_CACHE: dict[Any, Any] = {}


def _cached_cantilever(spec, cls):
    key = (spec, spec.name)
    if key not in _CACHE:
        if len(_CACHE) > 32:
            _CACHE.clear()
        _CACHE[key] = cls(spec)
    return _CACHE[key]


def load(spec, misalignment_deg: float, angles_deg: ArrayLike, *,
         torque_Nm: float | None = None, model: str | None = None,
         gap_offset_rad: ArrayLike | None = None, **accuracy: Any) -> LoadResult:
    """Load sharing of every tooth over rotations ``angles_deg`` at a misalignment.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float
        0-6 degrees.
    angles_deg : (M,) float
        Coupling rotations ``psi`` (degrees).
    torque_Nm : float, optional
        Signed torque (positive loads the ccw flanks); default ``spec.load.torque_Nm``.
    model : {"linear", "compliance", "surface"}, optional
        Default ``spec.load.model``.
    gap_offset_rad : (N,) or (2, N) float, optional
        Per-tooth additions to the gap angles (index errors, DESIGN.md §6).
    **accuracy
        Passed to :func:`gearcoupling.sweep.sweep` (``tolerance_mm``, ``grid``).
    """
    from ..sweep import sweep

    resolve_torque_Nm(spec, torque_Nm)
    resolve_model(spec, model)
    sw = sweep(spec, misalignment_deg, angles_deg, **accuracy)
    return load_from_sweep(spec, sw, torque_Nm=torque_Nm, model=model,
                           gap_offset_rad=gap_offset_rad)


def load_from_sweep(spec, sweep_result, *, torque_Nm: float | None = None,
                    model: str | None = None,
                    gap_offset_rad: ArrayLike | None = None) -> LoadResult:
    """Load sharing from an existing :class:`~gearcoupling.sweep.SweepResult`."""
    T = resolve_torque_Nm(spec, torque_Nm)
    m = resolve_model(spec, model)
    flank = 1 if T >= 0 else 0
    g = loaded_gaps(sweep_result, flank, gap_offset_rad)
    z, r = contact_points(spec, sweep_result, flank)
    if m == "linear":
        from .linear_model import solve_linear

        out = solve_linear(spec, g, z, r, abs(T) * 1e3)
    elif m == "compliance":
        from .compliance import solve_compliance

        out = solve_compliance(spec, g, z, r, abs(T) * 1e3, tooth_compliance(spec))
    else:
        from .surface import solve_surface

        out = solve_surface(spec, sweep_result, torque_Nm=T,
                            loaded_flank=FLANK_NAMES[flank], compliance=tooth_compliance(spec),
                            gap_offset_rad=gap_offset_rad)
        out = _complete_surface(spec, out, g, z, r)
    return _result(spec, sweep_result, T, m, flank, g, z, r, out)


def _complete_surface(spec, out: dict, g, z, r) -> dict:
    """Fill what the surface model does not report from the cantilever."""
    c = tooth_compliance(spec)
    R = spec.tooth.pitch_radius
    out = dict(out)
    Fn = np.asarray(out["normal_force_N"])
    out.setdefault("contact_regime", np.where(Fn > 0, 2, 0).astype(np.int8))
    if "root_stress_MPa" not in out and hasattr(c, "root_stress_MPa"):
        out["root_stress_MPa"] = c.root_stress_MPa(Fn, out.get("contact_z_mm", z),
                                                   out.get("contact_r_mm", r))
    if "mesh_stiffness_Nm_per_rad" not in out:
        k = R**2 / c.pair_compliance_mm_per_N(z, r)
        out["mesh_stiffness_Nm_per_rad"] = np.sum(np.where(Fn > 0, k, 0.0), axis=0) * 1e-3
    return out


def _result(spec, sw, T: float, model: str, flank: int, g, z, r, out: dict) -> LoadResult:
    sign = 1.0 if T >= 0 else -1.0
    shape = g.shape
    zeros = np.zeros(shape)

    def get(name, default=zeros):
        a = np.asarray(out.get(name, default))
        return np.broadcast_to(a, shape).copy() if a.shape != shape else a

    P = get("tangential_force_N")
    bad = [k for k, v in out.items() if isinstance(v, np.ndarray) and v.dtype.kind == "f"
           and not np.all(np.isfinite(v))]
    if bad:
        raise SpecError("torque_Nm", T, f"the {model} model gave non-finite {bad}; the load "
                        "is outside what the model covers")
    return LoadResult(
        spec=spec, misalignment_deg=float(sw.misalignment_deg), torque_Nm=T, model=model,
        loaded_flank=FLANK_NAMES[flank], angles_deg=np.asarray(sw.angles_deg),
        theta_deg=np.asarray(sw.theta_deg), windup_rad=sign * np.asarray(out["windup_rad"]),
        gap_angle_rad=g, deflection_mm=get("deflection_mm"), tangential_force_N=P,
        normal_force_N=get("normal_force_N"),
        contact_z_mm=get("contact_z_mm", z), contact_r_mm=get("contact_r_mm", r),
        max_pressure_MPa=get("max_pressure_MPa"),
        interior_pressure_MPa=get("interior_pressure_MPa", out.get("max_pressure_MPa", zeros)),
        edge_load_share=get("edge_load_share"), patch_length_mm=get("patch_length_mm"),
        patch_width_mm=get("patch_width_mm"),
        edge_contact=get("edge_contact", np.zeros(shape, bool)).astype(bool),
        contact_regime=get("contact_regime", np.zeros(shape, np.int8)).astype(np.int8),
        root_stress_MPa=get("root_stress_MPa"),
        mesh_stiffness_Nm_per_rad=np.asarray(out["mesh_stiffness_Nm_per_rad"], dtype=float),
    )
