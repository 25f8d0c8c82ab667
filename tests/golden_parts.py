"""Golden part volumes per template (``tests/golden/parts.json``): what they hold, their
source and how to regenerate them.

For every template and part: the default chordal tolerance (module / 200), the triangle
count and volume of the mesh built at it, and the volume of the STEP solid of the exact
geometry at a tolerance ten times finer, read back from the written file by OpenCASCADE
(``step_volume_mm3``, the independent source: B-spline surfaces through exact kernel
points, integrated adaptively). ``test_parts.py`` pins the mesh to the file and checks the
file against the STEP volume (the mesh is within the tolerance of the exact surface, so the
volumes differ by at most tolerance x area).

Run ``python tests/golden_parts.py`` after an intended geometry change and review the diff.
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

import gearcoupling as gc
from gearcoupling.export import export_part, read_step_volume
from gearcoupling.parts import build_part, check_tolerance

GOLDEN = Path(__file__).parent / "golden" / "parts.json"


def golden_parts(name: str) -> dict:
    spec = gc.load_spec(name)
    tol = check_tolerance(spec, None)
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for part in ("hub", "sleeve"):
            mesh = build_part(spec, part, tolerance_mm=tol)
            step = export_part(spec, part, Path(tmp) / f"{part}.step", tolerance_mm=tol / 10)
            out[part] = {"tolerance_mm": tol, "triangles": len(mesh.faces),
                         "volume_mm3": float(mesh.volume), "area_mm2": float(mesh.area),
                         "step_tolerance_mm": tol / 10,
                         "step_volume_mm3": read_step_volume(step)}
    return out


if __name__ == "__main__":
    data = {name: golden_parts(name) for name in gc.template_names()}
    GOLDEN.write_text(json.dumps(data, indent=1) + "\n")
