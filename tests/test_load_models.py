"""The load-model registry: one entry per model, nothing else tests a model's name, and a
model registered only here works through the load, the capacity and the CLI."""

import ast
from pathlib import Path

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.clearance import sweep
from gearcoupling.cli import build_parser
from gearcoupling.errors import ArgumentError
from gearcoupling.loading import MODELS, LoadModel, load_from_sweep, model_names, patch_maps
from gearcoupling.loading.models.registry import ModelOutput
from gearcoupling.spec.load import LOAD_MODELS

SRC = Path(gc.__file__).parent
BUILT_IN = tuple(MODELS)  # at import: before any test registers its own
REGISTRY = SRC / "loading" / "models"  # the models and their table


def test_the_spec_accepts_exactly_the_built_in_models():
    assert BUILT_IN == LOAD_MODELS
    assert all(m.name == name and m.what for name, m in MODELS.items())
    with pytest.raises(ArgumentError, match="cost"):
        LoadModel("x", MODELS["linear"].solve, MODELS["linear"].capacity, cost="cheap",
                  rotations=1, pressure_grid=False, takes_mesh_stiffness=False, what="x")


def _name_tests(path: Path) -> list[str]:
    """Comparisons with a model name and dicts keyed by one in the module at ``path``."""
    tree = ast.parse(path.read_text())
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare):
            operands = [node.left, *node.comparators]
        elif isinstance(node, ast.Dict):
            operands = [k for k in node.keys if k is not None]
        elif isinstance(node, ast.MatchValue):
            operands = [node.value]
        else:
            continue
        for op in operands:
            consts = op.elts if isinstance(op, ast.Tuple | ast.List | ast.Set) else [op]
            found += [f"{path.relative_to(SRC)}:{node.lineno} {c.value!r}" for c in consts
                      if isinstance(c, ast.Constant) and c.value in BUILT_IN]
    return found


def test_no_module_outside_the_registry_tests_a_model_name():
    """Branches on a model's name live in its :class:`LoadModel` (cost, pressure grid,
    capacity search, ...); the accuracy ladder's measured figures are data keyed by name."""
    allowed = {SRC / "loading" / "accuracy.py"}
    wrong = [hit for path in sorted(SRC.rglob("*.py"))
             if REGISTRY not in path.parents and path not in allowed
             for hit in _name_tests(path)]
    assert not wrong, wrong
    users = [str(p.relative_to(SRC)) for p in sorted(SRC.rglob("*.py"))
             for node in ast.walk(ast.parse(p.read_text()))
             if isinstance(node, ast.ImportFrom) and "LOAD_MODELS" in (a.name for a in node.names)]
    assert not users, users  # the spec's own check only: everything else asks the registry


def _uniform(problem, progress=None):
    """A toy model: the teeth that touch share the torque equally (tangential load
    ``T / (n R)`` on each of the ``n``), the wind-up is the first touch."""
    g = problem.gap_rad
    touch = np.isfinite(g)
    n = np.sum(touch, axis=0)
    P = np.where(touch, problem.torque_Nmm / (n * problem.spec.tooth.pitch_radius), 0.0)
    return ModelOutput.from_solver(problem, {
        "windup_rad": np.min(g, axis=0), "mesh_stiffness_Nm_per_rad": np.ones(g.shape[1]),
        "tangential_force_N": P, "normal_force_N": P})


def _fixed(problem, limits):
    """The toy's capacity search: every criterion at 1 kN·m."""
    return {name: 1000.0 for name in limits}, ()


@pytest.fixture
def toy(monkeypatch):
    model = LoadModel("uniform", _uniform, _fixed, cost="fast", rotations=3,
                      pressure_grid=False, takes_mesh_stiffness=False,
                      what="equal shares on the touching teeth (a test model)")
    monkeypatch.setitem(MODELS, model.name, model)
    return model


def test_a_model_registered_in_one_place_loads_searches_and_is_a_cli_choice(toy):
    spec = gc.load_spec("renzo-1967")
    sw = sweep(spec, 1.0, [0.0, 2.0])
    res = load_from_sweep(sw, torque_Nm=500.0, model="uniform")
    n = np.sum(np.isfinite(res.gap_angle_rad), axis=0)
    R = spec.tooth.pitch_radius
    assert res.model == "uniform"
    np.testing.assert_allclose(res.tangential_force_N.sum(axis=0) * R, 500e3, rtol=1e-12)
    np.testing.assert_allclose(res.tangential_force_N.max(axis=0), 500e3 / (n * R),
                               rtol=1e-12)
    assert len(patch_maps(res, 0, count=2)) == 2  # the analytic maps of its contact laws

    cap = gc.capacity(spec, 1.0, model="uniform")
    K = spec.load.accuracy_factor
    assert cap.model == "uniform" and cap.capacity_Nm == pytest.approx(1000.0 * K)
    # q at the governing torque from the toy's own load solve: T = q N P_max R
    at = load_from_sweep(sweep(spec, 1.0, cap_angles(spec)), torque_Nm=1.0, model="uniform")
    n_min = np.min(np.sum(np.isfinite(at.gap_angle_rad), axis=0))
    assert cap.q == pytest.approx(n_min / spec.tooth.teeth, rel=1e-9)

    assert "uniform" in model_names()
    args = build_parser().parse_args(["load", "renzo-1967", "--model", "uniform"])
    assert args.model == "uniform"


def cap_angles(spec):
    """The rotations a capacity search of the toy takes by default (its ``rotations``)."""
    return np.linspace(0.0, 360.0 / spec.tooth.teeth, MODELS["uniform"].rotations,
                       endpoint=False)


def test_an_unknown_model_is_refused_with_the_registered_names(toy):
    with pytest.raises(ArgumentError, match="'uniform'"):
        gc.load("renzo-1967", 1.0, [0.0], torque_Nm=1.0, model="bogus")
