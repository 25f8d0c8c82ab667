"""Checks made with the FE pipeline: the pipeline itself against a closed form (a straight
cantilever of rectangular section), and the misaligned FE sector posed where a load model
puts its most loaded tooth (:func:`fe_sector_at_loads`, the FE half of
:func:`gearcoupling.sector_check`)."""

from __future__ import annotations

import numpy as np

from ..errors import ArgumentError
from ..spec import CouplingSpec
from .backends import gmsh_session
from .ccx import run_ccx, solver_dir
from .deck import LoadCase, static_deck
from .mesh import extract_mesh
from .sector import FESectorResult, fe_contact_sector

CUT_DISTANCE_PITCHES = 2  # compared teeth stand at least this far from a cut


def check_sector(spec: CouplingSpec, sector) -> int:
    """``sector`` checked: whole teeth, enough for a tooth :data:`CUT_DISTANCE_PITCHES`
    from each cut, fewer than the coupling's."""
    lo = 2 * CUT_DISTANCE_PITCHES + 1
    if isinstance(sector, bool) or not (isinstance(sector, int)
                                        and lo <= sector < spec.tooth.teeth):
        raise ArgumentError("sector", sector, f"a whole number of teeth from {lo} (teeth "
                            f"{CUT_DISTANCE_PITCHES} pitches from a cut) to "
                            f"{spec.tooth.teeth - 1}")
    return sector


def fe_sector_at_loads(spec: CouplingSpec, tooth_loads_N: np.ndarray, *,
                       misalignment_deg: float, rotation_deg: float, windup_rad: float,
                       sector: int = 5, size_mm: float | None = None, workdir=None
                       ) -> tuple[FESectorResult, list[int], list[float]]:
    """The FE sector of ``sector`` teeth centred on the most loaded tooth of
    ``tooth_loads_N`` ``(N,)`` (a model's tangential loads at the pose), turned by
    ``windup_rad``; returns the FE result, the sector's compared teeth (indexes, at least
    :data:`CUT_DISTANCE_PITCHES` from a cut) and FE / given load on each."""
    W = np.asarray(tooth_loads_N, dtype=float)
    first = (int(np.argmax(W)) - check_sector(spec, sector) // 2) % W.size
    fe = fe_contact_sector(spec, misalignment_deg=misalignment_deg, rotation_deg=rotation_deg,
                           windup_rad=windup_rad, first_tooth=first, sector=sector,
                           size_mm=size_mm, workdir=workdir)
    compared = list(range(CUT_DISTANCE_PITCHES, sector - CUT_DISTANCE_PITCHES))
    return fe, compared, [fe.tangential_force_N[k] / W[fe.teeth[k]] for k in compared]


def timoshenko_tip_deflection(force_N: float, length_mm: float, width_mm: float,
                              height_mm: float, youngs_modulus_MPa: float,
                              poisson_ratio: float) -> float:
    """Tip deflection (mm) of a clamped rectangular cantilever under an end force along
    ``height``: bending ``F L³ / (3 E I)`` plus shear ``F L / (k G A)`` with Cowper's
    ``k = 10 (1 + nu) / (12 + 11 nu)``."""
    inertia = width_mm * height_mm**3 / 12.0
    shear_mod = youngs_modulus_MPa / (2.0 * (1.0 + poisson_ratio))
    k = 10.0 * (1.0 + poisson_ratio) / (12.0 + 11.0 * poisson_ratio)
    return (force_N * length_mm**3 / (3.0 * youngs_modulus_MPa * inertia)
            + force_N * length_mm / (k * shear_mod * width_mm * height_mm))


def cantilever_mesh(length_mm: float, width_mm: float, height_mm: float, size_mm: float):
    """Quadratic tet mesh of the box ``[0, L] x [0, b] x [0, h]`` with regions ``ROOT``
    (x = 0) and ``TIP`` (x = L)."""
    with gmsh_session() as gmsh:
        gmsh.model.occ.addBox(0, 0, 0, length_mm, width_mm, height_mm)
        gmsh.model.occ.synchronize()
        names = {}
        for _, s in gmsh.model.getEntities(2):
            x = gmsh.model.occ.getCenterOfMass(2, s)[0]
            names[s] = ("ROOT" if abs(x) < 1e-9 else "TIP" if abs(x - length_mm) < 1e-9
                        else "SIDE", 1.0)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size_mm)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size_mm)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.model.mesh.generate(3)
        return extract_mesh(gmsh, "box", names, None, size_mm, 2, 0.0)


def cantilever_tip_deflection(size_mm: float, *, length_mm: float = 100.0,
                              width_mm: float = 10.0, height_mm: float = 10.0,
                              force_N: float = 1000.0, youngs_modulus_MPa: float = 210e3,
                              poisson_ratio: float = 0.3, workdir=None) -> dict:
    """FE (gmsh C3D10 + ccx) and Timoshenko tip deflection of the clamped cantilever.

    The end force is spread over the tip face as equal nodal forces along z; the FE
    deflection is the mean z displacement of the tip nodes (its work conjugate)."""
    vm = cantilever_mesh(length_mm, width_mm, height_mm, size_mm)
    tip = vm.node_set("TIP")
    forces = np.zeros((len(tip), 3))
    forces[:, 2] = force_N / len(tip)
    deck = static_deck(vm, youngs_modulus_MPa=youngs_modulus_MPa, poisson_ratio=poisson_ratio,
                       fixed=["ROOT"], cases=[LoadCase(tip, forces)],
                       node_print=[("PTIP", tip)])
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, "cantilever")
    u = res.get("displacements", "PTIP")[0]
    fe = float(np.mean(u[:, 3]))
    theory = timoshenko_tip_deflection(force_N, length_mm, width_mm, height_mm,
                                       youngs_modulus_MPa, poisson_ratio)
    return {"size_mm": size_mm, "elements": len(vm.tets), "fe_mm": fe, "theory_mm": theory,
            "ratio": fe / theory, "solve_seconds": res.seconds}
