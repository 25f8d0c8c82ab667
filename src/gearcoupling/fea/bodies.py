"""The bodies under the teeth: whole hub and sleeve rings in CalculiX under tooth loads.

Mesh: one pitch of the part, meshed by gmsh with node-for-node periodic cuts
(:func:`~gearcoupling.fea.mesh_part`, ``sector=1, periodic=True``), and ``K`` copies of it
turned by one pitch each and joined at their cuts (:func:`assemble`). ``K = N`` is the
whole ring; every tooth is meshed alike, so the ring's response to a tooth load is exactly
circulant, and a sector of ``K`` copies has the same mesh under its teeth as the ring: the
local (Boussinesq-like) deformation under a patch load, which dwarfs the body term and
moves with the mesh, cancels between ring and sector.

Supports (:func:`solve_patches`): the hub bore (``BORE``; ``END`` without a bore) or the
sleeve outside diameter (``OUTER``) fixed, as for the tooth table
(:mod:`~gearcoupling.fea.stiffness`); a sector's cut faces either fixed (``"fixed"``: the
table's 3-tooth sector) or tied to each other by cyclic equations turned by the sector
angle (``"cyclic"``: the misaligned contact sector's cuts, :mod:`~gearcoupling.fea.sector`).

Loads and measure: the table's patch load (:func:`~gearcoupling.fea.stiffness.load_case`:
frictionless, along the flank normal, a unit tangential load at the pitch radius) on any
tooth at any ``(z, r)`` of its loaded (ccw) flank; a tooth's deflection is the work
conjugate ``sum f_i . u_i`` of its unit pattern: the circumferential displacement at the
pitch radius, the table's measure (mm per N of tangential load at the pitch radius).
"""

from __future__ import annotations

import math
import resource
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError, GeometryError
from ..geometry import rot_z
from ..io import inp_number
from ..spec import CouplingSpec
from .ccx import run_ccx, solver_dir
from .deck import LoadCase, static_deck
from .mesh import mesh_part
from .reference import cyclic_equations
from .stiffness import load_case, material
from .volume import VolumeMesh

SUPPORTS = ("ring", "fixed", "cyclic")


def pitch_mesh(spec: CouplingSpec, part: str, size_mm: float | None = None) -> VolumeMesh:
    """One pitch of ``part`` (tooth or space 0) with periodic cuts, for :func:`assemble`."""
    return mesh_part(spec, part, sector=1, size_mm=size_mm, periodic=True)


def _cut_partners(pitch: VolumeMesh, angle: float) -> tuple[NDArray, NDArray]:
    """``(cw, ccw)`` node indices of the pitch mesh's cuts, ``ccw[i]`` at ``cw[i]`` turned
    by ``angle``."""
    from scipy.spatial import cKDTree

    cw, ccw = pitch.node_set("CUT_CW"), pitch.node_set("CUT_CCW")
    dist, idx = cKDTree(pitch.nodes[ccw]).query(pitch.nodes[cw] @ rot_z(angle).T)
    if len(cw) != len(ccw) or dist.max() > 1e-2 * pitch.size_mm:
        raise GeometryError(f"the cut faces of the {pitch.part} pitch do not match node for "
                            f"node ({len(cw)} and {len(ccw)} nodes, worst {dist.max():.3g} mm)")
    return cw, ccw[idx]


def assemble(pitch: VolumeMesh, teeth: int, copies: int) -> VolumeMesh:
    """``copies`` copies of a one-pitch mesh turned by ``2 pi k / teeth`` (copy ``k`` holds
    tooth ``k``), each copy's cw cut joined to the previous copy's ccw cut; ``copies =
    teeth`` closes the whole ring (no ``CUT`` regions), else the first copy's ``CUT_CW`` and
    the last one's ``CUT_CCW`` remain.

    Returns
    -------
    VolumeMesh
        Regions ``T<k>_...`` of copy ``k``; ``BORE``, ``END``, ``BODY``, ``OUTER`` joined;
        ``teeth`` ``None`` for the ring, else ``[0 .. copies - 1]``.
    """
    if pitch.teeth != [0]:
        raise ArgumentError("pitch", pitch.teeth, "a one-pitch mesh of tooth 0")
    if not (isinstance(copies, int) and 1 <= copies <= teeth):
        raise ArgumentError("copies", copies, f"a whole number of pitches from 1 to {teeth}")
    step = 2 * math.pi / teeth
    cw, ccw = _cut_partners(pitch, step)
    n, ring = len(pitch.nodes), copies == teeth
    ids = np.arange(n * copies).reshape(copies, n)
    for k in range(1, copies):
        ids[k, cw] = ids[k - 1, ccw]
    if ring:
        ids[0, cw] = ids[-1, ccw]
    used, compact = np.unique(ids, return_inverse=True)
    compact = compact.reshape(ids.shape)
    nodes = np.concatenate([pitch.nodes @ rot_z(k * step).T for k in range(copies)])[used]
    tets = np.concatenate([compact[k][pitch.tets] for k in range(copies)])
    m = len(pitch.tets)
    regions: dict[str, list] = {}
    faces: dict[str, list] = {}
    for name, tri in pitch.regions.items():
        for k in range(copies):
            if (name == "CUT_CW" and (ring or k > 0)) or (
                    name == "CUT_CCW" and (ring or k < copies - 1)):
                continue
            key = f"T{k}_{name[3:]}" if name.startswith("T0_") else name
            regions.setdefault(key, []).append(compact[k][tri])
            faces.setdefault(key, []).append(pitch.faces[name] + [k * m, 0])
    quality = {"nodes": len(nodes), "elements": len(tets), "copies": copies,
               "pitch": dict(pitch.quality)}
    return VolumeMesh(pitch.part, nodes, tets,
                      {k: np.concatenate(v) for k, v in regions.items()},
                      {k: np.concatenate(v) for k, v in faces.items()},
                      None if ring else list(range(copies)), pitch.size_mm, quality)


def patch_load(vm: VolumeMesh, spec: CouplingSpec, tooth: int, z_mm: float, r_mm: float,
               patch_mm: float) -> LoadCase:
    """The unit patch load of ``tooth`` at ``(z_mm, r_mm)`` (1 N tangential at the pitch
    radius; module docstring)."""
    case, _ = load_case(vm, float(z_mm), float(r_mm), spec.tooth.pitch_radius, patch_mm,
                        tooth=tooth)
    return case


def combine(cases: list[LoadCase], loads) -> LoadCase:
    """One load case of unit patterns ``cases`` scaled by ``loads (k,)`` (N), summed per node."""
    nodes = np.concatenate([c.nodes for c in cases])
    forces = np.concatenate([c.forces * w for c, w in zip(cases, loads, strict=True)])
    uniq, inv = np.unique(nodes, return_inverse=True)
    out = np.zeros((len(uniq), 3))
    np.add.at(out, inv, forces)
    keep = np.any(out != 0, axis=1)
    return LoadCase(uniq[keep], out[keep])


@dataclass(frozen=True)
class PatchSolution:
    """Work conjugates of a solve: ``deflection_mm (s, o)`` of observation ``o`` under load
    case ``s``; ``twist_rad (s,)`` the mean circumferential displacement / radius of the
    ``twist_nodes`` (e.g. the root circle: the body's twist); solve figures."""

    deflection_mm: NDArray[np.float64]
    twist_rad: NDArray[np.float64]
    nodes: int
    solve_seconds: float
    max_rss_MB: float


def fixed_sets(vm: VolumeMesh, supports: str) -> list[str]:
    """The fixed regions: bore (hub; ``END`` without one) or outside diameter (sleeve), and
    the cuts when ``supports == "fixed"``."""
    base = ["OUTER"] if vm.part == "sleeve" else (["BORE"] if "BORE" in vm.regions else ["END"])
    return base + (["CUT"] if supports == "fixed" else [])


def solve_patches(vm: VolumeMesh, spec: CouplingSpec, cases: list[LoadCase],
                  observe: list[LoadCase], *, supports: str = "ring", twist_nodes=None,
                  solver: str = "SPOOLES",
                  workdir=None, job: str = "bodies") -> PatchSolution:
    """Solve the load ``cases`` on ``vm`` in one ccx run (one static step each) and return
    the work conjugate of every ``observe`` pattern (module docstring).

    ``supports``: ``"ring"`` (a whole ring, ``vm.teeth is None``), ``"fixed"`` or
    ``"cyclic"`` cuts of a sector of copies (module docstring).
    """
    if supports not in SUPPORTS:
        raise ArgumentError("supports", supports, f"one of {', '.join(SUPPORTS)}")
    if (supports == "ring") != (vm.teeth is None):
        raise ArgumentError("supports", supports, "ring for a whole ring, fixed or cyclic "
                            "for a sector")
    E, nu = material(spec, vm.part)
    twist_nodes = np.zeros(0, np.int64) if twist_nodes is None else np.asarray(twist_nodes)
    watch = np.unique(np.concatenate([c.nodes for c in observe] + [twist_nodes]))
    fixed = fixed_sets(vm, supports)
    deck = static_deck(vm, youngs_modulus_MPa=E, poisson_ratio=nu, fixed=fixed, cases=cases,
                       node_print=[("WATCH", watch)], solver=solver)
    if supports == "cyclic":
        held = np.unique(np.concatenate([vm.node_set(s) for s in fixed]))
        angle = 2 * math.pi * len(vm.teeth or ()) / spec.tooth.teeth
        eqs = "\n".join(cyclic_equations(vm, "CUT_CW", "CUT_CCW", rot_z(angle), held))
        head, sep, tail = deck.partition("\n*STEP\n")
        deck = head + "\n" + eqs + sep + tail
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, job)
    blocks = res.get("displacements", "WATCH")
    if len(blocks) != len(cases):
        raise GeometryError(f"ccx printed {len(blocks)} displacement blocks for {len(cases)} "
                            "load cases")
    pos = np.searchsorted(watch, np.arange(len(vm.nodes)))
    out = np.empty((len(cases), len(observe)))
    twist = np.zeros(len(cases))
    for s, rows in enumerate(blocks):
        if not np.array_equal(rows[:, 0].astype(np.int64), watch + 1):
            raise GeometryError("ccx printed other nodes than the watched ones")
        u = rows[:, 1:4]
        for o, c in enumerate(observe):
            out[s, o] = float(np.sum(c.forces * u[pos[c.nodes]]))
        if len(twist_nodes):
            p, uu = vm.nodes[twist_nodes], u[pos[twist_nodes]]
            twist[s] = float(np.mean((p[:, 0] * uu[:, 1] - p[:, 1] * uu[:, 0])
                                     / (p[:, 0] ** 2 + p[:, 1] ** 2)))
    return PatchSolution(out, twist, len(vm.nodes), res.seconds,
                         resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024)


def default_patch(spec: CouplingSpec, size_mm: float) -> float:
    """The load patch half-size of the tooth table (:mod:`~gearcoupling.fea.stiffness`)."""
    return max(size_mm, spec.tooth.module / 4.0)



def stack(pitch: VolumeMesh, blocks: int) -> VolumeMesh:
    """``blocks`` disjoint copies of a mesh at the same place (copy ``b``'s nodes offset by
    ``b n``), with only the supports' region, joined (``BORE``/``END``/``OUTER``)."""
    n = len(pitch.nodes)
    support = fixed_sets(pitch, "ring")[0]
    tri, faces = pitch.regions[support], pitch.faces[support]
    m = len(pitch.tets)
    return VolumeMesh(pitch.part, np.tile(pitch.nodes, (blocks, 1)),
                      np.concatenate([pitch.tets + b * n for b in range(blocks)]),
                      {support: np.concatenate([tri + b * n for b in range(blocks)])},
                      {support: np.concatenate([faces + [b * m, 0] for b in range(blocks)])},
                      [0], pitch.size_mm, {"nodes": n * blocks, "elements": m * blocks})


def bloch_equations(cw: NDArray, ccw: NDArray, turn: NDArray, phase: float, a: int,
                    b: int | None, skip: set) -> list[str]:
    """``*EQUATION`` lines of a Bloch-periodic pitch: the ccw cut follows the cw cut turned
    by ``turn (3, 3)`` times ``exp(i phase)``; the real part lives on the copy of node
    offset ``a``, the imaginary part on ``b`` (``None`` when the phase is 0 or pi: real).
    ``cw, ccw`` 0-based partner nodes; pairs whose ccw node is in ``skip`` are left out."""
    c, s = math.cos(phase), math.sin(phase)
    parts = [(a, [(a, c), (b, -s)]), (b, [(a, s), (b, c)])] if b is not None else \
        [(a, [(a, c)])]
    lines = ["*EQUATION"]
    for i, j in zip(cw, ccw, strict=True):
        if int(j) in skip:
            continue
        for dep, terms in parts:
            for d in range(3):
                row = [f"{dep + j + 1}, {d + 1}, 1.0"]
                row += [f"{off + i + 1}, {e + 1}, {inp_number(-w * turn[d, e])}"
                        for off, w in terms for e in range(3) if abs(w * turn[d, e]) > 1e-14]
                lines += [str(len(row)), ", ".join(row)]
    return lines


def bloch_solve(pitch: VolumeMesh, spec: CouplingSpec, phases, forces: NDArray,
                watch: NDArray, *, workdir=None, job: str = "bloch"
                ) -> tuple[NDArray[np.complex128], float]:
    """Displacements of a chain of pitches whose loads and response go as
    ``exp(i phase k)`` from pitch to pitch, one ccx run for all phases and cases.

    Parameters
    ----------
    phases : (P,) float
        Bloch phases per pitch (rad): ``2 pi n / N`` for harmonic ``n`` of the ring,
        ``2 pi j / K`` for a cyclic sector of ``K`` pitches.
    forces : (C, P, n, 3) complex
        Nodal forces on the pitch's nodes of every case and phase (the teeth's loads'
        discrete Fourier transform); imaginary parts at a phase of 0 or pi must be 0.
    watch : (w,) int
        Pitch nodes to return.

    Returns
    -------
    u : (C, P, w, 3) complex
    seconds : float
        The solver's time.
    """
    phases = np.asarray(phases, dtype=float)
    n = len(pitch.nodes)
    real = np.isclose(np.sin(phases), 0.0, atol=1e-12)
    offsets, k = [], 0
    for r in real:
        offsets.append((k * n, None if r else (k + 1) * n))
        k += 1 if r else 2
    mesh = stack(pitch, k)
    cw, ccw = _cut_partners(pitch, 2 * math.pi / spec.tooth.teeth)
    skip = set(pitch.node_set(fixed_sets(pitch, "ring")[0]).tolist())
    turn = rot_z(2 * math.pi / spec.tooth.teeth)
    eqs = []
    for ph, (a, b) in zip(phases, offsets, strict=True):
        eqs += bloch_equations(cw, ccw, turn, float(ph), a, b, skip)
    cases = []
    for f in forces:
        nodes, vals = [], []
        for p, (a, b) in enumerate(offsets):
            hit = np.flatnonzero(np.any(f[p] != 0, axis=1))
            nodes.append(hit + a)
            vals.append(f[p][hit].real)
            if b is not None:
                nodes.append(hit + b)
                vals.append(f[p][hit].imag)
        cases.append(LoadCase(np.concatenate(nodes), np.concatenate(vals)))
    E, nu = material(spec, pitch.part)
    watched = np.concatenate([watch + a for a, _ in offsets]
                             + [watch + b for _, b in offsets if b is not None])
    deck = static_deck(mesh, youngs_modulus_MPa=E, poisson_ratio=nu,
                       fixed=fixed_sets(pitch, "ring"), cases=cases,
                       node_print=[("WATCH", np.unique(watched))])
    head, sep, tail = deck.partition("\n*STEP\n")
    deck = head + "\n" + "\n".join(eqs) + sep + tail
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, job)
    blocks = res.get("displacements", "WATCH")
    if len(blocks) != len(cases):
        raise GeometryError(f"ccx printed {len(blocks)} displacement blocks for {len(cases)} "
                            "load cases")
    out = np.zeros((len(cases), len(phases), len(watch), 3), dtype=complex)
    for c, rows in enumerate(blocks):
        u = np.zeros((len(mesh.nodes), 3))
        u[rows[:, 0].astype(np.int64) - 1] = rows[:, 1:4]
        for p, (a, b) in enumerate(offsets):
            out[c, p] = u[watch + a] + (1j * u[watch + b] if b is not None else 0.0)
    return out, res.seconds


def chain_deflections(pitch: VolumeMesh, spec: CouplingSpec, period: int,
                      patterns: list[list[LoadCase]], loads: NDArray, *, workdir=None,
                      job: str = "bloch") -> tuple[NDArray[np.float64], float]:
    """Work-conjugate deflections of ``period`` teeth repeated round a chain (``period =
    N``: the whole ring; ``K < N``: a sector of K teeth with cyclic cuts) under patch loads.

    Parameters
    ----------
    patterns : list over cases of list over the ``period`` teeth of LoadCase
        Each tooth's unit pattern on the pitch mesh (tooth 0's frame; :func:`patch_load`).
    loads : (C, period) float
        Tooth loads (N, tangential at the pitch radius).

    Returns
    -------
    deflection_mm : (C, period) float
    seconds : float
    """
    C, K = np.shape(loads)
    n = len(pitch.nodes)
    harmonics = np.arange(K // 2 + 1)
    phases = 2 * math.pi * harmonics / K
    forces = np.zeros((C, len(phases), n, 3), dtype=complex)
    for c in range(C):
        for k, pat in enumerate(patterns[c]):
            if loads[c, k] == 0:
                continue
            w = loads[c, k] * np.exp(-1j * phases * k)
            np.add.at(forces[c], (slice(None), pat.nodes), w[:, None, None] * pat.forces)
    watch = np.unique(np.concatenate([p.nodes for pats in patterns for p in pats]))
    u, seconds = bloch_solve(pitch, spec, phases, forces, watch, workdir=workdir, job=job)
    weight = np.where((harmonics == 0) | (2 * harmonics == K), 1.0, 2.0) / K
    pos = np.searchsorted(watch, np.arange(n))
    out = np.zeros((C, K))
    for c in range(C):
        for k, pat in enumerate(patterns[c]):
            uk = np.einsum("p,pwd->wd", weight * np.exp(1j * phases * k), u[c][:, pos[pat.nodes]]).real
            out[c, k] = float(np.sum(pat.forces * uk))
    return out, seconds
