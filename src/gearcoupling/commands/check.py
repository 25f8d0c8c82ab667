"""``gearcoupling check``: interference and minimum gap of the posed meshes over rotation.

Writes ``interference.csv`` (one row per angle), ``interference.json`` (settings, timings,
every overlap), ``interference.png`` (overlap volume and signed minimum gap against the
angle, with the semi-analytic sweep's smallest normal clearance) and the posed meshes of
the worst pose (``worst_hub.stl``, ``worst_sleeve.stl``, ``worst_overlap.stl``), prints a
table of the worst angles, and exits with status 1 when any pose overlaps.
"""

from __future__ import annotations

import argparse

import numpy as np

from ..interference import check_interference
from ..outputs import files, write_interference
from . import whole
from .common import (
    MAX_TEETH,
    add_alignment_arguments,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    number_in,
    output_dir,
    positive_length,
    progress,
)
from .engagement import checked_spec
from .folders import claim, holds_folders

EXIT_INTERFERENCE = 1
MAX_CHECK_ANGLES = 3600  # every pose is a mesh boolean: the count bounds the run
MAX_HALF_WINDOW = MAX_TEETH // 2  # 2K+1 teeth cover the largest coupling


def _teeth(text: str) -> str | int:
    if text in ("sweep", "all"):
        return text
    try:
        return count(0, MAX_HALF_WINDOW)(text)
    except argparse.ArgumentTypeError as err:
        raise argparse.ArgumentTypeError(f"{text!r}: use 'sweep', 'all' or a half window K "
                                         f"from 0 to {MAX_HALF_WINDOW}") from err


def register(sub) -> None:
    p = sub.add_parser("check", help="interference and minimum gap of the posed part meshes "
                       "over rotation (exit status 1 when they overlap)")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--angles", type=count(1, MAX_CHECK_ANGLES), default=72, metavar="N",
                   help=f"rotation angles evenly spaced over a turn, 1-{MAX_CHECK_ANGLES} "
                        "(default 72)")
    p.add_argument("--method", choices=("boolean", "distance"), default="boolean",
                   help="overlap by manifold3d booleans (exact volume, default) or by "
                        "signed distances (faster, estimated volume)")
    p.add_argument("--tolerance", type=positive_length, default=None, metavar="MM",
                   help="chordal tolerance of the meshes (default: module / 200)")
    p.add_argument("--teeth", type=_teeth, default="sweep", metavar="sweep|all|K",
                   help="model: tooth pairs chosen by the sweep (default), windows of 2K+1 "
                        "teeth there, or the full parts")
    p.add_argument("--hub-rotation", type=number_in(-30.0, 30.0, "degrees"), default=0.0,
                   metavar="DEG", help="extra turn of the hub about its axis in degrees, "
                   "below half a tooth pitch (+ closes ccw flanks)")
    p.add_argument("--backlash", action="store_true",
                   help="also measure the free turn of the hub on the meshes (backlash)")
    p.add_argument("--worst", type=count(1, MAX_CHECK_ANGLES), default=10, metavar="N",
                   help=f"rows of the worst-angle table, 1-{MAX_CHECK_ANGLES} (default 10)")
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def overlapping_teeth(result, index: int, shown: int = 4) -> str:
    """The hub teeth overlapping at angle ``index``: the first ``shown`` and how many more,
    or "none"."""
    teeth = result.teeth_involved(index)
    if not teeth:
        return "none"
    more = len(teeth) - shown
    return " ".join(map(str, teeth[:shown])) + (f" +{more}" if more > 0 else "")


def print_table(result, count: int) -> None:
    from rich.console import Console
    from rich.table import Table

    t = Table(title=f"worst angles: {result.spec_name}, i = {result.misalignment_deg:g}°, "
                    f"{result.method} on {result.model}")
    for col in ("ψ°", "overlap mm³", "depth mm", "gap mm", "overlapping teeth",
                "at tooth: hub/sleeve"):
        t.add_column(col, justify="right", overflow="fold")
    for j in result.worst(count):
        t.add_row(f"{result.angles_deg[j]:.2f}", f"{result.overlap_volume_mm3[j]:.4g}",
                  f"{result.overlap_depth_mm[j]:.5f}", f"{result.min_gap_mm[j]:+.5f}",
                  overlapping_teeth(result, j),
                  f"{result.gap_tooth[j]}: {result.gap_hub_surface[j]}/"
                  f"{result.gap_sleeve_surface[j]}")
    console = Console()
    console.print(t)
    if result.backlash_mm is not None:
        console.print(f"mesh backlash at the pitch radius: {result.backlash_mm.min():.5f} .. "
                      f"{result.backlash_mm.max():.5f} mm")
    console.print(f"triangles hub/sleeve {result.triangles[0]}/{result.triangles[1]}, setup "
                  f"{result.setup_seconds:.2f} s, {1e3 * result.seconds_per_pose:.1f} ms per "
                  f"pose; {'INTERFERENCE' if result.interferes else 'no interference'}")


@holds_folders
def run(args) -> int:
    spec, alignment = checked_spec(args)
    if spec.coupling.engagements == 2:
        return whole.check(args, spec, alignment)
    mis = misalignment_deg(args, spec)
    angles = 360.0 * np.arange(args.angles) / args.angles
    out = claim(output_dir(args, spec), spec.to_dict(), files.INTERFERENCE)
    with progress(f"check {spec.name}", args.angles) as update:
        result = check_interference(spec, mis, angles, method=args.method,
                                    tolerance_mm=args.tolerance, teeth=args.teeth,
                                    hub_rotation_deg=args.hub_rotation,
                                    backlash=args.backlash, progress=update)
    written = write_interference(spec, result, out)
    print_table(result, args.worst)
    for path in written:
        print(path)
    return EXIT_INTERFERENCE if result.interferes else 0
