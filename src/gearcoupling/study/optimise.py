"""Crown optimisation (Wei et al. section 4): choose feed-path parameters that maximise the
capacity over a range of design angles, subject to a critical misalignment at or above the
largest angle and no binding there, with scipy's optimisers. Every evaluation is a row.

The study file names the parameters as ``[[vary]]`` ranges (the bounds) and the crown kind
in ``[set]``; ``[optimise]`` gives the angles, the objective and the evaluation budget::

    [optimise]
    angles_deg = [0.25, 0.5, 0.75, 1.0]
    objective = "mean"          # mean or min of the capacity over the angles, or
                                # "wear_life_h": the wear life at the largest angle (the
                                # spec's [wear] speed and hours, [conditions] torque)
    max_evaluations = 40
    compare = ["renzo-1967"]    # specs whose capacity curves are plotted beside the optimum
    model = "compliance"        # capacity model (default the spec's; "renzo": closed form)

Capacity is the load analysis' governing capacity (tooth load, contact and root stress)
at each angle, or Renzo's closed form with ``model = "renzo"``. Refused specs and
infeasible points are rows too (``feasible`` false) and score a penalty.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..arguments import GAP_TOLERANCE_MM
from ..clearance import critical_misalignment_deg, min_backlash_rad
from ..errors import GearCouplingError, SpecError
from ..io import atomic_path, plot_text
from ..loading import capacity
from ..plots import new_figure
from ..spec import CouplingSpec, load_spec
from .file import Study, build_spec, optimise_options, spec_hash
from .runner import pyarrow_modules
from .tolerance import ideal_map, linear_outputs, rotations
from .wear import wear_life_h

PENALTY_NM = 1e12


@dataclass(frozen=True)
class Optimum:
    """Best feasible row and every evaluation's row."""

    best: dict[str, Any] | None
    rows: list[dict[str, Any]]


def capacity_curve_Nm(spec: CouplingSpec, angles_deg, *, model: str | None = None, steps: int = 4,
                      tolerance_mm: float = GAP_TOLERANCE_MM) -> np.ndarray:
    """Capacity (N m) at each misalignment in ``angles_deg``: the load analysis' governing
    capacity (:func:`gearcoupling.loading.capacity.capacity`, ``model`` default the spec's,
    times the spec's accuracy factor), or with ``model = "renzo"`` Renzo's closed form
    (linear model, tooth-load criterion, K = 1, ``steps`` rotations per pitch)."""
    if model != "renzo":
        caps = [capacity(spec, a, model=model, tolerance_mm=tolerance_mm).capacity_Nm
                for a in angles_deg]
        if any(c is None for c in caps):
            raise SpecError("capacity", None, "no criterion is reached at some angle")
        return np.array(caps, dtype=float)
    psi = rotations(spec, steps)
    T = spec.load.torque_Nm or 0.0
    return np.array([linear_outputs(spec, ideal_map(spec, math.radians(a), psi, tolerance_mm),
                                    T)["capacity_Nm"] for a in angles_deg])


def crown_row(study: Study, inputs: dict[str, Any], options: dict[str, Any]) -> dict[str, Any]:
    """Evaluate one candidate crown: capacities, constraints, objective (a study row)."""
    angles = options["angles_deg"]
    acc = study.accuracy
    row: dict[str, Any] = {**inputs, "capacity_mean_Nm": None, "capacity_min_Nm": None,
                           "critical_misalignment_deg": None, "min_backlash_mm": None,
                           "feasible": False, "objective": -PENALTY_NM, "spec_hash": None,
                           "error": None}
    try:
        spec = build_spec(study.base_name, study.base_text, {**study.fixed, **inputs})
        row["spec_hash"] = spec_hash(spec)
        cap = capacity_curve_Nm(spec, angles, model=options["model"], steps=int(acc["steps"]),
                                tolerance_mm=acc["tolerance_mm"])
        row.update({f"capacity_{a:g}deg_Nm": float(c) for a, c in zip(angles, cap, strict=True)})
        row["capacity_mean_Nm"] = float(np.mean(cap))
        row["capacity_min_Nm"] = float(np.min(cap))
        crit = critical_misalignment_deg(spec, tolerance_deg=acc["angle_tolerance_deg"])
        row["critical_misalignment_deg"] = crit
        top = max(angles)
        backlash = min_backlash_rad(spec, top, steps=int(acc["steps"]))
        row["min_backlash_mm"] = backlash * spec.tooth.pitch_radius
        crit_ok = crit is None or crit >= top
        row["feasible"] = bool(crit_ok and backlash > 0)
        if options["objective"] == "wear_life_h":  # at the largest angle: the most sliding
            row["wear_life_h"] = wear_life_h(spec, top, study.conditions.get("torque_Nm"),
                                             acc)
            value = row["wear_life_h"]
        else:
            value = row[f"capacity_{options['objective']}_Nm"]
        # infeasible: penalised by how far the constraints are missed, so the search returns
        short = (0.0 if crit_ok else top - crit) + max(0.0, -backlash) * 1e3
        row["objective"] = value if row["feasible"] else value - PENALTY_NM * (1e-9 + short)
    except GearCouplingError as err:
        row["error"] = f"{type(err).__name__}: {err}"
    return row


def optimise_crown(study: Study, *, on_row: Callable[[dict[str, Any]], None] | None = None
                   ) -> Optimum:
    """Maximise the study's objective (the capacity, or the wear life) over its
    ``[[vary]]`` ranges.

    One parameter: bounded Brent (``minimize_scalar``); more: Nelder-Mead in coordinates
    scaled to the unit box (out-of-box points are clipped and evaluated). Every evaluation
    is a row (also passed to ``on_row``).
    """
    from scipy.optimize import minimize, minimize_scalar

    options = optimise_options(study)
    params = [q for q in study.parameters if q.low is not None]
    if not params or len(params) != len(study.parameters):
        raise SpecError(f"{study.source} vary", [q.key for q in study.parameters],
                        "optimisation varies ranges only (range = [low, high], no values)")
    rows: list[dict[str, Any]] = []
    lo = np.array([q.low for q in params])
    hi = np.array([q.high for q in params])

    seen: dict[tuple[float, ...], float] = {}

    def f(u) -> float:
        x = lo + (hi - lo) * np.clip(np.atleast_1d(u), 0.0, 1.0)
        if tuple(x) in seen:  # a clipped point met again: no second evaluation or row
            return seen[tuple(x)]
        inputs = {q.key: float(v) for q, v in zip(params, x, strict=True)}
        row = {"evaluation": len(rows), **crown_row(study, inputs, options)}
        rows.append(row)
        if on_row is not None:
            on_row(row)
        seen[tuple(x)] = -row["objective"] / 1e3
        return seen[tuple(x)]

    budget = options["max_evaluations"]
    if len(params) == 1:
        minimize_scalar(f, bounds=(0.0, 1.0), method="bounded",
                        options={"maxiter": budget, "xatol": 1e-3})
    else:
        x0 = np.full(len(params), 0.5)
        minimize(f, x0, method="Nelder-Mead", options={"maxfev": budget, "xatol": 1e-3,
                                                        "fatol": 1e-3,
                                                        "initial_simplex": _simplex(x0)})
    feasible = [r for r in rows if r["feasible"]]
    best = max(feasible, key=lambda r: r["objective"]) if feasible else None
    return Optimum(best, rows)


def _simplex(x0: np.ndarray) -> np.ndarray:
    pts = [x0]
    for k in range(x0.size):
        p = x0.copy()
        p[k] += 0.3
        pts.append(p)
    return np.array(pts)


def write_rows(rows: list[dict[str, Any]], path) -> None:
    """Rows with differing keys as one Parquet table (union of columns), atomically."""
    pa, pq = pyarrow_modules()
    names: list[str] = []
    for r in rows:
        names += [k for k in r if k not in names]
    table = pa.Table.from_pylist([{k: r.get(k) for k in names} for r in rows])
    with atomic_path(path) as tmp:
        pq.write_table(table, tmp)


def plot_capacity_curves(curves: dict[str, tuple[np.ndarray, np.ndarray]], *, ax=None):
    """Capacity (N m) against misalignment for named crowns; returns the Figure."""
    if ax is None:
        fig, ax = new_figure(figsize=(7, 4.5))
    else:
        fig = ax.figure
    for name, (angles, cap) in curves.items():
        ax.plot(angles, cap, "o-", ms=3, label=plot_text(name))
    ax.set_xlabel("misalignment (deg)")
    ax.set_ylabel("capacity (N m)")
    ax.legend(fontsize=8, loc="best")
    ax.grid(alpha=0.3)
    return fig


def compare_curves(study: Study, best: dict[str, Any], points: int = 8
                   ) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Capacity curves (``points`` angles up to the largest design angle) of the optimum
    and of the ``compare`` specs, by name."""
    options = optimise_options(study)
    acc = study.accuracy
    angles = np.linspace(0.0, max(options["angles_deg"]), points + 1)[1:]
    keys = [q.key for q in study.parameters]
    specs = {"optimum": build_spec(study.base_name, study.base_text,
                                   {**study.fixed, **{k: best[k] for k in keys}})}
    specs.update({name: load_spec(name) for name in options["compare"]})
    return {name: (angles, capacity_curve_Nm(s, angles, model=options["model"],
                                             steps=int(acc["steps"]),
                                             tolerance_mm=acc["tolerance_mm"]))
            for name, s in specs.items()}
