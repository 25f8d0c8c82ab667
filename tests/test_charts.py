"""Measuring charts: crown height and slopes against the feed path, straight hub zero."""

import csv
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.cli import main
from gearcoupling.geometry.hub import hub_flank_model, hub_model
from gearcoupling.hob import measuring_charts, plot_measuring_charts, write_nominal_csv


def independent_c_beta(spec, z, half_lead):
    """C_beta of sin(phi) * drop(z) (a revolved section moved in by drop(z) shifts the
    involute along the base tangent by drop sin(phi)) by numpy.polyfit over L_beta."""
    m = hub_model(spec)
    sel = np.abs(z) <= half_lead + 1e-9
    c = np.polyfit(z[sel], -math.sin(m.phi) * m.path.drop(z[sel]), 2)[0]
    return -c * half_lead**2


@pytest.mark.parametrize("name", ["renzo-1967", "renzo-1967-vari-crown",
                                  "renzo-1967-end-round", "mill-spindle"])
def test_c_beta_is_the_feed_path_crown_drop_over_the_evaluation_range(name):
    spec = gc.load_spec(name)
    rev = spec.replace(**{"hub.crowning.generation": "revolved"})
    for s, rel in ((rev, 1e-9), (spec, 0.01)):
        ch = measuring_charts(s, points=201)
        half = 0.5 * ch.lead_evaluation_mm
        b, m = spec.hub.face_width, spec.tooth.module
        assert half == pytest.approx(0.5 * b - min(0.05 * b, m), abs=1e-12)
        lead = [t for t in ch.traces if t.kind == "lead"]
        expect = independent_c_beta(spec, lead[0].x_mm, half)
        for flank in ("cw", "ccw"):
            # revolved: exact; enveloped: the tilted rack changes the section slightly
            # (Renzo Fig. 7), measured within 1 %
            assert ch.values[flank]["C_beta_mm"] == pytest.approx(expect, rel=rel)
            assert abs(ch.values[flank]["f_Hbeta_mm"]) < 1e-9
    # revolved lead trace is exactly -sin(phi) drop(z) point by point
    tr = next(t for t in measuring_charts(rev).traces if t.kind == "lead")
    m = hub_model(rev)
    np.testing.assert_allclose(tr.deviation_mm, -math.sin(m.phi) * m.path.drop(tr.x_mm),
                               atol=1e-9)


def test_straight_hub_has_zero_crown_and_slopes():
    spec = gc.load_spec("industrial-m2").replace(**{"hub.crowning.kind": "none"})
    ch = measuring_charts(spec)
    for v in ch.values.values():
        for key in ("C_beta_mm", "f_Hbeta_mm", "f_Halpha_mid_mm", "f_Halpha_z_plus_mm",
                    "f_Halpha_z_minus_mm"):
            assert abs(v[key]) < 1e-10, key
    assert max(np.max(np.abs(t.deviation_mm)) for t in ch.traces) < 1e-10


def test_end_profiles_tilt_alike_on_both_ends_and_flanks():
    """Crowned: the end profiles tilt (Renzo eq. 1) the same on both ends and flanks."""
    ch = measuring_charts(gc.load_spec("renzo-1967"))
    v = ch.values
    assert v["cw"]["f_Halpha_z_plus_mm"] == pytest.approx(v["cw"]["f_Halpha_z_minus_mm"],
                                                          rel=1e-9)
    assert v["cw"]["f_Halpha_z_plus_mm"] == pytest.approx(v["ccw"]["f_Halpha_z_plus_mm"],
                                                          rel=1e-9)
    assert v["cw"]["f_Halpha_z_plus_mm"] > 1e-4 and abs(v["cw"]["f_Halpha_mid_mm"]) < 1e-10


def test_nominal_csv_reloads_onto_the_exact_flank(tmp_path):
    spec = gc.load_spec("renzo-1967-vari-crown")
    ch = measuring_charts(spec, points=21)
    path = write_nominal_csv(ch, tmp_path / "nominal.csv")
    lines = path.read_text().splitlines()
    assert any("units: mm" in line for line in lines if line.startswith("#"))
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    assert len(rows) == 2 * 4 * 21
    m = hub_model(spec)
    for flank in ("cw", "ccw"):
        sel = [r for r in rows if r["flank"] == flank]
        p = np.array([[float(r[k]) for k in ("x_mm", "y_mm", "z_mm")] for r in sel])
        n = np.array([[float(r[k]) for k in ("nx", "ny", "nz")] for r in sel])
        exact, normals, _ = hub_flank_model(m, flank, p[:, 2], np.hypot(p[:, 0], p[:, 1]))
        assert np.max(np.abs(p - exact)) < 1e-8 and np.max(np.abs(n - normals)) < 1e-8
        np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-8)


def test_plot_accepts_axes_and_cli_writes_files(tmp_path, capsys):
    from gearcoupling.plots import new_figure

    ch = measuring_charts(gc.load_spec("renzo-1967"), points=11)
    fig, axes = new_figure(2, 2)
    assert plot_measuring_charts(ch, ax=axes.ravel()) is fig
    assert len(axes[0, 1].lines) >= 1
    with pytest.raises(gc.ArgumentError, match="4 Axes"):
        plot_measuring_charts(ch, ax=axes.ravel()[:2])
    assert main(["charts", "industrial-m2", "-o", str(tmp_path), "--points", "11"]) == 0
    for f in ("charts.png", "nominal_traces.csv", "charts.json"):
        assert (tmp_path / f).stat().st_size > 0
    assert main(["charts", "industrial-m2", "-o", str(tmp_path), "--points", "2"]) == 2
    assert "argument --points: 2: must be from 5" in capsys.readouterr().err


def test_lead_range_stops_where_a_tip_sphere_cuts_the_lead_radius():
    """A short, small hub: the tip sphere passes below the lead radius before the face end."""
    spec = gc.spec_from_dict({"tooth": {"teeth": 12, "module": 1.0, "pressure_angle_deg": 25},
                              "hub": {"face_width": 8.4, "root": {"dedendum": 1.0},
                                      "crowning": {"kind": "circular", "radius": 60.0}}})
    ch = measuring_charts(spec, points=41)
    m = hub_model(spec)
    r_lead = ch.values["cw"]["lead_radius_mm"]
    reach = math.sqrt(m.tip_radius**2 - r_lead**2)
    assert reach < m.half_face - min(0.05 * 8.4, 1.0)  # the ISO range would leave the flank
    assert 0.5 * ch.lead_evaluation_mm == pytest.approx(reach, rel=1e-9)
    lead = next(t for t in ch.traces if t.kind == "lead")
    assert np.all(np.hypot(lead.points[:, 0], lead.points[:, 1]) <= m.tip_radius)
    assert ch.values["cw"]["C_beta_mm"] > 0
