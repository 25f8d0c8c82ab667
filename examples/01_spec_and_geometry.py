"""Specs and exact tooth geometry: templates, overrides, flank points and sections.

Run: python examples/01_spec_and_geometry.py
"""

import math

import gearcoupling as gc

print(gc.template_names())
spec = gc.load_spec("renzo-1967")  # a bundled template (inches in the file)
# overrides are keys of the file, in the file's units: 3 in here
wider = gc.load_spec("renzo-1967", **{"hub.crowning.radius": 3.0})
print(spec.hub.crowning.radius, wider.hub.crowning.radius)  # mm: 63.5, 76.2
# the resolved spec is a file in mm and degrees; spec.replace changes that file
same = spec.replace(**{"hub.crowning.radius": 76.2})
assert math.isclose(same.hub.crowning.radius, wider.hub.crowning.radius)
custom = gc.spec_from_dict({"tooth": {"teeth": 38, "module": 2.0},
                            "hub": {"face_width": 16.0,
                                    "crowning": {"kind": "circular", "radius": 38.0}}})
try:
    gc.load_spec("renzo-1967", **{"hub.face_width": -1.0})
except gc.SpecError as err:  # names the field, the value and what is allowed
    print(err)

pts, normals = gc.hub_flank(spec, "cw", z_mm=[0.0, 3.0], r_mm=63.5)  # (2, 3) each
sleeve_pts, _ = gc.sleeve_flank(spec, "cw", z_mm=[0.0], r_mm=63.5)
outline = gc.transverse_section(spec, "hub", z_mm=5.0, tolerance_mm=1e-3)  # (n, 2)
path = gc.feed_path(spec.hub.crowning, spec.tooth.pitch_radius, spec.hub.face_width)
assert isinstance(path, gc.FeedPath)
phi = math.radians(20.0)
assert abs(float(gc.inv_inverse(gc.inv(phi))) - phi) < 1e-12
print(pts.shape, outline.shape, custom.tooth.teeth)
