"""The spec's stages: ``spec`` (``spec.json``, the resolved spec in mm and degrees with
its derived values) and ``sections`` (the transverse sections and the crown along the
face: ``sections.png``, ``crown_profile.csv``)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..io import write_csv_rows, write_json
from ..plots import crown_profile, plot_sections
from ..spec import CouplingSpec
from .stage import StageInputs

PROFILE_POINTS = 81  # planes of the crown profile over the face
PROFILE_COLUMNS = ("thickness_enveloped_mm", "thickness_revolved_mm",
                   "pressure_angle_enveloped_deg", "pressure_angle_revolved_deg",
                   "crown_drop_mm")


@dataclass(frozen=True)
class ResolvedSpec:
    """The resolved spec (mm, degrees) with its derived values, as plain data."""

    data: dict[str, Any]


@dataclass(frozen=True)
class CrownProfile:
    """Pitch-circle tooth thickness, transverse pressure angle and crown drop along the
    face (:func:`~gearcoupling.plots.crown_profile`), and the chordal tolerance of the
    section plots."""

    z_mm: NDArray[np.float64]
    columns: dict[str, NDArray[np.float64]]
    tolerance_mm: float


def resolved_spec(spec: CouplingSpec) -> dict[str, Any]:
    """The resolved spec (mm, degrees) with its derived values, as plain data."""
    data = spec.to_dict()
    data["derived"] = dict(spec.derived)
    return data


def resolve(inputs: StageInputs) -> ResolvedSpec:
    """The stage ``spec``."""
    return ResolvedSpec(resolved_spec(inputs.spec))


def files(result: ResolvedSpec, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``spec``'s ``spec.json``."""
    return [write_json(folder / "spec.json", result.data)]


def write_spec(spec: CouplingSpec, out: Path) -> list[Path]:
    """Write ``spec.json`` into ``out``."""
    return [write_json(out / "spec.json", resolved_spec(spec))]


def profile(inputs: StageInputs) -> CrownProfile:
    """The stage ``sections``: the crown profile at :data:`PROFILE_POINTS` planes."""
    spec = inputs.spec
    z = np.linspace(-0.5 * spec.hub.face_width, 0.5 * spec.hub.face_width, PROFILE_POINTS)
    prof = crown_profile(spec, z)
    return CrownProfile(z, {c: prof[c] for c in PROFILE_COLUMNS}, 1e-3 * spec.tooth.module)


def profile_files(result: CrownProfile, inputs: StageInputs, folder: Path) -> list[Path]:
    """The stage ``sections``'s data and picture."""
    return [write_csv_rows(folder / "crown_profile.csv", ("z_mm", *PROFILE_COLUMNS),
                           zip(result.z_mm, *result.columns.values(), strict=True)),
            plot_sections(inputs.spec, folder / "sections.png", result.tolerance_mm,
                          dpi=inputs.settings.dpi)]
