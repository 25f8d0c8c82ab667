"""``gearcoupling generate``: hub and sleeve solids as meshes and STEP files.

Writes ``<part>.<ext>`` (``<part>-teeth-<list>.<ext>`` for a sector) for every requested
part and format, and ``parts.json`` with the tolerance, triangle count, volume, validity
and files of each part.
"""

from __future__ import annotations

import sys

from ..arguments import parse_count
from ..errors import ArgumentError
from ..export import formats as registered
from ..outputs import PART_NAMES, files, write_parts
from .common import add_spec_arguments, output_dir, positive_length, progress, spec_from_args
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


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    parts = parse_list(args.parts, PART_NAMES, "--parts")
    fmts = parse_list(args.formats, registered(), "--format")
    teeth = parse_teeth(args.teeth, spec.tooth.teeth)
    out = claim(output_dir(args, spec), spec.to_dict(),
                files.part_files(parts, fmts, teeth))
    with progress(f"{spec.name} parts", len(parts) * (1 + len(fmts))) as update:
        written, report = write_parts(spec, out, parts, fmts, args.tolerance, teeth,
                                      progress=update)
    for part, info in report["parts"].items():
        state = "valid" if info["valid"] else "INVALID: " + "; ".join(info["problems"])
        print(f"{part}: {info['triangles']} triangles, {info['volume_mm3']:.6g} mm³, measured "
              f"deviation {info['measured_deviation_mm']:.3g} mm, {state}", file=sys.stderr)
    for path in written:
        print(path)
    return 0 if all(i["valid"] for i in report["parts"].values()) else 1
