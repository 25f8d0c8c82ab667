"""Golden values per template: what they hold and how to regenerate them.

Run ``python tests/golden_values.py`` after an intended geometry change and review the diff;
``test_templates.py`` compares against the files with explicit tolerances.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

import gearcoupling as gc
from gearcoupling.geometry.hub import form_radius, hub_model, tip_radius

GOLDEN = Path(__file__).parent / "golden"


def engagement_templates() -> list[str]:
    """The templates whose engagement's geometry (tooth system, hub, sleeve) no earlier
    template has: the double-engagement templates spacer-double and close-coupled share
    industrial-m2's, so the tests of one engagement's geometry, parts and design angles
    run on it once."""
    seen: set = set()
    names = []
    specs = {name: gc.load_spec(name) for name in gc.template_names()}
    for name in sorted(specs, key=lambda n: specs[n].coupling.engagements):  # singles first
        spec = specs[name]
        key = (spec.tooth, spec.hub, spec.sleeve)
        if key not in seen:
            seen.add(key)
            names.append(name)
    return sorted(names)


def golden(spec) -> dict:
    """Derived values and flank points (3 planes x 3 radii, both flanks) of a spec."""
    m = hub_model(spec)
    z = np.array([-0.9, 0.0, 0.6]) * m.half_face
    lo, hi = form_radius(m, z), tip_radius(m, z)
    r = lo[:, None] + (hi - lo)[:, None] * np.array([0.1, 0.5, 0.9])[None, :]
    zz = np.broadcast_to(z[:, None], r.shape)
    out = {"derived": {k: v for k, v in spec.derived.items() if np.isfinite(v)}, "flanks": {}}
    for flank in ("cw", "ccw"):
        p, n = gc.hub_flank(spec, flank, zz, r)
        out["flanks"][flank] = {"z_mm": zz.tolist(), "r_mm": r.tolist(),
                                "points_mm": p.tolist(), "normals": n.tolist()}
    return out


# --- sweep design angles ---
SWEEP_SOURCE = ("gearcoupling.clearance.design: critical_misalignment_deg (bisection) and "
                "binding_angle_deg (Brent), each to 1e-4 deg, 16 rotations per tooth pitch, "
                "default kernel tolerance 1e-7 mm; computed by this code and cross-checked "
                "where theory gives a value (renzo-1967: critical vs Renzo's b/2 = R_c cot(phi) i "
                "-> 2.085 deg, tests/test_sweep_theory.py)")


def golden_sweep(spec) -> dict:
    """The sweep's critical and binding angles (deg, ``None`` = not reached by 6°)."""
    from gearcoupling.clearance.design import binding_angle_deg, critical_misalignment_deg

    return {"critical_misalignment_deg": critical_misalignment_deg(spec),
            "binding_angle_deg": binding_angle_deg(spec),
            "tolerance_deg": 1e-4, "source": SWEEP_SOURCE}


if __name__ == "__main__":
    args = sys.argv[1:]
    sweep_only = "--sweep" in args
    names = [a for a in args if a != "--sweep"] or gc.template_names()
    for name in names:
        path = GOLDEN / f"{name}.json"
        spec = gc.load_spec(name)
        old = json.loads(path.read_text()) if path.exists() else {}
        new = dict(old) if sweep_only else {**golden(spec), **{k: v for k, v in old.items()
                                                              if k == "sweep"}}
        if sweep_only:
            new["sweep"] = golden_sweep(spec)
        path.write_text(json.dumps(new, indent=1) + "\n")
        print(path)
