"""Seeded random specs over the whole supported range, stratified by crown kind x
generation x tip (``tests/random_specs.py``): in every stratum most specs are accepted
(an acceptance floor, so that a test cannot pass by refusing everything), every accepted
spec builds finite, simple geometry, every refusal is a SpecError naming a real spec key,
and one accepted spec per stratum builds closed hub and sleeve meshes."""

import math

import numpy as np
import pytest
import shapely

import gearcoupling as gc
from gearcoupling.geometry.hub import form_radius, hub_model, tip_radius
from gearcoupling.spec import SPEC_KEYS
from random_specs import STRATA, random_spec_data

PER_STRATUM = 6
FLOOR = 5  # accepted of PER_STRATUM in every stratum (measured here: 6/6 in all 20 strata)


def _draw(stratum):
    rng = np.random.default_rng([STRATA.index(stratum), 2026])
    return [random_spec_data(rng, *stratum) for _ in range(PER_STRATUM)]


def _known_key(field: str) -> bool:
    table, _, key = field.rpartition(".")
    return key in SPEC_KEYS.get(table, ()) or field in SPEC_KEYS.get("", ())


def _check_geometry(spec):
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


@pytest.mark.parametrize("stratum", STRATA, ids=["/".join(s) for s in STRATA])
def test_each_stratum_is_mostly_accepted_and_builds_finite_geometry(stratum):
    accepted, refused = [], []
    for data in _draw(stratum):
        try:
            accepted.append(gc.spec_from_dict(data))
        except gc.SpecError as err:
            assert _known_key(err.field), str(err)
            refused.append(str(err))
    assert len(accepted) >= FLOOR, refused
    for spec in accepted:
        _check_geometry(spec)


@pytest.mark.parametrize("stratum", STRATA, ids=["/".join(s) for s in STRATA])
def test_one_spec_per_stratum_builds_closed_parts(stratum):
    from gearcoupling.parts import build_part

    spec = next(s for s in map(_try, _draw(stratum)) if s is not None)
    for part in ("hub", "sleeve"):
        mesh = build_part(spec, part, tolerance_mm=spec.tooth.module / 20, teeth=[0])
        assert mesh.is_watertight and mesh.volume > 0
        assert np.all(np.isfinite(mesh.vertices))


def _try(data):
    try:
        return gc.spec_from_dict(data)
    except gc.SpecError:
        return None


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
