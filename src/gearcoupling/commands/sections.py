"""``gearcoupling sections``: plot transverse sections and the crown along the face."""

from __future__ import annotations

from ..outputs import files
from ..plots import plot_sections
from .common import add_spec_arguments, output_dir, positive_length, progress, spec_from_args
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("sections", help="plot transverse sections and the axial crown view")
    add_spec_arguments(p)
    p.add_argument("--tolerance", type=positive_length, default=None, metavar="MM",
                   help="chordal tolerance of the plotted sections (default: module / 1000)")
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    out = claim(output_dir(args, spec), spec.to_dict(), files.SECTIONS)
    with progress(f"sections {spec.name}", 1) as update:
        path = plot_sections(spec, out / "sections.png", args.tolerance)
        update(1, 1)
    print(path)
    return 0
