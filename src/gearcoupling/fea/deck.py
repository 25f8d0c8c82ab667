"""CalculiX decks: linear static load cases on a :class:`VolumeMesh`, one ``*STEP`` per case
(:func:`static_deck`) or all cases on one factorisation (:func:`green_deck`)."""

from __future__ import annotations

from collections.abc import Sequence, Set
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import GeometryError
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
    conjugate gradients: less CPU on a 3-tooth hub sector, docs/fea.md; displacements
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


def green_deck(vm: VolumeMesh, *, youngs_modulus_MPa: float, poisson_ratio: float,
               fixed: Sequence[str], cases: Sequence[LoadCase],
               stress_sets: Sequence[str] = ()) -> str:
    """A deck of one ``*GREEN`` step: every load case solved on one factorisation.

    Each case gets a load node (numbered after the mesh nodes, node set ``LOADS``) whose
    displacement is tied by an ``*EQUATION`` to the work-conjugate combination of the
    case's nodal displacements, ``u_load = sum_i f_i . u_i``; a unit force on it (one Green
    function, SPOOLES) is then exactly the case's nodal forces, and its displacement the
    case's work ``sum f_i . u_i``. A grounded spring of 1e-9 N/mm (``SPRING1``) gives the
    load node its degree of freedom (1e-14 of a tooth's stiffness); its other two are
    fixed. ``*NODE PRINT`` prints the load nodes and ``*EL PRINT`` the ``stress_sets``
    once per case, in case order.
    """
    n_nodes, n_elems = len(vm.nodes), len(vm.tets)
    loads = np.arange(n_nodes + 1, n_nodes + 1 + len(cases))
    lines = [*inp_mesh_lines(vm), "*NODE, NSET=LOADS"]
    lines += [f"{node}, 0.0, 0.0, 0.0" for node in loads]
    lines += ["*ELEMENT, TYPE=SPRING1, ELSET=LOAD_SPRINGS"]
    lines += [f"{n_elems + 1 + i}, {node}" for i, node in enumerate(loads)]
    lines += ["*SPRING, ELSET=LOAD_SPRINGS", "1,", "1.E-9,", "*EQUATION"]
    # a fixed degree of freedom cannot be eliminated by an equation
    dependent = {(int(n) + 1, d) for name in fixed for n in vm.node_set(name) for d in (1, 2, 3)}
    shared = _shared_dofs(cases)
    for case, load in zip(cases, loads, strict=True):
        terms = _work_terms(case, dependent, shared)
        terms.append((int(load), 1, -1.0))
        lines.append(str(len(terms)))
        for i in range(0, len(terms), 4):
            lines.append(", ".join(f"{n}, {d}, {inp_number(c)}" for n, d, c in terms[i:i + 4]))
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC",
              f"{inp_number(youngs_modulus_MPa)}, {inp_number(poisson_ratio)}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL", "*BOUNDARY", "LOADS, 2, 3, 0.0"]
    lines += [f"{name}, 1, 3, 0.0" for name in fixed]
    lines += ["*STEP", "*GREEN, SOLVER=SPOOLES", "*CLOAD"]
    lines += [f"{node}, 1, 1.0" for node in loads]
    lines += ["*NODE PRINT, NSET=LOADS", "U"]
    for name in stress_sets:
        lines += [f"*EL PRINT, ELSET={name}", "S"]
    lines.append("*END STEP")
    return "\n".join(lines) + "\n"


def _case_terms(case: LoadCase) -> list[tuple[int, int, float]]:
    """``(node, dof, f)`` terms (1-based) of a case's work ``sum f_i . u_i``."""
    return [(int(n) + 1, d + 1, float(f[d])) for n, f in zip(case.nodes, case.forces,
                                                             strict=True)
            for d in range(3) if f[d] != 0]


def _shared_dofs(cases: Sequence[LoadCase]) -> set[tuple[int, int]]:
    """Degrees of freedom loaded by more than one case (overlapping patches)."""
    seen: set[tuple[int, int]] = set()
    shared: set[tuple[int, int]] = set()
    for case in cases:
        for n, d, _ in _case_terms(case):
            (shared if (n, d) in seen else seen).add((n, d))
    return shared


def _work_terms(case: LoadCase, dependent: set[tuple[int, int]],
                shared: Set[tuple[int, int]] = frozenset()) -> list[tuple[int, int, float]]:
    """``(node, dof, f)`` terms of ``sum f_i . u_i``, led by the largest term whose degree of
    freedom no earlier equation made dependent (ccx eliminates the first term), preferring
    one no other case loads: ccx's cascade fails ("zero coefficient on the dependent side")
    when a dependent degree of freedom is another equation's term."""
    terms = _case_terms(case)
    order = sorted(range(len(terms)), key=lambda i: (terms[i][:2] in shared, -abs(terms[i][2])))
    lead = next((i for i in order if terms[i][:2] not in dependent), None)
    if lead is None:
        raise GeometryError("every loaded degree of freedom of a load case is fixed or "
                            "already tied by another case")
    dependent.add(terms[lead][:2])
    return [terms[lead], *terms[:lead], *terms[lead + 1:]]


def principal_max(stress: NDArray) -> NDArray[np.float64]:
    """Largest principal stress ``(k,)`` of rows ``(sxx, syy, szz, sxy, sxz, syz)``."""
    s = np.asarray(stress)
    t = np.empty((*s.shape[:-1], 3, 3))
    t[..., 0, 0], t[..., 1, 1], t[..., 2, 2] = s[..., 0], s[..., 1], s[..., 2]
    t[..., 0, 1] = t[..., 1, 0] = s[..., 3]
    t[..., 0, 2] = t[..., 2, 0] = s[..., 4]
    t[..., 1, 2] = t[..., 2, 1] = s[..., 5]
    return np.linalg.eigvalsh(t)[..., -1]
