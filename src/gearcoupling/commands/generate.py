"""``gearcoupling generate``: hub and sleeve solids as meshes and STEP files.

Writes ``<part>.<ext>`` (``<part>-teeth-<list>.<ext>`` for a sector) for every requested
part and format, and ``parts.json`` with the tolerance, triangle count, volume, validity
and files of each part.
"""

from __future__ import annotations

import sys
from importlib.util import find_spec
from typing import Any

from ..arguments import parse_count
from ..coupling import coupling_assembly, spec_geometry
from ..errors import ArgumentError
from ..export import formats as registered
from ..outputs import ALIGNMENT_SETTINGS, PART_NAMES, files, write_parts
from ..spec import CouplingSpec
from .common import (
    add_alignment_arguments,
    add_spec_arguments,
    output_dir,
    positive_length,
    progress,
)
from .engagement import checked_spec
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("generate", help="write hub and sleeve solids (STL, STEP, VTU, ...)")
    add_spec_arguments(p)
    p.add_argument("--parts", default="hub,sleeve", metavar="LIST",
                   help="comma-separated parts: hub, sleeve (default: both)")
    p.add_argument("--tolerance", type=positive_length, default=None, metavar="MM",
                   help="chordal tolerance in mm, > 0 (default: module / 200)")
    p.add_argument("--format", dest="formats", default="stl", metavar="LIST",
                   help=f"comma-separated file formats: {', '.join(registered())} "
                        "(default: stl)")
    p.add_argument("--teeth", default=None, metavar="LIST",
                   help="only these teeth, e.g. 0,1,2,49 or 0-2,49 (a sector; default all)")
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def parse_list(text: str, allowed, option: str) -> list[str]:
    """Comma-separated choices, each checked against ``allowed``."""
    items = [t.strip().lower() for t in text.split(",") if t.strip()]
    bad = [t for t in items if t not in allowed]
    if bad or not items:
        raise ArgumentError(option, text, f"comma-separated values from {', '.join(allowed)}")
    return list(dict.fromkeys(items))


def parse_teeth(text: str | None, teeth: int) -> list[int] | None:
    """``"0-2,49"`` -> ``[0, 1, 2, 49]``; ``None`` -> all teeth."""
    if text is None:
        return None
    out: list[int] = []
    try:
        for item in text.split(","):
            lo, _, hi = item.strip().partition("-")
            first, last = parse_count(lo, "--teeth"), parse_count(hi or lo, "--teeth")
            if not 0 <= first <= last < teeth:  # before building a range (no MemoryError)
                raise ArgumentError("--teeth", text, f"tooth indices or ascending ranges from 0 "
                                f"to {teeth - 1}")
            out.extend(range(first, last + 1))
    except ValueError as err:
        raise ArgumentError("--teeth", text, "tooth indices or ranges, e.g. 0,1,2,49 or 0-2,49") \
            from err
    if not out or min(out) < 0 or max(out) >= teeth:
        raise ArgumentError("--teeth", text, f"tooth indices from 0 to {teeth - 1}")
    return sorted(set(out))


def assembly_files() -> tuple[str, ...]:
    """What :func:`write_assembly` writes: the glTF scene, and the STEP assembly where
    OpenCASCADE is installed (the ``step`` extra)."""
    return ("coupling.glb", *(("coupling.step",) if find_spec("OCP") else ()))


def write_assembly(spec: CouplingSpec, out, alignment: dict[str, Any],
                   tolerance_mm: float | None) -> list:
    """A double-engagement spec's parts placed at its alignment (rotation 0):
    ``coupling.glb`` (one named node per part) and ``coupling.step`` (AP214, every part a
    named solid at its placement; without OpenCASCADE a note says so)."""
    geom = spec_geometry(spec, {ALIGNMENT_SETTINGS[k]: v for k, v in alignment.items()})
    asm = coupling_assembly(spec, geom.layout, geom.alignment)
    written = [asm.write_glb(out / "coupling.glb", tolerance_mm)]
    if "coupling.step" in assembly_files():
        written.append(asm.write_step(out / "coupling.step", tolerance_mm))
    else:
        print("gearcoupling: coupling.step not written: STEP files need OpenCASCADE: pip "
              "install 'gearcoupling[step]'", file=sys.stderr)
    return written


@holds_folders
def run(args) -> int:
    spec, alignment = checked_spec(args)
    double = spec.coupling.engagements == 2
    parts = parse_list(args.parts, PART_NAMES, "--parts")
    fmts = parse_list(args.formats, registered(), "--format")
    teeth = parse_teeth(args.teeth, spec.tooth.teeth)
    if double and teeth is not None:
        raise ArgumentError("--teeth", args.teeth, "not for a double-engagement spec: its "
                            "assembly places whole parts")
    out = claim(output_dir(args, spec), spec.to_dict(),
                [*files.part_files(parts, fmts, teeth), *(assembly_files() if double else ())])
    with progress(f"{spec.name} parts", len(parts) * (1 + len(fmts))) as update:
        written, report = write_parts(spec, out, parts, fmts, args.tolerance, teeth,
                                      progress=update)
    if double:
        written += write_assembly(spec, out, alignment, args.tolerance)
    for part, info in report["parts"].items():
        state = "valid" if info["valid"] else "INVALID: " + "; ".join(info["problems"])
        print(f"{part}: {info['triangles']} triangles, {info['volume_mm3']:.6g} mm³, measured "
              f"deviation {info['measured_deviation_mm']:.3g} mm, {state}", file=sys.stderr)
    for path in written:
        print(path)
    return 0 if all(i["valid"] for i in report["parts"].values()) else 1
