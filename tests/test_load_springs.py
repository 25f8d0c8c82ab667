"""The tooth springs by name (``[load] stiffness``): the registry, the default fit's range
checks, its robustness over the supported range and its accuracy against the stored FE
tables it was fitted on; against a table computed in the session (real gmsh and CalculiX):
``tests/test_fea_stiffness.py`` (``test_default_springs_reproduce_the_fe_table``)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.loading import FittedCompliance
from gearcoupling.loading.springs import SPRINGS
from gearcoupling.spec import STIFFNESS_SOURCES
from random_specs import proportions_spec, springs_specs

TEMPLATES = ("renzo-1967", "renzo-1967-vari-crown", "renzo-1967-end-round", "industrial-m2",
             "mill-spindle")


def test_the_spec_allows_exactly_the_registered_springs_and_defaults_to_the_fit():
    assert set(STIFFNESS_SOURCES) == set(SPRINGS)
    spec = gc.load_spec("industrial-m2")
    assert spec.load.stiffness == "fe-fit" and spec.load.model == "surface"


@pytest.mark.parametrize("name", TEMPLATES)
def test_the_templates_lie_inside_the_fitted_range(name):
    assert FittedCompliance(gc.load_spec(name)).outside == []


def test_a_spec_outside_the_fitted_range_is_named_in_the_load_summary():
    """Ten teeth (the FE tables refuse so few: their far field is held by the sector's
    cuts) and the default sleeve fillet of module / 50: both named, with the range."""
    spec = gc.spec_from_dict({"tooth": {"teeth": 10, "module": 3.0},
                              "hub": {"face_width": 15.0, "crowning": {"radius": 60.0}},
                              "load": {"torque_Nm": 50.0}}, name="ten")
    outside = FittedCompliance(spec).outside
    assert any(o.startswith("teeth = 10 outside the fitted 14-") for o in outside), outside
    accuracy = gc.load(spec, 0.5, [0.0]).summary()["accuracy"]
    assert accuracy["springs"] == "fe-fit" and accuracy["outside_fitted_range"] == outside


def test_the_fit_is_finite_and_positive_over_random_specs():
    """Seeded random specs over the supported range (6-300 teeth, module 0.2-60 mm, the
    proportions drawn): the pair's far field at a 5 x 5 grid over the flank and its C are
    finite and positive, inside the fitted range or not."""
    rng = np.random.default_rng(24)
    for _ in range(12):
        spec = proportions_spec(rng)
        springs = FittedCompliance(spec)
        half = 0.5 * spec.hub.face_width
        lo, hi = springs.r_table[0], springs.r_table[-1]
        Z, R = np.meshgrid(np.linspace(0.0, half, 5), np.linspace(lo, hi, 5), indexing="ij")
        c = springs.pair_compliance_mm_per_N(Z, R)
        assert np.all(np.isfinite(c)) and np.all(c > 0), (spec.name, c)
        assert 0 < springs.mesh_stiffness_N_per_mm < np.inf


def test_the_default_springs_reproduce_every_stored_fe_far_field_within_10_percent():
    """The pair far field of the 40 FE tables the fit was made on (the templates and the
    seeded random specs of ``benchmarks/bench_springs.py``, stored by its ``--golden``)
    against the shipped fit at each table's load points (4 rows along the face, the last
    flush with the face end, x 3 radii): within 10 % at every point (the issue's target;
    -7.4 ... +7.8 % measured). The parts' fit alone, before the correction, misses it at
    18 % of the points, up to +22.9 %, most at the face end."""
    stored = json.loads((Path(__file__).parent / "golden" / "fe_far_field.json").read_text())
    by_name = {s.name: s for s in springs_specs(55)}
    worst = {}
    for name, t in stored.items():
        spec = by_name[name] if name.startswith("springs-") else gc.load_spec(name)
        Z, R = np.meshgrid(t["z_mm"], t["r_mm"], indexing="ij")
        err = FittedCompliance(spec).pair_compliance_mm_per_N(Z, R) / np.asarray(
            t["far_field_mm_per_N"]) - 1.0
        worst[name] = float(err.flat[np.argmax(np.abs(err))])
    assert len(worst) == 40
    assert all(abs(e) <= 0.10 for e in worst.values()), {
        k: round(v, 3) for k, v in worst.items() if abs(v) > 0.10}


@pytest.mark.parametrize("name", ["renzo-1967", "springs-47-none"])
def test_the_correction_is_held_beyond_the_tables_last_load_point(name):
    """The correction has data only up to the FE tables' last load row along the face (its
    patch flush with the face end; the stored table's last row): beyond it, it keeps its
    value there, as the table does, instead of the Gaussian process's extrapolation (which
    had moved the capacity at a misalignment up to 13 % from the FE table's springs when
    the tables ended at 0.8 of the half face, springs-47-none at 1°). Inside, it is the
    process's own mean, which varies along the face."""
    spec = ({s.name: s for s in springs_specs(55)}[name] if name.startswith("springs-")
            else gc.load_spec(name))
    springs = FittedCompliance(spec)
    z_last = springs.last_row_mm
    stored = json.loads((Path(__file__).parent / "golden" / "fe_far_field.json").read_text())
    assert z_last == pytest.approx(stored[name]["z_mm"][-1], rel=1e-12)
    r = np.linspace(springs.r_table[0], springs.r_table[-1], 4)
    beyond = np.linspace(z_last, springs.half_face_hub, 5)
    Z, R = np.meshgrid(np.concatenate([-beyond, beyond]), r, indexing="ij")
    for correction in (springs.correction, springs.exact_correction):
        at_last = correction(np.full_like(Z, z_last), R)
        np.testing.assert_allclose(correction(Z, R), at_last, rtol=1e-12)
        inside = correction(np.linspace(0.0, z_last, 5)[:, None], r[None, :])
        assert np.ptp(inside) > 1e-3


@pytest.mark.parametrize("name", [*TEMPLATES, "springs-06-vari_crown", "springs-18-end_round"])
def test_the_correction_spline_follows_the_process(name):
    """The correction is evaluated by a bicubic spline of the Gaussian process's log on
    25 x 25 knots per spec (a springs call on 960 points of renzo-1967 takes 0.8 ms with
    it, 7.7 ms with the process): within 1e-3 of the process at 2000 random flank points,
    a little beyond the face and the flank too (1e-4 at worst over the data set;
    ``bench_springs.py --spline`` has the table per knot grid)."""
    spec = ({s.name: s for s in springs_specs(55)}[name] if name.startswith("springs-")
            else gc.load_spec(name))
    springs = FittedCompliance(spec)
    rng = np.random.default_rng(7)
    Z = rng.uniform(-1.05, 1.05, 2000) * springs.half_face_hub
    R = rng.uniform(springs.r_table[0] - 0.1, springs.r_table[-1] + 0.1, 2000)
    np.testing.assert_allclose(springs.correction(Z, R), springs.exact_correction(Z, R),
                               rtol=1e-3)
