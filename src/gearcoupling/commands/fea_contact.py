"""``gearcoupling fea-contact``: the aligned CalculiX contact reference of a spec.

Writes ``fea_contact.json`` (wind-up, wind-up beyond first touch, tooth load against
equilibrium, peak and interior pressure, patch extent, mesh size, solver time and memory)
and keeps the deck, log and printout in ``fea_contact/`` beside it.
"""

from __future__ import annotations

import sys

from ..errors import ArgumentError
from ..fea import ccx_path, check_size, fe_contact, gmsh_module
from ..io import write_json
from .common import add_spec_arguments, number_in, output_dir, positive_length, spec_from_args
from .load import MAX_TORQUE_NM


def register(sub) -> None:
    p = sub.add_parser("fea-contact", help="CalculiX contact reference of the aligned coupling "
                                           "(one pitch, cyclic symmetry, loaded by the torque)")
    add_spec_arguments(p)
    p.add_argument("--torque", type=number_in(0.0, MAX_TORQUE_NM, "N·m", open_lo=True),
                   default=None, metavar="NM", help="torque in N·m, > 0 (default: the spec's)")
    p.add_argument("--misalignment", type=float, default=0.0, metavar="DEG",
                   help="0 only (the one-pitch reference holds for aligned shafts)")
    p.add_argument("--size", type=positive_length, default=None, metavar="MM",
                   help="element size on the teeth in mm (default module / 4)")
    p.add_argument("--contact-size", type=positive_length, default=None, metavar="MM",
                   help="element size on the loaded flanks near mid-face, the accuracy "
                        "knob (default --size; docs/fea.md has the convergence table)")
    p.set_defaults(func=run)


def run(args) -> int:
    spec = spec_from_args(args)
    if args.misalignment != 0:
        raise ArgumentError("--misalignment", args.misalignment, "0 only: the one-pitch "
                            "cyclic reference holds for aligned shafts")
    for part in ("hub", "sleeve"):
        check_size(spec, part, args.size)
        check_size(spec, part, args.contact_size)
    gmsh_module()
    ccx_path()
    out = output_dir(args, spec)
    print(f"{spec.name}: meshing and solving one pitch in contact (minutes)", file=sys.stderr)
    res = fe_contact(spec, torque_Nm=args.torque, misalignment_deg=args.misalignment,
                     size_mm=args.size, contact_size_mm=args.contact_size,
                     workdir=out / "fea_contact")
    print(f"{spec.name}: wind-up {res.windup_from_first_touch_rad * 1e6:.1f} µrad beyond first "
          f"touch at {res.torque_Nm:g} N·m; tooth load {res.tooth_load_N:.1f} N "
          f"(equilibrium {res.equilibrium_tooth_load_N:.1f} N); interior pressure "
          f"{res.interior_pressure_MPa:.0f} MPa", file=sys.stderr)
    print(write_json(out / "fea_contact.json", res.to_dict()))
    return 0
