"""``gc.coupling_data``: the API 671 data of a coupling for a rotor model, in one result.

Mass properties of hub, sleeve and coupling; torsional stiffness (secant, tangent and the
wind-up curve to the capacity); the 6 x 6 stiffness matrix at the operating point; the
allowable misalignment and the loads the coupling puts on the shafts there; and beside
every entry the model and springs that made it and their measured error.
docs/rotordynamics.md.
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..clearance import sweep
from ..errors import ArgumentError
from ..forked import ForkedMap, default_workers
from ..io import write_csv_rows, write_json
from ..loading import (
    Capacity,
    capacity,
    resolve_model,
    resolve_torque_Nm,
    springs_name,
    tooth_load_error,
    windup_error,
)
from ..spec import CouplingSpec, as_spec, check_misalignment_deg
from ..tables import dataframe
from .allowable import AllowableLoads, allowable_loads, known_capacities
from .mass import MassProperties, mass_properties
from .ross import coupling_element
from .stiffness import (
    DISPLACEMENT_UNITS,
    DOFS,
    FORCE_UNITS,
    StiffnessMatrix,
    default_rotations,
    pitch_rotations,
    stiffness_from_sweep,
)
from .torsion import (
    DEFAULT_POINTS,
    TorsionalStiffness,
    mesh_windup_from_touch,
    torsion_from_curve,
    windup_torques,
)

DATASHEET_COLUMNS = ("section", "quantity", "value", "unit", "source")
FILES = ("datasheet.json", "datasheet.csv", "stiffness_matrix.csv")
UNITS = {"N": "N", "Nm": "N·m"}

#: what the data describe and what they leave out
NOT_MODELLED = (
    "the shafts, keys, bolts, flanges and spacer: the hub and sleeve are as the spec "
    "describes them (hub body from bore to teeth over its length, sleeve from its teeth to "
    "its outside diameter over its face width)",
    "the second half of a double-engagement coupling: these data are one engagement "
    "(one hub in one sleeve); a double-engagement coupling has two in series",
    "bending of the hub and sleeve bodies (rigid in tilt and translation; their torsion "
    "is in the torsion entries)",
    "the teeth's stick stiffness along the axis below the slip force",
    "damping (none is computed)",
)

MASS_ACCURACY = ("closed part meshes within the chordal tolerance of the exact surfaces: "
                 "volume and inertia within 0.03 % of the STEP solid's OpenCASCADE "
                 "integration on the templates (docs/rotordynamics.md)")


@dataclass(frozen=True, eq=False)
class CouplingData:
    """The data sheet of one coupling at one operating point (module docstring).

    Attributes
    ----------
    spec : CouplingSpec
    misalignment_deg, torque_Nm : float
        The operating point (torque signed: the sign picks the loaded flank).
    model, springs : str
        Load model and tooth springs of every loaded entry.
    mass : dict of str -> MassProperties
        ``hub``, ``sleeve``, ``coupling``.
    torsion : TorsionalStiffness
    stiffness : StiffnessMatrix
    capacity_Nm : float or None
        At the operating misalignment (``None``: no criterion limits it).
    allowable : AllowableLoads
    seconds : float
        Wall time from the start of :func:`coupling_data` to its result (in the report the
        sections built meanwhile count).
    """

    spec: CouplingSpec = field(repr=False)
    misalignment_deg: float
    torque_Nm: float
    model: str
    springs: str
    mass: dict[str, MassProperties]
    torsion: TorsionalStiffness
    stiffness: StiffnessMatrix
    capacity_Nm: float | None
    allowable: AllowableLoads
    seconds: float = 0.0

    def accuracy(self) -> dict[str, str]:
        """Per section: the model, springs and measured error behind its entries."""
        wu = windup_error(self.model, self.springs)
        st = self.stiffness.steps
        return {
            "mass": MASS_ACCURACY,
            "torsion": wu + "; bodies: closed-form annulus torsion",
            "stiffness": (f"{wu}; {st['differences']} differences, step "
                          f"{st['relative_step']:g} of the "
                          f"largest tooth deflection (translation {st['translation_mm']:.3g} "
                          f"mm, tilt {st['tilt_rad']:.3g} rad), mean of {st['rotations']} "
                          "rotations over one pitch (their spread is listed)"),
            "allowable": tooth_load_error(self.model, self.springs),
        }

    @property
    def not_modelled(self) -> tuple[str, ...]:
        return NOT_MODELLED

    def as_dict(self) -> dict[str, Any]:
        """``datasheet.json``: plain data, units in the keys."""
        return {"spec": self.spec.name, "misalignment_deg": self.misalignment_deg,
                "torque_Nm": self.torque_Nm, "model": self.model, "springs": self.springs,
                "friction": self.spec.load.friction,
                "density_kg_per_m3": {p: getattr(self.spec.material, p).density_kg_per_m3
                                      for p in ("hub", "sleeve")},
                "mass": {k: v.as_dict() for k, v in self.mass.items()},
                "torsion": self.torsion.as_dict(), "stiffness": self.stiffness.as_dict(),
                "capacity_Nm": self.capacity_Nm, "allowable": self.allowable.as_dict(),
                "allowable_over_turn": [dict(zip(("psi_deg", *self.allowable.loads()), r,
                                                 strict=True))
                                        for r in self.allowable.rows()],
                "accuracy": self.accuracy(), "not_modelled": list(self.not_modelled),
                "seconds": self.seconds}

    def rows(self) -> list[tuple[str, str, float | None, str, str]]:
        """``datasheet.csv``: ``(section, quantity, value, unit, source)`` in the order of an
        API 671 coupling data sheet; values are numbers (or None), words go to source."""
        acc = self.accuracy()
        return [("operating point", "misalignment", self.misalignment_deg, "deg", ""),
                ("operating point", "torque", self.torque_Nm, "N·m",
                 f"{self.model} model, {self.springs} springs, friction "
                 f"{self.spec.load.friction:g}"),
                *_mass_rows(self.mass, acc["mass"]),
                *_torsion_rows(self, acc["torsion"]),
                *_stiffness_rows(self.stiffness, acc["stiffness"]),
                *_allowable_rows(self.allowable, acc["allowable"])]

    def to_dataframe(self):
        """:meth:`rows` as a pandas DataFrame with the columns of ``datasheet.csv``
        (:data:`DATASHEET_COLUMNS`; the ``pandas`` extra)."""
        return dataframe(DATASHEET_COLUMNS, self.rows())

    def matrix_rows(self):
        """``stiffness_matrix.csv`` rows: the row's coordinate and force unit, then the
        matrix row (hub bore against sleeve outside diameter)."""
        for i, dof in enumerate(DOFS):
            yield (dof, FORCE_UNITS[i], *(float(v) for v in self.stiffness.matrix[i]))

    def write(self, out: str | Path) -> list[Path]:
        """``datasheet.json``, ``datasheet.csv`` and ``stiffness_matrix.csv`` into the folder
        ``out``, each atomically; returns the paths."""
        folder = Path(out)
        cols = ("row", "force_unit", *(f"{d}_per_{u}" for d, u in
                                       zip(DOFS, DISPLACEMENT_UNITS, strict=True)))
        head = (f"{self.spec.name}: stiffness of hub bore against sleeve outside diameter at "
                f"i = {self.misalignment_deg:g} deg, T = {self.torque_Nm:.6g} N·m; "
                "K = -dQ/dq, Q on the hub (docs/rotordynamics.md)")
        return [write_json(folder / FILES[0], self.as_dict()),
                write_csv_rows(folder / FILES[1], DATASHEET_COLUMNS, self.rows()),
                write_csv_rows(folder / FILES[2], cols, self.matrix_rows(), comments=[head])]

    def to_ross(self, **options):
        """A ``ross.CouplingElement`` of these data (the ``rotordynamics`` extra); options as
        :func:`gearcoupling.rotordynamics.coupling_element`."""
        return coupling_element(self, **options)


Rows = list[tuple[str, str, float | None, str, str]]
STIFFNESS_UNITS = ("N/m", "N/m", "N/m", "N·m/rad", "N·m/rad", "N·m/rad")


def _mass_rows(mass: dict[str, MassProperties], accuracy: str) -> Rows:
    out: Rows = []
    for name, m in mass.items():
        out += [("mass", f"{name} mass", m.mass_kg, "kg", accuracy),
                ("mass", f"{name} centre of gravity z", float(m.centre_of_gravity_mm[2]),
                 "mm", "from the midplane of the hub teeth, along the axis"),
                ("mass", f"{name} polar inertia", m.polar_inertia_kg_m2, "kg·m²", accuracy),
                ("mass", f"{name} transverse inertia", m.transverse_inertia_kg_m2, "kg·m²",
                 "about its centre of gravity")]
    return out


def _torsion_rows(data: CouplingData, accuracy: str) -> Rows:
    t, k_body = data.torsion, data.stiffness.body_torsional_Nm_per_rad
    return [("torsion", "secant stiffness at the torque", t.secant_Nm_per_rad, "N·m/rad",
             accuracy),
            ("torsion", "tangent stiffness at the torque", t.tangent_Nm_per_rad, "N·m/rad",
             accuracy),
            ("torsion", "bodies' torsional stiffness", k_body if math.isfinite(k_body) else
             None, "N·m/rad", _body_source(data.spec.hub.body.bore_diameter)),
            ("torsion", "capacity at the misalignment", data.capacity_Nm, "N·m",
             "the wind-up curve ends here (datasheet.json)")]


def _body_source(bore_mm: float) -> str:
    """What the bodies' torsion spans: from the hub bore, or from the sleeve's teeth where
    the hub is solid (taken rigid, :func:`~gearcoupling.loading.body_windup_rad`)."""
    if bore_mm > 0:
        return f"hub bore ({bore_mm:.4g} mm) to sleeve outside diameter"
    return "sleeve to its outside diameter (the hub has no bore: taken rigid)"


def _stiffness_rows(s: StiffnessMatrix, accuracy: str) -> Rows:
    K = s.matrix
    out: Rows = []
    for i, dof in enumerate(DOFS):
        lo_hi = s.rotation_spread.get(dof)
        spread = (f"; over the pitch {lo_hi[0]:.4g} to {lo_hi[1]:.4g}" if lo_hi else
                  "; pitch mean (from the mean forces turned with the tilt axis)")
        out.append(("stiffness", f"K {dof}-{dof}", float(K[i, i]), STIFFNESS_UNITS[i],
                    accuracy + spread))
    out += [("stiffness", f"cross-coupled tilt {k.removesuffix('_Nm_per_rad')}", v, "N·m/rad",
             "moment on the hub about -x per tilt about y (k_xy), about -y per tilt about x "
             "(k_yx); stiffness_matrix.csv holds the whole matrix")
            for k, v in s.cross_coupled().items()]
    out.append(("stiffness", "axial slip force", s.axial_slip_force_N, "N",
                "friction times the tooth normal loads: the thrust at which the teeth slide"))
    return out


def _allowable_rows(a: AllowableLoads, accuracy: str) -> Rows:
    out: Rows = [("allowable", "allowable misalignment", a.misalignment_deg, "deg",
                  f"limited by the {a.criterion}"
                  + (f" ({a.capacity_criterion})" if a.capacity_criterion else "")),
                 ("allowable", "critical misalignment", a.critical_misalignment_deg, "deg",
                  "contact on the pivot teeth reaches a face end")]
    for key, ext in a.extremes().items():
        name, unit = key.rsplit("_", 1)
        out += [("allowable", f"{name.replace('_', ' ')} {stat} over a turn", ext[stat],
                 UNITS[unit], accuracy) for stat in ("min", "max")]
    return out


MAX_TORQUE_NM = 1e9  # as the load command: far above any coupling


def check_inputs(spec: CouplingSpec, torque_Nm: float | None) -> float:
    """What :func:`coupling_data` refuses before computing anything: the parts' densities
    (:class:`SpecError` where one is missing) and the torque (the argument, else the
    spec's; finite and not zero). Returns the torque."""
    for part in ("hub", "sleeve"):
        getattr(spec.material, part).mass_density_kg_per_m3()
    T = resolve_torque_Nm(spec, torque_Nm)
    if T == 0 or abs(T) > MAX_TORQUE_NM:
        raise ArgumentError("torque_Nm", T, f"a torque from -{MAX_TORQUE_NM:g} to "
                            f"{MAX_TORQUE_NM:g} N·m, not 0 (the data are those of loaded "
                            "teeth; at zero torque the coupling turns freely in its backlash)")
    return T


def coupling_data(spec: CouplingSpec, misalignment_deg: float | None = None,
                  torque_Nm: float | None = None, *, model: str | None = None,
                  rotations: int | None = None,
                  relative_step: float | None = None,
                  differences: str | None = None,
                  turn_angles: int | None = None, curve_points: int = DEFAULT_POINTS,
                  tolerance_mm: float | None = None, known: Sequence[Capacity] = (),
                  workers: int | None = None,
                  progress: Callable[[int, int], Any] | None = None) -> CouplingData:
    """The API 671 data of a coupling at an operating point (module docstring).

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg : float, optional
        0-6 degrees; default the spec's design angle.
    torque_Nm : float, optional
        Signed, not zero; default the spec's ``[load]`` torque.
    model : str, optional
        Load model; default the spec's ``[load] model``, the validated default.
    rotations : int, optional
        Rotations over one tooth pitch the stiffness is averaged over (accuracy knob);
        default :func:`~.stiffness.default_rotations`.
    relative_step : float, optional
        Difference step, a share of the largest tooth deflection (accuracy knob; default
        :data:`~.stiffness.DEFAULT_STEPS` of the scheme).
    differences : {"central", "forward"}, optional
        Difference scheme of the matrix (accuracy knob); default
        :func:`~.stiffness.default_differences` of the model (forward for ``surface``).
    turn_angles : int, optional
        Rotations of the turn at the allowable misalignment (accuracy knob); default
        :data:`~gearcoupling.loading.PHASES` per tooth pitch
        (:func:`~.allowable.allowable_loads`).
    curve_points : int
        Torques on the wind-up curve, at ``(i / (n - 1))^2`` of its end
        (:func:`~.torsion.windup_torques`).
    tolerance_mm : float, optional
        Chordal tolerance of the part meshes (default module / 200; accuracy knob).
    known : sequence of Capacity
        Capacities of this spec and model (ccw flank) already computed, such as the
        report's capacity curve: the capacity at the misalignment and the points of the
        allowable misalignment's search are taken from them where they have the angle.
    workers : {1, 2}, optional
        Two chains, the matrix and the allowable misalignment, with the wind-up curve's
        torques (:class:`StartedCouplingData`), computed in this process (1) or
        in two forked ones (2; the default where the machine has two cores and forking is
        safe, :func:`~gearcoupling.forked.default_workers`); the same numbers either way.
    progress : callable, optional
        ``progress(done, total)`` after each step (:class:`DatasheetSteps`: the masses,
        the capacity, the matrix, each torque of the wind-up curve, each capacity of the
        allowable misalignment's search and the turn there).

    Examples
    --------
    >>> import gearcoupling as gc
    >>> data = gc.coupling_data(gc.load_spec("renzo-1967"))  # doctest: +SKIP
    >>> data.stiffness.matrix.shape  # doctest: +SKIP
    (6, 6)
    """
    started = StartedCouplingData(spec, misalignment_deg, torque_Nm, model=model,
                                  rotations=rotations, relative_step=relative_step,
                                  differences=differences, turn_angles=turn_angles,
                                  curve_points=curve_points, tolerance_mm=tolerance_mm,
                                  known=known, workers=workers, progress=progress)
    try:
        return started.result()
    finally:
        started.stop()


@dataclass(frozen=True)
class DatasheetPlan:
    """:func:`coupling_data` cut into its two chains (:attr:`tasks`, picklable callables
    of no arguments, run in any process) and their combination (:meth:`combine`).
    Arguments of :func:`datasheet_plan`.

    The chains: the matrix, then every other torque of the wind-up curve on the matrix's
    sweep (each solve starts from the last pose of the one before, the first from the
    matrix's operating point); and the allowable misalignment with its turn. The other
    torques, on a copy of the sweep (their own chain of warm starts, from cold), follow
    the allowable misalignment when ``known`` capacities shorten its search (the
    report), else the matrix's torques: the two chains then cost about the same. Each
    sweep's solves are the same in the same order wherever the chains run, so the
    numbers are the same to the last bit.
    """

    spec: CouplingSpec = field(repr=False)
    misalignment_deg: float
    torque_Nm: float
    capacity: Capacity
    grid: NDArray[np.float64]
    mass: dict[str, MassProperties]
    tasks: tuple[Callable[[], Any], ...] = field(repr=False)

    def combine(self, values: Sequence[Any], seconds: float = 0.0) -> CouplingData:
        """The data sheet from the chains' values (in the order of :attr:`tasks`)."""
        (K, first), (allowed, second) = values
        even, odd = list(first) + list(second)
        rest: list[float] = [0.0] * (len(even) + len(odd))
        rest[0::2], rest[1::2] = even, odd
        found = iter(rest)
        T = self.torque_Nm
        curve = [K.operating_windup_rad if t == T else next(found) for t in self.grid]
        torsion = torsion_from_curve(self.spec, self.grid, curve, T, float(K.matrix[5, 5]),
                                     self.capacity.capacity_Nm)
        used = K.model
        return CouplingData(self.spec, self.misalignment_deg, T, used,
                            springs_name(self.spec, used), self.mass, torsion, K,
                            self.capacity.capacity_Nm, allowed, seconds)


def datasheet_plan(spec: CouplingSpec, misalignment_deg: float | None = None,
                   torque_Nm: float | None = None, *, model: str | None = None,
                   rotations: int | None = None, relative_step: float | None = None,
                   differences: str | None = None, turn_angles: int | None = None,
                   curve_points: int = DEFAULT_POINTS, tolerance_mm: float | None = None,
                   known: Sequence[Capacity] = (),
                   mass: dict[str, MassProperties] | None = None,
                   step: Callable[[], Any] | None = None) -> DatasheetPlan:
    """:func:`coupling_data`'s arguments checked and its chains made (:class:`DatasheetPlan`);
    the masses computed here unless given (a bad tolerance fails first). ``step()`` after
    the masses and after the capacity at the misalignment, where they are computed here.
    Each chain takes ``tick`` (default None), called after each of its steps
    (:class:`DatasheetSteps`)."""
    spec = as_spec(spec)
    mis = (spec.design_misalignment_deg if misalignment_deg is None else
           check_misalignment_deg(misalignment_deg, "misalignment_deg", ArgumentError))
    T = check_inputs(spec, torque_Nm)
    model = resolve_model(spec, model)
    given = known_capacities(spec, model, known)
    if mass is None:
        mass = mass_properties(spec, tolerance_mm)
        _call(step)
    sw = sweep(spec, mis, pitch_rotations(spec, default_rotations(model) if rotations is None
                                          else rotations))
    windup_torques(T, None, curve_points)  # the number of points checked before any work
    cap = given.get(float(mis))
    if cap is None:
        cap = capacity(spec, mis, model=model)
        _call(step)
    grid = windup_torques(T, cap.capacity_Nm, curve_points)
    others = [t for t in grid if t != T]
    halves = [(sw, others[0::2]), (copy.copy(sw), others[1::2])]
    # given capacities (the report's curve) leave the allowable misalignment's search
    # short: the second half of the curve goes with it, else with the matrix
    split = 1 if given else 2
    matrix = partial(_matrix_and_curve, sw, T, model, relative_step, differences,
                     halves[:split])
    allowable = partial(_allowable_and_curve, partial(
        allowable_loads, spec, T, model=model, angles=turn_angles,
        known=[*given.values(), cap]), halves[split:], model)
    return DatasheetPlan(spec, float(mis), T, cap, grid, mass, (matrix, allowable))


class DatasheetSteps:
    """``progress(done, total)`` of :func:`coupling_data`, a step each: the masses, the
    capacity at the misalignment, the matrix, each torque of the wind-up curve but the
    operating one, each capacity the allowable misalignment's search solves, and the turn
    there. The search's steps are known only as it goes: the total counts
    :data:`SEARCH_STEPS` for them, and the bar is never full before :meth:`end`."""

    def __init__(self, progress: Callable[[int, int], Any] | None, curve_points: int):
        self.progress = progress
        self.done, self.ended = 0, False
        self.curve(curve_points)

    def curve(self, torques: int) -> None:
        """The count of the curve's torques to solve (known once the capacity is)."""
        self.total = 4 + SEARCH_STEPS + torques  # the masses, capacity, matrix and turn
        self._report()

    def step(self) -> None:
        """One step done."""
        self.done += 1
        self._report()

    def end(self) -> None:
        """Everything done: the bar full."""
        self.total, self.ended = self.done, True
        self._report()

    def _report(self) -> None:
        if not self.ended:
            self.total = max(self.total, self.done + 1)
        if self.progress is not None:
            self.progress(self.done, self.total)


#: capacities the allowable misalignment's search solves, about, on the templates
#: (:func:`~.allowable.capacity_limit_deg`): what the progress bar expects of it
SEARCH_STEPS = 4


class StartedCouplingData:
    """:func:`coupling_data` started now, its two chains (:class:`DatasheetPlan`) in forked
    workers where it forks, and collected later by :meth:`result`; :meth:`stop` in a
    ``finally`` kills the workers still running. Arguments as :func:`coupling_data`;
    ``progress`` is told each step (:class:`DatasheetSteps`), from here to the result."""

    def __init__(self, spec: CouplingSpec, misalignment_deg: float | None = None,
                 torque_Nm: float | None = None, *, workers: int | None = None,
                 progress: Callable[[int, int], Any] | None = None, **options: Any):
        self.t0 = time.perf_counter()
        workers = default_workers() if workers is None else workers
        if workers not in (1, 2) or isinstance(workers, bool):
            raise ArgumentError("workers", workers, "1 or 2")
        self.steps = DatasheetSteps(progress, options.get("curve_points", DEFAULT_POINTS))
        self.plan = datasheet_plan(spec, misalignment_deg, torque_Nm, step=self.steps.step,
                                   **options)
        self.steps.curve(len(self.plan.grid) - 1)
        self.map = ForkedMap(lambda task, tick: task(tick=tick), list(self.plan.tasks),
                             workers, ticking=True)

    def result(self) -> CouplingData:
        values = self.map.results(tick=self.steps.step)
        self.steps.end()
        return self.plan.combine(values, time.perf_counter() - self.t0)

    def stop(self) -> None:
        self.map.stop()


def _call(step: Callable[[], Any] | None) -> None:
    if step is not None:
        step()


def _curves(halves, model: str, tick: Callable[[], Any] | None = None) -> list[list[float]]:
    """The teeth's wind-up from first touch at each ``(sweep, torques)`` of ``halves``, each
    solve starting from the last pose solved on its sweep; ``tick()`` after each."""
    out: list[list[float]] = []
    for sw, torques in halves:
        out.append([])
        for t in torques:
            out[-1].append(mesh_windup_from_touch(sw, t, model))
            _call(tick)
    return out


def _matrix_and_curve(sw, T: float, model: str, relative_step: float | None,
                      differences: str | None, halves, tick: Callable[[], Any] | None = None
                      ) -> tuple[StiffnessMatrix, list[list[float]]]:
    """The stiffness matrix at ``T`` on ``sw``, then the wind-up curve's ``halves``
    (:func:`_curves`; the first on ``sw``, from the matrix's operating point); ``tick()``
    after the matrix and after each torque."""
    K = stiffness_from_sweep(sw, T, model=model, relative_step=relative_step,
                             differences=differences)
    _call(tick)
    return K, _curves(halves, model, tick)


def _allowable_and_curve(allowable: Callable[..., AllowableLoads], halves, model: str,
                         tick: Callable[[], Any] | None = None
                         ) -> tuple[AllowableLoads, list[list[float]]]:
    """The allowable misalignment with its turn, then the wind-up curve's ``halves``;
    ``tick()`` after each capacity of the search, the turn and each torque."""
    loads = allowable(step=tick)
    _call(tick)
    return loads, _curves(halves, model, tick)


__all__ = ["DATASHEET_COLUMNS", "FILES", "MAX_TORQUE_NM", "NOT_MODELLED", "CouplingData",
           "DatasheetPlan", "StartedCouplingData", "check_inputs", "coupling_data",
           "datasheet_plan"]
