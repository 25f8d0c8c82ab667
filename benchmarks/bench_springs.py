"""The default tooth springs against the FE tooth-spring tables they reproduce.

Run: ``python benchmarks/bench_springs.py [--random 30] [--seed 2026] [--no-compute] [--fit]
[--holdout K] [--spline]``.

The data set: the five bundled templates and ``--random`` seeded random specs whose teeth,
module, pressure angle, face width, tooth proportions, fillets, rim and bore and crown
are drawn over the supported range (``tests/random_specs.py``,
``proportions_spec``). For each, the FE tooth-spring table
(:func:`gearcoupling.fea.tooth_compliance_table`, default settings: 3 radii x 4 rows of load
points, real gmsh and CalculiX; cached in ``$GEARCOUPLING_CACHE`` or the user's cache, so a
second run only reads) and the default springs (:class:`gearcoupling.loading.FittedCompliance`)
at the same load points. Printed: per spec, the largest error of the pair far field over
the grid, and of the whole compliance (far field + the table's half-space near field, what a
load model adds up); the error over every spec and grid point; the springs' time per spec. With
``--no-compute`` specs without a cached table are left out. ``--fit`` fits the coefficients
of :mod:`gearcoupling.loading.kernels.fitted` to the data set first and writes them to
``src/gearcoupling/loading/kernels/fitted.json`` (the table then shows the new fit);
``--holdout K`` fits on all but every K-th random spec and prints the error on those left out;
``--no-correction`` leaves the Gaussian-process correction out of the fit; ``--golden`` writes
the tables' far fields to ``tests/golden/fe_far_field.json``; ``--spline`` prints what the
correction's spline costs and buys against the Gaussian process it interpolates.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import gearcoupling as gc
from gearcoupling.errors import GearCouplingError
from gearcoupling.fea.stiffness import ComplianceTable, cache_dir, spec_hash
from random_specs import springs_specs

ROOT = Path(__file__).resolve().parents[1]
TEMPLATES = ("renzo-1967", "renzo-1967-vari-crown", "renzo-1967-end-round", "industrial-m2",
             "mill-spindle")


def dataset_specs(count: int, seed: int) -> list[gc.CouplingSpec]:
    """The templates and ``count`` random specs (named ``springs-<i>-<crown>``)."""
    return [gc.load_spec(name) for name in TEMPLATES] + springs_specs(count, seed)


def cached_table(spec: gc.CouplingSpec) -> ComplianceTable | None:
    """The cached FE table of ``spec`` at the default settings, or None."""
    key = spec_hash(spec, size_mm=None, sector=3, nz=3, nr=3)
    for path in cache_dir().glob(f"*-{key}.json"):
        return ComplianceTable.from_dict(json.loads(path.read_text()))
    return None


def fe_table(spec: gc.CouplingSpec, compute: bool) -> ComplianceTable | None:
    table = cached_table(spec)
    if table is None and compute:
        from gearcoupling.fea import tooth_compliance_table

        t0 = time.perf_counter()
        table = tooth_compliance_table(spec)
        print(f"  {spec.name}: FE table in {time.perf_counter() - t0:.0f} s", flush=True)
    return table


def part_records(spec: gc.CouplingSpec, table: ComplianceTable, springs) -> dict:
    """Per part at the table's ``P`` load points: features ``(P, F)``, the bending base
    ``(P,)`` (mm/N), the confinement shape ``(P,)`` per trial length (mm/N) and the FE far
    field ``(P,)`` (normal, mm/N); the pair's FE far field ``(P,)``."""
    from gearcoupling.loading.kernels.fitted import PARTS

    Z, R = (a.ravel() for a in np.meshgrid(table.z_mm, table.r_mm, indexing="ij"))
    cos2 = math.cos(spec.tooth.pressure_angle) ** 2
    out = {"pair": cos2 * table.far_field_mm_per_N.ravel()}
    whole = {"hub": table.hub_mm_per_N, "sleeve": table.sleeve_mm_per_N}
    for i, part in enumerate(PARTS):
        out[part] = {"features": springs.part_features(part, Z, R),
                     "bending": springs.bending(part, Z, R),
                     "confinement": {L: springs.confinement(part, R, L) for L in LENGTHS},
                     "far": cos2 * (whole[part] - table.near_field_mm_per_N[i]).ravel()}
    return out


LENGTHS = (0.2, 0.3, 0.45, 0.7, 1.0)  # trial confinement lengths (modules)


def fit(data: list[dict], ridge: float = 0.1) -> dict:
    """Coefficients per part minimising the log error of the pair far field over ``data``
    (:func:`part_records` of each spec), a small ridge on all but the constant; the
    confinement length per part the best of :data:`LENGTHS`."""
    from scipy.optimize import least_squares

    from gearcoupling.loading.kernels.fitted import FEATURES, PARTS

    nf = len(FEATURES)

    def model(x, d, lengths):
        total = 0.0
        for i, p in enumerate(PARTS):
            a, b = x[i * (nf + 1):i * (nf + 1) + nf], x[i * (nf + 1) + nf]
            q = d[p]
            total = total + q["bending"] * np.exp(q["features"] @ a) \
                - b * q["confinement"][lengths[p]]
        return total

    def resid(x, lengths):
        r = [np.log(np.maximum(model(x, d, lengths), 1e-3 * d["pair"]) / d["pair"])
             for d in data]
        reg = [x[i * (nf + 1) + 1:i * (nf + 1) + nf] for i in range(len(PARTS))]
        return np.concatenate([*r, ridge * np.concatenate(reg)])

    best = None
    for lh in LENGTHS:
        for ls in LENGTHS:
            lengths = {"hub": lh, "sleeve": ls}
            sol = least_squares(resid, np.zeros(2 * (nf + 1)), args=(lengths,), method="lm")
            if best is None or sol.cost < best[0].cost:
                best = (sol, lengths)
    sol, lengths = best
    parts = {}
    for i, p in enumerate(PARTS):
        f = np.concatenate([d[p]["features"] for d in data])
        x = sol.x[i * (nf + 1):(i + 1) * (nf + 1)]
        parts[p] = {"coefficients": x[:nf].tolist(), "confinement": float(x[nf]),
                    "confinement_length": lengths[p],
                    "low": f.min(axis=0).tolist(), "high": f.max(axis=0).tolist()}
    return {"features": list(FEATURES), "parts": parts}


#: the features (per part, by name) the correction's Gaussian process reads: all but the
#: constant and the square of the height (the process is not linear in its inputs), the
#: sleeve's without its crown (straight) and the pressure angle (the hub's holds it)
GP_INPUTS = {"hub": ("height", "face_end", "face_end_height", "other_end", "tip_edge",
                     "crown_thinning", "pressure_angle", "pressure_angle_height"),
             "sleeve": ("height", "face_end", "face_end_height", "other_end", "tip_edge",
                        "pressure_angle_height")}


#: the least noise variance of the correction (a log error of 2 %): without it the process
#: fitted on part of the data set interpolated it (0.2 % rms) and erred more on the specs
#: left out than the parts' fit alone
NOISE_FLOOR = 0.02**2


def correction_data(specs, tables, base: dict) -> tuple[np.ndarray, np.ndarray]:
    """The correction's inputs ``(P, d)`` (:data:`GP_INPUTS`) and targets ``(P,)``, the log
    of the FE pair far field over the base fit's (``base`` without a correction), at every
    load point of every table."""
    from gearcoupling.loading.kernels.fitted import FEATURES, PARTS, FittedCompliance

    X, y = [], []
    for spec, table in zip(specs, tables, strict=True):
        springs = FittedCompliance(spec, fit=base)
        Z, R = (a.ravel() for a in np.meshgrid(table.z_mm, table.r_mm, indexing="ij"))
        X.append(np.hstack([springs.part_features(p, Z, R)[:, [FEATURES.index(n)
                                                                for n in GP_INPUTS[p]]]
                            for p in PARTS]))
        y.append(np.log(table.far_field_mm_per_N.ravel()
                        / springs.pair_compliance_mm_per_N(Z, R)))
    return np.vstack(X), np.concatenate(y)


def fit_correction(X: np.ndarray, y: np.ndarray) -> dict:
    """A Gaussian process on ``y`` over the standardised ``X``: zero mean, squared-
    exponential kernel with a length per input, white noise; the lengths, the variance and
    the noise maximise the marginal likelihood (L-BFGS-B, exact gradient). Returns what
    :func:`gearcoupling.loading.kernels.fitted.gp_mean` reads."""
    from scipy.linalg import cho_factor, cho_solve
    from scipy.optimize import minimize

    mean, scale = X.mean(axis=0), X.std(axis=0)
    Z = (X - mean) / scale
    n, d = Z.shape
    D2 = (Z[:, None, :] - Z[None, :, :]) ** 2  # (n, n, d)

    def kernel(theta):
        length, variance = np.exp(theta[:d]), math.exp(theta[d])
        return variance * np.exp(-0.5 * (D2 @ length**-2)), length

    def nll(theta):
        Kf, length = kernel(theta)
        noise = math.exp(theta[d + 1])
        c = cho_factor(Kf + noise * np.eye(n), lower=True)
        a = cho_solve(c, y)
        W = np.outer(a, a) - cho_solve(c, np.eye(n))
        WK = W * Kf
        grad = np.concatenate([-0.5 * np.einsum("ij,ijk->k", WK, D2) / length**2,
                               [-0.5 * np.sum(WK), -0.5 * noise * np.trace(W)]])
        return 0.5 * y @ a + np.sum(np.log(np.diag(c[0]))), grad

    start = np.r_[np.full(d, math.log(3.0)), math.log(0.01), math.log(2.0 * NOISE_FLOOR)]
    bounds = [(math.log(0.3), math.log(100.0))] * d + [(math.log(1e-4), 0.0),
                                                      (math.log(NOISE_FLOOR), math.log(0.1))]
    theta = minimize(nll, start, jac=True, method="L-BFGS-B", bounds=bounds).x
    Kf, length = kernel(theta)
    noise = math.exp(theta[d + 1])
    weights = cho_solve(cho_factor(Kf + noise * np.eye(n), lower=True), y)
    return {"inputs": {p: list(v) for p, v in GP_INPUTS.items()}, "mean": mean.tolist(),
            "scale": scale.tolist(), "length": length.tolist(),
            "variance": math.exp(theta[d]), "noise": noise, "points": Z.tolist(),
            "weights": weights.tolist()}


def spec_ranges(specs) -> dict:
    """The data set's range of what :attr:`FittedCompliance.outside` checks."""
    from gearcoupling.loading.kernels.fitted import FittedCompliance

    vals: dict[str, list[float]] = {}
    for spec in specs:
        c = FittedCompliance(spec)
        for k, v in (("teeth", c.teeth), ("module_mm", c.module),
                     ("pressure_angle_deg", math.degrees(c.phi)),
                     ("face_over_module", 2.0 * c.half_face_hub / c.module),
                     ("depth_over_module", c.depth / c.module),
                     ("hub_rim_over_module", c.rim["hub"] / c.module),
                     ("sleeve_ring_over_module", c.rim["sleeve"] / c.module),
                     ("hub_fillet_over_module", c.fillet["hub"] / c.module),
                     ("sleeve_fillet_over_module", c.fillet["sleeve"] / c.module)):
            vals.setdefault(k, []).append(v)
    return {k: [min(v), max(v)] for k, v in vals.items()}


GOLDEN = ROOT / "tests" / "golden" / "fe_far_field.json"


def write_golden(specs, tables) -> None:
    """The FE tables' load points and pair far fields (Renzo's measure, mm/N) per spec, for
    ``tests/test_load_springs.py`` (which checks the shipped fit against them)."""
    out = {spec.name: {"z_mm": t.z_mm.tolist(), "r_mm": t.r_mm.tolist(),
                       "far_field_mm_per_N": t.far_field_mm_per_N.tolist()}
           for spec, t in zip(specs, tables, strict=True)}
    GOLDEN.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {GOLDEN} ({len(out)} specs)")


def spline_table(specs, grids=((9, 9), (17, 17), (25, 25), (33, 33)), points: int = 4000):
    """The correction's spline (:data:`~gearcoupling.loading.kernels.fitted.CORRECTION_GRID`)
    against the Gaussian process itself at ``points`` random flank points per spec (a little
    beyond the face and the flank too): the largest relative error and the time to build it,
    per knot grid; and the springs' time per call with each."""
    from gearcoupling.loading.kernels import fitted

    print("\n## The correction's spline: knots against error and cost\n")
    print("| knots (z x r) | largest error against the process | build ms per spec |")
    print("|---|---|---|")
    shipped = fitted.CORRECTION_GRID
    try:
        for grid in grids:
            fitted.CORRECTION_GRID = grid
            worst, build = 0.0, 0.0
            for i, spec in enumerate(specs):
                springs = fitted.FittedCompliance(spec)
                t0 = time.perf_counter()
                springs.correction(0.0, springs.R)
                build += time.perf_counter() - t0
                rng = np.random.default_rng(i)
                Z = rng.uniform(-1.05, 1.05, points) * springs.half_face_hub
                R = rng.uniform(springs.r_table[0] - 0.1, springs.r_table[-1] + 0.1, points)
                err = springs.correction(Z, R) / springs.exact_correction(Z, R) - 1.0
                worst = max(worst, float(np.abs(err).max()))
            print(f"| {grid[0]} x {grid[1]} | {worst:.1e} | {1e3 * build / len(specs):.1f} |")
    finally:
        fitted.CORRECTION_GRID = shipped
    springs = fitted.FittedCompliance(specs[0])
    Z, R = np.meshgrid(np.linspace(0.0, springs.half_face_hub, 40),
                       np.linspace(springs.r_table[0], springs.r_table[-1], 24), indexing="ij")
    for label, fn in (("spline", springs.correction), ("process", springs.exact_correction)):
        fn(Z, R)
        t0 = time.perf_counter()
        for _ in range(50):
            fn(Z, R)
        print(f"{specs[0].name}, 960 points: the correction by the {label} "
              f"{1e3 * (time.perf_counter() - t0) / 50:.2f} ms a call")


def describe(spec: gc.CouplingSpec) -> str:
    t = spec.tooth
    return (f"{t.teeth} teeth, m {t.module:.3g}, {math.degrees(t.pressure_angle):.1f}°, "
            f"b/m {spec.hub.face_width / t.module:.1f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--random", type=int, default=30)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--no-compute", action="store_true")
    ap.add_argument("--fit", action="store_true")
    ap.add_argument("--holdout", type=int, default=0)
    ap.add_argument("--no-correction", action="store_true",
                    help="with --fit or --holdout: the parts' fit alone (what the correction buys)")
    ap.add_argument("--golden", action="store_true",
                    help=f"write every table's far field to {GOLDEN.relative_to(ROOT)}")
    ap.add_argument("--spline", action="store_true",
                    help="only: the correction's spline against the process (no FE tables)")
    a = ap.parse_args()
    from gearcoupling.loading.kernels.fitted import FittedCompliance, load_fit

    if a.spline:
        spline_table(dataset_specs(a.random, a.seed))
        return

    specs, tables = [], []
    for spec in dataset_specs(a.random, a.seed):
        try:
            table = fe_table(spec, not a.no_compute)
        except GearCouplingError as err:
            print(f"  {spec.name}: FE refused: {err}")
            continue
        if table is not None:
            specs.append(spec)
            tables.append(table)
    if a.golden:
        write_golden(specs, tables)
    fitted = None
    if a.fit or a.holdout:
        data = [part_records(s, t, FittedCompliance(s)) for s, t in zip(specs, tables, strict=True)]
        keep = [i for i in range(len(specs))
                if not (a.holdout and i >= len(TEMPLATES) and i % a.holdout == 0)]
        fitted = fit([data[i] for i in keep])
        if not a.no_correction:
            fitted["correction"] = fit_correction(*correction_data(
                [specs[i] for i in keep], [tables[i] for i in keep], fitted))
        fitted["spec_ranges"] = spec_ranges([specs[i] for i in keep])
        points = sum(tables[i].far_field_mm_per_N.size for i in keep)
        fitted["data_set"] = (f"bench_springs.py: {len(keep)} specs (the templates and seeded "
                              f"random specs, seed {a.seed}), {points} load points")
        fitted["specs"] = [specs[i].name for i in keep]
        if a.fit and not a.holdout:
            path = ROOT / "src" / "gearcoupling" / "loading" / "kernels" / "fitted.json"
            path.write_text(json.dumps(fitted, indent=1) + "\n")
            print(f"wrote {path}")
    in_fit = set((fitted or load_fit()).get("specs", [s.name for s in specs]))
    rows: list = []
    groups: dict[str, list] = {"fitted on": [], "held out of the fit, inside its range": [],
                               "held out of the fit, outside its range (named)": []}
    labels = list(groups)
    for i, (spec, table) in enumerate(zip(specs, tables, strict=True)):
        t0 = time.perf_counter()
        springs = FittedCompliance(spec, fit=fitted)
        Z, R = np.meshgrid(table.z_mm, table.r_mm, indexing="ij")
        model = springs.pair_compliance_mm_per_N(Z, R)
        dt = time.perf_counter() - t0
        err = model / table.far_field_mm_per_N - 1.0
        near = table.near_field_mm_per_N.sum(axis=0)
        whole = (model + near) / (table.far_field_mm_per_N + near) - 1.0
        out = bool(a.holdout and i >= len(TEMPLATES) and i % a.holdout == 0) or (
            not a.fit and not a.holdout and spec.name not in in_fit)
        c_ratio = springs.mesh_stiffness_N_per_mm / table.mesh_stiffness_N_per_mm
        notes = (["not in the fit"] if out else []) + [
            "outside: " + ", ".join(o.split(" = ")[0] for o in springs.outside)] * bool(
            springs.outside)
        rows.append((spec.name + "".join(f" ({n})" for n in notes), describe(spec), err, whole,
                     dt, c_ratio))
        groups[labels[2 if springs.outside else 1] if out else labels[0]].append(
            (err.ravel(), whole.ravel()))
    print("\n| spec | teeth, module, pressure angle, face / module | far field: largest error "
          "| mean | whole compliance: largest error | C fit / FE | springs ms |")
    print("|---|---|---|---|---|---|---|")
    for name, what, err, whole, dt, c_ratio in rows:
        j, k = np.argmax(np.abs(err)), np.argmax(np.abs(whole))
        print(f"| {name} | {what} | {100 * err.ravel()[j]:+.1f} % | {100 * err.mean():+.1f} % "
              f"| {100 * whole.ravel()[k]:+.1f} % | {c_ratio:.3f} | {1e3 * dt:.0f} |")
    for label, pairs in groups.items():
        if pairs:
            for what, e in (("far field", np.concatenate([p[0] for p in pairs])),
                            ("whole compliance", np.concatenate([p[1] for p in pairs]))):
                print(f"\n{label}: {len(pairs)} specs, {e.size} load points, {what}: error "
                      f"{100 * e.min():+.1f} … {100 * e.max():+.1f} %, rms "
                      f"{100 * np.sqrt(np.mean(e**2)):.1f} %; within 10 %: "
                      f"{np.mean(np.abs(e) <= 0.1) * 100:.0f} % of the points")
    face_end(tables)


def face_end(tables) -> None:
    """How much softer the tables' face-end row is than their last even row (the pair's
    far field, every radius), over the tables that have both."""
    from gearcoupling.fea import TABLE_FACE_SHARE

    ratios = [t.far_field_mm_per_N[-1] / t.far_field_mm_per_N[-2] for t in tables
              if len(t.z_mm) > 3 and np.isclose(
                  t.z_mm[-2], TABLE_FACE_SHARE * (t.z_mm[-1] + t.info["patch_mm"]))]
    if ratios:
        r = np.concatenate(ratios)
        print(f"\nthe face-end row's far field against the row at {TABLE_FACE_SHARE:g} of the "
              f"half face: {r.min():.2f} … {r.max():.2f} times, median {np.median(r):.2f} "
              f"({len(ratios)} tables)")


if __name__ == "__main__":
    main()
