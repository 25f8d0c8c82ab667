"""STEP size, build time and measured deviation per template and part.

    python benchmarks/bench_step.py [--samples 200] [--tolerance-per-module 0.005] [NAME ...]

For each part: write the STEP at the tolerance (default module / 200), read it back with
gmsh, and measure the distance from exact kernel points (``exact_samples``: crown ends,
tips, fillets, roots, flanks on random teeth, bore / outer cylinder) to the nearest face.
Prints one Markdown row per part: size, time to build and write, max deviation and its
ratio to the tolerance, and the read-back volume.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

import gearcoupling as gc
from gearcoupling.export import export_part
from gearcoupling.fea.backends import gmsh_initialize
from gearcoupling.parts.deviation import exact_samples


def gmsh_distance(gmsh, pts: np.ndarray, reach: float) -> np.ndarray:
    """Distance from each point to the nearest face whose bounding box is within reach."""
    best = np.full(len(pts), np.inf)
    for dim, tag in gmsh.model.getEntities(2):
        box = np.array(gmsh.model.getBoundingBox(dim, tag))
        near = np.all((pts >= box[:3] - 2 * reach) & (pts <= box[3:] + 2 * reach), axis=1)
        if near.any():
            closest, _ = gmsh.model.getClosestPoint(dim, tag, pts[near].ravel())
            d = np.linalg.norm(np.reshape(closest, (-1, 3)) - pts[near], axis=1)
            best[near] = np.minimum(best[near], d)
    return best


def measure(name: str, part: str, per_module: float, samples: int, out: Path) -> dict:
    import gmsh

    spec = gc.load_spec(name)
    tol = per_module * spec.tooth.module
    t0 = time.perf_counter()
    path = export_part(spec, part, out / f"{name}-{part}.step", tolerance_mm=tol)
    seconds = time.perf_counter() - t0
    gmsh_initialize(gmsh, readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        volume = sum(gmsh.model.occ.getMass(*v) for v in gmsh.model.getEntities(3))
        pts = np.concatenate(list(exact_samples(spec, part, samples, seed=7).values()))
        dev = float(gmsh_distance(gmsh, pts, tol).max())
    finally:
        gmsh.finalize()
    return {"name": name, "part": part, "tol": tol, "kB": path.stat().st_size / 1e3,
            "s": seconds, "dev": dev, "volume": volume, "points": len(pts)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", default=gc.template_names())
    ap.add_argument("--samples", type=int, default=200, help="exact points per surface kind")
    ap.add_argument("--tolerance-per-module", type=float, default=1 / 200)
    args = ap.parse_args()
    print("| template | part | tolerance mm | STEP kB | build+write s | max deviation mm "
          "| / tolerance | volume mm³ |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.names:
            for part in ("hub", "sleeve"):
                r = measure(name, part, args.tolerance_per_module, args.samples, Path(tmp))
                print(f"| {name} | {part} | {r['tol']:.4g} | {r['kB']:.0f} | {r['s']:.2f} | "
                      f"{r['dev']:.2e} | {r['dev'] / r['tol']:.2f} | {r['volume']:.1f} |",
                      flush=True)


if __name__ == "__main__":
    main()
