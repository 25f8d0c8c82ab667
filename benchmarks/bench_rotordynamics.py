"""Coupling data for rotordynamics: time of the data sheet, convergence of the stiffness
matrix in its two knobs, and the validation figures of docs/rotordynamics.md.

Run: ``python benchmarks/bench_rotordynamics.py [--quick] [--only SECTION]`` (``--quick``
leaves out the STEP solids and the ROSS rotor; ``--only`` runs one section).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from functools import partial
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

import gearcoupling as gc
from gearcoupling.loading import mesh_stiffness_N_per_mm, springs_name
from gearcoupling.rotordynamics import (
    WINDUP_ERROR_PCT,
    coupling_data,
    mass_properties,
    stiffness_matrix,
)
from gearcoupling.rotordynamics.stiffness import (
    DEFAULT_STEPS,
    default_differences,
    default_rotations,
)
from gearcoupling.rotordynamics.torsion import mesh_windup_from_touch

ROOT = Path(__file__).resolve().parents[1]
ENTRIES = (("K x-x", 0, 0), ("K y-y", 1, 1), ("K tilt_x", 3, 3), ("K tilt_y", 4, 4),
           ("K torsion", 5, 5), ("k_xy", 3, 4), ("k_yx", 4, 3), ("K tilt_x-torsion", 3, 5))


def timing() -> None:
    print("## Time of the data sheet (default model and knobs; a fresh process per spec "
          "builds its flank table first)\n")
    print("| spec | seconds | model | K torsion N·m/rad | allowable deg (criterion) |")
    print("|---|---|---|---|---|")
    for name in gc.template_names():
        spec = gc.load_spec(name)
        t0 = time.perf_counter()
        d = coupling_data(spec)
        dt = time.perf_counter() - t0
        print(f"| {name} | {dt:.1f} | {d.model} | {d.stiffness.matrix[5, 5]:.4g} | "
              f"{d.allowable.misalignment_deg:.3g} ({d.allowable.criterion}) |")


def _table(title: str, knob: str, values, build) -> None:
    print(f"\n## {title}\n")
    print(f"| {knob} | " + " | ".join(e for e, _, _ in ENTRIES) + " | seconds |")
    print("|---|" + "---|" * (len(ENTRIES) + 1))
    rows = []
    for v in values:
        t0 = time.perf_counter()
        K = build(v).matrix
        rows.append((v, K, time.perf_counter() - t0))
    ref = rows[-1][1] if knob == "rotations" else rows[0][1]
    for v, K, dt in rows:
        cells = [f"{K[i, j]:.5g} ({K[i, j] / ref[i, j] - 1:+.2%})" if ref[i, j] else
                 f"{K[i, j]:.5g}" for _, i, j in ENTRIES]
        print(f"| {v:g} | " + " | ".join(cells) + f" | {dt:.1f} |")


def convergence() -> None:
    """The knobs of the matrix: the default model (``surface``, over fewer rotations) and
    ``compliance``, renzo-1967 at 1° and the spec's torque."""
    spec = gc.load_spec("renzo-1967")
    for model, steps, rotations in (("surface", (0.00125, 0.0025, 0.005, 0.01), (2, 4, 8, 16)),
                                    ("compliance", (0.005, 0.01, 0.02, 0.05, 0.1),
                                     (1, 2, 4, 8, 16, 32))):
        n, scheme = default_rotations(model), default_differences(model)
        _table(f"Step convergence ({model}, renzo-1967, 1°, spec torque, {n} rotations, "
               f"{scheme} differences; change against the smallest step)", "relative_step",
               steps, lambda s, m=model: stiffness_matrix(spec, 1.0, model=m, relative_step=s))
        _table(f"Rotations over one pitch ({model}, renzo-1967, 1°, {scheme} differences, step "
               f"{DEFAULT_STEPS[scheme]:g}; change against {rotations[-1]})", "rotations",
               rotations,
               lambda r, m=model: stiffness_matrix(spec, 1.0, model=m, rotations=r))


def breakdown() -> None:
    """Where a data sheet's CPU goes, in one process, with the report's capacity curve as
    ``known=`` (its 7 misalignments through the design point, computed first)."""
    print("\n## Where the CPU goes (one process, the report's capacity curve as known=; "
          "CPU seconds)\n")
    print("| spec | matrix, forward | matrix, central | wind-up curve (other torques) | "
          "allowable search | turn at the allowable misalignment | allowable |")
    print("|---|---|---|---|---|---|---|")
    for name in ("renzo-1967", "industrial-m2"):
        _breakdown_row(gc.load_spec(name))


def _breakdown_row(spec) -> None:
    from gearcoupling.outputs.capacity import comparison_range, through  # the report's curve
    from gearcoupling.rotordynamics.allowable import allowable_loads, capacity_limit_deg
    from gearcoupling.rotordynamics.stiffness import pitch_rotations, stiffness_from_sweep
    from gearcoupling.rotordynamics.torsion import windup_torques

    mis, T = spec.design_misalignment_deg, spec.load.torque_Nm
    known = [gc.capacity(spec, float(m)) for m in through(comparison_range([spec], 7)[0], mis)]
    cap = next(c for c in known if c.misalignment_deg == mis)
    sw = gc.sweep(spec, mis, pitch_rotations(spec, default_rotations(spec.load.model)))
    cells = []

    def cpu(run):
        t0 = time.process_time()
        out = run()
        cells.append(time.process_time() - t0)
        return out

    for scheme in ("forward", "central"):
        cpu(lambda s=scheme: stiffness_from_sweep(sw, T, differences=s))
    cpu(lambda: [mesh_windup_from_touch(sw, t, None)
                 for t in windup_torques(T, cap.capacity_Nm) if t not in (0, T)])
    top = gc.critical_misalignment_deg(spec) or 6.0
    cpu(lambda: capacity_limit_deg(spec, T, top, known=known))
    a = cpu(lambda: allowable_loads(spec, T, known=known))
    cells[-1] -= cells[-2]  # the search again, then the turn
    print(f"| {spec.name} | " + " | ".join(f"{c:.1f}" for c in cells)
          + f" | {a.misalignment_deg:.3g}° ({a.criterion}) |")


def schemes() -> None:
    """Forward against central differences at the design points (the surface model's
    default is forward): every entry the data sheet prints from the matrix, and its CPU."""
    print("\n## Difference schemes (surface, design point, spec torque, 3 rotations; change "
          "against central at its default step; largest off-diagonal change over "
          "sqrt(K_ii K_jj))\n")
    names = [e for e, _, _ in ENTRIES if e != "k_xy"] + ["k_yx held torque"]
    print("| spec | scheme, step | " + " | ".join(names) + " | off-diagonal | CPU s |")
    print("|---|---|" + "---|" * (len(names) + 2))
    for name in ("renzo-1967", "industrial-m2"):
        spec = gc.load_spec(name)
        ref = None
        for scheme, step in (("central", DEFAULT_STEPS["central"]), ("forward", 0.005),
                             ("forward", DEFAULT_STEPS["forward"])):
            t0 = time.process_time()
            S = stiffness_matrix(spec, spec.design_misalignment_deg, differences=scheme,
                                 relative_step=step)
            dt = time.process_time() - t0
            K = S.matrix
            vals = [K[i, j] for e, i, j in ENTRIES if e != "k_xy"]
            vals.append(S.cross_coupled()["k_yx_held_torque_Nm_per_rad"])
            if ref is None:
                ref = (K, vals)
                cells = [f"{v:.5g}" for v in vals] + ["", f"{dt:.1f}"]
            else:
                d = np.sqrt(np.abs(np.outer(np.diag(ref[0]), np.diag(ref[0]))))
                off = np.max(np.where(d > 0, np.abs(K - ref[0]) / np.where(d > 0, d, 1), 0))
                cells = [f"{v / r - 1:+.2%}" if r else f"{v:.3g}"
                         for v, r in zip(vals, ref[1], strict=True)]
                cells += [f"{off:.2%}", f"{dt:.1f}"]
            print(f"| {name} | {scheme} {step:g} | " + " | ".join(cells) + " |")


def _asymmetry(K) -> float:
    d = np.abs(np.diag(K))
    worst = 0.0
    for i in range(6):
        for j in range(i):
            if d[i] > 0 and d[j] > 0:
                worst = max(worst, abs(K[i, j] - K[j, i]) / math.sqrt(d[i] * d[j]))
    return worst


def validation(quick: bool) -> None:
    print("\n## Validation (tests/test_rotordynamics.py holds each)\n")
    print("| check | figure |")
    print("|---|---|")
    spec = gc.load_spec("renzo-1967")
    # linear model, aligned: closed forms
    K = stiffness_matrix(spec, 0.0, model="linear")
    C, N = mesh_stiffness_N_per_mm(spec), spec.tooth.teeth
    phi, R = spec.tooth.pressure_angle, spec.tooth.pitch_radius
    radial = N * C / (2 * math.cos(phi) ** 2) * 1e3
    print(f"| linear, 0°: K x-x / (N C / 2 cos² φ) − 1 | {K.mesh_matrix[0, 0] / radial - 1:+.1e} |")
    print(f"| linear, 0°: K torsion (teeth) / (N C R²) − 1 | "
          f"{K.mesh_matrix[5, 5] / (N * C * R**2 * 1e-3) - 1:+.1e} |")
    for model in ("linear", spec.load.model):
        K0 = stiffness_matrix(spec, 1.0, model=model, friction=0.0)
        print(f"| {model}, 1°, no friction: largest asymmetry |K_ij − K_ji| / √(K_ii K_jj) | "
              f"{_asymmetry(K0.mesh_matrix):.2%} |")
    for name, deg in (("renzo-1967", 1.0), ("industrial-m2", 0.75)):
        s = gc.load_spec(name)
        with_f = stiffness_matrix(s, deg).at_constant_torque()
        without = stiffness_matrix(s, deg, friction=0.0).at_constant_torque()
        anti = 0.5 * ((with_f[3, 4] - with_f[4, 3]) - (without[3, 4] - without[4, 3]))
        a, h = math.radians(deg), 0.02 * math.radians(deg)
        mf = _friction_moment(s, deg)
        dmf = (_friction_moment(s, math.degrees(a + h))
               - _friction_moment(s, math.degrees(a - h))) / (2 * h)
        expected = 0.5 * (mf / a + dmf)
        print(f"| {name} {deg:g}°: friction's antisymmetric tilt part / (M_f/i + dM_f/di)/2 − 1 "
              f"({anti:.0f} N·m/rad) | {anti / expected - 1:+.2%} |")
    refs = json.loads((ROOT / "tests" / "golden" / "fe_contact_reference.json").read_text())
    stored = refs.get("specs", {})  # the random specs, with their references
    for name, by_torque in refs["references"].items():
        s = gc.spec_from_dict(stored[name], name=name) if name in stored else gc.load_spec(name)
        lo, hi = WINDUP_ERROR_PCT[(s.load.model, springs_name(s, s.load.model))]
        sw = gc.sweep(s, 0.0, [0.0])
        for torque, ref in by_torque.items():
            T = float(torque)
            w = mesh_windup_from_touch(sw, T, None) + gc.body_windup_rad(s, T)["body_rad"]
            print(f"| {name} {T:g} N·m aligned: wind-up (secant) vs CalculiX (ladder band "
                  f"{lo:+g}…{hi:+g} %) | {w / ref['windup_from_first_touch_rad'] - 1:+.1%} |")
    if not quick:
        _step_masses()
        _ross_rotor()


def _friction_moment(spec, deg):
    res = gc.load(spec, deg, np.arange(8) * 360.0 / spec.tooth.teeth / 8)
    cos = np.abs(np.cos(np.radians(res.theta_deg)))
    return spec.load.friction * np.mean(np.sum(res.normal_force_N * res.contact_r_mm * cos,
                                               axis=0)) * 1e-3


def _step_masses() -> None:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    from gearcoupling.parts import default_tolerance, part_solid

    for name in ("renzo-1967", "industrial-m2"):
        spec = gc.load_spec(name)
        mass = mass_properties(spec)
        for part in ("hub", "sleeve"):
            props = GProp_GProps()
            BRepGProp.VolumeProperties_s(part_solid(spec, part, default_tolerance(spec)), props)
            inertia = props.MatrixOfInertia()
            m = mass[part]
            ip = m.polar_inertia_kg_m2 / (7850e-15 * inertia.Value(3, 3)) - 1
            print(f"| {name} {part}: mesh vs STEP solid, volume · polar inertia | "
                  f"{m.volume_mm3 / props.Mass() - 1:+.3%} · {ip:+.3%} |")


def _ross_rotor() -> None:
    from gearcoupling.rotordynamics import import_ross

    rs = import_ross()
    data = coupling_data(gc.load_spec("renzo-1967"))
    steel = rs.materials.steel
    length, d, J = 0.05, 0.15, 5.0
    coupling = data.to_ross()
    shafts = [rs.ShaftElement(length, 0.0, d, material=steel), coupling,
              rs.ShaftElement(length, 0.0, d, material=steel)]
    disks = [rs.DiskElement(n=0, m=100.0, Id=2.5, Ip=J), rs.DiskElement(n=3, m=100.0, Id=2.5,
                                                                        Ip=J)]
    bearings = [rs.BearingElement(n=n, kxx=1e8, cxx=0) for n in (0, 3)]
    modal = rs.Rotor(shafts, disks, bearings).run_modal(speed=0, num_modes=40, sparse=False)
    wn = min(w for w, s in zip(modal.wn, modal.shapes, strict=False)
             if s.mode_type == "Torsional" and w > 1.0)
    k = 1.0 / (2.0 / (steel.G_s * math.pi * d**4 / 32 / length) + 1.0 / coupling.kr_z)
    closed = math.sqrt(2.0 * k / J)
    print(f"| ROSS rotor (renzo-1967 coupling): first torsional {wn / 2 / math.pi:.2f} Hz vs "
          f"two-inertia {closed / 2 / math.pi:.2f} Hz | {wn / closed - 1:+.2%} |")


#: random specs of the springs data set (tests/random_specs.py, ``bench_springs.py --random
#: 55``) with other tooth counts: 360 rotations hold 2, 5, 6, 12, 360 and 360 poses per
#: pitch of them (180, 72, 60, 30, 37 and 31 teeth)
TURN_EXTRA = ("springs-34-vari_crown", "springs-01-circular", "springs-18-end_round",
              "springs-23-circular", "springs-14-vari_crown", "springs-24-circular")
TURN_PHASES = (4, 6, 8, 12, 18, 24, 36)
TURN_REFERENCE = 72  # every phase count above divides it: their rotations are its


def turn() -> None:
    """The turn at the allowable misalignment against its rotations per tooth pitch: each
    load's largest value over the turn (and the mean) against a turn of
    :data:`TURN_REFERENCE` per pitch, and the CPU of the turn. With ideal teeth a turn of
    ``P`` per pitch holds ``P`` distinct poses; 360 rotations a turn hold 360 / gcd(360,
    N) of them per pitch (36 on 50 teeth, 180 on 38, 6 on 300)."""
    from gearcoupling.loading import turn_phases
    from gearcoupling.rotordynamics.allowable import allowable_loads

    print("\n## The turn at the allowable misalignment: rotations per tooth pitch (largest "
          "change of a load's max or mean over the turn against a turn of "
          f"{TURN_REFERENCE} per pitch, the forces' against the largest slip force; CPU "
          "seconds of the turn)\n")
    print("| spec | teeth | allowable | " + " | ".join(f"{n} per pitch" for n in TURN_PHASES)
          + " | 360 rotations (per pitch) |")
    print("|---|---|---|" + "---|" * (len(TURN_PHASES) + 1))
    sys.path.insert(0, str(ROOT / "tests"))
    from random_specs import springs_specs

    extra = {s.name: s for s in springs_specs(55) if s.name in TURN_EXTRA}
    for spec in [*map(gc.load_spec, gc.template_names()), *extra.values()]:
        name = spec.name
        # a random spec has no torque: half its capacity at the design angle
        T = spec.load.torque_Nm or 0.5 * gc.capacity(spec, spec.design_misalignment_deg
                                                     ).capacity_Nm
        a = allowable_loads(spec, T, angles=8)  # the angle: its search, a short turn
        loads = partial(_turn_loads, spec, a.misalignment_deg, T)
        ref, _ = loads(turn_phases(spec, TURN_REFERENCE))
        cells = []
        for angles in [*(turn_phases(spec, n) for n in TURN_PHASES),
                       np.arange(360) * 1.0]:
            got, cpu = loads(angles)
            err = _turn_change(got, ref)
            cells.append(f"{100 * err:.3f} % ({cpu:.1f} s)")
        per = 360 // math.gcd(360, spec.tooth.teeth)
        cells[-1] += f" ({per})"
        print(f"| {name} | {spec.tooth.teeth} | {a.misalignment_deg:.3g}° | "
              + " | ".join(cells) + " |", flush=True)


def _turn_loads(spec, misalignment_deg: float, torque_Nm: float, angles
                ) -> tuple[dict[str, np.ndarray], float]:
    """The loads of the data sheet's turn at ``angles`` (magnitudes) and its CPU seconds."""
    from gearcoupling.loading import machine_loads

    t0 = time.process_time()
    res = gc.load(spec, misalignment_deg, angles, torque_Nm=torque_Nm)
    ml = machine_loads(res)
    slip = spec.load.friction * np.sum(res.normal_force_N, axis=0)
    out = {k: np.abs(np.asarray(v, float)) for k, v in (
        ("moment", ml["tilting_moment_Nm"]), ("axial", ml["axial_force_N"]),
        ("radial", ml["radial_force_N"]), ("slip", slip))}
    return out, time.process_time() - t0


def _turn_change(got: dict, ref: dict) -> float:
    """The largest change of the max and the mean of each load over the turn: the moment's
    against its own, the forces' against the reference's largest slip force (the radial
    force and the thrust cancel between opposite teeth of an even count: near zero)."""
    force = float(np.max(ref["slip"]))
    out = 0.0
    for k in ref:
        scale_max = float(np.max(ref[k])) if k == "moment" else force
        scale_mean = float(np.mean(ref[k])) if k == "moment" else force
        out = max(out, abs(np.max(got[k]) - np.max(ref[k])) / scale_max,
                  abs(np.mean(got[k]) - np.mean(ref[k])) / scale_mean)
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="no STEP solids, no ROSS rotor")
    p.add_argument("--only", choices=("timing", "breakdown", "convergence", "schemes",
                                      "validation", "turn"))
    a = p.parse_args()
    sections = {"timing": timing, "breakdown": breakdown, "convergence": convergence,
                "schemes": schemes, "validation": lambda: validation(a.quick), "turn": turn}
    for name, run in sections.items():
        if a.only in (None, name):
            run()


if __name__ == "__main__":
    main()
