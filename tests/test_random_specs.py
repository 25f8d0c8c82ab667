"""Seeded random specs over the whole supported range build finite geometry or raise
SpecError — never NaN, never another exception."""

import math

import numpy as np
import shapely
from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st

import gearcoupling as gc
from gearcoupling.geometry.hub import form_radius, hub_model, tip_radius


@st.composite
def raw_specs(draw):
    teeth = draw(st.integers(6, 300))
    module = math.exp(draw(st.floats(math.log(0.2), math.log(60.0))))
    phi = draw(st.floats(14.5, 30.0))
    R = module * teeth / 2
    kind = draw(st.sampled_from(["none", "circular", "vari_crown", "end_round", "table"]))
    face = draw(st.floats(0.05, 1.2)) * R
    rc = draw(st.one_of(st.just(math.inf), st.floats(0.2, 50.0).map(lambda f: f * R)))
    crowning = {"kind": kind, "generation": draw(st.sampled_from(["enveloped", "revolved"]))}
    if kind == "circular":
        crowning["radius"] = rc
    elif kind == "vari_crown":
        crowning.update(radius=min(rc, 1e6), end_radius=min(rc, 1e6) * draw(st.floats(1.1, 4)))
    elif kind == "end_round":
        crowning.update(radius=rc, end_radius=draw(st.floats(0.05, 0.9)) * min(rc, 10 * R),
                        start_z=draw(st.floats(0.0, 0.99)) * face / 2)
    elif kind == "table":
        z = np.linspace(0, face / 2, draw(st.integers(3, 6)))
        crowning.update(z=list(z), drop=list(draw(st.floats(0, 0.5)) * module * (z / z[-1]) ** 2))
    return {
        "design_misalignment_deg": draw(st.sampled_from([0.0, 0.25, 1.0, 3.0, 6.0])),
        "tooth": {"teeth": teeth, "module": module, "pressure_angle_deg": phi},
        "hub": {
            "face_width": face,
            "backlash": draw(st.floats(0.0, 0.3)) * module,
            "tip": {"kind": draw(st.sampled_from(["sphere", "cylinder"]))},
            "root": {"dedendum": draw(st.floats(0.8, 1.4)) * module,
                     "fillet_radius": draw(st.floats(0.0, 0.45)) * module},
            "crowning": crowning,
        },
    }


@settings(max_examples=120, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(raw_specs())
def test_random_specs_build_or_raise_spec_error(data):
    try:
        spec = gc.spec_from_dict(data)
    except gc.SpecError as err:
        note(f"refused: {err}")
        assert err.field and str(err)
        return
    m = hub_model(spec)
    z = np.linspace(-m.half_face, m.half_face, 7)
    lo, hi = form_radius(m, z), tip_radius(m, z)
    r = lo[:, None] + (hi - lo)[:, None] * np.linspace(0, 1, 6)[None, :]
    for flank in ("cw", "ccw"):
        p, n = gc.hub_flank(spec, flank, np.broadcast_to(z[:, None], r.shape), r)
        assert np.all(np.isfinite(p)) and np.all(np.isfinite(n))
        assert np.allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-12)
    tol = 0.02 * spec.tooth.module
    for part, planes in (("hub", (0.0, m.half_face)), ("sleeve", (0.0,))):
        for zz in planes:
            poly = gc.transverse_section(spec, part, zz, tol)
            assert np.all(np.isfinite(poly))
            assert shapely.LinearRing(poly).is_simple, f"{part} z={zz}"
    assert all(math.isfinite(v) or math.isinf(v) for v in spec.derived.values())


def test_the_extremes_of_the_range_build():
    cases = [
        ({"teeth": 6, "module": 60.0, "pressure_angle_deg": 30},
         {"root": {"dedendum": 0.8 * 60, "fillet_radius": 0.3 * 60}}),
        ({"teeth": 300, "module": 0.2, "pressure_angle_deg": 14.5}, {}),
        ({"teeth": 40, "module": 0.2, "pressure_angle_deg": 20},
         {"crowning": {"kind": "circular", "radius": 1.0}}),
    ]
    for tooth, hub in cases:
        R = tooth["module"] * tooth["teeth"] / 2
        data = {"design_misalignment_deg": 6.0, "tooth": tooth,
                "hub": {"face_width": 0.2 * R, "crowning": {"kind": "circular", "radius": R},
                        **hub}}
        spec = gc.spec_from_dict(data)
        poly = gc.transverse_section(spec, "hub", spec.hub.face_width / 2, 1e-2 * tooth["module"])
        assert np.all(np.isfinite(poly)) and shapely.LinearRing(poly).is_simple
