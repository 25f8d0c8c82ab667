"""``gearcoupling view``: the browser 3D viewer (viser), or its static HTML with ``--html``."""

from __future__ import annotations

import sys
import time
from typing import Any

from ..errors import ArgumentError
from ..interrupts import reset as forget_interrupt
from ..io import writable_file
from ..outputs import ALIGNMENT_SETTINGS
from ..viewer import (
    COLOR_MODES,
    CUTAWAYS,
    FRAMES,
    LOD_DIVISORS,
    AssemblySettings,
    ViewSettings,
    check_pose,
    exposure_warning,
    lod_tolerance,
    serve,
    write_html,
)
from .common import (
    add_alignment_arguments,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    finite_float,
    misalignment_deg,
    output_dir,
    positive,
    positive_length,
    writing_into,
)
from .engagement import checked_spec

MAX_SERVE_S = 365 * 24 * 3600.0  # a year (time.sleep overflows far beyond)


def register(sub) -> None:
    p = sub.add_parser("view", help="3D viewer in the browser (viser) or a static HTML scene")
    add_spec_arguments(p)
    p.add_argument("--host", default="127.0.0.1",
                   help="address to serve on (default 127.0.0.1, this machine only; another "
                        "address exposes the viewer and its save button to the network)")
    p.add_argument("--port", type=count(1, 65535), default=8080,
                   help="port (default 8080; if taken, the next free one of the following "
                        "few is used)")
    add_misalignment_argument(p)
    p.add_argument("--angle", type=finite_float, default=0.0, metavar="DEG",
                   help="start rotation psi in degrees (default 0)")
    p.add_argument("--cutaway", choices=CUTAWAYS, default="quarter",
                   help="part of the sleeve removed to show the teeth (default quarter)")
    p.add_argument("--frame", choices=FRAMES, default="sleeve",
                   help="what stays still: the sleeve (the hub wobbles in it) or the ground "
                        "(both members turn; default sleeve)")
    p.add_argument("--color-by", choices=COLOR_MODES, default="clearance",
                   help="flank colours: clearance, or separation (clearance minus the "
                        "flank's smallest: 0 where torque makes first contact)")
    p.add_argument("--lod", choices=tuple(LOD_DIVISORS), default="coarse",
                   help="mesh level of detail: chordal tolerance module/20, /100, /400")
    p.add_argument("--tolerance", type=positive_length, default=None, metavar="MM",
                   help="chordal tolerance of the meshes in mm (overrides --lod)")
    p.add_argument("--html", metavar="FILE", default=None,
                   help="write a self-contained HTML of the scene to FILE and exit")
    p.add_argument("--serve-seconds", type=positive("s", MAX_SERVE_S), default=None,
                   metavar="S", help=f"stop the server after S seconds, at most {MAX_SERVE_S:g} "
                   "(default: until Ctrl-C)")
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def whole_settings(args, alignment: dict[str, Any]) -> AssemblySettings:
    """A double-engagement spec's view: the whole coupling at the alignment the options
    change (``--frame`` is a single engagement's: refused unless left at its default)."""
    if args.frame != "sleeve":
        raise ArgumentError("--frame", args.frame, "not for a double-engagement spec: its "
                            "view is the coupling frame (shaft A's), every part placed")
    _, psi = check_pose(0.0, args.angle, ("--misalignment", "--angle"))
    return AssemblySettings(**{ALIGNMENT_SETTINGS[k]: v for k, v in alignment.items()},
                            psi_deg=psi,
                            cutaway=args.cutaway, color_mode=args.color_by)


def run(args) -> int:
    spec, alignment = checked_spec(args)
    if args.html is not None:
        writing_into(writable_file(args.html, "--html").parent, create=False)
    settings: ViewSettings | AssemblySettings
    if spec.coupling.engagements == 2:
        settings = whole_settings(args, alignment)
    else:
        mis, psi = check_pose(misalignment_deg(args, spec), args.angle,
                              ("--misalignment", "--angle"))
        settings = ViewSettings(misalignment_deg=mis, psi_deg=psi, cutaway=args.cutaway,
                                color_mode=args.color_by, frame=args.frame)
    tol = lod_tolerance(spec, args.lod) if args.tolerance is None else args.tolerance
    if args.html is not None:
        t0 = time.perf_counter()
        path = write_html(spec, args.html, settings=settings, tolerance_mm=tol)
        print(f"{path} ({path.stat().st_size / 1e6:.2f} MB, "
              f"{time.perf_counter() - t0:.1f} s)")
        return 0

    warning = exposure_warning(args.host)
    if warning:
        print(f"gearcoupling: warning: {warning}", file=sys.stderr)
    t0 = time.perf_counter()
    app = serve(spec, host=args.host, port=args.port, settings=settings, lod=args.lod,
                tolerance_mm=args.tolerance,
                html_path=output_dir(args, spec) / "viewer.html")
    print(f"gearcoupling viewer for {spec.name}: {app.url}  (scene ready in "
          f"{time.perf_counter() - t0:.2f} s; Ctrl-C to stop)", flush=True)
    try:
        if args.serve_seconds is not None:
            time.sleep(args.serve_seconds)
        else:
            while True:
                time.sleep(3600)
    except KeyboardInterrupt:  # the server's way to stop: not an interruption
        forget_interrupt()
        print("stopping", file=sys.stderr)
    finally:
        app.stop()
    return 0
