"""``gearcoupling datasheet``: the coupling's data for a rotor model (API 671 data sheet)."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..io import terminal_text, writable_file
from ..loading import PHASES, model_names
from ..rotordynamics import (
    DEFAULT_STEPS,
    DIFFERENCES,
    FILES,
    MAX_TORQUE_NM,
    ROSS_SUFFIXES,
    CouplingData,
    check_inputs,
    coupling_data,
    import_ross,
    write_ross,
)
from . import whole
from .common import (
    add_alignment_arguments,
    add_misalignment_argument,
    add_spec_arguments,
    count,
    misalignment_deg,
    number_in,
    output_dir,
    progress,
)
from .engagement import checked_spec
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("datasheet", help="coupling data for a rotor model: mass properties, "
                       "torsional stiffness, the 6x6 stiffness matrix under load and the loads "
                       "at the allowable misalignment (datasheet.json, datasheet.csv, "
                       "stiffness_matrix.csv; --ross: a ROSS coupling element)")
    add_spec_arguments(p)
    add_misalignment_argument(p)
    p.add_argument("--torque", type=number_in(-MAX_TORQUE_NM, MAX_TORQUE_NM, "N·m"),
                   default=None, metavar="NM",
                   help=f"operating torque in N·m, 0 < |T| <= {MAX_TORQUE_NM:g}; the sign picks "
                        "the loaded flank (default: the spec's)")
    p.add_argument("--model", choices=model_names(), default=None,
                   help="load model (default: the spec's [load] model, the validated surface "
                        "model unless the spec says otherwise)")
    p.add_argument("--rotations", type=count(1, 64), default=None, metavar="N",
                   help="rotations over one tooth pitch the stiffness is averaged over, 1-64 "
                        "(default: the model's load-study rotations, 3 for surface, else 8)")
    p.add_argument("--differences", choices=DIFFERENCES, default=None,
                   help="difference scheme of the stiffness matrix: forward (one solve per "
                        "column) or central (two, second order); default forward for the "
                        "surface model, else central")
    p.add_argument("--step", type=number_in(1e-4, 0.2, "of the tooth deflection"),
                   default=None, metavar="S",
                   help="difference step as a share of the largest tooth deflection, "
                        "1e-4 to 0.2 (default: " + ", ".join(
                            f"{v:g} {k}" for k, v in DEFAULT_STEPS.items()) + ")")
    p.add_argument("--angles", type=count(4, 3600), default=None, metavar="N",
                   help="rotations over the turn at the allowable misalignment, 4-3600 "
                        f"(default {PHASES} per tooth pitch)")
    p.add_argument("--ross", type=ross_file, default=None, metavar="FILE",
                   help="also write the ROSS coupling element to FILE (.toml or .json, "
                        "ROSS's formats; the rotordynamics extra; a double-engagement "
                        "spec: the whole coupling's pieces)")
    add_alignment_arguments(p)
    p.set_defaults(func=run)


def ross_file(text: str) -> Path:
    """argparse type: a ``.toml`` or ``.json`` path for ROSS's ``save``."""
    path = Path(text)
    if path.suffix.lower() not in ROSS_SUFFIXES:
        raise argparse.ArgumentTypeError(f"{text!r}: must end in .toml or .json (the formats "
                                         "ROSS saves and loads)")
    return path


@holds_folders
def run(args) -> int:
    spec, alignment = checked_spec(args)
    check_inputs(spec, args.torque)
    if args.ross is not None:
        import_ross()  # a missing extra is refused before the computation
        writable_file(args.ross, "--ross")
    if spec.coupling.engagements == 2:
        return whole.datasheet(args, spec, alignment)
    mis = misalignment_deg(args, spec)
    out = claim(output_dir(args, spec), spec.to_dict(), FILES)
    with progress(f"datasheet {spec.name}", 1) as update:  # the total: coupling_data's
        data = coupling_data(spec, mis, args.torque, model=args.model,
                             rotations=args.rotations, relative_step=args.step,
                             differences=args.differences,
                             turn_angles=args.angles, progress=update)
    paths = data.write(out)
    if args.ross is not None:
        paths.append(write_ross(data.to_ross(), args.ross))
    for line in key_figures(data):
        print(line)
    for path in paths:
        print(path)
    return 0


def key_figures(data: CouplingData) -> list[str]:
    """The data sheet's key figures in a few lines (the spec's name as
    :func:`~gearcoupling.io.terminal_text`): the masses, the torsional stiffness, the
    allowable misalignment and the capacity at the operating point."""
    t, a, m = data.torsion, data.allowable, data.mass
    why = a.criterion + (f", {a.capacity_criterion.replace('_', ' ')}"
                         if a.capacity_criterion else "")
    cap = ("no criterion limits it" if data.capacity_Nm is None else
           f"{data.capacity_Nm:.4g} N·m (K = {data.spec.load.accuracy_factor:g} applied)")
    return [f"{terminal_text(data.spec.name)}: i = {data.misalignment_deg:g}°, "
            f"T = {data.torque_Nm:.4g} N·m ({data.model} model, {data.springs} springs)",
            "  mass: " + ", ".join(f"{k} {v.mass_kg:.4g} kg" for k, v in m.items()),
            f"  torsional stiffness at the torque: secant {t.secant_Nm_per_rad:.4g} N·m/rad, "
            f"tangent {t.tangent_Nm_per_rad:.4g} N·m/rad",
            f"  allowable misalignment: {a.misalignment_deg:.4g}° (limited by the {why})",
            f"  capacity at {data.misalignment_deg:g}°: {cap}"]
