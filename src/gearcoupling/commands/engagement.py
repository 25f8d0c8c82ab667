"""A command's spec with its engagements: a double-engagement spec's coupling resolved and
the shaft alignment options checked before any work (docs/coupling.md)."""

from __future__ import annotations

import argparse
from typing import Any

from ..coupling import spec_geometry
from ..errors import ArgumentError
from ..spec import CouplingSpec
from .common import ALIGNMENT_OPTIONS, alignment_given, spec_from_args

#: each alignment option's field of :class:`~gearcoupling.coupling.ShaftAlignment`
FIELDS = {"--offset": "offset_mm", "--offset-azimuth": "offset_azimuth_deg",
          "--shaft-angle": "angle_deg", "--angle-azimuth": "angle_azimuth_deg"}


def checked_spec(args: argparse.Namespace) -> tuple[CouplingSpec, dict[str, Any]]:
    """The command's spec and its alignment options as keywords of
    :class:`~gearcoupling.StageSettings`, checked before any work: a double-engagement
    spec's coupling is resolved at the alignment the options make (a refusal names the
    option, or the spec's key where the value is the spec's); the options are refused
    for a single engagement, ``--misalignment`` for a double one."""
    spec = spec_from_args(args)
    given = alignment_given(args)
    if spec.coupling.engagements == 1:
        if given:
            option = next(iter(given))
            raise ArgumentError(option, given[option], "only for a double-engagement spec "
                                "([coupling] engagements = 2): one engagement takes "
                                "--misalignment")
        return spec, {}
    if getattr(args, "misalignment", None) is not None:
        raise ArgumentError("--misalignment", args.misalignment, "not for a double-engagement "
                            "spec: each mesh's angle follows from the shaft alignment "
                            "(--offset, --shaft-angle and their azimuths, or the spec's "
                            "[alignment])")
    spec_geometry(spec, {FIELDS[o]: v for o, v in given.items()},
                  names={FIELDS[o]: o for o in ALIGNMENT_OPTIONS})
    return spec, {ALIGNMENT_OPTIONS[o]: v for o, v in given.items()}
