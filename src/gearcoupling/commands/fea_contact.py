"""``gearcoupling fea-contact``: the CalculiX contact reference of a spec.

Aligned (``--misalignment 0``, the default): one pitch in cyclic symmetry, loaded by the
torque. Writes ``fea_contact.json`` (wind-up, wind-up beyond first touch, tooth load
against equilibrium, peak and interior pressure, patch extent, mesh size, solver time and
memory). Misaligned: the load model at the pose, then a sector of ``--sector`` teeth on its
most loaded tooth, turned by the model's wind-up plus the bodies' torsion; the JSON holds
both, tooth by tooth. The deck, log and printout stay in ``fea_contact/`` beside it.
"""

from __future__ import annotations

import sys

from ..arguments import TORQUE_RANGE_NM, resolve_torque_Nm
from ..errors import ArgumentError
from ..fea import ccx_path, check_size, fe_contact, fillet_notes, gmsh_module
from ..io import write_json
from ..loading import model_names, sector_check
from ..spec import MISALIGNMENT_RANGE_DEG
from .common import (
    add_spec_arguments,
    count,
    number_in,
    output_dir,
    positive_length,
    spec_from_args,
)
from .folders import claim, holds_folders

#: the JSON of the command and the folder of the solver's files beside it
REPORT, WORK = "fea_contact.json", "fea_contact"


def register(sub) -> None:
    p = sub.add_parser("fea-contact", help="CalculiX contact reference: one pitch in cyclic "
                                           "symmetry (aligned) or a sector (misaligned)")
    add_spec_arguments(p)
    p.add_argument("--torque", type=number_in(*TORQUE_RANGE_NM, "N·m"), default=None,
                   metavar="NM", help=f"torque in N·m, {TORQUE_RANGE_NM[0]:g} to "
                   f"{TORQUE_RANGE_NM[1]:g} (default: the spec's)")
    p.add_argument("--misalignment", type=number_in(*MISALIGNMENT_RANGE_DEG, "°"), default=0.0,
                   metavar="DEG", help="misalignment in degrees, 0 to 6 (default 0)")
    p.add_argument("--rotation", type=number_in(-360.0, 360.0, "°"), default=0.0,
                   metavar="DEG", help="turning angle of a misaligned pose (default 0)")
    p.add_argument("--sector", type=count(5, 299), default=5, metavar="K",
                   help="teeth in a misaligned pose's sector (default 5; docs/fea.md)")
    p.add_argument("--model", choices=model_names(), default=None,
                   help="load model a misaligned pose is compared with (default: the spec's)")
    p.add_argument("--size", type=positive_length, default=None, metavar="MM",
                   help="element size on the teeth in mm (default module / 4)")
    p.add_argument("--contact-size", type=positive_length, default=None, metavar="MM",
                   help="aligned: element size on the loaded flanks near mid-face, the "
                        "accuracy knob (default --size; docs/fea.md has the convergence table)")
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    spec = spec_from_args(args)
    if args.misalignment > 0 and args.contact_size is not None:
        raise ArgumentError("--contact-size", args.contact_size, "aligned poses only: a "
                            "misaligned sector takes one --size")
    for part in ("hub", "sleeve"):
        check_size(spec, part, args.size, "--size")
        check_size(spec, part, args.contact_size, "--contact-size")
    if not resolve_torque_Nm(spec, args.torque, "--torque", zero=False) > 0:  # before any work
        raise ArgumentError("load.torque_Nm", spec.load.torque_Nm, "a torque above 0 N·m: FE "
                            "contact needs a load (set it, or give --torque)")
    for note in fillet_notes(spec, args.size):
        print(f"{spec.name}: {note}", file=sys.stderr)
    gmsh_module()
    ccx_path()
    out = claim(output_dir(args, spec), spec.to_dict(), [REPORT], [WORK])
    work = out / WORK
    if args.misalignment > 0:
        print(f"{spec.name}: meshing and solving a {args.sector}-tooth sector in contact "
              "(tens of minutes)", file=sys.stderr)
        chk = sector_check(spec, args.misalignment, rotation_deg=args.rotation,
                           torque_Nm=args.torque, model=args.model, sector=args.sector,
                           size_mm=args.size, workdir=work)
        for k, r in zip(chk.compared, chk.ratio, strict=True):
            print(f"{spec.name}: tooth {chk.fe.teeth[k]}: FE "
                  f"{chk.fe.tangential_force_N[k]:.0f} N, {chk.model} "
                  f"{chk.model_tangential_force_N[k]:.0f} N (FE / model {r:.3f})",
                  file=sys.stderr)
        print(write_json(out / REPORT, chk.to_dict()))
        return 0
    print(f"{spec.name}: meshing and solving one pitch in contact (minutes)", file=sys.stderr)
    res = fe_contact(spec, torque_Nm=args.torque, size_mm=args.size,
                     contact_size_mm=args.contact_size, workdir=work)
    print(f"{spec.name}: wind-up {res.windup_from_first_touch_rad * 1e6:.1f} µrad beyond first "
          f"touch at {res.torque_Nm:g} N·m; tooth load {res.tooth_load_N:.1f} N "
          f"(equilibrium {res.equilibrium_tooth_load_N:.1f} N); interior pressure "
          f"{res.interior_pressure_MPa:.0f} MPa", file=sys.stderr)
    print(write_json(out / REPORT, res.to_dict()))
    return 0
