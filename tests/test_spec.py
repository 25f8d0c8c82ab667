"""Spec loading, units, overrides and validation errors that name field, value and range."""

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.io import parse_override, plain
from gearcoupling.spec import spec_from_dict

BASE = {
    "units": "mm",
    "tooth": {"teeth": 38, "module": 2.0, "pressure_angle_deg": 20},
    "hub": {"face_width": 16.0, "backlash": 0.25, "crowning": {"kind": "circular", "radius": 38.0}},
}


def build(**changes):
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in BASE.items()}
    data["hub"] = {**BASE["hub"], "crowning": dict(BASE["hub"]["crowning"])}
    for key, value in changes.items():
        node = data
        parts = key.split("__")
        for p in parts[:-1]:
            node = node.setdefault(p, {})
        node[parts[-1]] = value
    return spec_from_dict(data)


def test_defaults_follow_the_module():
    s = build()
    m, R = 2.0, 38.0
    assert s.hub.tip.diameter == pytest.approx(2 * (R + m))
    assert s.hub.root.dedendum == pytest.approx(1.25 * m)
    assert s.sleeve.space_width == pytest.approx(math.pi * m / 2)
    assert s.sleeve.space_width - s.hub.tooth_thickness == pytest.approx(0.25)
    assert s.design_misalignment == 0.0


def test_inches_and_diametral_pitch_convert_to_mm():
    s = gc.load_spec("renzo-1967")
    assert s.tooth.module == pytest.approx(2.54)
    assert s.tooth.pitch_radius == pytest.approx(2.5 * 25.4)
    assert s.hub.crowning.radius == pytest.approx(63.5)
    assert s.derived["renzo_z0_mm"] / 25.4 == pytest.approx(0.00105, abs=5e-6)
    mm = gc.load_spec("renzo-1967", units="mm", **{
        "tooth.diametral_pitch": 10, "hub.face_width": 12.7, "hub.backlash": 0.1524,
        "hub.tip.diameter": 132.08, "hub.root.dedendum": 3.175, "hub.root.fillet_radius": 0.762,
        "hub.crowning.radius": 63.5, "hub.body.bore_diameter": 88.9, "hub.body.length": 25.4,
        "sleeve.face_width": 19.05, "sleeve.minor_diameter": 122.682,
        "sleeve.major_diameter": 133.35, "sleeve.tip_chamfer": 0.254,
        "sleeve.root_fillet_radius": 0.508, "sleeve.outer_diameter": 152.4})
    # same coupling, whatever the file's units (up to the rounding of inch conversions)
    assert mm.derived == pytest.approx(s.derived, rel=1e-12)
    assert mm.hub.tooth_thickness == pytest.approx(s.hub.tooth_thickness, rel=1e-12)


def test_overrides_and_replace():
    s = gc.load_spec("renzo-1967", **{"hub.crowning.radius": 2.0})
    assert s.hub.crowning.radius == pytest.approx(50.8)
    assert s.replace(**{"hub.crowning.radius": 50.8}) == s
    assert parse_override("hub.crowning.radius=80") == ("hub.crowning.radius", 80)
    assert parse_override("hub.crowning.kind=none") == ("hub.crowning.kind", "none")
    assert parse_override("hub.crowning.radius=inf")[1] == math.inf
    with pytest.raises(gc.SpecError, match="KEY=VALUE"):
        parse_override("nonsense")


@pytest.mark.parametrize(
    "changes, field, words",
    [
        ({"tooth__teeth": 5}, "tooth.teeth", "6 to 300"),
        ({"tooth__teeth": 12.5}, "tooth.teeth", "whole number"),
        ({"tooth__module": 0.1}, "tooth.module", "0.2-60"),
        ({"tooth__pressure_angle_deg": 35}, "tooth.pressure_angle_deg", "14.5-30"),
        ({"hub__face_width": -3.0}, "hub.face_width", "positive"),
        ({"hub__backlash": -0.1}, "hub.backlash", ">= 0"),
        ({"hub__crowning__kind": "parabolic"}, "hub.crowning.kind", "one of"),
        ({"hub__crowning__radius": 4.0}, "hub.crowning.radius", "dedendum"),
        ({"hub__crowning__radius": 10.0}, "hub.crowning.radius", "face width"),
        ({"hub__tip__diameter": 82.0}, "hub.tip.diameter", "reach the sleeve root"),
        ({"hub__tip__diameter": 72.0}, "hub.tip.diameter", "do not reach the sleeve flank"),
        ({"hub__root__dedendum": 1.0, "sleeve__minor_diameter": 73.0}, "sleeve.minor_diameter",
         "hub root"),
        ({"sleeve__minor_diameter": 70.0}, "sleeve.minor_diameter", "base diameter"),
        ({"sleeve__minor_diameter": 72.5}, "sleeve.minor_diameter", "hub root fillets"),
        ({"hub__tip__diameter": 80.9, "sleeve__major_diameter": 81.0},
         "hub.tip.diameter", "sleeve root fillets"),
        ({"sleeve__major_diameter": 60.0}, "sleeve.major_diameter", "minor"),
        ({"hub__root__fillet_radius": 3.0}, "hub.root.fillet_radius", "dedendum"),
        ({"hub__body__bore_diameter": 70.0}, "hub.body.bore_diameter", "rim"),
        ({"sleeve__face_width": 10.0}, "sleeve.face_width", "cover the hub"),
        ({"design_misalignment_deg": 7.0}, "design_misalignment_deg", "from 0.0 to 6.0"),
        ({"units": "cm"}, "units", "one of"),
        ({"hub__colour": "red"}, "hub.colour", "unknown key"),
        ({"hub__crowning__generation": "milled"}, "hub.crowning.generation", "one of"),
        ({"hub__crowning__kind": "vari_crown", "hub__crowning__end_radius": 20.0},
         "hub.crowning.end_radius", "exceed"),
        ({"hub__crowning__kind": "end_round", "hub__crowning__end_radius": 20.0,
          "hub__crowning__start_z": 9.0}, "hub.crowning.start_z", "half face"),
        ({"hub__crowning__kind": "table", "hub__crowning__z": [0, 4, 8],
          "hub__crowning__drop": [0.1, 0.2, 0.3]}, "hub.crowning.drop", "0 at z = 0"),
        ({"hub__crowning__kind": "table", "hub__crowning__s": [0, 4, 8]},
         "hub.crowning.kappa", "as many samples"),
        ({"tooth__module": "two"}, "tooth.module", "number"),
    ],
)
def test_invalid_values_name_field_value_and_range(changes, field, words):
    with pytest.raises(gc.SpecError) as info:
        build(**changes)
    err = info.value
    assert err.field == field, str(err)
    assert words in str(err), str(err)
    assert isinstance(err, ValueError)


def test_undercut_is_refused():
    with pytest.raises(gc.SpecError, match="undercut") as info:
        spec_from_dict({"tooth": {"teeth": 9, "module": 3.0, "pressure_angle_deg": 14.5},
                        "hub": {"face_width": 10.0, "crowning": {"kind": "none"},
                                "root": {"fillet_radius": 0.3}},
                        "sleeve": {"minor_diameter": 26.6}})
    assert info.value.field == "hub.root.dedendum"


def test_missing_and_unknown_templates():
    with pytest.raises(gc.SpecError, match="templates"):
        gc.load_spec("no-such-coupling")
    with pytest.raises(gc.SpecError, match="required"):
        spec_from_dict({"tooth": {"teeth": 20, "module": 1.0}, "hub": {}})


def test_table_crowning_by_curvature_and_by_drop():
    s = build(hub__crowning={"kind": "table", "s": [0, 4, 8, 12], "kappa": [1 / 38] * 4})
    c = build()
    import numpy as np

    from gearcoupling.geometry.hub import hub_model

    z = np.linspace(-8, 8, 9)
    assert np.allclose(hub_model(s).path.drop(z), hub_model(c).path.drop(z), atol=1e-12)
    d = build(hub__crowning={"kind": "table", "z": [0, 4, 8],
                             "drop": [0, 0.2, 0.8], "generation": "revolved"})
    assert hub_model(d).path.drop(4.0) == pytest.approx(0.2, abs=1e-6)


def test_spec_dict_is_json_ready():
    import json

    data = gc.load_spec("renzo-1967", **{"hub.crowning.kind": "none"}).to_dict()
    text = json.dumps(plain(data), allow_nan=False)  # what every JSON writer does
    assert '"inf"' in text and data["tooth"]["pressure_angle_deg"] == pytest.approx(20)


def _draw_valid_range(rng):
    """A spec inside the documented ranges that leaves every proportion to the defaults."""
    teeth = int(rng.integers(6, 301))
    module = float(np.exp(rng.uniform(np.log(0.2), np.log(60.0))))
    R = 0.5 * module * teeth
    return {"tooth": {"teeth": teeth, "module": module,
                      "pressure_angle_deg": float(rng.uniform(14.5, 30.0))},
            "hub": {"face_width": float(rng.uniform(0.05, 0.3)) * R,
                    "backlash": float(rng.uniform(0.0, 0.3)) * module,
                    "tip": {"kind": str(rng.choice(["sphere", "cylinder"]))},
                    "crowning": {"kind": "circular", "radius": float(rng.uniform(1.0, 3.0)) * R,
                                 "generation": str(rng.choice(["enveloped", "revolved"]))}}}


def test_defaults_always_validate_over_the_documented_range():
    # 18 % of such specs were refused for the default hob tip radius, and
    # item 10: every spec of 12 or fewer teeth for undercut with default proportions
    rng = np.random.default_rng(14)
    refused = []
    for _ in range(150):
        data = _draw_valid_range(rng)
        try:
            spec_from_dict(data)
        except gc.SpecError as err:
            refused.append(str(err))
    assert refused == []


@pytest.mark.parametrize("teeth", [6, 7, 9, 12])
@pytest.mark.parametrize("phi", [14.5, 20.0, 30.0])
def test_few_teeth_build_with_default_proportions_and_no_undercut(teeth, phi):
    from gearcoupling.geometry.hub import hub_model, radius_squared

    data = {"tooth": {"teeth": teeth, "module": 3.0, "pressure_angle_deg": phi},
            "hub": {"face_width": 0.2 * 1.5 * teeth, "crowning": {"kind": "none"}}}
    spec = spec_from_dict(data)
    m = hub_model(spec)
    # independent spur relation: no undercut while the form depth stays above R sin^2 phi
    assert m.h_form < m.R * math.sin(m.phi) ** 2
    assert radius_squared(m, 0.0, m.h_form, m.phi)[1] < 0


def test_a_refused_derived_value_says_it_was_derived_and_what_to_set():
    with pytest.raises(gc.SpecError) as info:
        build(hub__face_width=60.0, hub__crowning={"kind": "circular", "radius": 300.0})
    err = info.value
    assert err.field == "hub.tip.diameter"
    assert "not in the spec: derived" in str(err) and "set hub.tip.diameter" in str(err)
    with pytest.raises(gc.SpecError) as info:  # given explicitly: no such note
        build(hub__face_width=60.0, hub__crowning={"kind": "circular", "radius": 300.0},
              hub__tip={"diameter": 80.0})
    assert "derived" not in str(info.value)


@pytest.mark.parametrize("changes, field, words", [
    ({"tooth__teth": 38}, "tooth.teth", "did you mean 'teeth'"),
    ({"hub__crowing": {"kind": "none"}}, "hub.crowing", "did you mean 'crowning'"),
    ({"toth": {"teeth": 3}}, "toth", "did you mean 'tooth'"),
])
def test_a_misspelt_key_is_reported_before_missing_ones(changes, field, words):
    data = {"tooth": {"module": 2.0}, "hub": {}}  # teeth and face width missing
    for key, value in changes.items():
        head, _, tail = key.partition("__")
        if tail:
            data[head][tail] = value
        else:
            data[head] = value
    with pytest.raises(gc.SpecError) as info:
        spec_from_dict(data)
    assert info.value.field == field and words in str(info.value)


@pytest.mark.parametrize("kind", ["none", "table", "circular"])
@pytest.mark.parametrize("key", ["radius", "end_radius", "start_z"])
def test_negative_crown_values_are_refused_even_where_the_kind_ignores_them(kind, key):
    crown = {"kind": kind, key: -5.0}
    if kind == "table":
        crown.update(z=[0, 4, 8], drop=[0, 0.1, 0.4])
    if kind == "circular" and key != "radius":
        crown["radius"] = 38.0
    with pytest.raises(gc.SpecError) as info:
        build(hub__crowning=crown)
    assert info.value.field == f"hub.crowning.{key}"


def test_design_misalignment_of_6_survives_the_degree_round_trip():
    s = build(design_misalignment_deg=6)
    assert math.degrees(s.design_misalignment) > 6.0  # the radian round trip overshoots
    assert s.design_misalignment_deg == 6.0 and s.to_dict()["design_misalignment_deg"] == 6.0
    from gearcoupling.spec import check_misalignment_deg

    assert check_misalignment_deg(6.000000000000001) == 6.0
    for bad in (6.001, -0.001, math.nan, math.inf, "6", True):
        with pytest.raises(gc.SpecError):
            check_misalignment_deg(bad)


@pytest.mark.parametrize("key, value", [("hub__backlash", math.nan), ("hub__backlash", math.inf),
                                        ("tooth__module", math.nan),
                                        ("hub__crowning__radius", math.nan)])
def test_nan_and_inf_values_are_spec_errors(key, value):
    with pytest.raises(gc.SpecError) as info:
        build(**{key: value})
    assert info.value.field == key.replace("__", ".")


def test_a_spec_file_that_is_not_utf8_is_a_spec_error(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes("# Kupplung für Walzwerk\n[tooth]\nteeth = 38\n".encode("latin-1"))
    with pytest.raises(gc.SpecError, match="UTF-8"):
        gc.load_spec(path)


def test_a_table_crown_is_checked_along_its_spline_not_only_at_its_samples():
    from gearcoupling.geometry.feedpath import feed_path

    # the samples are all >= 0 but the spline between them dips below 0
    bad = {"kind": "table", "z": [0, 2, 4, 6], "drop": [0, 0, 0, 0.2]}
    s = gc.spec_from_dict({"tooth": {"teeth": 38, "module": 2.0},
                           "hub": {"face_width": 12.0, "crowning": {"kind": "none"}}})
    path = feed_path(s.hub.crowning.__class__(kind="table", table_z=(0, 2, 4, 6),
                                              table_drop=(0, 0, 0, 0.2)), 38.0, 12.0)
    assert np.min(path.drop(np.linspace(0, 6, 61))) < -1e-3  # the dip is real
    with pytest.raises(gc.SpecError, match="rises above the midplane") as info:
        build(hub__face_width=12.0, hub__crowning=bad)
    assert info.value.field == "hub.crowning.drop"
    with pytest.raises(gc.SpecError, match="reach the face end") as info:  # no extrapolation
        build(hub__face_width=16.0, hub__crowning={"kind": "table", "z": [0, 3, 6],
                                                   "drop": [0, 0.05, 0.2]})
    assert info.value.field == "hub.crowning.z"


@pytest.mark.parametrize("key, typed, mm, words", [
    ("hub.crowning.radius", 0.1, 2.54, "at least twice the hub dedendum"),
    ("hub.crowning.radius", -1.0, -25.4, "must be positive"),
    ("sleeve.outer_diameter", 1.0, 25.4, "must exceed the major diameter"),
    ("hub.backlash", 1.0, 25.4, "below the sleeve space width"),
])
def test_an_inch_file_error_quotes_the_value_as_typed_with_mm_beside(key, typed, mm, words):
    # renzo-1967 is an inch template: the user reads the value they typed, in inches
    with pytest.raises(gc.SpecError) as err:
        gc.load_spec("renzo-1967", **{key: typed})
    assert err.value.field == key and err.value.value == typed
    assert str(err.value).startswith(f"{key} = {typed!r} in ({mm!r} mm): ")
    assert words in str(err.value)


def test_a_millimetre_file_error_quotes_the_value_once():
    with pytest.raises(gc.SpecError) as err:
        gc.load_spec("industrial-m2", **{"hub.crowning.radius": -1.0})
    assert str(err.value).startswith("hub.crowning.radius = -1.0: must be positive")


def test_an_inch_table_crown_error_quotes_its_samples_as_typed():
    data = {**BASE, "units": "in", "tooth": {"teeth": 38, "diametral_pitch": 12.7},
            "hub": {"face_width": 0.63, "backlash": 0.01,
                    "crowning": {"kind": "table", "z": [0, 0.1, 0.3], "drop": [0, -0.01, 0]}}}
    with pytest.raises(gc.SpecError) as err:
        spec_from_dict(data)
    assert err.value.field == "hub.crowning.drop" and err.value.value == (0.0, -0.01, 0.0)
    assert "[0.0, -0.01, 0.0] in ([0.0, -0.254, 0.0] mm)" in str(err.value)


def test_a_spec_error_with_its_typed_value_survives_pickling():
    import pickle

    with pytest.raises(gc.SpecError) as err:
        gc.load_spec("renzo-1967", **{"hub.crowning.radius": 0.1})
    again = pickle.loads(pickle.dumps(err.value))
    assert str(again) == str(err.value) and again.value == 0.1


def test_the_geometry_takes_spec_objects_and_the_public_functions_load_names():
    """No loader is injected into the geometry: its functions refuse a template name and the
    public ones load it (``gc.hub_flank`` of a name is the geometry's of the loaded spec);
    importing the package or the geometry imports no spec module."""
    import subprocess
    import sys

    from gearcoupling import geometry

    with pytest.raises(gc.ArgumentError) as err:
        geometry.hub_flank("industrial-m2", "cw", 0.0, 38.0)
    assert err.value.field == "spec"
    by_name = gc.hub_flank("industrial-m2", "cw", 0.0, 38.0)
    by_spec = geometry.hub_flank(gc.load_spec("industrial-m2"), "cw", 0.0, 38.0)
    for a, b in zip(by_name, by_spec, strict=True):
        np.testing.assert_array_equal(a, b)
    code = ("import sys, gearcoupling, gearcoupling.geometry; "
            "print([m for m in sys.modules if m.startswith('gearcoupling.spec')])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"
