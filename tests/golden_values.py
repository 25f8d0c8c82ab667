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


if __name__ == "__main__":
    names = sys.argv[1:] or gc.template_names()
    for name in names:
        path = GOLDEN / f"{name}.json"
        path.write_text(json.dumps(golden(gc.load_spec(name)), indent=1) + "\n")
        print(path)
