"""The sweep at the extremes of the range: finite everywhere,
heavy binding as a large negative clearance, never NaN; the aligned clearance against its
closed form on the specs whose flank table stalled before it was cut at curvature jumps."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.arguments import GAP_TOLERANCE_MM
from gearcoupling.clearance import KINDS, sweep
from gearcoupling.clearance.flank_table import flank_table
from gearcoupling.clearance.reference import brute_force
from gearcoupling.errors import GeometryError
from gearcoupling.geometry.sleeve import sleeve_model

#: 120 straight teeth, NaN and "All-NaN slice" at 6°
ISSUE_EXAMPLE = {"units": "mm",
                 "tooth": {"teeth": 120, "module": 2.793, "pressure_angle_deg": 21.78},
                 "hub": {"face_width": 9.44, "backlash": 0.153, "tip": {"kind": "cylinder"},
                         "crowning": {"kind": "none"}}}
#: sqrt of a negative at 6°: the active interval lay wholly above the sleeve fillet start,
#: and the secant for a crossing that did not exist left [0, 1] (t = -0.61, y = -4e22)
ABOVE_FILLET = {"units": "mm",
                "tooth": {"teeth": 273, "module": 0.2221547424441338,
                          "pressure_angle_deg": 15.067822495336474},
                "hub": {"face_width": 22.255277113491317, "backlash": 0.010308210280267896,
                        "tip": {"kind": "cylinder"},
                        "crowning": {"kind": "end_round", "generation": "enveloped",
                                     "radius": 344.288537687625,
                                     "end_radius": 215.0574909508832,
                                     "start_z": 8.210125193087645}}}


def _end_round(teeth, module, phi, face, backlash, tip, gen, rc, re, start):
    return {"units": "mm",
            "tooth": {"teeth": teeth, "module": module, "pressure_angle_deg": phi},
            "hub": {"face_width": face, "backlash": backlash, "tip": {"kind": tip},
                    "crowning": {"kind": "end_round", "generation": gen, "radius": rc,
                                 "end_radius": re, "start_z": start}}}


#: the worst aligned errors found over 150 random specs before the fix (0° clearance too
#: high by 1.6e-5 mm, flank tables stalled at 1e-5 .. 4.4e-4 mm)
STALLED = {
    "m3.6-N232": _end_round(232, 3.6181659517086064, 17.115480071929504, 322.3728200174488,
                            0.5175849677277355, "cylinder", "enveloped", 14717.283880739162,
                            3506.2123339105997, 56.07293694096678),
    "m4.6-N293-straight-then-round": _end_round(
        293, 4.597372707825367, 19.112291278605504, 226.6511507525976, 0.1220996097939414,
        "cylinder", "enveloped", math.inf, 2654.0583647858275, 23.494533041842686),
    "m13-N238": _end_round(238, 13.067161447135897, 17.840269045609823, 595.4910004131129,
                           0.1370240329239469, "sphere", "enveloped", 6054.3164134546305,
                           1080.7431332390067, 245.39585010037868),
    "m0.53-N91-revolved": _end_round(91, 0.531397339750411, 19.66854324155718,
                                     20.272513940834283, 0.14776397994035181, "cylinder",
                                     "revolved", math.inf, 149.28784859137616,
                                     5.117913902728386),
}


def _aligned_normal_clearance(spec) -> float:
    """Closed form at 0°: the normal gap is ``r_b`` times half the aligned backlash angle
    (involutes of one base circle are parallel; the crown is thickest at the midplane)."""
    return (spec.tooth.base_radius * spec.derived["aligned_backlash_mm"]
            / (2 * spec.tooth.pitch_radius))


def test_issue_example_binds_heavily_and_stays_finite():
    spec = gc.spec_from_dict(ISSUE_EXAMPLE)
    res = sweep(spec, 6.0, np.arange(0.0, 3.0, 0.5)).check_finite()
    assert np.all(res.backlash_mm < -0.5)  # heavy binding (binds at 0.91°), a value
    f, k, j = np.unravel_index(np.argmin(res.normal_clearance_mm), res.normal_clearance_mm.shape)
    theta = math.radians(res.theta_deg[k, j]) if f == 0 else math.pi - math.radians(
        res.theta_deg[k, j])
    # independent: dense exact flank points, the pose matrices and the sleeve's half angle
    ref = brute_force(spec, math.radians(6.0), theta, normal=True, nz=81, nt=41)
    assert res.normal_clearance_mm[f, k, j] <= ref + 1e-6
    assert res.normal_clearance_mm[f, k, j] == pytest.approx(ref, abs=1e-3)
    assert res.normal_clearance_mm[f, k, j] < -0.4


def test_active_interval_wholly_above_the_sleeve_fillet_start():
    """The active interval of every plane of 180 poses at 6° (the compiled kernel's own
    ``interval``) lies in [0, 1] and in order where it is feasible, also where all of it
    lies above the sleeve fillet start (the case of the regression occurs)."""
    from gearcoupling.clearance import kernel

    compiled = kernel.kernels()
    spec = gc.spec_from_dict(ABOVE_FILLET)
    table, sm = flank_table(spec), sleeve_model(spec)
    tab, ws = kernel._compiled_arrays(compiled, table, sm, math.radians(6.0),
                                      spec.tooth.pitch_radius, 1e-7, 17)
    po = compiled._entry(tab, 0) + compiled.EPL
    above = 0
    for z in np.linspace(-table.half_face, table.half_face, 17):
        compiled.plane_at(tab, ws, po, z, np.bool_(False))
        for theta in np.radians(np.arange(0.0, 360.0, 2.0)):
            feasible, t_lo, _, p_lo, t_a, _, _, t_hi, _, _ = compiled.interval(
                tab, ws, po, math.cos(theta), math.sin(theta))
            if feasible:
                assert 0.0 <= t_lo <= t_a <= t_hi <= 1.0
                above += math.hypot(p_lo[0], p_lo[1]) > sm.r_fillet
    assert above > 0
    res = sweep(spec, 6.0, [0.0, 0.5]).check_finite()
    assert np.all(np.isfinite(res.backlash_mm))


@pytest.mark.parametrize("name", sorted(STALLED))
def test_aligned_clearance_within_the_table_promise(name):
    spec = gc.spec_from_dict(STALLED[name])
    table = flank_table(spec)
    assert table.max_error_mm <= GAP_TOLERANCE_MM  # was 1e-5 .. 4.4e-4 mm
    assert len(table.edges) > 2  # cut at the end_round start
    res = sweep(spec, 0.0, [0.0, 7.0])
    err = res.normal_clearance_mm.min(axis=(1, 2)) - _aligned_normal_clearance(spec)
    assert np.all(err <= 1e-7)  # never too high (the unsafe side) by more than promised
    assert np.all(err >= -2e-7)


def _random_spec(rng) -> dict:
    """A spec drawn over the documented ranges (6-300 teeth, module 0.2-60 mm, pressure
    angle 14.5-30°, every crown kind, generation and tip)."""
    teeth = int(rng.integers(6, 301))
    module = math.exp(rng.uniform(math.log(0.2), math.log(60.0)))
    R = module * teeth / 2
    kind = str(rng.choice(["none", "circular", "vari_crown", "end_round", "table"]))
    face = rng.uniform(0.05, 1.2) * R
    rc = math.inf if rng.random() < 0.3 else rng.uniform(0.2, 50) * R
    cr: dict = {"kind": kind, "generation": str(rng.choice(["enveloped", "revolved"]))}
    if kind == "circular":
        cr["radius"] = rc
    elif kind == "vari_crown":
        cr.update(radius=min(rc, 1e6), end_radius=min(rc, 1e6) * rng.uniform(1.1, 4))
    elif kind == "end_round":
        cr.update(radius=rc, end_radius=rng.uniform(0.05, 0.9) * min(rc, 10 * R),
                  start_z=rng.uniform(0, 0.99) * face / 2)
    elif kind == "table":
        z = np.linspace(0, face / 2, int(rng.integers(3, 7)))
        drop = rng.uniform(0, 0.5) * module * (z / z[-1]) ** 2
        cr.update(z=z.tolist(), drop=drop.tolist())
    phi = rng.uniform(14.5, 30)
    return {"units": "mm",
            "tooth": {"teeth": teeth, "module": module, "pressure_angle_deg": phi},
            "hub": {"face_width": face, "backlash": rng.uniform(0, 0.3) * module,
                    "tip": {"kind": str(rng.choice(["sphere", "cylinder"]))}, "crowning": cr}}


def _accepted_specs(count: int, seed: int):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        try:
            out.append(gc.spec_from_dict(_random_spec(rng)))
        except gc.SpecError:
            continue
    return out


@pytest.mark.parametrize("mis", [0.0, 6.0])
def test_random_specs_are_finite(mis):
    """Seeded specs over the documented ranges: every value finite where a flank faces the
    sleeve (else "no contact" and inf), backlash finite, no warning (-W error); at 0° the
    clearance equals its closed form within the promised accuracy."""
    for spec in _accepted_specs(10, seed=14):
        N = spec.tooth.teeth
        psi = np.linspace(0.0, 360.0 / N, max(1, math.ceil(240 / N)), endpoint=False)
        res = sweep(spec, mis, psi).check_finite()
        assert np.all(np.isfinite(res.backlash_mm)), spec.to_dict()
        facing = res.contact_kind != KINDS.index("no contact")
        assert np.all(np.abs(res.contact_z_mm[facing]) <= res.half_face_mm * (1 + 1e-9))
        if mis == 0.0:
            err = res.normal_clearance_mm.min() - _aligned_normal_clearance(spec)
            assert -1e-6 <= err <= max(1e-7, res.table_error_mm) + 1e-9, spec.to_dict()


def test_check_finite_names_the_array(tmp_path):
    res = sweep(gc.load_spec("renzo-1967"), 1.0, [0.0, 10.0])
    bad = res.normal_clearance_mm.copy()
    bad[0, 3, 1] = np.nan
    from dataclasses import replace

    with pytest.raises(GeometryError, match="normal_clearance_mm"):
        replace(res, normal_clearance_mm=bad).check_finite()
    from gearcoupling.io import NonFiniteError, write_json

    with pytest.raises(NonFiniteError, match=r"sweep_summary\.json: .* is NaN"):
        write_json(tmp_path / "sweep_summary.json",
                   replace(res, normal_clearance_mm=bad).summary())
    assert not (tmp_path / "sweep_summary.json").exists()


def test_plots_return_figures_draw_into_given_axes_and_keep_the_backend(monkeypatch):
    import matplotlib
    from matplotlib.figure import Figure

    from gearcoupling.clearance import plots

    def refuse(*args, **kwargs):
        raise AssertionError("matplotlib.use called")

    monkeypatch.setattr(matplotlib, "use", refuse)
    spec = gc.spec_from_dict(ISSUE_EXAMPLE)
    res = sweep(spec, 6.0, [0.0, 1.0])
    fig = plots.plot_clearance_map(res, spec)  # the swing tooth faces no sleeve flank
    assert isinstance(fig, Figure)
    assert "no point faces" in " ".join(t.get_text() for t in fig.axes[1].texts)
    host = Figure()
    axes = host.subplots(2, 2)
    assert plots.plot_clearance(res, ax=axes) is host
    assert len(axes[0, 0].collections[0].get_segments()) == res.teeth  # a line per tooth
    assert len(axes[0, 0].lines) == 1  # and the contacting tooth's
    host = Figure()
    pair = host.subplots(1, 2)
    assert plots.plot_contact_path(res, spec, ax=pair) is host
    with pytest.raises(gc.ArgumentError, match="4 Axes"):
        plots.plot_clearance(res, ax=pair)


def test_sweep_command_at_6_deg_on_the_issue_example(tmp_path):
    """Was "All-NaN slice encountered" in the clearance map (the swing tooth faces no
    sleeve flank at 6°): now every file written, no NaN in them, and exit 1: the teeth
    bind there (smallest backlash below 0), a finding the command reports."""
    from gearcoupling.cli import main

    spec_file = tmp_path / "straight120.toml"
    spec_file.write_text('units = "mm"\n[tooth]\nteeth = 120\nmodule = 2.793\n'
                         "pressure_angle_deg = 21.78\n[hub]\nface_width = 9.44\n"
                         'backlash = 0.153\n[hub.tip]\nkind = "cylinder"\n'
                         '[hub.crowning]\nkind = "none"\n')
    out = tmp_path / "o"
    assert main(["sweep", str(spec_file), "--misalignment", "6", "--angles", "3",
                 "--no-design", "--quick-plots", "-o", str(out)]) == 1
    assert "nan" not in (out / "sweep.csv").read_text().lower()
    summary = (out / "sweep_summary.json").read_text()
    assert "NaN" not in summary
    assert json.loads(summary)["min_backlash_mm"] < -0.5
    assert (out / "sweep_clearance_map.png").stat().st_size > 10_000


def test_the_contact_path_draws_each_place_once_with_the_colour_drawn_last():
    """A tooth at a turning angle another tooth had gives the same point: the figure keeps
    one per place, the one drawn last (its colour covered the others), in drawing order."""
    from gearcoupling.clearance import plots

    spec = gc.load_spec("renzo-1967")
    res = sweep(spec, 1.0, np.arange(0.0, 360.0, 5.0))
    fig = plots.plot_contact_path(res, spec)
    for f in range(2):
        touch = np.isfinite(res.normal_clearance_mm[f])
        z, r = res.contact_z_mm[f][touch], res.contact_r_mm[f][touch]
        theta = res.theta_deg[touch]
        last = {}
        for i, place in enumerate(zip(z.tolist(), r.tolist(), strict=True)):
            last[place] = i  # the index drawn last at each place
        order = sorted(last.values())
        scatter = fig.axes[f].collections[-1]
        assert len(order) <= z.size // 2  # the teeth repeat each other's points
        np.testing.assert_array_equal(scatter.get_offsets(), np.stack([z, r], axis=1)[order])
        np.testing.assert_array_equal(scatter.get_array(), theta[order])
