"""``gearcoupling fea``: quadratic tetrahedral meshes of hub and sleeve sectors.

Writes ``<part>-sector-<k>.<ext>`` (``<part>-whole.<ext>`` with ``--whole``) in the formats
asked (inp, msh, vtu) and ``fea_mesh.json`` with the element quality, the region ids of the
MSH/VTU files and the sets of the INP.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

from ..export import formats as volume_formats
from ..fea import check_size, fillet_notes, mesh_part, region_ids, sector_teeth, write_mesh
from ..io import write_json
from ..spec import CouplingSpec
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
from .generate import PART_NAMES, parse_list


def register(sub) -> None:
    p = sub.add_parser("fea", help="write FE-ready quadratic tet meshes (INP, MSH, VTU)")
    add_spec_arguments(p)
    p.add_argument("--parts", default="hub,sleeve", metavar="LIST",
                   help="comma-separated parts: hub, sleeve (default: both)")
    p.add_argument("--sector", type=count(1, MAX_TEETH), default=3, metavar="K",
                   help="teeth in the sector, 1 to the number of teeth (default 3)")
    p.add_argument("--whole", action="store_true", help="mesh the whole parts")
    p.add_argument("--size", type=positive_length, default=None, metavar="MM",
                   help="element size on the teeth in mm, > 0 (default module / 4)")
    p.add_argument("--format", dest="formats", default=",".join(volume_formats("volume")),
                   metavar="LIST", help="comma-separated: "
                   f"{', '.join(volume_formats('volume'))} (default: all)")
    p.set_defaults(func=run)


MESH_REPORT = "fea_mesh.json"


def _stem(teeth: list[int] | None) -> str:
    """``whole``, or ``sector-<k>`` for ``k`` teeth: the middle of the mesh files' names."""
    return "whole" if teeth is None else f"sector-{len(teeth)}"


def fea_meshes(spec: CouplingSpec, out: Path, parts, formats, *, sector=3, size_mm=None,
               progress: Callable[[int, int], None] | None = None) -> tuple[list[Path], dict]:
    """Mesh every part and write every format; returns the files and the report."""
    teeth = sector_teeth(spec, sector)
    for part in parts:  # refuse a bad size before any meshing
        check_size(spec, part, size_mm)
    stem = _stem(teeth)
    written: list[Path] = []
    report: dict = {"spec": spec.name, "teeth": teeth, "parts": {}}
    for part in parts:
        vm = mesh_part(spec, part, sector=sector, size_mm=size_mm)
        files = [write_mesh(vm, out / f"{part}-{stem}.{ext}") for ext in formats]
        written += files
        report["parts"][part] = {"size_mm": vm.size_mm, **vm.quality,
                                 "region_ids": region_ids(vm), "sets": vm.set_names(),
                                 "files": [f.name for f in files]}
        if progress:
            progress(len(report["parts"]), len(parts))
    written.append(write_json(out / MESH_REPORT, report))
    return written, report


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    parts = parse_list(args.parts, PART_NAMES, "--parts")
    fmts = parse_list(args.formats, volume_formats("volume"), "--format")
    sector = None if args.whole else args.sector

    stem = _stem(sector_teeth(spec, sector))
    for part in parts:
        check_size(spec, part, args.size)
    for note in fillet_notes(spec, args.size, parts):
        print(f"{spec.name}: {note}", file=sys.stderr)
    out = claim(output_dir(args, spec), spec.to_dict(),
                [*(f"{part}-{stem}.{ext}" for part in parts for ext in fmts), MESH_REPORT])
    with progress(f"{spec.name} volume meshes", len(parts)) as update:
        written, report = fea_meshes(spec, out, parts, fmts, sector=sector,
                                     size_mm=args.size, progress=update)
    for part, info in report["parts"].items():
        print(f"{part}: {info['nodes']} nodes, {info['elements']} C3D10, min scaled Jacobian "
              f"{info['min_scaled_jacobian']:.3f}, max aspect ratio "
              f"{info['max_aspect_ratio']:.3g}", file=sys.stderr)
    for path in written:
        print(path)
    return 0
