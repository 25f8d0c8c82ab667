"""The whole coupling: the validation figures of docs/coupling.md and what each calculation
costs, on two spacer couplings (industrial-m2 and renzo-1967 hubs, flanged half-sleeves and
a spacer tube).

Run: ``python benchmarks/bench_coupling.py [--quick] [--only SECTION]`` (``--quick`` leaves
out the STEP solids, the ROSS train and the default-model timings; ``--only`` runs one of
angles, single, balance, torsion, beam, mass, ross, time).
"""

from __future__ import annotations

import argparse
import math
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np

import gearcoupling as gc
from gearcoupling.coupling import (
    CouplingLayout,
    ShaftAlignment,
    allowable_offset,
    beam_frequencies_Hz,
    coupling_assembly,
    coupling_geometry,
    whole_capacity,
    whole_coupling_data,
    whole_loads,
)
from gearcoupling.coupling.beam import Segment, annulus_EI_Nm2, pinned_pinned_Hz
from gearcoupling.loading import machine_loads

CHEAP = "compliance"
#: spacer couplings around two templates: flanged half-sleeves, a spacer tube (mm)
COUPLINGS = {
    "industrial-m2": (400.0, dict(sleeve="flanged", flange_outer_diameter_mm=140.0,
                                  flange_thickness_mm=12.0, spacer_outer_diameter_mm=110.0,
                                  spacer_inner_diameter_mm=90.0, spacer_length_mm=200.0)),
    "renzo-1967": (2260.0, dict(sleeve="flanged", flange_outer_diameter_mm=200.0,
                                flange_thickness_mm=16.0, spacer_outer_diameter_mm=160.0,
                                spacer_inner_diameter_mm=140.0, spacer_length_mm=300.0)),
}


def _setup(name: str):
    torque, layout = COUPLINGS[name]
    return gc.load_spec(name), CouplingLayout(**layout), torque


def angles() -> None:
    """Mesh angles against a second construction: hub B's centre from the shafts' lines,
    angles by the chord formula, over random alignments."""
    rng = np.random.default_rng(40)
    spec, layout, _ = _setup("industrial-m2")
    worst = 0.0
    for _ in range(2000):
        al = ShaftAlignment(rng.uniform(0, 10), rng.uniform(-180, 180), rng.uniform(0, 3),
                            rng.uniform(-180, 180))
        g = coupling_geometry(spec, layout, al)
        S = g.span_mm
        a, o = np.radians([al.angle_azimuth_deg, al.offset_azimuth_deg])
        t = math.radians(al.angle_deg)
        b = np.array([math.sin(t) * math.cos(a), math.sin(t) * math.sin(a), math.cos(t)])
        ob = np.array([al.offset_mm * math.cos(o), al.offset_mm * math.sin(o), S / 2])
        ob += S / 2 * b
        s = ob / np.linalg.norm(ob)
        for m, h in (("A", np.array([0.0, 0.0, 1.0])), ("B", b)):
            chord = math.degrees(2 * math.asin(0.5 * np.linalg.norm(s - h)))
            worst = max(worst, abs(chord - g.misalignment_deg(m)))
    print(f"mesh angles, 2000 random alignments: largest difference {worst:.2e} deg")


def single() -> None:
    """No offset, a shaft angle split evenly: each mesh against a single engagement."""
    spec, _, torque = _setup("industrial-m2")
    lay, al = CouplingLayout(span_mm=300.0), ShaftAlignment(angle_deg=1.5)
    w = whole_loads(spec, lay, al, torque, model=CHEAP)
    worst = 0.0
    for m, sign in (("A", 1.0), ("B", -1.0)):
        psi = w.geometry.mesh_rotations_deg(m, w.angles_deg)
        ref = gc.load(spec, 0.75, psi, torque_Nm=sign * torque, model=CHEAP)
        got = w.results[m]
        worst = max(worst, float(np.max(np.abs(got.tangential_force_N - ref.tangential_force_N)))
                    / float(np.max(ref.tangential_force_N)),
                    float(np.max(np.abs(got.windup_rad / ref.windup_rad - 1))))
    cap = whole_capacity(spec, lay, al, model=CHEAP)
    ref_cap = gc.capacity(spec, 0.75, model=CHEAP).capacity_Nm
    print(f"two meshes at 0.75° against single engagements: loads and wind-up {worst:.1e}, "
          f"capacity {cap.capacity_Nm / ref_cap - 1:+.1e} ({cap.governing_mesh}, "
          f"{cap.criterion})")


def balance() -> None:
    """The floating member's residual and the torque loss against the friction work."""
    for name in COUPLINGS:
        spec, layout, torque = _setup(name)
        for al in (ShaftAlignment(0.4, 30.0, 0.2, 100.0), ShaftAlignment(angle_deg=1.5)):
            w = whole_loads(spec, layout, al, torque, model=CHEAP)
            s = w.summary()
            eq = s["equilibrium"]
            work = sum(np.mean(spec.load.friction * np.sum(
                r.normal_force_N * machine_loads(r)["sliding_mm_per_rad"], axis=0)) * 1e-3
                for r in w.results.values())
            print(f"{name} {al.summary()}: residual force {eq['relative_force']:.1e}, "
                  f"moment {eq['relative_moment']:.1e}; torque loss {s['torque_loss_Nm']:.4g} "
                  f"N·m against friction work {work:.4g} N·m/rad "
                  f"({s['torque_loss_Nm'] / work - 1:+.2e}); shear up to {eq['shear_max_N']:.4g}"
                  f" N, bending moments {s['mesh_A']['bending_moment_Nm']['max']:.4g} · "
                  f"{s['mesh_B']['bending_moment_Nm']['max']:.4g} N·m")


def torsion() -> None:
    for name in COUPLINGS:
        spec, layout, torque = _setup(name)
        d = whole_coupling_data(spec, layout, None, torque, model=CHEAP, matrices=False)
        t = d.torsion
        sp = d.geometry.annuli[1]
        G = spec.material.sleeve.shear_modulus_MPa
        closed = sp.length_mm / (G * math.pi * ((2 * sp.outer_mm) ** 4 - (2 * sp.inner_mm) ** 4)
                                 / 32) * 1e3
        print(f"{name}: secant {t.secant_Nm_per_rad:.4g}, tangent {t.tangent_Nm_per_rad:.4g} "
              f"N·m/rad; spacer against L/(GJ) {t.secant_rad_per_Nm['spacer'] / closed - 1:+.1e};"
              " compliance shares " + ", ".join(
                  f"{k} {v / sum(t.secant_rad_per_Nm.values()):.1%}"
                  for k, v in t.secant_rad_per_Nm.items()))


def beam() -> None:
    EI = annulus_EI_Nm2(45.0, 55.0, 206_000.0)
    m = 7850.0 * math.pi * (0.055**2 - 0.045**2)
    for n in (4, 10, 40):
        f = beam_frequencies_Hz([Segment(0.0, 0.3, EI, m)], [0.0, 0.3], elements=n)[0]
        print(f"uniform tube, {n} elements: {f / pinned_pinned_Hz(0.3, EI, m) - 1:+.1e} "
              "against Euler-Bernoulli")
    for name in COUPLINGS:
        spec, layout, torque = _setup(name)
        d = whole_coupling_data(spec, layout, None, torque, model=CHEAP, matrices=False)
        f, alone = d.lateral_frequency_Hz, d.spacer_formula_Hz
        print(f"{name}: floating member {f:.4g} Hz, spacer alone {alone:.4g} Hz "
              f"({f / alone - 1:+.1%})")


def mass() -> None:
    """Each half against OpenCASCADE's integration of the placed STEP solids."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.BRepGProp import BRepGProp
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Pnt, gp_Trsf
    from OCP.GProp import GProp_GProps

    for name in COUPLINGS:
        spec, layout, torque = _setup(name)
        d = whole_coupling_data(spec, layout, None, torque, model=CHEAP, matrices=False)
        asm = coupling_assembly(spec, layout, ShaftAlignment())
        solids = asm.solids()
        mid = 0.5 * d.geometry.span_mm
        for side, lo, hi in (("A", -1e4, mid), ("B", mid, 1e4)):
            box = BRepPrimAPI_MakeBox(gp_Pnt(-1e4, -1e4, lo), gp_Pnt(1e4, 1e4, hi)).Shape()
            total = GProp_GProps()
            for p in asm.parts:
                trsf = gp_Trsf()
                trsf.SetValues(*p.placement[:3].ravel().tolist())
                piece = BRepAlgoAPI_Common(BRepBuilderAPI_Transform(solids[p.name], trsf, True)
                                           .Shape(), box).Shape()
                props = GProp_GProps()
                BRepGProp.VolumeProperties_s(piece, props, 1e-6)
                rho = (spec.material.hub if p.kind == "hub" else spec.material.sleeve)
                if props.Mass() > 0:
                    total.Add(props, rho.density_kg_per_m3 * 1e-9)
            tensor = total.MatrixOfInertia()
            got = d.halves[side]
            across = 0.5e-6 * (tensor.Value(1, 1) + tensor.Value(2, 2))
            print(f"{name} half {side}: mass {got.mass_kg / total.Mass() - 1:+.2e}, polar "
                  f"inertia {got.polar_inertia_kg_m2 / (tensor.Value(3, 3) * 1e-6) - 1:+.2e}, "
                  f"transverse {got.transverse_inertia_kg_m2 / across - 1:+.2e}, "
                  f"CG {got.centre_of_gravity_mm[2] - total.CentreOfMass().Z():+.1e} mm")


def ross() -> None:
    from gearcoupling.rotordynamics import import_ross

    spec, layout, torque = _setup("industrial-m2")
    d = whole_coupling_data(spec, layout, None, torque, model=CHEAP, rotations=2)
    rs = import_ross()
    steel = rs.materials.steel
    L, D, J1, J3 = 0.1, 0.05, 0.2, 0.3
    p = d.to_ross(n=2)
    shafts = ([rs.ShaftElement(L, 0.0, D, material=steel, n=i) for i in (0, 1)] + p.elements
              + [rs.ShaftElement(L, 0.0, D, material=steel, n=p.last_node + i) for i in (0, 1)])
    disks = [rs.DiskElement(n=0, m=20.0, Id=0.1, Ip=J1), *p.disks,
             rs.DiskElement(n=p.last_node + 2, m=20.0, Id=0.1, Ip=J3)]
    bearings = [rs.BearingElement(n=n, kxx=1e8, cxx=0)
                for n in (0, 1, p.last_node + 1, p.last_node + 2)]
    t0 = time.perf_counter()
    modal = rs.Rotor(shafts, disks, bearings).run_modal(speed=0, num_modes=40, sparse=False)
    dt = time.perf_counter() - t0
    wn = min(w for w, s in zip(modal.wn, modal.shapes, strict=False)
             if s.mode_type == "Torsional" and w > 1.0)
    t = d.torsion
    ks = steel.G_s * math.pi * D**4 / 32 / (2 * L)
    js = steel.rho * math.pi * D**4 / 32 * 2 * L
    k = [1 / (1 / ks + 1 / t.side_Nm_per_rad(m) + 0.5 * t.tangent_rad_per_Nm["spacer"])
         for m in "AB"]
    J = np.diag([J1 + js / 2 + d.parts["hub A"].polar_inertia_kg_m2,
                 d.floating.polar_inertia_kg_m2,
                 J3 + js / 2 + d.parts["hub B"].polar_inertia_kg_m2])
    K = np.array([[k[0], -k[0], 0], [-k[0], k[0] + k[1], -k[1]], [0, -k[1], k[1]]])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(J, K)).real)
    closed = math.sqrt(w2[1])
    print(f"ROSS train: first torsional {wn / 2 / math.pi:.2f} Hz against three inertias "
          f"{closed / 2 / math.pi:.2f} Hz ({wn / closed - 1:+.2%}); modal {dt:.1f} s")


def _time(label: str, f) -> None:
    t0, c0 = time.perf_counter(), time.process_time()
    f()
    print(f"| {label} | {time.perf_counter() - t0:.1f} | {time.process_time() - c0:.1f} |")


def timing(quick: bool) -> None:
    print("| calculation | wall s | CPU s |")
    print("|---|---|---|")
    for name in COUPLINGS:
        spec, layout, torque = _setup(name)
        al = ShaftAlignment(0.4, 30.0, 0.2, 100.0)
        args = (spec, layout, al)
        for model in (CHEAP,) if quick else (CHEAP, None):
            label = model or spec.load.model
            for f, torqued in ((whole_loads, True), (whole_capacity, False),
                               (allowable_offset, True), (whole_coupling_data, True)):
                extra = (torque,) if torqued else ()
                _time(f"{name} {f.__name__}, {label}",
                      lambda f=f, a=args + extra, m=model: f(*a, model=m))
        asm = coupling_assembly(spec, layout, al)
        _time(f"{name} assembly GLB", lambda a=asm: a.write_glb("/tmp/bench-coupling.glb"))
        _time(f"{name} overlap of mesh A", lambda a=asm: a.overlap_mm3("A"))
        if not quick:
            _time(f"{name} assembly STEP", lambda a=asm: a.write_step("/tmp/bench-coupling.step"))


SECTIONS = {"angles": angles, "single": single, "balance": balance, "torsion": torsion,
            "beam": beam, "mass": mass, "ross": ross}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", choices=[*SECTIONS, "time"])
    args = ap.parse_args()
    for key, f in SECTIONS.items():
        if args.only in (None, key) and not (args.quick and key in ("mass", "ross")):
            print(f"\n## {key}\n")
            f()
    if args.only in (None, "time"):
        print("\n## time\n")
        timing(args.quick)


if __name__ == "__main__":
    main()
