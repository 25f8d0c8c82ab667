"""Part meshes and STEP: the tolerance table the README publishes.

Run: ``python benchmarks/bench_parts.py [TEMPLATE ...] [--no-step]`` (default: every
template). For each template and chordal tolerance (module/50 ... module/2000) it builds
hub and sleeve from scratch and prints triangles, build time (cold: grid sampling and
assembly, median of 3), the measured largest distance from exact kernel points (flanks to
the crown ends, fillets, tip, root, circles; 3000 per surface kind) to the mesh, and the
volume change against the next finer tolerance. Then, with the ``step`` extra, the STEP
solids at the default tolerance: build and write time, file size, read-back volume and
its difference from the finest mesh. Markdown tables on stdout.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import gearcoupling as gc
from gearcoupling.parts import build_part, default_tolerance
from gearcoupling.parts.deviation import measure_deviation
from gearcoupling.parts.hub import hub_layout
from gearcoupling.parts.sleeve import sleeve_layout
from gearcoupling.parts.validity import check_part

PER_MODULE = (1 / 50, 1 / 200, 1 / 1000, 1 / 2000)


def cold_build(spec, part, tol, repeat=3):
    times = []
    for _ in range(repeat):
        hub_layout.cache_clear()
        sleeve_layout.cache_clear()
        t0 = time.perf_counter()
        mesh = build_part(spec, part, tolerance_mm=tol)
        times.append(time.perf_counter() - t0)
    return mesh, float(np.median(times))


def mesh_table(spec) -> list[dict]:
    rows = []
    for part in ("hub", "sleeve"):
        built = []
        for f in PER_MODULE:
            tol = round(spec.tooth.module * f, 6)
            mesh, seconds = cold_build(spec, part, tol)
            check = check_part(mesh)
            dev = measure_deviation(spec, mesh, samples=3000)["max"]
            built.append((tol, mesh, seconds, dev, check.ok))
        for i, (tol, mesh, seconds, dev, ok) in enumerate(built):
            finer = built[i + 1][1].volume if i + 1 < len(built) else None
            rows.append({"part": part, "tol": tol, "triangles": len(mesh.faces),
                         "seconds": seconds, "dev": dev, "volume": mesh.volume,
                         "dv": None if finer is None else (mesh.volume - finer) / finer,
                         "valid": ok})
    return rows


def print_mesh_table(name, rows) -> None:
    print(f"\n#### {name}\n")
    print("| part | tolerance mm | triangles | build s | measured max deviation mm "
          "| deviation / tolerance | volume mm³ | volume change vs next finer | valid |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        dv = "—" if r["dv"] is None else f"{r['dv']:+.2e}"
        print(f"| {r['part']} | {r['tol']:g} | {r['triangles']} | {r['seconds']:.2f} "
              f"| {r['dev']:.2e} | {r['dev'] / r['tol']:.2f} | {r['volume']:.6g} | {dv} "
              f"| {'yes' if r['valid'] else 'NO'} |")


def step_rows(spec, reference: dict[str, float]) -> list[str]:
    from gearcoupling.export import export_part, read_step_volume

    tol = default_tolerance(spec)
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for part in ("hub", "sleeve"):
            hub_layout.cache_clear()
            sleeve_layout.cache_clear()
            t0 = time.perf_counter()
            path = export_part(spec, part, Path(tmp) / f"{part}.step", tolerance_mm=tol)
            seconds = time.perf_counter() - t0
            volume = read_step_volume(path)
            ref = reference[part]
            out.append(f"| {spec.name} | {part} | {tol:g} | {seconds:.1f} "
                       f"| {path.stat().st_size / 1e6:.2f} | {volume:.6g} "
                       f"| {(volume - ref) / ref:+.1e} |")
    return out


def main(argv: list[str]) -> int:
    names = [a for a in argv if not a.startswith("--")] or gc.template_names()
    with_step = "--no-step" not in argv
    step_lines = []
    for name in names:
        spec = gc.load_spec(name)
        rows = mesh_table(spec)
        print_mesh_table(name, rows)
        finest = {r["part"]: r["volume"] for r in rows if r["dv"] is None}
        if with_step:
            try:
                step_lines += step_rows(spec, finest)
            except gc.BackendError as err:
                print(f"\nSTEP skipped: {err}")
                with_step = False
    if step_lines:
        print("\n#### STEP at the default tolerance (module / 200)\n")
        print("| template | part | tolerance mm | build + write s | file MB | read-back volume "
              "mm³ | vs finest mesh volume |")
        print("|---|---|---|---|---|---|---|")
        print("\n".join(step_lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
