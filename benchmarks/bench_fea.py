"""FE meshes and CalculiX tooth stiffness: the tables docs/fea.md publishes.

Run: ``python benchmarks/bench_fea.py [cantilever] [convergence] [compare]`` (default all;
the contact references are ``bench_fea_contact.py``, aligned, and ``bench_fea_sector.py``,
misaligned).

- ``cantilever``: gmsh C3D10 + ccx tip deflection of a clamped 100 x 10 x 10 mm steel
  cantilever against Timoshenko at several element sizes.
- ``convergence``: industrial-m2 hub, 3-tooth sector: mesh time, elements, solve time and
  hub tooth compliance at the pitch point (mid-face, one load case) for three element sizes
  (ratio sqrt 2); Richardson extrapolation gives the converged value and each size's error.
- ``compare``: renzo-1967 and industrial-m2 at the default size: FE pair compliance and C
  at the pitch point against the tapered cantilever (``gearcoupling.loading.cantilever``, when
  available) and ISO 6336's c' (single-pair stiffness 14 N/(mm µm) of face width).
- ``contact``: renzo-1967 at 1° and psi = 20°: the ``surface`` load model (branch
  load-surface) at the spec torque gives the wind-up; CalculiX surface-to-surface contact
  of 3 hub teeth in 3 sleeve spaces turned by that wind-up gives the tooth loads and peak
  pressures to compare.

Markdown tables on stdout. The machine is shared: times are single runs, noisy.
"""

from __future__ import annotations

import sys
import tempfile
import time

import numpy as np

from gearcoupling import load_spec
from gearcoupling.fea import mesh_part
from gearcoupling.fea.stiffness import part_compliance, tooth_compliance_table
from gearcoupling.fea.validation import cantilever_tip_deflection

ISO_C_PRIME = 14.0  # N/(mm µm), ISO 6336-1 single-pair stiffness of a standard spur pair


def cantilever() -> None:
    print("\n### Cantilever (100 x 10 x 10 mm, clamped, 1 kN) vs Timoshenko\n")
    print("| size mm | C3D10 | FE tip mm | Timoshenko mm | FE / theory | solve s |")
    print("|---|---|---|---|---|---|")
    for size in (5.0, 2.5, 1.5):
        r = cantilever_tip_deflection(size)
        print(f"| {size} | {r['elements']} | {r['fe_mm']:.5f} | {r['theory_mm']:.5f} | "
              f"{r['ratio']:.4f} | {r['solve_seconds']:.1f} |")


def richardson(h, c):
    """Order p and extrapolated value from three (size, value) pairs, c = c0 + A h^p."""
    from scipy.optimize import brentq

    h, c = np.asarray(h, float), np.asarray(c, float)
    ratio = (c[0] - c[1]) / (c[1] - c[2])

    def f(p):
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - ratio

    try:
        p = brentq(f, 0.2, 6.0)
    except ValueError:
        p = 2.0  # not monotone: assume the nominal order of quadratic elements
    a = (c[0] - c[1]) / (h[0] ** p - h[1] ** p)
    return p, c[0] - a * h[0] ** p


def convergence(sizes=(1.0, 0.7, 0.5)) -> None:
    spec = load_spec("industrial-m2")
    R = spec.tooth.pitch_radius
    print("\n### Mesh convergence: industrial-m2 hub, 3-tooth sector, load at mid-face, "
          "pitch radius\n")
    rows = []
    for size in sizes:
        t0 = time.perf_counter()
        vm = mesh_part(spec, "hub", sector=3, size_mm=size)
        t_mesh = time.perf_counter() - t0
        with tempfile.TemporaryDirectory() as tmp:
            c, s, info = part_compliance(vm, spec, np.array([0.0]), np.array([R]),
                                         patch_mm=0.5, workdir=tmp, job="hub")
        rows.append((size, vm.quality["elements"], vm.quality["nodes"], t_mesh,
                     info["solve_seconds"], float(c[0, 0]), float(s[0, 0]),
                     vm.quality["min_scaled_jacobian"]))
    p, c0 = richardson([r[0] for r in rows], [r[5] for r in rows])
    print("| size mm | C3D10 | nodes | mesh s | solve s | hub compliance µm/N | error vs "
          "extrapolated | root stress MPa/N | min scaled Jacobian |")
    print("|---|---|---|---|---|---|---|---|---|")
    for size, ne, nn, tm, ts, c, s, sj in rows:
        print(f"| {size} | {ne} | {nn} | {tm:.1f} | {ts:.1f} | {1e3 * c:.5f} | "
              f"{100 * (c - c0) / c0:+.2f} % | {s:.4f} | {sj:.3f} |")
    print(f"\nRichardson: observed order p = {p:.2f}, extrapolated compliance "
          f"{1e3 * c0:.5f} µm/N (patch 0.5 mm fixed).")


def _cantilever_pair(spec):
    try:
        from gearcoupling.loading.cantilever import CantileverCompliance
    except ImportError:
        return None
    return float(CantileverCompliance(spec).pair_compliance_mm_per_N(0.0,
                                                                      spec.tooth.pitch_radius))


def compare(names=("renzo-1967", "industrial-m2")) -> None:
    print("\n### FE vs tapered cantilever vs ISO 6336 c' (pitch point, mid-face)\n")
    print("| spec | b mm | FE hub µm/N | FE sleeve µm/N | FE pair µm/N | FE C N/mm | "
          "FE c' N/(mm µm) | cantilever pair µm/N | cantilever / FE | ISO C N/mm | "
          "ISO / FE | FE s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in names:
        spec = load_spec(name)
        b = spec.hub.face_width
        t0 = time.perf_counter()
        with tempfile.TemporaryDirectory() as cache:
            t = tooth_compliance_table(spec, nz=2, nr=3, cache=cache)
        secs = time.perf_counter() - t0
        R = spec.tooth.pitch_radius
        hub = float(t._interp(t.hub_mm_per_N, 0.0, R))
        sl = float(t._interp(t.sleeve_mm_per_N, 0.0, R))
        pair = hub + sl
        cant = _cantilever_pair(spec)
        iso = ISO_C_PRIME * 1e3 * b
        cant_txt = ("n/a", "n/a") if cant is None else (f"{1e3 * cant:.5f}",
                                                       f"{cant / pair:.2f}")
        print(f"| {name} | {b:g} | {1e3 * hub:.5f} | {1e3 * sl:.5f} | {1e3 * pair:.5f} | "
              f"{1 / pair:.4g} | {1 / pair / b / 1e3:.3g} | {cant_txt[0]} | {cant_txt[1]} | "
              f"{iso:.4g} | {iso * pair:.2f} | {secs:.0f} |")


def main(argv) -> None:
    steps = argv or ["cantilever", "convergence", "compare"]
    for step in steps:
        {"cantilever": cantilever, "convergence": convergence, "compare": compare}[step]()


if __name__ == "__main__":
    main(sys.argv[1:])
