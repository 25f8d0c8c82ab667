"""Bad arguments to the public Python API raise the project's errors (``ArgumentError`` for
a call argument, ``SpecError`` for a spec or study value) naming the field, before any
costly work; a template name where a spec is expected is loaded (``gc.load_spec``). The
counterpart of tests/test_cli_bad_input.py; the seeded fuzz of every public function is
in tests/test_api_fuzz.py."""

import math
import os
import signal

import numpy as np
import pytest

import gearcoupling as gc

M2 = "industrial-m2"


@pytest.fixture(scope="module")
def spec():
    return gc.load_spec(M2)


@pytest.fixture(scope="module")
def sw(spec):
    return gc.sweep(spec, 0.5, [0.0])


@pytest.fixture(autouse=True)
def no_hang():
    """A call that hangs fails after 60 s instead of stopping the suite (signal.alarm
    interrupts Python code; numpy loops end first)."""
    def stop(*_):
        raise TimeoutError("over 60 s")

    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


A, S = gc.ArgumentError, gc.SpecError
NAN, INF = float("nan"), float("inf")

# (id, call(spec, sweep, tmp_path), error class, words the message must contain); every
# call would be refused before any work that takes more than a moment
BAD = [
    # a spec argument that is no spec
    ("load None spec", lambda s, w, t: gc.load(None, 0.5, [0]), A, "spec"),
    ("load 42 spec", lambda s, w, t: gc.load(42, 0.5, [0]), A, "spec"),
    ("sweep unknown name", lambda s, w, t: gc.sweep("nope", 0.5, [0]), S, "templates"),
    ("critical dict spec", lambda s, w, t: gc.critical_misalignment_deg({"a": 1}), A, "spec"),
    ("section bytes spec", lambda s, w, t: gc.transverse_section(b"x", "hub", 0, 0.01), A,
     "spec"),
    ("hub_flank list spec", lambda s, w, t: gc.hub_flank([1], "cw", 0, 20), A, "spec"),
    ("capacity None spec", lambda s, w, t: gc.capacity(None, 0.5), A, "spec"),
    ("report None spec", lambda s, w, t: gc.report(None, t / "r"), A, "spec"),
    ("run 1.5 spec", lambda s, w, t: gc.run(1.5, t / "r"), A, "spec"),
    ("write_html None spec", lambda s, w, t: gc.write_html(None, t / "v.html"), A, "spec"),
    ("build_part None spec", lambda s, w, t: gc.build_part(None, "hub"), A, "spec"),
    ("hob None spec", lambda s, w, t: gc.hob_program(None, 60), A, "spec"),
    ("charts None spec", lambda s, w, t: gc.measuring_charts(None), A, "spec"),
    ("body_windup None spec", lambda s, w, t: gc.body_windup_rad(None, 1.0), A, "spec"),
    ("fe_contact None spec", lambda s, w, t: gc.fe_contact(None, torque_Nm=1.0), A, "spec"),
    ("mesh_part None spec", lambda s, w, t: gc.mesh_part(None, "hub"), A, "spec"),
    ("compliance table None", lambda s, w, t: gc.tooth_compliance_table(None), A, "spec"),
    ("check_interference None", lambda s, w, t: gc.check_interference(None, 0.5, [0]), A,
     "spec"),
    ("pose_state None spec", lambda s, w, t: gc.pose_state(None, 0.5, 0), A, "spec"),
    ("compare_part None spec", lambda s, w, t: gc.compare_part(None, t / "x.stl"), A, "spec"),
    ("compare_capacity None", lambda s, w, t: gc.compare_capacity(None), A, "specs"),
    ("compare_capacity []", lambda s, w, t: gc.compare_capacity([]), A, "specs"),
    ("compare_capacity twice", lambda s, w, t: gc.compare_capacity([s, s]), A, "specs"),
    ("load_from_sweep None", lambda s, w, t: gc.load_from_sweep(None), A, "sweep_result"),
    ("check_part None", lambda s, w, t: gc.check_part(None), A, "mesh"),
    ("run_study None", lambda s, w, t: gc.run_study(None, t / "s"), A, "study"),
    # load_spec, spec_from_dict, load_study of the wrong kind
    ("load_spec None", lambda s, w, t: gc.load_spec(None), A, "name_or_path"),
    ("load_spec 42", lambda s, w, t: gc.load_spec(42), A, "name_or_path"),
    ("load_spec bytes", lambda s, w, t: gc.load_spec(b"industrial-m2"), A, "name_or_path"),
    ("load_spec empty", lambda s, w, t: gc.load_spec(""), A, "name_or_path"),
    ("load_spec override None", lambda s, w, t: gc.load_spec(M2, **{"tooth.teeth": "x"}), S,
     "tooth.teeth"),
    ("spec_from_dict None", lambda s, w, t: gc.spec_from_dict(None), A, "data"),
    ("spec_from_dict list", lambda s, w, t: gc.spec_from_dict([1, 2]), A, "data"),
    ("spec_from_dict name 42", lambda s, w, t: gc.spec_from_dict({}, name=42), A, "name"),
    ("load_study None", lambda s, w, t: gc.load_study(None), A, "path"),
    ("load_study 42", lambda s, w, t: gc.load_study(42), A, "path"),
    # output paths
    ("report /dev/null", lambda s, w, t: gc.report(s, os.devnull), A, "character device"),
    ("run /dev/null", lambda s, w, t: gc.run(s, os.devnull), A, "character device"),
    ("report None out", lambda s, w, t: gc.report(s, None), A, "out"),
    ("report empty out", lambda s, w, t: gc.report(s, ""), A, "empty"),
    ("run 42 out", lambda s, w, t: gc.run(s, 42), A, "out"),
    ("write_html None path", lambda s, w, t: gc.write_html(s, None), A, "path"),
    ("write_html empty path", lambda s, w, t: gc.write_html(s, ""), A, "empty"),
    ("export_part None path", lambda s, w, t: gc.export_part(s, "hub", None), A, "path"),
    ("run_study empty out", lambda s, w, t: gc.run_study(gc.load_study("renzo-tolerances"),
                                                         ""), A, "empty"),
    # angle lists
    ("load ['a']", lambda s, w, t: gc.load(s, 0.5, ["a"]), A, "angles_deg"),
    ("sweep '0,1,2'", lambda s, w, t: gc.sweep(s, 1, "0,1,2"), A, "angles_deg"),
    ("sweep []", lambda s, w, t: gc.sweep(s, 1, []), A, "angles_deg"),
    ("sweep [[0]]", lambda s, w, t: gc.sweep(s, 1, [[0, 1]]), A, "angles_deg"),
    ("sweep [nan]", lambda s, w, t: gc.sweep(s, 1, [NAN]), A, "angles_deg"),
    ("sweep [True]", lambda s, w, t: gc.sweep(s, 1, [True]), A, "angles_deg"),
    ("sweep 10**6 angles", lambda s, w, t: gc.sweep(s, 1, range(10**6)), A, "angles_deg"),
    ("sweep None angles", lambda s, w, t: gc.sweep(s, 1, None), A, "angles_deg"),
    ("check_interference 10**5 poses", lambda s, w, t: gc.check_interference(
        s, 0.5, np.zeros(10**5)), A, "angles_deg"),
    # misalignments
    ("sweep misalignment '1'", lambda s, w, t: gc.sweep(s, "1", [0]), A, "misalignment_deg"),
    ("sweep misalignment nan", lambda s, w, t: gc.sweep(s, NAN, [0]), A, "misalignment_deg"),
    ("load misalignment 7", lambda s, w, t: gc.load(s, 7, [0]), A, "misalignment_deg"),
    ("capacity misalignment None", lambda s, w, t: gc.capacity(s, None), A,
     "misalignment_deg"),
    ("capacity_curve []", lambda s, w, t: gc.capacity_curve(s, []), A, "misalignments_deg"),
    ("capacity_curve 'abc'", lambda s, w, t: gc.capacity_curve(s, "abc"), A,
     "misalignments_deg"),
    ("capacity_curve 1000 values", lambda s, w, t: gc.capacity_curve(
        s, np.linspace(0, 1, 1000)), A, "misalignments_deg"),
    ("capacity_curve [7]", lambda s, w, t: gc.capacity_curve(s, [7.0]), A,
     "misalignments_deg"),
    ("compare_capacity [-1]", lambda s, w, t: gc.compare_capacity([s], [-1.0]), A,
     "misalignments_deg"),
    # tolerances, steps, grids
    ("critical tol nan", lambda s, w, t: gc.critical_misalignment_deg(s, tolerance_deg=NAN), A,
     "tolerance_deg"),
    ("critical tol 0", lambda s, w, t: gc.critical_misalignment_deg(s, tolerance_deg=0), A,
     "tolerance_deg"),
    ("critical tol -1", lambda s, w, t: gc.critical_misalignment_deg(s, tolerance_deg=-1), A,
     "tolerance_deg"),
    ("critical tol 1e-300", lambda s, w, t: gc.critical_misalignment_deg(
        s, tolerance_deg=1e-300), A, "tolerance_deg"),
    ("critical tol '0.1'", lambda s, w, t: gc.critical_misalignment_deg(
        s, tolerance_deg="0.1"), A, "tolerance_deg"),
    ("binding tol -1", lambda s, w, t: gc.binding_angle_deg(s, tolerance_deg=-1), A,
     "tolerance_deg"),
    ("binding tol inf", lambda s, w, t: gc.binding_angle_deg(s, tolerance_deg=INF), A,
     "tolerance_deg"),
    ("binding steps 0", lambda s, w, t: gc.binding_angle_deg(s, steps=0), A, "steps"),
    ("binding steps 2.5", lambda s, w, t: gc.binding_angle_deg(s, steps=2.5), A, "steps"),
    ("binding steps 10**9", lambda s, w, t: gc.binding_angle_deg(s, steps=10**9), A, "steps"),
    ("min_backlash steps -1", lambda s, w, t: gc.min_backlash_rad(s, 0.5, steps=-1), A,
     "steps"),
    ("design_quantities tol nan", lambda s, w, t: gc.design_quantities(
        s, 0.5, tolerance_deg=NAN), A, "tolerance_deg"),
    ("contact_travel tol 0", lambda s, w, t: gc.contact_travel(s, 0.5, tolerance_mm=0), A,
     "tolerance_mm"),
    ("sweep tol 0", lambda s, w, t: gc.sweep(s, 0.5, [0], tolerance_mm=0), A, "tolerance_mm"),
    ("sweep tol nan", lambda s, w, t: gc.sweep(s, 0.5, [0], tolerance_mm=NAN), A,
     "tolerance_mm"),
    ("sweep tol '1e-7'", lambda s, w, t: gc.sweep(s, 0.5, [0], tolerance_mm="1e-7"), A,
     "tolerance_mm"),
    ("sweep tol 1e-300", lambda s, w, t: gc.sweep(s, 0.5, [0], tolerance_mm=1e-300), A,
     "tolerance_mm"),
    ("sweep grid 10**7", lambda s, w, t: gc.sweep(s, 1, [0], grid=10**7), A, "grid"),
    ("sweep grid 0", lambda s, w, t: gc.sweep(s, 1, [0], grid=0), A, "grid"),
    ("sweep grid 2.5", lambda s, w, t: gc.sweep(s, 1, [0], grid=2.5), A, "grid"),
    ("sweep periodic 'no'", lambda s, w, t: gc.sweep(s, 1, [0], periodic="no"), A,
     "periodic"),
    ("charts points 10**9", lambda s, w, t: gc.measuring_charts(s, points=10**9), A, "points"),
    ("charts tip nan", lambda s, w, t: gc.measuring_charts(s, tip_exclusion=NAN), A,
     "tip_exclusion"),
    ("hob table_points 10**9", lambda s, w, t: gc.hob_program(s, 60, table_points=10**9), A,
     "table_points"),
    ("hob diameter '60'", lambda s, w, t: gc.hob_program(s, "60"), A, "hob_diameter_mm"),
    ("double_engagement nan", lambda s, w, t: gc.double_engagement(s, NAN, 0, 100, [0]), A,
     "offset_mm"),
    ("double_engagement '1'", lambda s, w, t: gc.double_engagement(s, "1", 0, 100, [0]), A,
     "offset_mm"),
    ("pose_state band nan", lambda s, w, t: gc.pose_state(s, 0.5, 0, band_mm=NAN), A,
     "band_mm"),
    ("pose_state psi 'x'", lambda s, w, t: gc.pose_state(s, 0.5, "x"), A, "psi_deg"),
    ("section tol 0", lambda s, w, t: gc.transverse_section(s, "hub", 0.0, 0), A,
     "tolerance_mm"),
    ("section z nan", lambda s, w, t: gc.transverse_section(s, "hub", NAN, 0.01), A, "z_mm"),
    ("section part", lambda s, w, t: gc.transverse_section(s, "wheel", 0.0, 0.01), A, "part"),
    ("inv nan", lambda s, w, t: gc.inv(NAN), A, "a"),
    ("inv 'x'", lambda s, w, t: gc.inv("x"), A, "a"),
    ("inv_inverse 'x'", lambda s, w, t: gc.inv_inverse("x"), A, "y"),
    ("inv_inverse nan", lambda s, w, t: gc.inv_inverse(NAN), A, "y"),
    ("feed_path None", lambda s, w, t: gc.feed_path(None, 20.0, 16.0), A, "crowning"),
    ("feed_path radius nan", lambda s, w, t: gc.feed_path(s.hub.crowning, NAN, 16.0), A,
     "pitch_radius"),
    # torques: one range for every entry point
    ("load torque '100'", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm="100"), A,
     "torque_Nm"),
    ("load torque 1e300", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm=1e300), A,
     "torque_Nm"),
    ("load torque 1.7e308", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm=1.7e308), A,
     "torque_Nm"),
    ("load torque 1e-300", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm=1e-300), A,
     "torque_Nm"),
    ("load torque -5e-324", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm=-5e-324), A,
     "-5e-324"),
    ("load torque nan", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm=NAN), A, "torque_Nm"),
    ("load_from_sweep torque inf", lambda s, w, t: gc.load_from_sweep(w, torque_Nm=INF), A,
     "torque_Nm"),
    ("load torque True", lambda s, w, t: gc.load(s, 0.5, [0], torque_Nm=True), A,
     "torque_Nm"),
    ("body_windup 'abc'", lambda s, w, t: gc.body_windup_rad(s, "abc"), A, "torque_Nm"),
    ("body_windup 1e30", lambda s, w, t: gc.body_windup_rad(s, 1e30), A, "torque_Nm"),
    ("report torque 1e30", lambda s, w, t: gc.report(s, t / "r", torque_Nm=1e30), A,
     "torque_Nm"),
    ("spec torque 1e300", lambda s, w, t: gc.load_spec(M2, **{"load.torque_Nm": 1e300}), S,
     "load.torque_Nm"),
    ("fe_contact torque 0", lambda s, w, t: gc.fe_contact(s, torque_Nm=0), A, "torque_Nm"),
    ("fe_contact torque 1e30", lambda s, w, t: gc.fe_contact(s, torque_Nm=1e30), A,
     "torque_Nm"),
    ("sector_check torque 1e-300", lambda s, w, t: gc.sector_check(s, 0.5, torque_Nm=1e-300),
     A, "torque_Nm"),
    # keywords and choices
    # explicit keyword-only signatures: an unknown keyword is Python's TypeError naming it
    ("capacity_curve bogus=1", lambda s, w, t: gc.capacity_curve(s, [0.5], bogus=1),
     TypeError, "bogus"),
    ("capacity bogus=1", lambda s, w, t: gc.capacity(s, 0.5, bogus=1), TypeError, "bogus"),
    ("load bogus=1", lambda s, w, t: gc.load(s, 0.5, [0], bogus=1), TypeError, "bogus"),
    ("double_engagement bogus=1", lambda s, w, t: gc.double_engagement(
        s, 0.0, 0.5, 100.0, [0.0], bogus=1), TypeError, "bogus"),
    ("build_part positional tolerance", lambda s, w, t: gc.build_part(s, "hub", 0.01),
     TypeError, "positional"),
    ("hob_program positional tolerance", lambda s, w, t: gc.hob_program(s, 60.0, 0.01),
     TypeError, "positional"),
    ("load model bogus", lambda s, w, t: gc.load(s, 0.5, [0], model="bogus"), A, "model"),
    ("capacity flank bogus", lambda s, w, t: gc.capacity(s, 0.5, loaded_flank="up"), A,
     "loaded_flank"),
    ("build_part wheel", lambda s, w, t: gc.build_part(s, "wheel"), A, "part"),
    ("export_part .xyz", lambda s, w, t: gc.export_part(s, "hub", t / "a.xyz"), A, "file"),
    ("mesh_part sector 0", lambda s, w, t: gc.mesh_part(s, "hub", sector=0), A, "sector"),
    ("compliance table nz 1", lambda s, w, t: gc.tooth_compliance_table(s, nz=1), A, "nz"),
    ("serve port 0", lambda s, w, t: gc.serve(s, port=0), A, "port"),
    ("serve bogus=1", lambda s, w, t: gc.serve(s, bogus=1), TypeError, "bogus"),
    ("run workers '2'", lambda s, w, t: gc.run(s, t / "r", workers="2"), A, "workers"),
    ("run only 'spec'", lambda s, w, t: gc.run(s, t / "r", only="spec"), A, "only"),
    ("report bogus=1", lambda s, w, t: gc.report(s, t / "r", bogus=1), A, "bogus"),
    ("report angles 10**9", lambda s, w, t: gc.report(s, t / "r", angles=10**9), A, "angles"),
    ("run_study workers 0", lambda s, w, t: gc.run_study(gc.load_study("renzo-tolerances"),
                                                         t / "s", workers=0), A, "workers"),
    ("compare_part fit_points 10**9", lambda s, w, t: gc.compare_part(
        s, np.zeros((40, 3)), fit_points=10**9), A, "fit_points"),
    ("compare_part units 'cm'", lambda s, w, t: gc.compare_part(
        s, np.zeros((40, 3)), units="cm"), A, "units"),
]


@pytest.mark.parametrize("call, error, words", [c[1:] for c in BAD], ids=[c[0] for c in BAD])
def test_a_bad_argument_is_refused_naming_the_field(call, error, words, spec, sw, tmp_path):
    with pytest.raises(error) as info:
        call(spec, sw, tmp_path)
    assert words in str(info.value), str(info.value)
    assert len(str(info.value)) < 600
    assert not any(tmp_path.iterdir())  # nothing written


def test_there_are_many_bad_arguments():
    assert len(BAD) >= 100


# --- a template name where a spec is expected is loaded, for every spec-taking function

NAMED = [
    ("sweep", lambda: gc.sweep(M2, 0.5, [0.0])),
    ("load", lambda: gc.load(M2, 0.5, [0.0], torque_Nm=100.0, model="linear")),
    ("critical_misalignment_deg", lambda: gc.critical_misalignment_deg(M2, tolerance_deg=0.1)),
    ("binding_angle_deg", lambda: gc.binding_angle_deg(M2, tolerance_deg=0.1, steps=4)),
    ("min_backlash_rad", lambda: gc.min_backlash_rad(M2, 0.5, steps=4)),
    ("contact_travel", lambda: gc.contact_travel(M2, 0.5)),
    ("transverse_section", lambda: gc.transverse_section(M2, "hub", 0.0, 0.05)),
    ("hub_flank", lambda: gc.hub_flank(M2, "cw", 0.0, 38.0)),
    ("sleeve_flank", lambda: gc.sleeve_flank(M2, "cw", 0.0, 38.0)),
    ("body_windup_rad", lambda: gc.body_windup_rad(M2, 100.0)),
    ("measuring_charts", lambda: gc.measuring_charts(M2, points=11)),
    ("hob_program", lambda: gc.hob_program(M2, 60.0)),
    ("capacity", lambda: gc.capacity(M2, 0.5, model="linear", angles_deg=[0.0, 4.0])),
    ("pose_state", lambda: gc.pose_state(M2, 0.5, 0.0)),
]


@pytest.mark.parametrize("call", [c[1] for c in NAMED], ids=[c[0] for c in NAMED])
def test_a_template_name_is_loaded_where_a_spec_is_expected(call, spec):
    by_name = call()
    assert by_name is not None


def test_a_name_gives_what_the_loaded_spec_gives(spec):
    a = gc.sweep(M2, 0.5, [0.0, 3.0])
    b = gc.sweep(spec, 0.5, [0.0, 3.0])
    assert np.array_equal(a.clearance_mm, b.clearance_mm)
    assert gc.critical_misalignment_deg(M2, tolerance_deg=0.01) == \
        gc.critical_misalignment_deg(spec, tolerance_deg=0.01)


# --- silent wrong answers and the torque range's ends ---------------------------------

def test_critical_misalignment_is_the_same_at_any_accepted_tolerance(spec):
    # a NaN tolerance stopped the bisection at once (3.0 instead of 4.28)
    coarse = gc.critical_misalignment_deg(spec, tolerance_deg=0.1)
    fine = gc.critical_misalignment_deg(spec, tolerance_deg=1e-3)
    assert abs(coarse - fine) <= 0.1 and 4.2 < fine < 4.35


@pytest.mark.parametrize("model", ["linear", "compliance", "surface"])
@pytest.mark.parametrize("torque", [1e-9, -1e-9, 1e9, -1e9, 0.0])
def test_the_torque_range_ends_give_finite_loads_with_the_sign_kept(torque, model, sw):
    res = gc.load_from_sweep(sw, torque_Nm=torque, model=model)
    assert np.all(np.isfinite(res.windup_rad)) and np.all(np.isfinite(res.normal_force_N))
    carried = np.sum(res.tangential_force_N, axis=0) * sw.pitch_radius_mm * 1e-3
    if torque:
        assert np.allclose(carried, abs(torque), rtol=1e-6)
        assert np.all(np.sign(res.windup_rad) == np.sign(torque))
    else:
        assert np.all(carried == 0)


def test_loads_are_continuous_at_the_bottom_of_the_torque_range(sw):
    at_zero = gc.load_from_sweep(sw, torque_Nm=0.0, model="compliance")
    tiny = gc.load_from_sweep(sw, torque_Nm=1e-9, model="compliance")
    assert np.allclose(tiny.windup_rad, at_zero.windup_rad, rtol=1e-6)
    assert np.max(tiny.normal_force_N) < 1e-6


def test_one_torque_range_everywhere(spec, tmp_path):
    from gearcoupling.arguments import TORQUE_RANGE_NM

    lo, hi = TORQUE_RANGE_NM
    for bad in (hi * 1.001, lo / 2):
        for call in (lambda t: gc.load(spec, 0.5, [0], torque_Nm=t),
                     lambda t: gc.body_windup_rad(spec, t),
                     lambda t: gc.ReportSettings(torque_Nm=t),
                     lambda t: gc.load_spec(M2, **{"load.torque_Nm": t})):
            with pytest.raises((A, S), match="1e-09 to 1e\\+09"):
                call(bad)
    assert math.isfinite(gc.body_windup_rad(spec, hi)["body_rad"])


def test_the_load_studies_take_zero_torque(spec, tmp_path):
    # the three curves (T/2, T, 2T) had one label at 0 N·m and the plots failed
    from gearcoupling.outputs import load_studies

    paths = load_studies(spec, 0.0, "linear", tmp_path)
    assert {p.name for p in paths} >= {"load_max_vs_misalignment.png",
                                        "load_moment_vs_misalignment.png"}
