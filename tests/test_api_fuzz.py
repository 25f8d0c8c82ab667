"""A seeded fuzz of every public function of ``gearcoupling``: arguments drawn from valid
and hostile values (wrong kinds, NaN, infinities, huge and tiny numbers, empty and huge
lists, template names, devices as paths). A call either returns a result without NaN or
raises an error of the project's hierarchy (``gc.GearCouplingError``), within 10 s.

Each draw makes up to two arguments hostile; costly functions (meshes, FE, reports,
studies, servers) get at least one hostile argument in every draw: they must refuse it
before the costly work starts, which the 10 s bound checks (a hostile value that is in
fact allowed, such as None for a default, must then finish within it too). Derandomized
(the same draws on every run), 15 examples per function: about 20 s in all.
"""

from __future__ import annotations

import dataclasses
import math
import os
import signal
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import gearcoupling as gc

pytestmark = pytest.mark.slow

M2 = "industrial-m2"
LIMIT_S = 10.0
NAN, INF = float("nan"), float("inf")


class Hang(BaseException):
    """A call still running well past the limit (raised by SIGALRM)."""


# ------------------------------------------------------- values of each kind of argument
# (valid, surely invalid); a spec is a template name or the loaded spec (SPEC below)
SPEC = object()  # stands for the loaded industrial-m2 spec
OUT = object()  # stands for a fresh path in the test's folder
KINDS = {
    "spec": ([M2, SPEC], [None, 42, b"industrial-m2", "no-such-template", [], {}, 1.5, ""]),
    "mis": ([0.0, 0.5, 1, np.float64(2.0)],
            [NAN, INF, -1.0, 6.5, "1", None, True, [1.0], 1e300]),
    "angles": ([[0.0], [0.0, 4.5], np.array([1.0]), range(0, 10, 5)],
               [[], "0,1", ["a"], [NAN], None, [[1.0, 2.0]], {}, range(10**7), [True]]),
    "torque": ([100.0, -100.0, 0.0, 1e-9, -1e9],
               [NAN, INF, 1e30, 1e-300, -5e-324, "100", True, [1.0], 1.7e308]),
    "tol_mm": ([1e-7, 1e-5], [0.0, -1.0, NAN, INF, "1e-7", 1e-300, [1e-7], True]),
    "tol_deg": ([0.1, 0.05], [0.0, -1.0, NAN, INF, 1e-300, "0.1", None, True]),
    "count": ([2, 4, np.int64(3)], [0, -1, 2.5, 10**9, "3", True, None, [3], NAN]),
    "model": ([None, "linear", "compliance"], ["bogus", 1, ["linear"], b"linear", ""]),
    "flank": (["ccw", "cw"], ["up", 1, None, ["cw"]]),
    "part": (["hub", "sleeve"], ["wheel", None, 0, ["hub"], ""]),
    "flag": ([True, False], ["no", 2, None, [True]]),
    "file": ([OUT], [None, "", os.devnull, 42, b"x.html"]),
    "folder": ([OUT], [None, "", os.devnull, 42, b"out"]),
    "length": ([16.0, 38.0], [NAN, INF, -1.0, 0.0, "16", None]),
    "real": ([0.0, 1.0, -3.0], [NAN, INF, "1", None, [1.0], 1e300]),
    "array": ([0.0, [0.0, 1.0], np.array([0.1, 0.2])], ["x", [NAN], None, {}, [[1], [2, 3]]]),
}

# function -> (costly?, {parameter: kind}); keyword parameters after the positional ones
FUNCTIONS = {
    "sweep": (False, {"spec": "spec", "misalignment_deg": "mis", "angles_deg": "angles",
                      "tolerance_mm": "tol_mm", "grid": "count", "periodic": "flag"}),
    "load": (False, {"spec": "spec", "misalignment_deg": "mis", "angles_deg": "angles",
                     "torque_Nm": "torque", "model": "model"}),
    "load_from_sweep": (False, {"sweep_result": "sweep", "torque_Nm": "torque",
                                "model": "model"}),
    "capacity": (False, {"spec": "spec", "misalignment_deg": "mis_range", "model": "model",
                         "loaded_flank": "flank", "angles_deg": "angles"}),
    "capacity_curve": (True, {"spec": "spec", "misalignments_deg": "angles",
                              "model": "model", "angles_deg": "angles"}),
    "compare_capacity": (True, {"specs": "specs", "misalignments_deg": "angles",
                                "model": "model", "count": "count"}),
    "body_windup_rad": (False, {"spec": "spec", "torque_Nm": "torque"}),
    "coupling_data": (True, {"spec": "spec", "misalignment_deg": "mis", "torque_Nm": "torque"}),
    "critical_misalignment_deg": (False, {"spec": "spec", "tolerance_deg": "tol_deg"}),
    "binding_angle_deg": (True, {"spec": "spec", "tolerance_deg": "tol_deg",
                                 "steps": "count"}),
    "design_quantities": (True, {"spec": "spec", "misalignment_deg": "mis",
                                 "tolerance_deg": "tol_deg"}),
    "min_backlash_rad": (False, {"spec": "spec", "misalignment_deg": "mis",
                                 "steps": "count", "tolerance_mm": "tol_mm"}),
    "contact_travel": (False, {"spec": "spec", "misalignment_deg": "mis",
                               "tolerance_mm": "tol_mm"}),
    "double_engagement": (False, {"spec": "spec", "offset_mm": "real", "angle_deg": "real",
                                  "span_mm": "length", "angles_deg": "angles"}),
    "transverse_section": (False, {"spec": "spec", "part": "part", "z_mm": "real",
                                   "tolerance_mm": "chordal"}),
    "hub_flank": (False, {"spec": "spec", "flank": "flank", "z_mm": "array",
                          "r_mm": "radius"}),
    "sleeve_flank": (False, {"spec": "spec", "flank": "flank", "z_mm": "array",
                             "r_mm": "radius"}),
    "inv": (False, {"a": "array"}),
    "inv_inverse": (False, {"y": "array"}),
    "feed_path": (False, {"crowning": "crowning", "pitch_radius": "length",
                          "face_width": "length"}),
    "measuring_charts": (False, {"spec": "spec", "points": "points"}),
    "hob_program": (False, {"spec": "spec", "hob_diameter_mm": "hob",
                            "table_points": "points"}),
    "pose_state": (False, {"spec": "spec", "misalignment_deg": "mis", "psi_deg": "real",
                           "band_mm": "real"}),
    "build_part": (True, {"spec": "spec", "part": "part", "tolerance_mm": "tol_mm"}),
    "export_part": (True, {"spec": "spec", "part": "part", "path": "file"}),
    "check_interference": (True, {"spec": "spec", "misalignment_deg": "mis",
                                  "angles_deg": "angles", "hub_rotation_deg": "real"}),
    "check_part": (True, {"mesh": "mesh"}),
    "compare_part": (True, {"spec": "spec", "source": "array", "units": "units"}),
    "write_html": (True, {"spec": "spec", "path": "file", "tolerance_mm": "tol_mm"}),
    "serve": (True, {"spec": "spec", "port": "count", "lod": "part"}),
    "report": (True, {"spec": "spec", "out": "folder", "torque_Nm": "torque",
                      "angles": "count"}),
    "run": (True, {"spec": "spec", "out": "folder", "only": "model", "workers": "count"}),
    "run_study": (True, {"study": "study", "out": "folder", "workers": "count"}),
    "load_study": (True, {"path": "spec"}),
    "load_spec": (False, {"name_or_path": "spec"}),
    "spec_from_dict": (False, {"data": "dict", "name": "part"}),
    "template_names": (False, {}),
    "fe_contact": (True, {"spec": "spec", "torque_Nm": "torque", "size_mm": "length"}),
    "fe_contact_sector": (True, {"spec": "spec", "misalignment_deg": "mis",
                                 "rotation_deg": "real", "windup_rad": "real",
                                 "sector": "count"}),
    "sector_check": (True, {"spec": "spec", "misalignment_deg": "mis", "torque_Nm": "torque",
                            "sector": "count"}),
    "mesh_part": (True, {"spec": "spec", "part": "part", "sector": "count",
                         "size_mm": "length"}),
    "write_mesh": (True, {"vm": "mesh", "path": "file", "fmt": "part"}),
    "tooth_compliance_table": (True, {"spec": "spec", "nz": "count", "nr": "count",
                                      "sector": "count"}),
    "coupling_geometry": (False, {"spec": "spec", "layout": "layout",
                                  "alignment": "alignment"}),
    "coupling_assembly": (False, {"spec": "spec", "layout": "layout",
                                  "alignment": "alignment", "psi_deg": "real"}),
    "whole_loads": (True, {"spec": "spec", "layout": "layout", "alignment": "alignment",
                           "torque_Nm": "torque", "angles_deg": "turn", "model": "model"}),
    "whole_capacity": (True, {"spec": "spec", "layout": "layout", "alignment": "alignment",
                              "model": "model", "loaded_flank": "flank"}),
    "allowable_offset": (True, {"spec": "spec", "layout": "layout", "alignment": "alignment",
                                "torque_Nm": "torque", "model": "model"}),
    "whole_coupling_data": (True, {"spec": "spec", "layout": "layout",
                                   "alignment": "alignment", "torque_Nm": "torque",
                                   "model": "model"}),
    "spec_geometry": (False, {"spec": "double", "changes": "changes", "names": "names"}),
    "assembly_pose": (False, {"spec": "double", "psi_deg": "real", "changes": "changes",
                              "band_mm": "length", "pressure": "flag"}),
    "wear": (True, {"spec": "spec", "misalignment_deg": "wear_mis", "torque_Nm": "torque",
                    "speed_rpm": "speed", "hours": "hours"}),
}
# the whole supported range, past industrial-m2's critical misalignment (4.28°) too, where
# every patch lies at a face end (issue 38: the default capacity raised there)
KINDS["mis_range"] = ([6.0, 4.5, 0.5, 0.0], KINDS["mis"][1])
# kinds whose valid values need the fixture objects
KINDS["sweep"] = (["SWEEP"], [None, 42, "industrial-m2", {}])
KINDS["specs"] = ([[M2], [SPEC]], [None, [], M2, [SPEC, SPEC], [None], 42])
KINDS["crowning"] = (["CROWNING"], [None, 42, "circular", {}])
KINDS["mesh"] = ([], [None, 42, "hub", {}, [1, 2, 3]])  # building a mesh is costly
KINDS["study"] = ([], [None, 42, "renzo-tolerances", {}])  # running a study is costly
KINDS["radius"] = ([38.0, [37.5, 38.5]], [NAN, "38", None, [[1], [2, 3]], 1e300])
KINDS["chordal"] = ([0.01, 0.002], [0.0, -1.0, NAN, 1e-300, "0.01", None])
KINDS["points"] = ([5, 11, 101], [0, 4, 10**9, 2.5, "11", None, True])
KINDS["hob"] = ([60.0, 80], [NAN, 0.0, 1e9, "60", None, 5.0])
KINDS["units"] = (["mm", "in"], ["cm", None, 1, ""])
# wear: None is the design angle there, so it is not among the bad angles
KINDS["wear_mis"] = ([0.5, 1.0], [v for v in KINDS["mis"][1] if v is not None])
KINDS["speed"] = ([1800.0, 60], [NAN, INF, 0.0, -1.0, "1800", None, 1e300])
KINDS["hours"] = ([10.0, 0.5], [NAN, INF, 0.0, -5.0, "10", 1e300, [1.0]])
# the whole coupling: None is a default where it is allowed, so it is not among the bad
KINDS["layout"] = (["LAYOUT"], [None, 42, "one-piece", {}, 300.0])
KINDS["alignment"] = (["ALIGNMENT"], [42, {}, "0.4", [0.4], 0.4])
KINDS["turn"] = (KINDS["angles"][0], [v for v in KINDS["angles"][1] if v is not None])
# a double-engagement spec (its [coupling] and [alignment]) and changes of its alignment
KINDS["double"] = (["close-coupled"], [None, 42, M2, SPEC, "no-such-template", [], ""])
KINDS["changes"] = ([None, {}, {"offset_mm": 0.2}, {"angle_deg": 0.5, "angle_azimuth_deg": 10}],
                    [{"offset_mm": NAN}, {"offset_mm": 1e3}, {"bogus": 1.0}, "offset", [0.2],
                     {"angle_deg": INF}, {"offset_mm": "0.2"}])
KINDS["names"] = ([None, {"offset_mm": "--offset"}], [42, "offset", {"offset_mm": 1}, [1]])
KINDS["dict"] = ([{}, {"tooth": {"teeth": 38, "module": 2.0}, "hub": {"face_width": 16.0}}],
                 [None, [1], "x", {"tooth": 5}, {"tooth": {"teeth": NAN}}])

# the public functions the fuzz covers: every one (classes are built by them)
PUBLIC = sorted(n for n in gc.__all__ if callable(getattr(gc, n))
                and not isinstance(getattr(gc, n), type))


def test_the_fuzz_covers_every_public_function():
    assert sorted(FUNCTIONS) == PUBLIC


@pytest.fixture(scope="module")
def objects():
    spec = gc.load_spec(M2)
    return {"SPEC": spec, "SWEEP": gc.sweep(spec, 0.5, [0.0]), "CROWNING": spec.hub.crowning,
            "LAYOUT": gc.CouplingLayout(span_mm=300.0), "ALIGNMENT": gc.ShaftAlignment(0.4)}


def _draws(name: str):
    """Keyword arguments for ``name``: each parameter valid or invalid; a costly
    function gets at least one invalid one."""
    costly, params = FUNCTIONS[name]

    @st.composite
    def arguments(draw):
        names = sorted(params)
        k = draw(st.integers(1 if costly else 0, min(2, len(names)))) if names else 0
        invalid = set(draw(st.lists(st.sampled_from(names), min_size=k, max_size=k,
                                    unique=True))) if k else set()
        out = {}
        for p, kind in params.items():
            valid, bad = KINDS[kind]
            out[p] = draw(st.sampled_from(bad if (p in invalid or not valid) else valid))
        return out

    return arguments()


def _resolve(value, objects, tmp_path, n=[0]):  # noqa: B006 - a counter for fresh paths
    if value is SPEC:
        return objects["SPEC"]
    if value is OUT:
        n[0] += 1
        return tmp_path / f"out-{n[0]}.html"
    if isinstance(value, str) and value in objects:
        return objects[value]
    if isinstance(value, list):
        return [_resolve(v, objects, tmp_path) for v in value]
    return value


def _nan_in(value, depth: int = 0) -> bool:
    """Whether a result holds NaN anywhere (arrays, numbers, dataclass fields, dicts,
    sequences), a few levels deep."""
    if depth > 4:
        return False
    if isinstance(value, float | np.floating):
        return math.isnan(value)
    if isinstance(value, np.ndarray):
        return value.dtype.kind == "f" and bool(np.isnan(value).any())
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return any(_nan_in(getattr(value, f.name), depth + 1)
                   for f in dataclasses.fields(value) if f.name != "spec")
    if isinstance(value, dict):
        return any(_nan_in(v, depth + 1) for v in value.values())
    if isinstance(value, list | tuple):
        return any(_nan_in(v, depth + 1) for v in value[:1000])
    return False


def _call(name: str, kwargs: dict):
    def stop(*_):
        raise Hang(f"{name}({kwargs}) still running after {3 * LIMIT_S:g} s")

    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(int(3 * LIMIT_S))
    t0 = time.perf_counter()
    try:
        try:
            result = getattr(gc, name)(**kwargs)
        except gc.GearCouplingError:
            result = None
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    elapsed = time.perf_counter() - t0
    assert elapsed < LIMIT_S, f"{name}({kwargs}) took {elapsed:.1f} s"
    if name == "serve" and result is not None:  # pragma: no cover - a valid draw
        result.stop()
    assert not _nan_in(result), f"{name}({kwargs}) returned NaN"


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_public_function_takes_hostile_arguments(name, objects, tmp_path):
    @settings(max_examples=15, derandomize=True, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(_draws(name))
    def check(kwargs):
        _call(name, {k: _resolve(v, objects, tmp_path) for k, v in kwargs.items()})

    check()
