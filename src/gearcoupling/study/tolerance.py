"""Tolerance Monte Carlo: manufacturing scatter per tooth -> backlash, load sharing,
capacity and Renzo's accuracy factor ``K = capacity with errors / without``.

Error model (all per hub tooth ``k``, zero mean, independent between teeth unless said):

- ``index_sd_mm``: tooth position error at the pitch circle (arc), normal.
- ``pitch_sd_mm``: single pitch deviations ``f_pt`` (normal); the cumulative pitch error is
  their running sum, closed over the turn (the deviations sum to zero).
- ``hub_runout_mm`` / ``sleeve_runout_mm``: radial runout ``F_r`` (total indicator reading),
  an eccentricity ``e = F_r / 2`` of that member at a uniformly random phase.
- ``thickness_sd_mm``: tooth thickness at the pitch circle (arc), normal.
- ``crown_sd_mm``: crown height (the drop of the feed path at the face end), normal
  (circular crowns; the tooth's crowning radius is solved from its drop).

ISO 1328-style tolerance limits convert with :meth:`Tolerances.from_limits` (limit = 3 sd
unless another coverage is given).

Three ways to get the per-tooth gap-angle map ``g[flank, tooth, rotation]``:

- ``fast``: the ideal map plus rigid per-tooth offsets (``gap_offset_rad``, docs/conventions.md,
Loaded analysis):
  a position error ``t`` moves both flanks by ``t / R`` (cw opens, ccw closes); a thickness
  change ``ds`` closes both by ``ds / (2R)`` - also a rigid rotation of each flank, because
  the hob's rack shift along its pitch line equals a rotation of the generated flank about
  the hub axis (checked against the exact path in tests); runout's radial part ``rho``
  closes both by ``rho tan(phi) / R`` (first order: exact at the pitch point only). Crown
  scatter is not represented.
- ``interpolated``: the ideal map at five crown heights (Chebyshev nodes over +-4 sd),
  interpolated per tooth to its crown height, plus the rigid offsets.
- ``exact``: every tooth and flank through the clearance kernel with its own geometry (a
  spec with that flank's thickness - position errors as a thickness change of one flank -
  and that tooth's crowning radius); runout's radial part enters first order as above.

Capacity, ``model = "renzo"`` (default, closed form, fastest): Renzo's linear model
(``[load]`` mesh stiffness ``C``, allowable tooth load ``P_i``): at each rotation the
wind-up that brings the most-loaded tooth to ``P_i`` gives the torque
``sum_k C R^2 max(0, dpsi - g_k)``; the capacity is its minimum over the turn
(``P_c = q N P_i R`` with errors included). ``"linear"`` or ``"compliance"``: the load
analysis' :func:`~gearcoupling.loading.capacity.capacity_from_sweep` on the per-tooth map
(every criterion: tooth load, contact and root stress; the governing one). ``K`` is the
ratio to the same spec and model without errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..arguments import GAP_TOLERANCE_MM, resolve_torque_Nm
from ..clearance import check_misalignment, flank_minima, sweep
from ..errors import ArgumentError, SpecError
from ..loading import (
    capacity_from_sweep,
    load_from_sweep,
    load_model,
    mesh_stiffness_N_per_mm,
    model_names,
    solve_windup,
)
from ..spec import CouplingSpec

PATHS = ("fast", "interpolated", "exact")
CROWN_NODES = 5
CROWN_SPAN_SD = 4.0


def capacity_models() -> tuple[str, ...]:
    """The capacity models of a tolerance study: ``renzo`` (the closed form) and the load
    models of cost class ``fast`` (every draw solves its own map)."""
    return ("renzo", *(n for n in model_names() if load_model(n).cost == "fast"))


@dataclass(frozen=True)
class Tolerances:
    """Manufacturing scatter (mm, standard deviations or runout; see the module docs)."""

    index_sd_mm: float = 0.0
    pitch_sd_mm: float = 0.0
    hub_runout_mm: float = 0.0
    sleeve_runout_mm: float = 0.0
    thickness_sd_mm: float = 0.0
    crown_sd_mm: float = 0.0

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v >= 0):
                raise SpecError(f"tolerances.{f.name}", v, "must be a finite number >= 0 (mm)")

    @classmethod
    def from_limits(cls, *, coverage: float = 3.0, **limits_mm: float) -> Tolerances:
        """From tolerance limits (ISO 1328 style, mm) taken as ``coverage`` standard
        deviations: ``index_mm``, ``pitch_mm`` (single pitch f_pt), ``thickness_mm``,
        ``crown_mm``; ``hub_runout_mm`` and ``sleeve_runout_mm`` (F_r) are used as given."""
        if not (math.isfinite(coverage) and coverage > 0):
            raise SpecError("coverage", coverage, "must be > 0 standard deviations")
        out = {}
        for key, value in limits_mm.items():
            if key.endswith("_runout_mm"):
                out[key] = value
            elif key in ("index_mm", "pitch_mm", "thickness_mm", "crown_mm"):
                out[key.replace("_mm", "_sd_mm")] = value / coverage
            else:
                raise SpecError(f"tolerances.{key}", value, "unknown limit; allowed: index_mm, "
                                "pitch_mm, thickness_mm, crown_mm, hub_runout_mm, "
                                "sleeve_runout_mm")
        return cls(**out)

    @property
    def zero(self) -> bool:
        return all(getattr(self, f.name) == 0 for f in fields(self))


@dataclass(frozen=True)
class ToothErrors:
    """One sample of per-tooth errors, all ``(N,)`` mm: tangential position (arc at the
    pitch circle, + toward increasing polar angle), radial displacement, thickness, crown."""

    position_mm: NDArray[np.float64]
    radial_mm: NDArray[np.float64]
    thickness_mm: NDArray[np.float64]
    crown_mm: NDArray[np.float64]


def draw_errors(tol: Tolerances, teeth: int, rng: np.random.Generator) -> ToothErrors:
    """Draw one sample of per-tooth errors (see the module docstring for the model)."""
    n = teeth
    pos = tol.index_sd_mm * rng.standard_normal(n)
    fpt = tol.pitch_sd_mm * rng.standard_normal(n)
    cum = np.cumsum(fpt - fpt.mean())
    pos = pos + cum - cum.mean()
    alpha = 2.0 * np.pi * np.arange(n) / n
    d = np.zeros(2)
    for runout in (tol.hub_runout_mm, -tol.sleeve_runout_mm):  # hub relative to the sleeve
        beta = rng.uniform(0.0, 2.0 * np.pi)
        d += 0.5 * runout * np.array([math.cos(beta), math.sin(beta)])
    pos = pos + d[1] * np.cos(alpha) - d[0] * np.sin(alpha)
    radial = d[0] * np.cos(alpha) + d[1] * np.sin(alpha)
    return ToothErrors(pos, radial, tol.thickness_sd_mm * rng.standard_normal(n),
                       tol.crown_sd_mm * rng.standard_normal(n))


def no_errors(teeth: int) -> ToothErrors:
    z = np.zeros(teeth)
    return ToothErrors(z, z, z, z)


def gap_offsets_rad(spec: CouplingSpec,
                    err: ToothErrors, *, rigid_only: bool = False) -> NDArray[np.float64]:
    """Rigid per-tooth gap-angle offsets ``(2, N)`` (cw, ccw) of the fast path; with
    ``rigid_only`` just the radial (runout) part, which the exact path also adds."""
    R = spec.tooth.pitch_radius
    radial = -err.radial_mm * math.tan(spec.tooth.pressure_angle) / R
    if rigid_only:
        return np.stack([radial, radial])
    t = err.position_mm / R
    half = -0.5 * err.thickness_mm / R
    return np.stack([t + half + radial, -t + half + radial])


def crown_radius_for_drop(spec: CouplingSpec, drop_mm: float) -> float:
    """Crowning radius (mm) of a circular crown with drop ``drop_mm`` at the face end."""
    if spec.hub.crowning.kind != "circular":
        raise SpecError("hub.crowning.kind", spec.hub.crowning.kind,
                        "crown-height scatter supports circular crowns only")
    b = 0.5 * spec.hub.face_width
    if not drop_mm > 0:
        raise SpecError("tolerances.crown_sd_mm", drop_mm, "the scatter makes a crown drop "
                        "<= 0; reduce crown_sd_mm")
    return (b * b + drop_mm * drop_mm) / (2.0 * drop_mm)


def nominal_drop_mm(spec: CouplingSpec) -> float:
    rc = spec.hub.crowning.radius
    b = 0.5 * spec.hub.face_width
    return rc - math.sqrt(rc * rc - b * b)


def rotations(spec: CouplingSpec, steps: int) -> NDArray[np.float64]:
    """Rotations ``psi`` (rad) over a full turn, ``steps`` per tooth pitch: every tooth's
    turning angles then lie on one grid of ``N * steps`` angles."""
    N = spec.tooth.teeth
    return 2.0 * np.pi * np.arange(N * steps) / (N * steps)


def _theta(spec: CouplingSpec, psi):
    N = spec.tooth.teeth
    return psi[None, :] + 2.0 * np.pi * np.arange(N)[:, None] / N  # (N, M)


def _gap_map(spec: CouplingSpec,
             mis: float, theta_both, tolerance_mm: float, periodic: bool = True):
    mins, _ = flank_minima(spec, mis, theta_both, tolerance_mm=tolerance_mm, periodic=periodic)
    with np.errstate(invalid="ignore", divide="ignore"):
        g = mins["normal"] / spec.tooth.base_radius / mins["rate"]
    return np.where(np.isfinite(g), g, np.inf)


def ideal_map(spec: CouplingSpec, mis: float, psi, tolerance_mm: float) -> NDArray[np.float64]:
    """Gap angles ``(2, N, M)`` of the ideal teeth (cw at theta, ccw at pi - theta)."""
    th = _theta(spec, psi)
    return _gap_map(spec, mis, np.stack([th, np.pi - th]), tolerance_mm)


def exact_map(spec: CouplingSpec, mis: float, psi, err: ToothErrors, tolerance_mm: float
              ) -> NDArray[np.float64]:
    """Per-tooth gap angles ``(2, N, M)`` with every tooth flank's own geometry: each
    distinct (flank thickness, crowning radius) is one spec variant through the kernel."""
    th = _theta(spec, psi)
    N = spec.tooth.teeth
    T = spec.hub.tooth_thickness
    drop0 = nominal_drop_mm(spec) if np.any(err.crown_mm) else 0.0
    groups: dict[tuple[float, float | None], list[tuple[int, int]]] = {}
    for k in range(N):
        rc = (crown_radius_for_drop(spec, drop0 + err.crown_mm[k]) if err.crown_mm[k]
              else None)
        for f, sign in ((0, -1.0), (1, 1.0)):
            thick = float(T + err.thickness_mm[k] + sign * 2.0 * err.position_mm[k])
            groups.setdefault((thick, rc), []).append((f, k))
    both = np.stack([th, np.pi - th])  # (2, N, M) turning angles of cw and ccw
    out = np.empty((2, N, psi.size))
    for (thick, rc), members in groups.items():
        changes: dict[str, Any] = {} if thick == T else {"hub.tooth_thickness": thick}
        if rc is not None:
            changes["hub.crowning.radius"] = rc
        variant = spec.replace(**changes) if changes else spec
        f, k = np.array(members).T
        out[f, k] = _gap_map(variant, mis, both[f, k], tolerance_mm, periodic=False)
    return out + gap_offsets_rad(spec, err, rigid_only=True)[:, :, None]


class CrownMaps:
    """Ideal maps at Chebyshev nodes of crown height; per-tooth barycentric interpolation."""

    def __init__(self, spec: CouplingSpec, mis: float, psi, crown_sd_mm: float, tolerance_mm: float,
                 nodes: int = CROWN_NODES):
        self.spec, self.psi, self.mis, self.tolerance_mm = spec, psi, mis, tolerance_mm
        self.nominal = ideal_map(spec, mis, psi, tolerance_mm)
        self.sd = crown_sd_mm
        if crown_sd_mm == 0:
            return
        j = np.arange(nodes)
        self.x = np.cos((2 * j + 1) * np.pi / (2 * nodes))  # in (-1, 1)
        self.w = (-1.0) ** j * np.sin((2 * j + 1) * np.pi / (2 * nodes))
        drop0 = nominal_drop_mm(spec)
        self.half = CROWN_SPAN_SD * crown_sd_mm
        self.maps = np.stack([ideal_map(spec.replace(**{
            "hub.crowning.radius": crown_radius_for_drop(spec, drop0 + self.half * x)}),
            mis, psi, tolerance_mm) for x in self.x])  # (nodes, 2, N, M)

    @cached_property
    def skeleton(self):
        """The ideal :class:`~gearcoupling.clearance.SweepResult` on these rotations (contact
        points and shapes for the load analysis; its gap angles are replaced per sample)."""
        return sweep(self.spec, math.degrees(self.mis), np.degrees(self.psi),
                     tolerance_mm=self.tolerance_mm)

    def gap(self, err: ToothErrors) -> NDArray[np.float64]:
        """Per-tooth map ``(2, N, M)`` at each tooth's crown height (no rigid offsets)."""
        if self.sd == 0 or not np.any(err.crown_mm):
            return self.nominal
        u = np.clip(err.crown_mm / self.half, -1.0, 1.0)  # (N,)
        diff = u[:, None] - self.x[None, :]
        exact = np.isclose(diff, 0.0, atol=1e-14)
        with np.errstate(divide="ignore", invalid="ignore"):
            c = self.w[None, :] / diff
        c = np.where(exact.any(axis=1, keepdims=True), exact.astype(float), c)
        c = c / c.sum(axis=1, keepdims=True)  # (N, nodes)
        return np.einsum("kn,nfkm->fkm", c, self.maps)


def model_outputs(spec: CouplingSpec,
                  skeleton, gap: NDArray[np.float64], torque_Nm: float, model: str
                  ) -> dict[str, float]:
    """:func:`linear_outputs` through the load analysis (``model`` linear or compliance) on
    the ideal sweep ``skeleton`` with the gap angles ``gap`` ``(2, N, M)``."""
    sw = replace(skeleton, gap_angle_rad=gap)
    res = load_from_sweep(sw, torque_Nm=torque_Nm, model=model)
    cap = capacity_from_sweep(sw, model=model,
                              loaded_flank="ccw" if torque_Nm >= 0 else "cw")
    contact = np.sum(res.in_contact, axis=0)
    backlash = float(np.min(np.min(gap[0], axis=0) + np.min(gap[1], axis=0)))
    if cap.capacity_Nm is None:
        raise SpecError("capacity", None, "no finite capacity (no criterion is reached)")
    return {"backlash_mm": backlash * spec.tooth.pitch_radius,
            "teeth_in_contact_min": int(np.min(contact)),
            "teeth_in_contact_mean": float(np.mean(contact)),
            "max_tooth_load_N": float(np.max(res.tangential_force_N)),
            "capacity_Nm": float(cap.capacity_Nm)}


def linear_outputs(spec: CouplingSpec,
                   gap: NDArray[np.float64], torque_Nm: float) -> dict[str, float]:
    """Backlash, teeth in contact, largest tooth load at ``torque_Nm`` and the capacity of
    one gap map ``(2, N, M)`` under Renzo's linear model (module docstring)."""
    P_i = spec.load.allowable_tooth_load_N
    if P_i is None:
        raise SpecError("load.allowable_tooth_load_N", None, "the tolerance study's capacity "
                        "uses Renzo's allowable tooth load P_i: give it in [load]")
    R = spec.tooth.pitch_radius
    C = mesh_stiffness_N_per_mm(spec)
    flank = 1 if torque_Nm >= 0 else 0
    g = gap[flank]  # (N, M) loaded flank
    backlash = float(np.min(np.min(gap[0], axis=0) + np.min(gap[1], axis=0)))
    windup = solve_windup(g, C * R * R, abs(torque_Nm) * 1e3)
    P = C * R * np.maximum(windup[None, :] - g, 0.0)
    contact = np.sum(P > 0, axis=0)
    dpsi = np.min(g, axis=0) + P_i / (C * R)  # most-loaded tooth at P_i, per rotation
    cap = np.sum(np.maximum(dpsi[None, :] - g, 0.0), axis=0) * C * R * R  # N mm
    return {"backlash_mm": backlash * R, "teeth_in_contact_min": int(np.min(contact)),
            "teeth_in_contact_mean": float(np.mean(contact)),
            "max_tooth_load_N": float(np.max(P)), "capacity_Nm": float(np.min(cap)) * 1e-3}


_CACHE: dict[Any, Any] = {}


def _maps(spec: CouplingSpec,
          mis_deg: float, steps: int, crown_sd: float, tolerance_mm: float) -> CrownMaps:
    key = (spec, spec.name, mis_deg, steps, crown_sd, tolerance_mm)
    if key not in _CACHE:
        if len(_CACHE) > 8:
            _CACHE.clear()
        _CACHE[key] = CrownMaps(spec, math.radians(mis_deg), rotations(spec, steps), crown_sd,
                                tolerance_mm)
    return _CACHE[key]


def tolerance_sample(spec: CouplingSpec,
                     misalignment_deg: float, tol: Tolerances, seed: int, sample: int, *,
                     path: str = "fast", torque_Nm: float | None = None, steps: int = 4,
                     tolerance_mm: float = GAP_TOLERANCE_MM,
                     model: str = "renzo") -> dict[str, float]:
    """One Monte Carlo sample (errors seeded by ``(seed, sample)``, so any chunking gives
    the same rows): the outputs with errors, the nominal capacity and ``K``."""
    if path not in PATHS:
        raise ArgumentError("path", path, f"one of {PATHS}")
    if model not in capacity_models():
        raise SpecError("tolerances.model", model, f"one of {capacity_models()}")

    check_misalignment(misalignment_deg)
    T = resolve_torque_Nm(spec, torque_Nm)
    err = draw_errors(tol, spec.tooth.teeth, np.random.default_rng([seed, sample]))
    maps = _maps(spec, misalignment_deg, steps, tol.crown_sd_mm if path == "interpolated"
                 else 0.0, tolerance_mm)
    ideal = maps.nominal
    if path == "exact":
        i = math.radians(misalignment_deg)
        key = ("exact", spec, spec.name, misalignment_deg, steps, tolerance_mm)
        if key not in _CACHE:  # the exact path's own ideal map: K = 1 exactly without errors
            _CACHE[key] = exact_map(spec, i, maps.psi, no_errors(spec.tooth.teeth),
                                    tolerance_mm)
        ideal = _CACHE[key]
        gap = exact_map(spec, i, maps.psi, err, tolerance_mm)
    else:
        base = maps.gap(err) if path == "interpolated" else maps.nominal
        gap = base + gap_offsets_rad(spec, err)[:, :, None]
    if model == "renzo":
        out = linear_outputs(spec, gap, T)
        nominal = linear_outputs(spec, ideal, T)["capacity_Nm"]
    else:
        out = model_outputs(spec, maps.skeleton, gap, T, model)
        nominal_key = ("nominal", model, id(ideal), T)
        if nominal_key not in _CACHE:
            _CACHE[nominal_key] = model_outputs(spec, maps.skeleton, ideal, T,
                                                model)["capacity_Nm"]
        nominal = _CACHE[nominal_key]
    out["nominal_capacity_Nm"] = nominal
    out["K"] = out["capacity_Nm"] / nominal
    return out


def summarise_k(k_values, *, precision: float = 0.01, confidence: float = 0.95
                ) -> dict[str, float]:
    """Distribution of ``K``: mean with its confidence interval, spread, percentiles, and
    the samples needed for the mean to ``+-precision`` at ``confidence`` (normal approx.)."""
    from scipy.stats import norm

    k = np.asarray(k_values, dtype=float)
    k = k[np.isfinite(k)]
    if k.size == 0:
        raise SpecError("K", None, "no finite samples to summarise")
    z = float(norm.ppf(0.5 + 0.5 * confidence))
    sd = float(np.std(k, ddof=1)) if k.size > 1 else 0.0
    half = z * sd / math.sqrt(k.size)
    return {"samples": int(k.size), "K_mean": float(np.mean(k)), "K_sd": sd,
            "K_mean_low": float(np.mean(k)) - half, "K_mean_high": float(np.mean(k)) + half,
            "K_p05": float(np.percentile(k, 5)), "K_p50": float(np.percentile(k, 50)),
            "K_p95": float(np.percentile(k, 95)), "K_min": float(np.min(k)),
            "confidence": confidence, "precision": precision,
            "samples_needed": math.ceil((z * sd / precision) ** 2) if sd > 0 else 1}


def summarise_rows(study, rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """K summaries of a tolerance study's rows, one per point of its varied inputs."""
    keys = [q.key for q in study.parameters]
    points: dict[tuple, list[float]] = {}
    refused: dict[tuple, int] = {}
    for r in rows:
        key = tuple(r[k] for k in keys)
        if r["error"] is None and r.get("K") is not None:
            points.setdefault(key, []).append(r["K"])
        else:
            refused[key] = refused.get(key, 0) + 1
    out = []
    for key, ks in points.items():
        s = summarise_k(ks, precision=study.tolerances["precision"])
        out.append({**dict(zip(keys, key, strict=True)), **s, "refused": refused.get(key, 0),
                    "path": study.tolerances["path"], "tolerances": study.tolerances["values"]})
    return out
