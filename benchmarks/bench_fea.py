"""FE meshes and CalculiX tooth stiffness: the tables docs/fea.md publishes.

Run: ``python benchmarks/bench_fea.py [cantilever] [table] [convergence] [compare]
[--specs A B] [--against OLD_CHECKOUT]`` (default all; the contact references are
``bench_fea_contact.py``, aligned, and ``bench_fea_sector.py``, misaligned).

- ``cantilever``: gmsh C3D10 + ccx tip deflection of a clamped 100 x 10 x 10 mm steel
  cantilever against Timoshenko at several element sizes.
- ``table``: the FE tooth-spring table of each spec at the default settings, each in a
  fresh Python: wall and CPU seconds; with ``--against`` also with another checkout's code
  (``git worktree add /tmp/old 18dde9b``) in the same run, and the change of the far field
  and the whole FE compliance at every grid point. Runs are kept in
  ``outputs/bench_fea_table.json`` (the other checkout's are reused).
- ``convergence``: the table's far field on a ladder of finer meshes (default, finer
  loaded flank, size / 1.4, size / 2) against the finest, every grid point; kept in
  ``outputs/bench_fea_convergence.json``.
- ``compare``: renzo-1967 and industrial-m2 at the default size: FE pair compliance and C
  at the pitch point against the tapered cantilever
  (``gearcoupling.loading.kernels.cantilever``) and ISO 6336's c' (single-pair stiffness
  14 N/(mm µm) of face width).

Markdown tables on stdout. The machine is shared: times are single runs, noisy.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from gearcoupling import load_spec
from gearcoupling.fea.stiffness import ComplianceTable, tooth_compliance_table
from gearcoupling.fea.validation import cantilever_tip_deflection

ROOT = Path(__file__).resolve().parent.parent
TEMPLATES = ("renzo-1967", "industrial-m2", "mill-spindle")

ISO_C_PRIME = 14.0  # N/(mm µm), ISO 6336-1 single-pair stiffness of a standard spur pair


def cantilever() -> None:
    print("\n### Cantilever (100 x 10 x 10 mm, clamped, 1 kN) vs Timoshenko\n")
    print("| size mm | C3D10 | FE tip mm | Timoshenko mm | FE / theory | solve s |")
    print("|---|---|---|---|---|---|")
    for size in (5.0, 2.5, 1.5):
        r = cantilever_tip_deflection(size)
        print(f"| {size} | {r['elements']} | {r['fe_mm']:.5f} | {r['theory_mm']:.5f} | "
              f"{r['ratio']:.4f} | {r['solve_seconds']:.1f} |")


def _table_in_subprocess(name: str, src: Path, **settings) -> dict:
    """Compute a spec's FE table with the code under ``src`` in a fresh Python (imports,
    CAD, meshes and solves all counted): wall and CPU seconds (its own and ccx's) and the
    table."""
    code = (
        "import json, resource, sys, time\n"
        "t0 = time.perf_counter()\n"
        "import gearcoupling as gc\n"
        "import gearcoupling.fea.stiffness as S\n"
        "kw = json.loads(sys.argv[2])\n"
        "for k in [k for k in kw if k.isupper()]: setattr(S, k, kw.pop(k))\n"
        "t = S.compute_compliance_table(gc.load_spec(sys.argv[1]), **kw)\n"
        "me = resource.getrusage(resource.RUSAGE_SELF)\n"
        "ccx = resource.getrusage(resource.RUSAGE_CHILDREN)\n"
        "print(json.dumps({'wall_s': time.perf_counter() - t0,\n"
        "                  'cpu_s': me.ru_utime + me.ru_stime,\n"
        "                  'ccx_cpu_s': ccx.ru_utime + ccx.ru_stime, 'table': t.to_dict()}))\n")
    env = dict(os.environ, PYTHONPATH=str(src))
    out = subprocess.run([sys.executable, "-c", code, name, json.dumps(settings)], env=env,
                         capture_output=True, text=True, check=True, cwd=src.parent)
    return json.loads(out.stdout.splitlines()[-1])


def _far_change(new: dict, old: dict) -> str:
    a, b = ComplianceTable.from_dict(new["table"]), ComplianceTable.from_dict(old["table"])
    d = 100 * (a.far_field_mm_per_N / b.far_field_mm_per_N - 1)
    return f"{d.min():+.1f} .. {d.max():+.1f} %"


def table(names=TEMPLATES, against: Path | None = None, store: Path | None = None) -> None:
    """The FE tooth-spring table per spec (default settings) with this checkout and, with
    ``against``, with another one (``git worktree add /tmp/old 18dde9b``) in the same run:
    seconds, and the change of the far field and of the whole FE compliance at every grid
    point."""
    store = store or ROOT / "outputs" / "bench_fea_table.json"
    runs = json.loads(store.read_text()) if store.exists() else {}
    checkouts = {"after": ROOT / "src"} | ({"before": against / "src"} if against else {})
    for name in names:
        for tag, src in checkouts.items():
            if tag == "before" and tag in runs.get(name, {}):
                continue  # the old code does not change: its run is kept
            runs.setdefault(name, {})[tag] = _table_in_subprocess(name, src)
            store.parent.mkdir(parents=True, exist_ok=True)
            store.write_text(json.dumps(runs))
    print("\n### FE tooth-spring table, default settings (wall s / CPU s: Python + ccx)\n")
    print("| spec | before s | after s | after CPU s (Python + ccx) | nodes hub + sleeve | "
          "far field change | whole FE change | C before → after N/mm |")
    print("|---|---|---|---|---|---|---|---|")
    for name in names:
        new, old = runs[name]["after"], runs[name].get("before")
        t = ComplianceTable.from_dict(new["table"])
        nodes = " + ".join(str(t.info["mesh"][p]["nodes"]) for p in ("hub", "sleeve"))
        cpu = f"{new['cpu_s'] + new['ccx_cpu_s']:.0f} ({new['cpu_s']:.0f} + {new['ccx_cpu_s']:.0f})"
        if old is None:
            print(f"| {name} | — | {new['wall_s']:.0f} | {cpu} | {nodes} | — | — | "
                  f"{t.mesh_stiffness_N_per_mm:.4g} |")
            continue
        o = ComplianceTable.from_dict(old["table"])
        fe = 100 * ((t.hub_mm_per_N + t.sleeve_mm_per_N)
                    / (o.hub_mm_per_N + o.sleeve_mm_per_N) - 1)
        print(f"| {name} | {old['wall_s']:.0f} | {new['wall_s']:.0f} | {cpu} | {nodes} | "
              f"{_far_change(new, old)} | {fe.min():+.1f} .. {fe.max():+.1f} % | "
              f"{o.mesh_stiffness_N_per_mm:.4g} → {t.mesh_stiffness_N_per_mm:.4g} |")


LADDER = (("default", {}), ("flank 0.25", {"FLANK_SIZE": 0.25}),
          ("size / 1.4, flank 0.35", {"size": 1 / 1.4}), ("size / 2", {"size": 0.5}))
"""The far field's convergence ladder: settings against the default (``size`` in units of
the default size module / 4; upper-case names are :mod:`gearcoupling.fea.stiffness`
constants)."""


def convergence(names=("renzo-1967",), store: Path | None = None) -> None:
    """The table's far field on a ladder of finer meshes (:data:`LADDER`): every grid point
    against the finest, and the old set-up's (``outputs/bench_fea_table.json``, ``table
    --against``) where it was run."""
    store = store or ROOT / "outputs" / "bench_fea_convergence.json"
    runs = json.loads(store.read_text()) if store.exists() else {}
    for name in names:
        m = load_spec(name).tooth.module
        for label, settings in LADDER:
            if label not in runs.get(name, {}):
                kw = {k: (v * m / 4 if k == "size" else v) for k, v in settings.items()}
                kw = {("size_mm" if k == "size" else k): v for k, v in kw.items()}
                runs.setdefault(name, {})[label] = _table_in_subprocess(name, ROOT / "src", **kw)
                store.parent.mkdir(parents=True, exist_ok=True)
                store.write_text(json.dumps(runs))
        finest = runs[name][LADDER[-1][0]]
        print(f"\n### {name}: far field against the finest mesh ({LADDER[-1][0]}), every grid "
              "point (|z| rows x r columns, row-major)\n")
        print("| mesh | nodes hub + sleeve | CPU s | far field µm/N | against the finest |")
        print("|---|---|---|---|---|")
        old = json.loads((ROOT / "outputs" / "bench_fea_table.json").read_text()).get(
            name, {}).get("before") if (ROOT / "outputs" / "bench_fea_table.json").exists() \
            else None
        rows = [(label, runs[name][label]) for label, _ in LADDER]
        rows += [("before (18dde9b set-up)", old)] if old else []
        for label, run in rows:
            t = ComplianceTable.from_dict(run["table"])
            nodes = " + ".join(str(t.info["mesh"][p]["nodes"]) for p in ("hub", "sleeve"))
            far = " ".join(f"{1e3 * v:.5f}" for v in t.far_field_mm_per_N.ravel())
            print(f"| {label} | {nodes} | {run['cpu_s'] + run['ccx_cpu_s']:.0f} | {far} | "
                  f"{_far_change(run, finest)} |")


def _cantilever_pair(spec):
    try:
        from gearcoupling.loading.kernels.cantilever import CantileverCompliance
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
        hub = float(t.interpolate(t.hub_mm_per_N, 0.0, R))
        sl = float(t.interpolate(t.sleeve_mm_per_N, 0.0, R))
        pair = hub + sl
        cant = _cantilever_pair(spec)
        iso = ISO_C_PRIME * 1e3 * b
        cant_txt = ("n/a", "n/a") if cant is None else (f"{1e3 * cant:.5f}",
                                                       f"{cant / pair:.2f}")
        print(f"| {name} | {b:g} | {1e3 * hub:.5f} | {1e3 * sl:.5f} | {1e3 * pair:.5f} | "
              f"{1 / pair:.4g} | {1 / pair / b / 1e3:.3g} | {cant_txt[0]} | {cant_txt[1]} | "
              f"{iso:.4g} | {iso * pair:.2f} | {secs:.0f} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("steps", nargs="*", default=["cantilever", "table", "convergence", "compare"])
    ap.add_argument("--specs", nargs="*", default=None)
    ap.add_argument("--against", type=Path, default=None,
                    help="another checkout (its src/ is imported) for the table's before")
    a = ap.parse_args()
    for step in a.steps:
        if step == "table":
            table(a.specs or TEMPLATES, a.against)
        elif step == "convergence":
            convergence(a.specs or ("renzo-1967",))
        else:
            {"cantilever": cantilever, "compare": compare}[step]()


if __name__ == "__main__":
    main()
