"""Study files (TOML): a base spec, the parameters to vary, the outputs wanted.

A study file::

    [study]
    name = "crown-vs-angle"
    base = "renzo-1967"            # template name, or a spec path relative to this file
    method = "grid"                # grid | random | lhs
    samples = 20                   # random and lhs only
    seed = 1                       # random and lhs only
    chunk = 4                      # samples per dask task
    outputs = ["critical_misalignment_deg", "min_backlash_mm"]

    [set]                          # fixed overrides of the base spec (file units)
    "sleeve.tip_chamfer" = 0.02

    [conditions]                   # operating conditions when not varied
    misalignment_deg = 1.0         # default: the spec's design angle
    torque_Nm = 500.0              # default: the spec's [load] torque
    load_model = "linear"          # default: the spec's [load] model

    [accuracy]                     # knobs of the evaluations (defaults shown in ACCURACY)
    tolerance_mm = 1e-7

    [[vary]]
    key = "hub.crowning.radius"    # any spec key (dotted, file units) or a condition
    range = [1.5, 5.0]             # with steps (grid) or sampled (random, lhs)
    steps = 8
    [[vary]]
    key = "tooth.pressure_angle_deg"
    values = [20, 25]              # explicit values

    [[plot]]
    x = "hub.crowning.radius"
    y = "critical_misalignment_deg"
    group = ["tooth.pressure_angle_deg"]

Errors name the file, the line and the key (:class:`~gearcoupling.errors.SpecError`).
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..arguments import (
    ANGLE_TOLERANCE_RANGE_DEG,
    GAP_TOLERANCE_MM,
    MAXIMA,
    count,
    real,
    sweep_tolerance_mm,
    torque_Nm,
)
from ..errors import SpecError
from ..io import (
    Table,
    array_lengths,
    as_path,
    bundled_names,
    line_of,
    parse_toml,
    read_toml,
    resolve_bundled,
    set_dotted,
)
from ..loading import model_names
from ..spec import (
    MISALIGNMENT_RANGE_DEG,
    UNIT_SIBLINGS,
    CouplingSpec,
    check_misalignment_deg,
    resolve_spec_path,
    spec_from_dict,
)
from .tolerance import PATHS, Tolerances, capacity_models

METHODS = ("grid", "random", "lhs")
CONDITIONS = ("misalignment_deg", "torque_Nm")
SPEC_OUTPUTS = ("critical_misalignment_deg", "binding_angle_deg")
ANGLE_OUTPUTS = ("min_backlash_mm", "contact_z_min_mm", "contact_z_max_mm")
LOAD_OUTPUTS = ("max_tooth_load_N", "q", "capacity_Nm")
#: the wear life (``gc.wear``'s ``life_h``) at the study's angle and torque, the speed and
#: hours of the spec's ``[wear]`` (the base spec's, ``[set]`` or ``[[vary]]``)
WEAR_OUTPUTS = ("wear_life_h",)
OUTPUTS = SPEC_OUTPUTS + ANGLE_OUTPUTS + LOAD_OUTPUTS + WEAR_OUTPUTS
#: a tolerance Monte Carlo's outputs without the wear life (what it gives by default)
TOLERANCE_DEFAULT = ("backlash_mm", "teeth_in_contact_min", "teeth_in_contact_mean",
                     "max_tooth_load_N", "capacity_Nm", "nominal_capacity_Nm", "K")
TOLERANCE_OUTPUTS = TOLERANCE_DEFAULT + WEAR_OUTPUTS
TOLERANCE_KEYS = ("index_sd_mm", "pitch_sd_mm", "hub_runout_mm", "sleeve_runout_mm",
                  "thickness_sd_mm", "crown_sd_mm")
LIMIT_KEYS = ("index_mm", "pitch_mm", "thickness_mm", "crown_mm")
ACCURACY = {"tolerance_mm": GAP_TOLERANCE_MM, "angle_tolerance_deg": 1e-4, "steps": 16,
            "load_angles": 72}
#: the wear history's knobs (``gc.wear``'s defaults), in ``[accuracy]`` only where given
WEAR_ACCURACY = {"wear_face_cells": 24, "wear_depth_cells": 16, "wear_phases": 2}
MAX_SAMPLES = MAXIMA["samples"]
#: of a crown optimisation: the mean or min capacity over the angles, or the wear life at
#: the largest angle
OBJECTIVES = ("mean", "min", "wear_life_h")


@dataclass(frozen=True)
class Parameter:
    """One varied input: explicit ``values`` or a ``range`` (with ``steps`` on a grid)."""

    key: str
    line: int
    values: tuple[Any, ...] = ()
    low: float | None = None
    high: float | None = None
    steps: int | None = None
    integer: bool = False

    def count(self) -> int:
        """How many grid values :meth:`grid` gives (without making them)."""
        return len(self.values) if self.values else (self.steps or 1)

    def grid(self) -> tuple[Any, ...]:
        """The grid values: ``values`` or ``steps`` evenly spaced over the range."""
        if self.values:
            return self.values
        n = self.steps or 1
        low, high = self.bounds()
        pts = [low + (high - low) * k / max(n - 1, 1) for k in range(n)]
        return tuple(round(p) if self.integer else p for p in pts)

    def at(self, u: float) -> Any:
        """The value at unit coordinate ``u`` in [0, 1) (random and Latin-hypercube)."""
        if self.values:
            return self.values[min(int(u * len(self.values)), len(self.values) - 1)]
        low, high = self.bounds()
        value = low + (high - low) * u
        return round(value) if self.integer else value

    def bounds(self) -> tuple[float, float]:
        """``(low, high)`` of a parameter given by a range."""
        if self.low is None or self.high is None:
            raise SpecError(f"line {self.line} vary '{self.key}'", None,
                            "needs values or a range [low, high]")
        return self.low, self.high


@dataclass(frozen=True)
class Study:
    """A parsed, validated study file (see the module docstring)."""

    name: str
    source: str
    base_name: str
    base_text: str
    fixed: dict[str, Any]
    parameters: tuple[Parameter, ...]
    method: str
    samples: int
    seed: int
    chunk: int
    outputs: tuple[str, ...]
    conditions: dict[str, Any]
    accuracy: dict[str, float]
    plots: tuple[dict[str, Any], ...] = field(default=())
    tolerances: dict[str, Any] | None = None  # Monte Carlo: Tolerances fields, path, draws
    optimise: dict[str, Any] | None = None  # crown optimisation options (see .optimise)

    def payload(self) -> dict[str, Any]:
        """Plain data a dask worker needs to evaluate samples (no file access)."""
        return {"base_name": self.base_name, "base_text": self.base_text, "fixed": self.fixed,
                "outputs": list(self.outputs), "conditions": self.conditions,
                "accuracy": self.accuracy, "tolerances": self.tolerances, "seed": self.seed}

    def digest(self) -> str:
        """Hash of everything that determines the rows (resuming refuses another study)."""
        data = {**self.payload(), "parameters": [p.__dict__ | {"line": 0}
                                                 for p in self.parameters],
                "method": self.method, "samples": self.samples, "seed": self.seed,
                "chunk": self.chunk}
        return hashlib.sha256(json.dumps(data, sort_keys=True, default=str).encode()
                              ).hexdigest()[:16]


def build_spec(base_name: str, base_text: str, overrides: dict[str, Any]):
    """The base spec (TOML text) with dotted overrides in the file's units."""
    data = parse_toml(base_text, base_name)
    for key, value in overrides.items():
        set_dotted(data, key, value, UNIT_SIBLINGS)
    return spec_from_dict(data, name=base_name)


def _parameter(entry: Any, index: int, text: str, path: str) -> Parameter:
    starts = [n for n, s in enumerate(text.splitlines(), 1) if s.strip() == "[[vary]]"]
    line = starts[index] if index < len(starts) else 0
    r = Table(entry, f"vary[{index}]", source=path, text=text, line=line)
    key = r.get("key", str, required=True)
    line = line_of(text, f'"{key}"', line)
    r.line = line
    values = r.get("values", list)
    rng = r.get("range", list)
    steps = r.get("steps", int)
    r.done()
    where = f"vary '{key}'"
    if (values is None) == (rng is None):
        r.fail(where, None, "give exactly one of values = [...] or range = [low, high]", line)
    if values is not None:
        if not values:
            r.fail(where, values, "values must not be empty", line)
        return Parameter(key, line, values=tuple(values))
    ok = (len(rng) == 2 and all(isinstance(v, int | float) and not isinstance(v, bool)
                                and math.isfinite(v) for v in rng))
    if not ok:
        r.fail(where, rng, "range must be [low, high], two finite numbers", line)
    if not rng[0] < rng[1]:
        r.fail(where, rng, "empty range: low must be below high", line)
    if steps is not None and not 1 <= steps <= MAX_SAMPLES:
        r.fail(where, steps, f"steps must be from 1 to {MAX_SAMPLES}", line)
    integer = all(isinstance(v, int) for v in rng)
    return Parameter(key, line, low=float(rng[0]), high=float(rng[1]), steps=steps,
                     integer=integer)


def _check_values(p: Parameter, study_path: str, base_name: str, base_text: str,
                  fixed: dict[str, Any]) -> None:
    """Every explicit value and both range ends must pass the spec's validation alone."""
    probes = list(p.values) if p.values else list(p.bounds())
    if p.integer:
        probes = [round(v) for v in probes]
    for value in probes:
        if p.key == "misalignment_deg":
            check_misalignment_deg(value, f"{study_path}:{p.line} vary '{p.key}'")
            continue
        if p.key == "torque_Nm":  # the range of every entry point
            torque_Nm(value, f"{study_path}:{p.line} vary '{p.key}'", error=SpecError)
            continue
        try:
            build_spec(base_name, base_text, {**fixed, p.key: value})
        except SpecError as err:
            raise SpecError(f"{study_path}:{p.line} vary '{p.key}'", value,
                            f"refused by the spec: {err}") from err


def load_study(path: str | Path) -> Study:
    """Parse and validate a study file (a path, or the name of a bundled study)."""
    as_path(path, "path")
    p = resolve_study_path(path)
    src = str(p)
    data, text = read_toml(p, lambda t: _check_list_lengths(t, src))
    root = Table(data, "", source=src, text=text)
    s = Table(root.get("study", dict, {}), "study", source=src, text=text,
              line=line_of(text, "[study]"))
    name = s.get("name", str, p.stem)
    base = s.get("base", str, required=True)
    method = s.get("method", str, "grid")
    if method not in METHODS:
        s.fail("study.method", method, f"must be one of {METHODS}")
    samples = s.get("samples", int, 0)
    seed = s.get("seed", int, 0)
    chunk = s.get("chunk", int, 1)
    outputs = tuple(s.get("outputs", list, ["critical_misalignment_deg"]))
    s.done()
    _check_chunk_outputs(s, chunk, outputs)
    base_path = _resolve_base(base, p.parent)
    _, base_text = read_toml(base_path)
    fixed = root.get("set", dict, {})
    conditions = _conditions(root, src, text)
    accuracy = _accuracy(root, src, text)
    params = tuple(_parameter(e, k, text, src) for k, e in enumerate(root.get("vary", list, [])))
    plots = tuple(root.get("plot", list, []))
    optimise = root.get("optimise", dict)
    tolerances = None
    if "tolerances" in root.data:
        tolerances = _tolerances(Table(root.get("tolerances", dict), "tolerances", source=src,
                                       text=text))
        outputs = tuple(o for o in outputs if o in TOLERANCE_OUTPUTS) or TOLERANCE_DEFAULT
    elif any(o in TOLERANCE_OUTPUTS and o not in OUTPUTS for o in outputs):
        s.fail("study.outputs", list(outputs), "tolerance outputs need a [tolerances] table")
    root.done()
    _check_sampling(s, params, src, method, samples, optimise)
    if optimise is None:  # before a spec is built: each value of a [[vary]] builds one
        draws = tolerances["draws"] if tolerances else 1
        n = _count(params, method, samples, draws)
        if not 1 <= n <= MAX_SAMPLES:
            raise SpecError(f"{src} samples", n, _count_text(params, method, draws))
    _check_base_and_values(params, src, text, p.stem, base_path.stem, base_text, fixed)
    study = Study(name, src, base_path.stem, base_text, fixed, params, method, samples, seed,
                  chunk, outputs, conditions, accuracy, plots, tolerances, optimise)
    _check_wear_asked(study)
    if optimise is not None:
        optimise_options(study)
        return study
    for i, plot in enumerate(plots):
        _check_plot(plot, i, study, text)
    return study


def _check_wear_asked(study: Study) -> None:
    """A study asking for the wear life (an output or the optimisation's objective) names
    its speed and hours: ``[wear] speed_rpm`` and ``hours`` of the base spec, ``[set]`` or a
    ``[[vary]]`` key; else refused naming ``study.outputs`` (or ``optimise.objective``)."""
    objective = (study.optimise or {}).get("objective")
    if "wear_life_h" not in study.outputs and objective != "wear_life_h":
        return
    base = build_spec(study.base_name, study.base_text, study.fixed)
    given = {k for k, _ in base.wear} | {q.key.removeprefix("wear.") for q in study.parameters}
    missing = [k for k in ("speed_rpm", "hours") if k not in given]
    if missing:
        where = "study.outputs" if "wear_life_h" in study.outputs else "optimise.objective"
        raise SpecError(f"{study.source} {where}", "wear_life_h", "the wear life needs "
                        f"[wear] {' and '.join(missing)} in the base spec, [set] "
                        f"(\"wear.{missing[0]}\" = ...) or a [[vary]] key")


def _check_list_lengths(text: str, src: str) -> None:
    """Refuse a ``values`` list longer than :data:`MAX_SAMPLES` from the text's commas,
    before it is parsed (a list of millions is slow to parse); only a file with more
    commas than that is scanned."""
    if text.count(",") <= MAX_SAMPLES:
        return
    for line, commas in array_lengths(text, "values"):
        if commas > MAX_SAMPLES:
            raise SpecError(f"{src}:{line} values", None, f"at most {MAX_SAMPLES} values in a "
                            "[[vary]] list", shown=f"a list of {commas} values or more")


def _count(params: tuple[Parameter, ...], method: str, samples: int, draws: int) -> int:
    """Samples a study asks for, from the lists' lengths and steps (nothing is built):
    the grid's product or ``samples``, times the draws of a tolerance study."""
    if method != "grid":
        return samples * draws
    return math.prod(q.count() for q in params) * draws


def _count_text(params: tuple[Parameter, ...], method: str, draws: int) -> str:
    """What the count is made of, and its range."""
    made = (f"a grid of {' x '.join(str(q.count()) for q in params)} values" if method == "grid"
            else f"study.samples of method '{method}'")
    times = f" times {draws} draws" if draws > 1 else ""
    return f"{made}{times}; a study may have 1 to {MAX_SAMPLES} samples"


def _check_chunk_outputs(s: Table, chunk: int, outputs: tuple[str, ...]) -> None:
    """``study.chunk`` is at least 1 and ``study.outputs`` names known outputs, at least
    one."""
    if chunk < 1:
        s.fail("study.chunk", chunk, "must be at least 1 sample per task")
    for out in outputs:
        if out not in OUTPUTS + TOLERANCE_OUTPUTS:
            s.fail("study.outputs", out, f"unknown output; allowed: {list(OUTPUTS)}, or with "
                   f"[tolerances] {list(TOLERANCE_OUTPUTS)}")
    if not outputs:
        s.fail("study.outputs", outputs, "name at least one output")


def _conditions(root: Table, src: str, text: str) -> dict[str, Any]:
    """The ``[conditions]`` table: torque and misalignment in the range of every entry point,
    and the load model."""
    cond_r = Table(root.get("conditions", dict, {}), "conditions", source=src, text=text)
    conditions: dict[str, Any] = {k: cond_r.get(k, float) for k in CONDITIONS
                                  if k in cond_r.data}
    where = f"{src}:{line_of(text, '[conditions]')} conditions"
    if "torque_Nm" in conditions:  # the range of every entry point
        torque_Nm(conditions["torque_Nm"], f"{where}.torque_Nm", error=SpecError)
    if "misalignment_deg" in conditions:
        check_misalignment_deg(conditions["misalignment_deg"], f"{where}.misalignment_deg")
    if "load_model" in cond_r.data:
        conditions["load_model"] = cond_r.get("load_model", str)
    cond_r.done()
    return conditions


def _accuracy(root: Table, src: str, text: str) -> dict[str, Any]:
    """The ``[accuracy]`` knobs (defaults :data:`ACCURACY`), each within the range the
    entry points allow."""
    acc_r = Table(root.get("accuracy", dict, {}), "accuracy", source=src, text=text)
    accuracy = {k: acc_r.get(k, type(v), v) for k, v in ACCURACY.items()}
    accuracy.update({k: acc_r.get(k, int) for k in WEAR_ACCURACY if k in acc_r.data})
    acc_r.done()
    limits = {"tolerance_mm": lambda v, f: sweep_tolerance_mm(v, f, SpecError),
              "angle_tolerance_deg": lambda v, f: real(v, f, *ANGLE_TOLERANCE_RANGE_DEG,
                                                       unit="degrees", error=SpecError),
              "steps": lambda v, f: count(v, f, 1, MAXIMA["steps"], error=SpecError),
              "load_angles": lambda v, f: count(v, f, 1, MAXIMA["angles"], error=SpecError),
              "wear_face_cells": lambda v, f: count(v, f, 4, 512, error=SpecError),
              "wear_depth_cells": lambda v, f: count(v, f, 4, 512, error=SpecError),
              "wear_phases": lambda v, f: count(v, f, 1, 64, error=SpecError)}
    for k, v in accuracy.items():
        limits[k](v, f"{src}:{line_of(text, k)} accuracy.{k}")
    return accuracy


def _check_base_and_values(params: tuple[Parameter, ...], src: str, text: str, stem: str,
                           base_name: str, base_text: str, fixed: dict[str, Any]) -> None:
    """No key is varied twice, the base spec takes the ``[set]`` overrides (read under the
    study's name ``stem``) and every varied value passes alone."""
    keys = [q.key for q in params]
    if len(set(keys)) != len(keys):
        dup = next(k for k in keys if keys.count(k) > 1)
        raise SpecError(f"{src}:{line_of(text, dup)} vary", dup, "varied twice")
    try:
        build_spec(stem, base_text, fixed)
    except SpecError as err:
        raise SpecError(f"{src}:{line_of(text, '[set]')} set", None,
                        f"the base spec with these overrides is refused: {err}") from err
    for q in params:
        _check_values(q, src, base_name, base_text, fixed)


def _check_sampling(s: Table, params: tuple[Parameter, ...], src: str, method: str,
                    samples: int, optimise: dict | None) -> None:
    """Random and LHS studies take ``samples`` and no steps; a grid range needs steps
    (unless the study optimises)."""
    if method != "grid":
        if not 1 <= samples <= MAX_SAMPLES:
            s.fail("study.samples", samples, f"method '{method}' needs samples from 1 to "
                   f"{MAX_SAMPLES}")
        for q in params:
            if q.steps is not None:
                raise SpecError(f"{src}:{q.line} vary '{q.key}'", q.steps,
                                f"steps apply to grids only, not method '{method}'")
    elif optimise is None:
        for q in params:
            if q.low is not None and q.steps is None:
                raise SpecError(f"{src}:{q.line} vary '{q.key}'", None,
                                "a range on a grid needs steps = N")


def _check_plot(plot: Any, k: int, study: Study, text: str) -> None:
    r = Table(plot, f"plot[{k}]", source=study.source, text=text)
    x = r.get("x", str, required=True)
    y = r.get("y", str, required=True)
    group = r.get("group", list, [])
    r.get("title", str)
    r.done()
    known = {q.key for q in study.parameters}
    for key in [x, *group]:
        if key not in known:
            r.fail(f"plot[{k}]", key, f"not a varied key; varied: {sorted(known)}")
    if y not in study.outputs:
        r.fail(f"plot[{k}].y", y, f"not an output of this study: {list(study.outputs)}")


def _resolve_base(base: str, folder: Path) -> Path:
    candidate = folder / base
    if candidate.suffix == ".toml" and candidate.is_file():
        return candidate
    return resolve_spec_path(base)


def study_names() -> list[str]:
    """Names of the bundled study files."""
    return bundled_names("studies")


def resolve_study_path(path: str | Path) -> Path:
    """A study file path, or the name of a bundled study."""
    return resolve_bundled("studies", path)


def _tolerances(r: Table) -> dict[str, Any]:
    """``[tolerances]``: standard deviations (``*_sd_mm``) or ISO-style limits (``*_mm``,
    divided by ``coverage``), runouts, ``path``, ``draws`` per point, ``precision`` of K."""
    coverage = r.get("coverage", float, 3.0)
    values = {k: r.get(k, float) for k in TOLERANCE_KEYS if k in r.data}
    limits = {k: r.get(k, float) for k in LIMIT_KEYS if k in r.data}
    path = r.get("path", str, "fast")
    model = r.get("model", str, "renzo")
    draws = r.get("draws", int, 100)
    precision = r.get("precision", float, 0.01)
    r.done()
    if path not in PATHS:
        r.fail("tolerances.path", path, f"one of {PATHS}")
    if model not in capacity_models():
        r.fail("tolerances.model", model, f"one of {capacity_models()}")
    if not 1 <= draws <= MAX_SAMPLES or not precision > 0:
        r.fail("tolerances.draws", (draws, precision), f"draws from 1 to {MAX_SAMPLES} and "
               "precision > 0")
    for key in limits:
        if key.replace("_mm", "_sd_mm") in values:
            r.fail(f"tolerances.{key}", limits[key], "give a limit or a standard deviation")
    try:
        tol = Tolerances.from_limits(coverage=coverage, **limits) if limits else Tolerances()
        from dataclasses import asdict, replace

        tol = replace(tol, **values)
    except SpecError as err:
        r.fail("tolerances", None, str(err))
    return {"values": asdict(tol), "path": path, "model": model, "draws": draws,
            "precision": precision}


def sample_count(study: Study) -> int:
    """Samples (rows) of the study."""
    draws = study.tolerances["draws"] if study.tolerances else 1
    return _count(study.parameters, study.method, study.samples, draws)


def samples(study: Study) -> list[dict[str, Any]]:
    """Every sample's inputs in a fixed order (seeded for random and lhs)."""
    points = _points(study)
    if not study.tolerances:
        return points
    return [{**p, "draw": d} for p in points for d in range(study.tolerances["draws"])]


def _points(study: Study) -> list[dict[str, Any]]:
    params = study.parameters
    if study.method == "grid":
        import itertools

        return [dict(zip((q.key for q in params), combo, strict=True))
                for combo in itertools.product(*(q.grid() for q in params))]
    import numpy as np

    if study.method == "lhs":
        from scipy.stats import qmc

        u = qmc.LatinHypercube(d=max(len(params), 1), seed=study.seed).random(study.samples)
    else:
        u = np.random.default_rng(study.seed).random((study.samples, max(len(params), 1)))
    return [{q.key: _plain(q.at(float(u[n, j]))) for j, q in enumerate(params)}
            for n in range(study.samples)]


def _plain(value: Any) -> Any:
    return value if not hasattr(value, "item") else value.item()


def spec_hash(spec: CouplingSpec) -> str:
    """Short SHA-256 of the resolved spec (mm, degrees), independent of its name."""
    data = spec.to_dict()
    data.pop("name", None)
    return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()[:16]


def optimise_options(study: Study) -> dict[str, Any]:
    opt = dict(study.optimise or {})
    angles = opt.get("angles_deg")
    lo, hi = MISALIGNMENT_RANGE_DEG
    if not (isinstance(angles, list) and angles
            and all(isinstance(a, int | float) and lo < a <= hi for a in angles)):
        raise SpecError(f"{study.source} optimise.angles_deg", angles,
                        f"a non-empty list of design angles in ({lo:g}, {hi:g}] degrees")
    objective = opt.get("objective", "mean")
    if objective not in OBJECTIVES:
        raise SpecError(f"{study.source} optimise.objective", objective, f"one of {OBJECTIVES}")
    budget = opt.get("max_evaluations", 40)
    if not (isinstance(budget, int) and budget >= 3):
        raise SpecError(f"{study.source} optimise.max_evaluations", budget, "an integer >= 3")
    compare = opt.get("compare", [])
    if not (isinstance(compare, list) and all(isinstance(c, str) for c in compare)):
        raise SpecError(f"{study.source} optimise.compare", compare, "a list of spec names")
    model = opt.get("model")
    if model is not None and model not in ("renzo", *model_names()):
        raise SpecError(f"{study.source} optimise.model", model,
                        f"renzo or {', '.join(model_names())} (default: the spec's)")
    unknown = set(opt) - {"angles_deg", "objective", "max_evaluations", "compare", "model"}
    if unknown:
        raise SpecError(f"{study.source} optimise", sorted(unknown)[0], "unknown key")
    return {"angles_deg": [float(a) for a in angles], "objective": objective,
            "max_evaluations": budget, "compare": compare, "model": model}
