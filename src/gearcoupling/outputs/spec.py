"""``spec.json``: the resolved spec in mm and degrees with its derived values."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..io import write_json
from ..spec import CouplingSpec


def resolved_spec(spec: CouplingSpec) -> dict[str, Any]:
    """The resolved spec (mm, degrees) with its derived values, as plain data."""
    data = spec.to_dict()
    data["derived"] = dict(spec.derived)
    return data


def write_spec(spec: CouplingSpec, out: Path) -> list[Path]:
    """Write ``spec.json`` into ``out``."""
    return [write_json(out / "spec.json", resolved_spec(spec))]
