"""What a part writer receives: :class:`PartJob`."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..parts import build_part


@dataclass
class PartJob:
    """The spec and the part, and its mesh (built on first use).

    A writer is ``writer(job, path)``: it writes the part to ``path`` (a temporary file with
    the right suffix, renamed onto the target only when the writer succeeded).
    """

    spec: object
    part: str
    tolerance_mm: float | None = None
    teeth: object = None
    _mesh: object = field(default=None, repr=False)

    @property
    def mesh(self):
        if self._mesh is None:
            self._mesh = build_part(self.spec, self.part, tolerance_mm=self.tolerance_mm,
                                    teeth=self.teeth)
        return self._mesh

    @property
    def title(self) -> str:
        """``<spec name>-<part>``, the name files give the part."""
        return f"{getattr(self.spec, 'name', 'gearcoupling')}-{self.part}"
