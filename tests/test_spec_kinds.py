"""The crown kind table: a kind registered in ``CROWN_KINDS`` only (here, in the test, a
parabolic crown) is named by a spec file, checked like the built-in kinds, and sweeps, loads
and meshes like them (docs/api.md, "A crown kind")."""

import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.geometry import FeedPath
from gearcoupling.spec import CROWN_KINDS, CROWNING_KINDS, CrownKind, resolve_spec_path

RHO = 38.0  # the parabola's radius at the midplane: industrial-m2's R_c
FACE = 16.0  # industrial-m2's face width


def parabola_t(s, rho):
    """``t = tan e = z / rho`` at arc length ``s`` of ``v = R - z² / (2 rho)``, where
    ``s = rho/2 (t sqrt(1 + t²) + asinh t)`` (Newton from the right: converges)."""
    t = np.asarray(s, dtype=float) / rho
    for _ in range(60):
        q = np.sqrt(1.0 + t * t)
        step = (0.5 * rho * (t * q + np.arcsinh(t)) - s) / (rho * q)
        t = t - step
        if np.all(np.abs(step) <= 1e-16 * (1.0 + np.abs(t))):
            break
    return t


def parabolic_path(crowning, R, face_width):
    """The toy kind's path function: ``kappa = cos³e / rho`` with ``tan e = z / rho`` up to
    ``z = face_width`` (past the face ends), then an arc of the curvature reached there."""
    rho = crowning.radius

    def smooth(s):
        t = parabola_t(s, rho)
        return 1.0 / (rho * (1.0 + t * t) ** 1.5), np.arctan(t)

    t_end = face_width / rho
    s_end = 0.5 * rho * (t_end * math.sqrt(1.0 + t_end**2) + math.asinh(t_end))
    k_end = 1.0 / (rho * (1.0 + t_end**2) ** 1.5)
    return FeedPath(R, [(s_end, None), (math.inf, k_end)], smooth, kind=crowning.kind)


PARABOLIC = CrownKind("parabolic", parabolic_path, "v = R - z² / (2 radius) (a test kind)",
                      needs=("radius",))


@pytest.fixture
def parabolic(monkeypatch):
    """The toy kind, in the table for one test."""
    monkeypatch.setitem(CROWN_KINDS, PARABOLIC.name, PARABOLIC)
    return PARABOLIC


def spec_file(tmp_path, crowning: str):
    """industrial-m2 as a spec file with its ``[hub.crowning]`` table replaced."""
    head, _, rest = resolve_spec_path("industrial-m2").read_text().partition("[hub.crowning]")
    _, body, tail = rest.partition("[hub.body]")
    path = tmp_path / "toy.toml"
    path.write_text(f"{head}[hub.crowning]\n{crowning}\n\n{body}{tail}")
    return path


def test_a_spec_file_names_a_kind_once_it_is_in_the_table(tmp_path, monkeypatch):
    path = spec_file(tmp_path, f'kind = "parabolic"\nradius = {RHO}')
    with pytest.raises(gc.SpecError) as err:
        gc.load_spec(path)
    assert err.value.field == "hub.crowning.kind" and err.value.allowed == \
        f"one of {CROWNING_KINDS}"
    monkeypatch.setitem(CROWN_KINDS, PARABOLIC.name, PARABOLIC)
    spec = gc.load_spec(path)
    assert spec.hub.crowning.kind == "parabolic" and spec.hub.crowning.radius == RHO
    with pytest.raises(gc.SpecError, match="'parabolic'") as err:  # the table is the list
        gc.load_spec(path, **{"hub.crowning.kind": "elliptic"})
    assert err.value.field == "hub.crowning.kind"
    with pytest.raises(gc.SpecError, match="is required") as err:  # the fields it needs
        gc.load_spec(path, **{"hub.crowning.radius": None})
    assert err.value.field == "hub.crowning.radius"


def test_the_spec_checks_and_derived_values_hold_for_a_new_kind(parabolic):
    spec = gc.load_spec("industrial-m2", **{"hub.crowning.kind": "parabolic"})
    b = 0.5 * FACE
    assert spec.derived["crown_drop_at_face_end_mm"] == pytest.approx(b * b / (2 * RHO),
                                                                      rel=1e-12)
    assert spec.derived["crowning_radius_midplane_mm"] == pytest.approx(RHO, rel=1e-15)
    path = spec.hub.crowning.feed_path(spec.tooth.pitch_radius, FACE)
    z = np.linspace(-b, b, 33)
    np.testing.assert_allclose(path.drop(z), z * z / (2 * RHO), rtol=0, atol=1e-12)
    assert path.kind == "parabolic"
    # the curvature check of every kind: R_c at least twice the dedendum (2.5 mm)
    with pytest.raises(gc.SpecError, match="twice the hub dedendum") as err:
        spec.replace(**{"hub.crowning.radius": 4.0})
    assert err.value.field == "hub.crowning.radius" and err.value.value == pytest.approx(4.0)


def test_a_new_kind_sweeps_loads_and_meshes_like_the_table_of_the_same_crown(parabolic):
    """Against the built-in ``table`` kind given the same parabola as drop samples (a cubic
    spline holds a parabola exactly): equal to rounding; the sweep of the circle of the same
    midplane radius (drop 0.0096 mm apart at the face ends) is apart by much more."""
    base = gc.load_spec("industrial-m2")
    par = base.replace(**{"hub.crowning.kind": "parabolic"})
    z = np.linspace(0.0, 0.5 * FACE, 9)
    table = base.replace(**{"hub.crowning.kind": "table", "hub.crowning.radius": None,
                            "hub.crowning.z": list(z),
                            "hub.crowning.drop": list(z * z / (2 * RHO))})
    angles = np.linspace(0.0, 360.0 / 38, 5, endpoint=False)
    a, t, c = (gc.sweep(s, 2.0, angles).clearance_mm for s in (par, table, base))
    assert np.all(np.isfinite(a))
    assert np.max(np.abs(a - t)) < 1e-8  # mm (5.7e-10 measured; sweep tolerance 1e-7)
    assert np.max(np.abs(a - c)) > 1e-4  # mm (2.0e-4 measured)

    a, t = (gc.load(s, 0.75, angles, torque_Nm=400.0, model="linear").tangential_force_N
            for s in (par, table))
    assert np.max(np.abs(a - t)) < 1e-6 * np.max(a)  # 7e-8 measured (the circle: 3e-4)

    hub, twin = (gc.build_part(s, "hub", teeth=[0]) for s in (par, table))
    assert hub.is_watertight
    assert hub.volume == pytest.approx(twin.volume, rel=2e-5)  # 6e-7 measured (circle 7e-4)
