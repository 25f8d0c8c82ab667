"""Write ``benchmarks/RESULTS.md``: the figures of the benchmarks, stamped with the machine,
the versions and the commit they were measured on.

Run: ``python benchmarks/results.py [--full] [--only NAME ...]``. Each benchmark runs as its
own process (its printed tables are copied verbatim); ``--full`` adds the slow ones (FE
convergence and contact, studies on Dask, random specs). Figures are medians of repeated
runs where the benchmark repeats; they depend on the machine's load, which is recorded.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time
from importlib import metadata
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
# (name, arguments, what it measures); the slow ones only with --full
QUICK = [
    ("bench_import.py", [], "time of `import gearcoupling`"),
    ("bench_geometry.py", [], "flank and section kernels: time and error"),
    ("bench_sweep.py", ["--quick"], "clearance sweep: time and accuracy"),
    ("bench_load.py", ["--quick"], "load models, capacity, Renzo's q and examples"),
    ("bench_surface.py", ["--quick"], "surface model: grid trade and speed"),
    ("bench_parts.py", ["--no-step"], "part meshes: time, size, deviation"),
    ("bench_hob.py", [], "hob program: chordal deviation and time"),
    ("bench_report.py", [], "the design report: time per section"),
]
FULL = [
    ("bench_fea.py", [], "FE: cantilever check, convergence, FE vs cantilever vs ISO"),
    ("bench_springs.py", ["--random", "55", "--no-compute"],
     "the default tooth springs (fe-fit) against every cached FE tooth table"),
    ("bench_default.py", ["--random", "55", "--no-compute"],
     "the default model and springs against surface with FE springs: capacity, tooth load"),
    ("bench_load_study.py", [], "the surface model's load studies: cost and accuracy"),
    ("bench_fea_contact.py", ["--from-golden"],
     "the load models against the stored CalculiX contact references (aligned)"),
    ("bench_fea_sector.py", ["--stored", "--sectors", "5"],
     "misaligned FE sector: the models at equal wind-up (the stored FE runs)"),
    ("bench_bodies.py", ["--stored"],
     "the bodies tooth by tooth: FE rings, the influence model, the sector's own bodies"),
    ("bench_study.py", [], "studies on dask.distributed"),
    ("bench_random_specs.py", [], "1000 seeded random specs: accepted, finite, closed parts"),
]
PACKAGES = ("numpy", "scipy", "trimesh", "manifold3d", "matplotlib", "numba", "gmsh",
            "dask", "viser")


def stamp() -> list[str]:
    """Machine, versions, commit and load of this measurement."""
    def version(p: str) -> str:
        try:
            return metadata.version(p)
        except metadata.PackageNotFoundError:
            return "absent"

    commit = _commit()
    ccx = subprocess.run(["sh", "-c", "ccx -v 2>&1 | head -3"], capture_output=True,
                         text=True).stdout.split("Version")[-1].strip().split("\n")[0]
    return [
        f"- measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} on commit "
        f"`{commit}`",
        f"- machine: {platform.machine()}, {os.cpu_count()} cores, "
        f"{platform.system()} {platform.release()}; load average at the start "
        f"{os.getloadavg()[0]:.2f}",
        f"- Python {platform.python_version()}; " + ", ".join(
            f"{p} {version(p)}" for p in PACKAGES) + (f"; CalculiX {ccx}" if ccx else ""),
    ]


def _commit() -> str:
    return subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                          capture_output=True, text=True).stdout.strip() or "unknown"


def _sections(text: str) -> dict[str, list[str]]:
    """The sections of an existing RESULTS.md by benchmark file name (after the stamp)."""
    out: dict[str, list[str]] = {}
    name = None
    for line in text.splitlines():
        if line.startswith("## `"):
            name = line[4:].split()[0].rstrip("`")
            out[name] = []
        if name is not None:
            out[name].append(line)
    return out


def run(name: str, args: list[str]) -> tuple[str, float, int]:
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, str(HERE / name), *args], cwd=ROOT,
                         capture_output=True, text=True, timeout=6 * 3600)
    text = out.stdout.strip() or out.stderr.strip()[-2000:]
    return text, time.perf_counter() - t0, out.returncode


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--full", action="store_true", help="also the slow benchmarks")
    p.add_argument("--only", nargs="*", default=None,
                   help="benchmark file names: these are run again, the other sections of "
                        "RESULTS.md are kept")
    a = p.parse_args(argv)
    chosen = QUICK + (FULL if a.full else [])
    if a.only:
        chosen = [c for c in QUICK + FULL if c[0] in a.only]
    lines = ["# Benchmark results", "",
             "Written by `python benchmarks/results.py` (do not edit by hand). Each section is "
             "the output of one benchmark, run as its own process.", "", *stamp(), ""]
    target = HERE / "RESULTS.md"
    kept = {}
    if a.only and target.exists():  # the stamp stays that of the kept sections
        old = target.read_text()
        head = old.split("\n## `", 1)[0].rstrip("\n").splitlines()
        note = "Sections measured later say so under their title."
        lines = [*head, *([] if note in head else ["", note]), ""]
        kept = _sections(old)
    for name, args, what in chosen:
        if not (HERE / name).is_file():
            continue
        print(f"running {name} {' '.join(args)}", file=sys.stderr)
        text, seconds, rc = run(name, args)
        status = "" if rc == 0 else f" — exited {rc}"
        kept[name] = [f"## `{' '.join([name, *args])}`", "",
                      f"{what} ({seconds:.0f} s{status})", "", "```", text, "```", ""]
        if a.only:
            kept[name].insert(3, f"(measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}"
                                 f" on `{_commit()}`, load average {os.getloadavg()[0]:.2f})")
            kept[name].insert(4, "")
    order = [c[0] for c in QUICK + FULL]
    for name in sorted(kept, key=lambda n: order.index(n) if n in order else len(order)):
        lines += kept[name]
    tmp = target.with_suffix(".md.tmp")
    tmp.write_text("\n".join(lines))
    tmp.replace(target)
    print(target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
