"""Seeded random specs through spec, sweep and (a sample) parts: ok / refused / NaN / crash.

Draws ``--count`` specs (default 1000) over the documented range, cycling through the 20
strata crown kind x generation x tip of ``tests/random_specs.py`` (face width, backlash,
crown proportions and misalignment drawn there; everything else left to the defaults),
and runs each accepted spec through

* ``sweep`` at its design misalignment over ``--angles`` rotations (tolerance
  ``--tolerance``): *ok*, *ok-no-contact* (finite, with +inf clearance where a flank faces
  no sleeve flank: large misalignment, or a pitch line outside the sleeve flank on few
  teeth), *NaN* (a NaN anywhere or a non-finite backlash), *warning* (numpy emitted a
  RuntimeWarning; counted, the result may still be finite), *refused* (a
  ``GearCouplingError``) or *crash* (any other exception);
* every ``--parts-every``-th accepted spec per stratum: hub and sleeve meshes of tooth 0
  at tolerance module/20: *ok* (closed and finite), *refused* or *crash*.

Prints the totals per stage and a table per stratum, and writes the details (every
refusal's field, every NaN/crash spec) to ``outputs/bench_random_specs.json``.

Run: ``python benchmarks/bench_random_specs.py [--count 1000] [--seed 0]`` (about 20 min
for 1000 specs on a loaded 2-core machine; ``--count 100`` for a quick look).
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import sys
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import gearcoupling as gc
from gearcoupling.clearance import sweep
from random_specs import STRATA, random_spec_data


def run_sweep(spec, angles: int, tolerance_mm: float) -> str:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = sweep(spec, spec.design_misalignment_deg, np.arange(angles) * 360.0 / angles,
                  tolerance_mm=tolerance_mm)
    arrays = (r.clearance_mm, r.normal_clearance_mm, r.pitch_clearance_mm, r.backlash_mm)
    if any(np.any(np.isnan(a)) for a in arrays) or not np.all(np.isfinite(r.backlash_mm)):
        return "NaN"
    if any(issubclass(w.category, RuntimeWarning) for w in caught):
        return "warning"
    # +inf clearance is the kernel's "this flank faces no sleeve flank at this pose" (large
    # misalignment, or a pitch line outside the sleeve flank on few teeth): a valid answer
    return "ok-no-contact" if not all(np.all(np.isfinite(a)) for a in arrays) else "ok"


def run_parts(spec) -> str:
    from gearcoupling.parts import build_part

    tol = spec.tooth.module / 20
    for part in ("hub", "sleeve"):
        mesh = build_part(spec, part, tolerance_mm=tol, teeth=[0])
        if not (mesh.is_watertight and np.all(np.isfinite(mesh.vertices))):
            return "open"
    return "ok"


def attempt(fn, *args) -> tuple[str, str]:
    try:
        return fn(*args), ""
    except gc.GearCouplingError as err:
        return "refused", str(err)[:300]
    except Exception as err:
        return "crash", f"{type(err).__name__}: {err}"[:300]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--angles", type=int, default=8)
    ap.add_argument("--tolerance", type=float, default=1e-4)
    ap.add_argument("--parts-every", type=int, default=10)
    ap.add_argument("--out", default="outputs/bench_random_specs.json")
    args = ap.parse_args()

    stages = ("spec", "sweep", "parts")
    totals = {s: collections.Counter() for s in stages}
    per = {st: {s: collections.Counter() for s in stages} for st in STRATA}
    refused_fields: collections.Counter = collections.Counter()
    details = []
    t0 = time.perf_counter()
    for i in range(args.count):
        stratum = STRATA[i % len(STRATA)]
        data = random_spec_data(np.random.default_rng([args.seed, i]), *stratum)
        row = {"index": i, "stratum": "/".join(stratum)}
        try:
            spec = gc.spec_from_dict(data)
            outcome = {"spec": "ok"}
        except gc.SpecError as err:
            spec, outcome = None, {"spec": "refused"}
            refused_fields[err.field] += 1
            row["spec_error"] = str(err)[:300]
        except Exception as err:
            spec, outcome = None, {"spec": "crash"}
            row["spec_error"] = f"{type(err).__name__}: {err}"[:300]
        if spec is not None:
            outcome["sweep"], note = attempt(run_sweep, spec, args.angles, args.tolerance)
            if note:
                row["sweep_error"] = note
            if per[stratum]["spec"]["ok"] % args.parts_every == 0:
                outcome["parts"], note = attempt(run_parts, spec)
                if note:
                    row["parts_error"] = note
        for stage, result in outcome.items():
            totals[stage][result] += 1
            per[stratum][stage][result] += 1
        if any(v not in ("ok", "ok-no-contact") for k, v in outcome.items() if k != "spec") \
                or outcome["spec"] != "ok":
            row.update(outcome, data=data)
            details.append(row)
        if (i + 1) % 100 == 0:
            print(f"  {i + 1}/{args.count} specs, {time.perf_counter() - t0:.0f} s",
                  file=sys.stderr, flush=True)

    elapsed = time.perf_counter() - t0
    print(f"\n{args.count} seeded specs (seed {args.seed}), sweep {args.angles} angles at "
          f"{args.tolerance:g} mm, parts every {args.parts_every}th accepted spec per "
          f"stratum; {elapsed:.0f} s\n")
    keys = ("ok", "ok-no-contact", "refused", "NaN", "warning", "open", "crash")
    print(f"{'stage':8s}" + "".join(f"{k:>14s}" for k in keys))
    for s in stages:
        print(f"{s:8s}" + "".join(f"{totals[s][k]:14d}" for k in keys))
    print("(ok-no-contact: finite, with +inf clearance where a flank faces no sleeve flank)")
    print("\nrefusals by field:", dict(refused_fields.most_common()))
    print(f"\n{'stratum (kind/generation/tip)':34s} {'spec ok/n':>10s} {'sweep ok/n':>11s} "
          f"{'NaN':>4s} {'crash':>6s} {'parts ok/n':>11s}")
    for st in STRATA:
        c = per[st]
        n_spec, n_sw, n_pa = (sum(c[s].values()) for s in stages)
        crash = c["spec"]["crash"] + c["sweep"]["crash"] + c["parts"]["crash"]
        print(f"{'/'.join(st):34s} {c['spec']['ok']:4d}/{n_spec:<5d} "
              f"{c['sweep']['ok'] + c['sweep']['ok-no-contact']:5d}/{n_sw:<5d} "
              f"{c['sweep']['NaN']:4d} {crash:6d} {c['parts']['ok']:5d}/{n_pa:<5d}")
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"args": vars(args), "seconds": elapsed,
                               "totals": {s: dict(totals[s]) for s in stages},
                               "refused_fields": dict(refused_fields),
                               "not_ok": details}, indent=1, default=str))
    print(f"\ndetails: {out}")


if __name__ == "__main__":
    main()
