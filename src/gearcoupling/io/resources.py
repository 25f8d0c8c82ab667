"""The files bundled with gearcoupling: spec templates and study files."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from ..errors import SpecError
from .files import not_a_file, require_file

KINDS = {"templates": "spec", "studies": "study"}


def bundled_dir(kind: str) -> Path:
    """Folder of the bundled ``templates`` or ``studies`` (in the wheel, or the
    repository's folder of that name)."""
    packaged = resources.files("gearcoupling") / kind
    if packaged.is_dir():
        return Path(str(packaged))
    return Path(__file__).resolve().parents[3] / kind


def bundled_names(kind: str) -> list[str]:
    """Names of the bundled TOML files of ``kind``."""
    return sorted(p.stem for p in bundled_dir(kind).glob("*.toml"))


def resolve_bundled(kind: str, name_or_path: str | Path) -> Path:
    """A TOML file path, or the name of a bundled file of ``kind``; else :class:`SpecError`
    naming what is bundled."""
    field = KINDS[kind]
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.exists() or p.is_symlink():
        return require_file(p, field, f"a {field} file or the name of a bundled one")
    candidate = bundled_dir(kind) / f"{name_or_path}.toml"
    if not_a_file(candidate) is not None:
        raise SpecError(field, str(name_or_path), f"not a file and not one of the bundled "
                        f"{kind}: {bundled_names(kind)}")
    return candidate
