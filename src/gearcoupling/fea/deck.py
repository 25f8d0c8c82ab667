"""CalculiX decks: linear static load cases on a :class:`VolumeMesh`."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..io import inp_id_lines, inp_number
from .volume import VolumeMesh
from .write import inp_mesh_lines


@dataclass(frozen=True)
class LoadCase:
    """Nodal forces of one step: ``nodes (k,)`` 0-based indices, ``forces (k, 3)`` N."""

    nodes: NDArray[np.int64]
    forces: NDArray[np.float64]


def static_deck(vm: VolumeMesh, *, youngs_modulus_MPa: float, poisson_ratio: float,
                fixed: Sequence[str], cases: Sequence[LoadCase],
                node_print: Sequence[tuple[str, NDArray]] = (),
                stress_sets: Sequence[str] = (), solver: str = "SPOOLES") -> str:
    """A deck of one linear static ``*STEP`` per load case.

    ``fixed`` regions/aggregates have all three displacements fixed; ``node_print`` gives
    ``(name, 0-based nodes)`` sets whose displacements are printed, ``stress_sets`` the
    element sets whose integration-point stresses are printed (to ``<job>.dat``).
    ``solver``: ``"SPOOLES"`` (direct) or ``"ITERATIVE CHOLESKY"`` (preconditioned
    conjugate gradients: measured 2.6x less CPU on a 3-tooth hub sector, displacements
    equal to 1e-4 relative).
    """
    lines = inp_mesh_lines(vm)
    for name, nodes in node_print:
        lines.append(f"*NSET, NSET={name}")
        lines += inp_id_lines(np.asarray(nodes) + 1)
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC",
              f"{inp_number(youngs_modulus_MPa)}, {inp_number(poisson_ratio)}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL", "*BOUNDARY"]
    lines += [f"{name}, 1, 3, 0.0" for name in fixed]
    for case in cases:
        lines += ["*STEP", f"*STATIC, SOLVER={solver}", "*CLOAD, OP=NEW"]
        for node, f in zip(case.nodes, case.forces, strict=True):
            lines += [f"{node + 1}, {d + 1}, {inp_number(f[d])}" for d in range(3) if f[d] != 0]
        for name, _ in node_print:
            lines += [f"*NODE PRINT, NSET={name}", "U"]
        for name in stress_sets:
            lines += [f"*EL PRINT, ELSET={name}", "S"]
        lines.append("*END STEP")
    return "\n".join(lines) + "\n"


def principal_max(stress: NDArray) -> NDArray[np.float64]:
    """Largest principal stress ``(k,)`` of rows ``(sxx, syy, szz, sxy, sxz, syz)``."""
    s = np.asarray(stress)
    t = np.empty((*s.shape[:-1], 3, 3))
    t[..., 0, 0], t[..., 1, 1], t[..., 2, 2] = s[..., 0], s[..., 1], s[..., 2]
    t[..., 0, 1] = t[..., 1, 0] = s[..., 3]
    t[..., 0, 2] = t[..., 2, 0] = s[..., 4]
    t[..., 1, 2] = t[..., 2, 1] = s[..., 5]
    return np.linalg.eigvalsh(t)[..., -1]
