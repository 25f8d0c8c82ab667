"""``gearcoupling stiffness``: tooth compliance and mesh stiffness from CalculiX.

Writes ``stiffness.csv`` (one row per load point: hub, sleeve and pair compliance, pair
stiffness, fillet stress per N) and ``stiffness.json`` (the table, the pitch-point figures
and the set-up: supports, sizes, times). The table is cached per spec hash and settings,
used only when its key and checksum match (see
:func:`gearcoupling.fea.tooth_compliance_table`); the cache folder is checked before the FE
runs.
"""

from __future__ import annotations

import csv
import io
import sys
from pathlib import Path

from ..errors import ArgumentError
from ..fea import (
    ccx_path,
    check_size,
    fe_cache_folder,
    fillet_notes,
    gmsh_module,
    pitch_point_compliance,
    tooth_compliance_table,
)
from ..io import write_json, write_text
from .common import (
    MAX_TEETH,
    add_spec_arguments,
    count,
    output_dir,
    positive_length,
    progress,
    spec_from_args,
)
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("stiffness", help="FE tooth compliance and mesh stiffness (CalculiX)")
    add_spec_arguments(p)
    p.add_argument("--size", type=positive_length, default=None, metavar="MM",
                   help="element size on the teeth in mm, > 0 (default module / 4)")
    p.add_argument("--sector", type=count(1, MAX_TEETH), default=3, metavar="K",
                   help="teeth per sector, odd, at most the number of teeth; the middle one "
                        "is loaded (default 3)")
    p.add_argument("--nz", type=count(2, 9), default=3, metavar="N",
                   help="axial load positions, 2-9 (default 3)")
    p.add_argument("--nr", type=count(2, 9), default=3, metavar="N",
                   help="load radii, 2-9 (default 3)")
    p.add_argument("--cache", default=None, metavar="DIR",
                   help="cache folder (default ~/.cache/gearcoupling/fea)")
    p.add_argument("--refresh", action="store_true", help="recompute, ignoring the cache")
    p.set_defaults(func=run)


FILES = ("stiffness.csv", "stiffness.json")


def write_table(table, out: Path) -> list[Path]:
    """``stiffness.csv`` and ``stiffness.json`` of a compliance table."""
    rows = table.rows()
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows({k: f"{v:.6g}" for k, v in row.items()} for row in rows)
    csv_path = write_text(out / FILES[0], buf.getvalue())
    summary = pitch_point_compliance(table)
    json_path = write_json(out / FILES[1], {"pitch_point": summary, **table.to_dict()})
    return [csv_path, json_path]


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    for part in ("hub", "sleeve"):
        check_size(spec, part, args.size, "--size")
    for note in fillet_notes(spec, args.size):
        print(f"{spec.name}: {note}", file=sys.stderr)
    if args.sector < 1 or args.sector % 2 == 0 or args.sector > spec.tooth.teeth:
        raise ArgumentError("--sector", args.sector, f"an odd number of teeth from 1 to "
                        f"{spec.tooth.teeth} (the middle tooth is loaded)")
    # before the FE runs, which write the cache at the end: --cache, GEARCOUPLING_CACHE or
    # the user's cache folder
    fe_cache_folder(args.cache, "--cache")
    gmsh_module()
    ccx_path()
    out = claim(output_dir(args, spec), spec.to_dict(), FILES)
    with progress(f"{spec.name} FE stiffness", 4) as update:
        table = tooth_compliance_table(spec, size_mm=args.size, sector=args.sector,
                                       nz=args.nz, nr=args.nr, cache=args.cache,
                                       refresh=args.refresh, progress=update)
    written = write_table(table, out)
    c = table.mesh_stiffness_N_per_mm
    print(f"{spec.name}: mesh stiffness C = {c:.4g} N/mm per tooth pair "
          f"({c / spec.hub.face_width / 1e3:.3g} N/(mm·µm) per hub face width); far field "
          f"at the pitch point {pitch_point_compliance(table)['pair_far_field_um_per_N']:.4g} "
          f"µm/N (the load models' springs with [load] stiffness = \"fe\"); "
          f"{table.z_mm.size * table.r_mm.size} load points", file=sys.stderr)
    for path in written:
        print(path)
    return 0
