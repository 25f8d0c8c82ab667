"""Watertight hub and sleeve meshes and their files (STL here; STEP with the step extra).

Run: python examples/04_parts_and_export.py
"""

from pathlib import Path

import gearcoupling as gc

spec = gc.load_spec("industrial-m2")
out = Path("outputs/examples")
hub = gc.build_part(spec, "hub")  # trimesh.Trimesh, kind and tooth per triangle
check: gc.PartCheck = gc.check_part(hub)
print(len(hub.faces), "triangles, valid:", check.ok)
print(gc.export_part(spec, "sleeve", out / "sleeve.stl"))
