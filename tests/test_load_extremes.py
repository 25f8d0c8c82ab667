"""Loaded contact at the extremes: every template, straight and tight crowns, 6° and 0°,
few and many teeth, tiny and huge modules, zero and huge torque - finite or refused."""

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import sweep
from gearcoupling.errors import ArgumentError, SpecError
from gearcoupling.loading import capacity_from_sweep, load_from_sweep

MINIMAL = {  # specs from the defaults, to reach the edges of the allowed ranges
    "6-teeth": dict(tooth=dict(teeth=6, module=2.0, pressure_angle_deg=30),
                    hub=dict(face_width=6.0, root=dict(dedendum=1.2, fillet_radius=0.6),
                             crowning=dict(kind="circular", radius=40.0))),
    "300-teeth": dict(tooth=dict(teeth=300, module=1.0, pressure_angle_deg=20),
                      hub=dict(face_width=10.0, crowning=dict(kind="circular", radius=150.0))),
    "module-0.2": dict(tooth=dict(teeth=30, module=0.2, pressure_angle_deg=20),
                       hub=dict(face_width=1.5, crowning=dict(kind="circular", radius=3.0))),
    "module-60": dict(tooth=dict(teeth=30, module=60.0, pressure_angle_deg=30),
                      hub=dict(face_width=400.0, root=dict(dedendum=75.0, fillet_radius=5.0),
                               crowning=dict(kind="circular", radius=900.0))),
    "phi-14.5": dict(tooth=dict(teeth=40, module=3.0, pressure_angle_deg=14.5),
                     hub=dict(face_width=20.0, root=dict(dedendum=3.0, fillet_radius=0.6),
                              crowning=dict(kind="circular", radius=60.0))),
}
CASES = [
    ("industrial-m2", {}, 0.75),
    ("mill-spindle", {}, 4.0),
    ("mill-spindle", {}, 6.0),
    ("renzo-1967-end-round", {}, 2.0),
    ("renzo-1967-vari-crown", {}, 0.0),
    ("industrial-m2", {"hub.crowning.kind": "none"}, 0.5),
    *[(name, None, mis) for name in MINIMAL for mis in (0.5, 3.0)],
]


def base_spec(name, over):
    if over is None:
        return gc.spec_from_dict({**MINIMAL[name], "load": {"torque_Nm": 100.0}}, name=name)
    return gc.load_spec(name, **over)


@pytest.mark.parametrize("name, over, mis", CASES)
def test_finite_and_balanced_everywhere(name, over, mis):
    spec = base_spec(name, over)
    sw = sweep(spec, mis, np.linspace(0, 360.0 / spec.tooth.teeth, 5, endpoint=False))
    R = spec.tooth.pitch_radius
    for model in ("linear", "compliance"):
        for T in (0.0, 1e-3, 500.0, -500.0, 1e7):
            r = load_from_sweep(sw, torque_Nm=T, model=model)
            for f in ("tangential_force_N", "max_pressure_MPa", "interior_pressure_MPa",
                      "root_stress_MPa", "patch_length_mm", "windup_rad", "edge_load_share",
                      "mesh_stiffness_Nm_per_rad"):
                assert np.all(np.isfinite(getattr(r, f))), (model, T, f)
            tq = r.tangential_force_N.sum(axis=0) * R * 1e-3
            np.testing.assert_allclose(tq, abs(T), rtol=1e-9, atol=1e-300)
            s = r.summary()
            assert s["q"] is not None and 0 < s["q"] <= 1 + 1e-12
        c = capacity_from_sweep(sw, model=model)
        assert c.capacity_Nm is not None and c.capacity_Nm >= 0


def test_huge_torque_is_reported_as_a_limit_not_hidden():
    spec = gc.load_spec("renzo-1967")
    sw = sweep(spec, 1.0, [0.0])
    s = load_from_sweep(sw, torque_Nm=1e7).summary()
    assert any("edge contact" in n for n in s["limits"])
    assert any("root bending" in n for n in s["limits"])


@pytest.mark.parametrize("model", ["compliance", "surface"])
@pytest.mark.parametrize("torque_Nm", [1e9, -1e9])
def test_absurd_torque_stays_finite_and_scales(torque_Nm, model):
    """At the top of the torque range, far past any limit, the tooth loads stay finite (no
    overflow in the contact law) and still carry the torque to 1e-9; beyond it the torque
    is refused, naming the range."""
    spec = gc.load_spec("renzo-1967")
    sw = sweep(spec, 1.0, [0.0])
    res = load_from_sweep(sw, torque_Nm=torque_Nm, model=model)
    P = res.tangential_force_N
    assert np.all(np.isfinite(P)) and np.all(np.isfinite(res.windup_rad))
    np.testing.assert_allclose(P.sum() * spec.tooth.pitch_radius * 1e-3, abs(torque_Nm),
                               rtol=1e-9)
    with pytest.raises(ArgumentError, match="1e-09 to 1e\\+09"):
        load_from_sweep(sw, torque_Nm=torque_Nm * 1e191)


def test_zero_stiffness_and_bad_offsets_are_refused():
    with pytest.raises(SpecError, match="mesh_stiffness"):
        gc.load_spec("renzo-1967", **{"load.mesh_stiffness_lbf_per_in": 0.0})
    spec = gc.load_spec("renzo-1967")
    sw = sweep(spec, 1.0, [0.0])
    with pytest.raises(ArgumentError, match="gap_offset_rad"):
        load_from_sweep(sw, gap_offset_rad=np.zeros(7))
    with pytest.raises(ArgumentError, match="gap_offset_rad"):
        load_from_sweep(sw, gap_offset_rad=np.full(50, np.nan))


def test_material_defaults_and_per_part_overrides():
    spec = gc.load_spec("industrial-m2")  # no [material]: the stated steel defaults
    assert spec.material.hub.youngs_modulus_MPa == 206000.0
    assert spec.material.sleeve.allowable_contact_stress_MPa == 700.0
    mixed = gc.load_spec("industrial-m2", **{"material.youngs_modulus_MPa": 110000.0,
                                             "material.sleeve.youngs_modulus_MPa": 206000.0})
    assert mixed.material.hub.youngs_modulus_MPa == 110000.0
    assert mixed.material.sleeve.youngs_modulus_MPa == 206000.0
    with pytest.raises(SpecError, match=r"material\.hub\.density"):
        gc.load_spec("industrial-m2", **{"material.hub.density": 7.8})
    with pytest.raises(SpecError, match="unknown key"):
        gc.load_spec("industrial-m2", **{"load.torque": 5.0})


def test_inch_pound_keys_convert_exactly():
    spec = gc.load_spec("renzo-1967")
    assert spec.load.torque_Nm == pytest.approx(20000 * 4.4482216152605 * 0.0254, rel=1e-12)
    assert spec.load.mesh_stiffness_N_per_mm == pytest.approx(4e6 * 4.4482216152605 / 25.4)
    assert spec.material.hub.youngs_modulus_MPa == pytest.approx(30e6 * 0.00689475729, rel=1e-8)
