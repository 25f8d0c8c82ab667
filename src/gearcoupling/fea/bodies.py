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

import json
import math
import resource
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentError, GeometryError
from ..geometry import rot_z
from ..io import inp_number, safe_name, write_json
from ..spec import CouplingSpec
from .ccx import run_ccx, solver_dir
from .deck import LoadCase, static_deck
from .mesh import check_size, mesh_part
from .reference import cyclic_equations
from .stiffness import cache_dir, load_case, material, spec_hash
from .volume import VolumeMesh

SUPPORTS = ("ring", "fixed", "cyclic")
BODIES_VERSION = 1  # bump when the set-up changes: old cache entries are then ignored


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
            faces.setdefault(key, []).append(pitch.faces[name] + np.array([k * m, 0]))
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


@dataclass(frozen=True)
class RingSolution:
    """Deflections of a ring (or cyclic sector) solved harmonic by harmonic:
    ``deflection_mm (C, K)`` of every tooth per case, ``twist_rad (C,)`` the mean turn of
    the watched root nodes (0 when none were asked for), the pitch mesh's ``nodes``, the
    number of ``harmonics`` solved, solver time and the largest solver memory so far."""

    deflection_mm: NDArray[np.float64]
    twist_rad: NDArray[np.float64]
    nodes: int
    harmonics: int
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
                      {support: np.concatenate([faces + np.array([b * m, 0]) for b in range(blocks)])},
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
                watch: NDArray, *, per_run: int = 4, workdir=None, job: str = "bloch"
                ) -> tuple[NDArray[np.complex128], float]:
    """Displacements of a chain of pitches whose loads and response go as
    ``exp(i phase k)`` from pitch to pitch.

    Each phase is one pitch mesh (two, real and imaginary part, unless the phase is 0 or
    pi) whose ccw cut follows its cw cut turned by a pitch times ``exp(i phase)``
    (:func:`bloch_equations`); ``per_run`` phases share one ccx run as disjoint meshes
    (the solver's memory grows with it), every case is a step. Phases without load are
    not solved (their response is 0).

    Parameters
    ----------
    phases : (P,) float
        Bloch phases per pitch (rad): ``2 pi n / N`` for harmonic ``n`` of the ring,
        ``2 pi j / K`` for a cyclic sector of ``K`` pitches.
    forces : (C, P, n, 3) complex
        Nodal forces on the pitch's nodes of every case and phase (the teeth's loads'
        discrete Fourier transform); imaginary parts at a phase of 0 or pi are ignored.
    watch : (w,) int
        Pitch nodes to return.

    Returns
    -------
    u : (C, P, w, 3) complex
    seconds : float
        The solver's time, all runs.
    """
    phases = np.asarray(phases, dtype=float)
    forces = np.asarray(forces)
    out = np.zeros((len(forces), len(phases), len(watch), 3), dtype=complex)
    loaded = [p for p in range(len(phases)) if np.any(forces[:, p] != 0)]
    seconds = 0.0
    with solver_dir(workdir) as work:
        for g in range(0, len(loaded), max(1, int(per_run))):
            group = loaded[g:g + max(1, int(per_run))]
            cases = [c for c in range(len(forces)) if np.any(forces[c][group] != 0)]
            u, secs = _bloch_run(pitch, spec, phases[group], forces[cases][:, group], watch,
                                 work, f"{job}_{g}")
            out[np.ix_(cases, group)] = u
            seconds += secs
    return out, seconds


def _bloch_run(pitch: VolumeMesh, spec: CouplingSpec, phases: NDArray, forces: NDArray,
               watch: NDArray, work, job: str) -> tuple[NDArray[np.complex128], float]:
    """One ccx run of :func:`bloch_solve`: ``phases (P,)``, ``forces (C, P, n, 3)``."""
    n = len(pitch.nodes)
    real = np.isclose(np.sin(phases), 0.0, atol=1e-12)
    offsets, k = [], 0
    for r in real:
        offsets.append((k * n, None if r else (k + 1) * n))
        k += 1 if r else 2
    mesh = stack(pitch, k)
    cw, ccw = _cut_partners(pitch, 2 * math.pi / spec.tooth.teeth)
    support = fixed_sets(pitch, "ring")
    skip = set(pitch.node_set(support[0]).tolist())
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
    deck = static_deck(mesh, youngs_modulus_MPa=E, poisson_ratio=nu, fixed=support,
                       cases=cases, node_print=[("WATCH", np.unique(watched))])
    head, sep, tail = deck.partition("\n*STEP\n")
    res = run_ccx(head + "\n" + "\n".join(eqs) + sep + tail, work, job)
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
                      patterns: list[list[LoadCase]], loads: NDArray, *,
                      twist_nodes: NDArray | None = None, workdir=None,
                      job: str = "bloch") -> RingSolution:
    """Work-conjugate deflections of ``period`` teeth repeated round a chain (``period =
    N``: the whole ring; ``K < N``: a sector of K teeth with cyclic cuts) under patch loads.

    Parameters
    ----------
    patterns : list over cases of list over the ``period`` teeth of LoadCase
        Each tooth's unit pattern on the pitch mesh (tooth 0's frame; :func:`patch_load`).
    loads : (C, period) float
        Tooth loads (N, tangential at the pitch radius).

    twist_nodes : (t,) int, optional
        Pitch nodes whose mean turn ``u_theta / r`` over the teeth is returned per case
        (the root circle: the body's twist).
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
    extra = np.zeros(0, np.int64) if twist_nodes is None else np.asarray(twist_nodes)
    watch = np.unique(np.concatenate([p.nodes for pats in patterns for p in pats] + [extra]))
    u, seconds = bloch_solve(pitch, spec, phases, forces, watch, workdir=workdir, job=job)
    weight = np.where((harmonics == 0) | (2 * harmonics == K), 1.0, 2.0) / K
    pos = np.searchsorted(watch, np.arange(n))
    out = np.zeros((C, K))
    for c in range(C):
        for k, pat in enumerate(patterns[c]):
            turn = weight * np.exp(1j * phases * k)
            uk = np.einsum("p,pwd->wd", turn, u[c][:, pos[pat.nodes]]).real
            out[c, k] = float(np.sum(pat.forces * uk))
    twist = np.zeros(C)
    if len(extra):
        p, u0 = pitch.nodes[extra], u[:, 0, pos[extra]].real / K  # (C, t, 3)
        twist = np.mean((p[:, 0] * u0[..., 1] - p[:, 1] * u0[..., 0])
                        / (p[:, 0] ** 2 + p[:, 1] ** 2), axis=-1)
    return RingSolution(out, twist, len(pitch.nodes), len(phases), seconds,
                        resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024)


def unit_patterns(pitch: VolumeMesh, spec: CouplingSpec, z_mm, r_mm,
                  patch_mm: float) -> list[LoadCase]:
    """Unit patch patterns on the pitch's tooth at the points ``z_mm, r_mm (k,)`` (equal
    points share one pattern)."""
    seen: dict[tuple[float, float], LoadCase] = {}
    out = []
    for z, r in zip(np.ravel(z_mm), np.ravel(r_mm), strict=True):
        key = (round(float(z), 9), round(float(r), 9))
        if key not in seen:
            seen[key] = patch_load(pitch, spec, 0, key[0], key[1], patch_mm)
        out.append(seen[key])
    return out


def ring_deflections(pitch: VolumeMesh, spec: CouplingSpec, loads, z_mm, r_mm, *,
                     patch_mm: float, period: int | None = None, twist: bool = False,
                     workdir=None, job: str = "ring") -> RingSolution:
    """Each tooth's deflection (work conjugate of its own unit pattern, mm) under every
    tooth's load at its own point, round the whole ring of ``pitch`` copies (``period``
    ``None``: N teeth) or a cyclic sector of ``period`` teeth.

    Parameters
    ----------
    loads, z_mm, r_mm : (C, K) float
        Tangential load at the pitch radius (N) and load point of every tooth, per case.

    twist : bool
        Also the mean turn of the tooth root circle (hub ``ROOT``; sleeve ``ROOT``, at its
        major diameter) per case.
    """
    loads = np.atleast_2d(np.asarray(loads, dtype=float))
    K = spec.tooth.teeth if period is None else int(period)
    z = np.broadcast_to(np.asarray(z_mm, dtype=float), loads.shape)
    r = np.broadcast_to(np.asarray(r_mm, dtype=float), loads.shape)
    if loads.shape[1] != K:
        raise ArgumentError("loads", loads.shape, f"(cases, {K}): one load per tooth")
    pats = [unit_patterns(pitch, spec, z[c], r[c], patch_mm) for c in range(len(loads))]
    roots = pitch.node_set("T0_ROOT") if twist else None
    return chain_deflections(pitch, spec, K, pats, loads, twist_nodes=roots, workdir=workdir,
                             job=job)


def sector_self(pitch: VolumeMesh, spec: CouplingSpec, z_mm, r_mm, *, patch_mm: float,
                sector: int = 3, workdir=None, job: str = "sector"
                ) -> tuple[NDArray[np.float64], float]:
    """The tooth table's measure on copies of ``pitch``: the middle tooth's own deflection
    per unit load (mm/N) in a sector of ``sector`` teeth with fixed cuts (the table's
    :data:`~gearcoupling.fea.stiffness` set-up), at each point ``z_mm, r_mm (q,)``."""
    vm = assemble(pitch, spec.tooth.teeth, sector)
    pats = [patch_load(vm, spec, sector // 2, z, r, patch_mm)
            for z, r in zip(np.ravel(z_mm), np.ravel(r_mm), strict=True)]
    sol = solve_patches(vm, spec, pats, pats, supports="fixed", workdir=workdir, job=job)
    return np.diag(sol.deflection_mm).copy(), sol.solve_seconds


@dataclass(frozen=True)
class BodyInfluenceTable:
    """The bodies' influence between teeth, from the FE ring and the table's sector.

    Attributes
    ----------
    z_mm : (nz,) float
        Axial load points ``|z|`` at the pitch radius (the ring is even in z).
    ring_mm_per_N : (2, nz, N) float
        Hub / sleeve ring: deflection of tooth ``m`` (work conjugate of its unit pattern at
        ``(z_i, R)``) under a unit tangential load on tooth 0 at the same point.
    sector_mm_per_N : (2, nz) float
        The loaded tooth's own deflection in the tooth table's 3-tooth sector with fixed
        cuts, on the same mesh: what the table already holds.
    root_twist_rad_per_N : (2,) float
        Mean turn of the root circle per N of load on every tooth (hub: against the bore;
        sleeve: against the outside diameter).
    pitch_radius_mm : float
    info : dict
        Spec name and hash, element size, patch, nodes, harmonics, times.
    """

    z_mm: NDArray[np.float64]
    ring_mm_per_N: NDArray[np.float64]
    sector_mm_per_N: NDArray[np.float64]
    root_twist_rad_per_N: NDArray[np.float64]
    pitch_radius_mm: float
    info: dict = field(default_factory=dict)

    @property
    def kernel_mm_per_N(self) -> NDArray[np.float64]:
        """Hub + sleeve body influence ``(nz, N)``: ring less, on the loaded tooth, what
        the 3-tooth table holds (``b(m)``, :mod:`gearcoupling.loading.body`)."""
        k = self.ring_mm_per_N.sum(axis=0)
        k[:, 0] -= self.sector_mm_per_N.sum(axis=0)
        return k

    def to_dict(self) -> dict:
        d = asdict(self)
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in d.items()}

    @classmethod
    def from_dict(cls, d: dict) -> BodyInfluenceTable:
        arrays = {k: np.asarray(d[k], dtype=float) for k in
                  ("z_mm", "ring_mm_per_N", "sector_mm_per_N", "root_twist_rad_per_N")}
        return cls(**arrays, pitch_radius_mm=float(d["pitch_radius_mm"]), info=d["info"])


def compute_body_influence(spec: CouplingSpec, *, size_mm: float | None = None, nz: int = 3,
                           workdir=None) -> BodyInfluenceTable:
    """Solve the ring and the 3-tooth sector of hub and sleeve (no cache): unit loads at
    ``|z|`` from 0 to 0.8 of the hub half face at the pitch radius."""
    size = default_size_bodies(spec) if size_mm is None else float(size_mm)
    R, N = spec.tooth.pitch_radius, spec.tooth.teeth
    z = np.linspace(0.0, 0.4 * spec.hub.face_width, nz)
    patch = default_patch(spec, size)
    ring, sector, twist, info = [], [], [], {"spec": spec.name, "size_mm": size,
                                             "patch_mm": patch, "parts": {}}
    t0 = time.perf_counter()
    with solver_dir(workdir) as work:
        for part in ("hub", "sleeve"):
            pitch = pitch_mesh(spec, part, size)
            loads = np.zeros((nz + 1, N))
            loads[:nz, 0] = 1.0
            loads[nz] = 1.0  # every tooth at mid-face: the root twist
            zz = np.zeros((nz + 1, N))
            zz[:nz] = z[:, None]
            sol = ring_deflections(pitch, spec, loads, zz, R, patch_mm=patch, twist=True,
                                   workdir=work, job=f"{part}_ring")
            self_, secs = sector_self(pitch, spec, z, np.full(nz, R), patch_mm=patch,
                                      workdir=work, job=f"{part}_sector")
            ring.append(sol.deflection_mm[:nz])
            sector.append(self_)
            twist.append(sol.twist_rad[nz])
            info["parts"][part] = {"pitch_nodes": sol.nodes, "harmonics": sol.harmonics,
                                   "ring_seconds": sol.solve_seconds,
                                   "sector_seconds": secs, "max_rss_MB": sol.max_rss_MB}
    info["total_seconds"] = time.perf_counter() - t0
    return BodyInfluenceTable(z, np.array(ring), np.array(sector), np.array(twist), R, info)


def default_size_bodies(spec: CouplingSpec) -> float:
    """Default element size of the body rings: the coarsest :func:`check_size` allows on
    both parts (module / 2, or twice the smaller root fillet radius)."""
    return min(spec.tooth.module / 2.0, 2.0 * spec.hub.root.fillet_radius,
               2.0 * spec.sleeve.root_fillet_radius)


def body_influence_table(spec: CouplingSpec, *, size_mm: float | None = None, nz: int = 3,
                         cache: str | Path | None = None, refresh: bool = False
                         ) -> BodyInfluenceTable:
    """The body influence table of a spec, cached like the tooth table
    (:func:`~gearcoupling.fea.tooth_compliance_table`: ``<cache>/<name>-<hash>.json``)."""
    size = default_size_bodies(spec) if size_mm is None else size_mm
    check_size(spec, "hub", size)
    check_size(spec, "sleeve", size)
    key = spec_hash(spec, size_mm=size, nz=nz, kind="bodies", version=BODIES_VERSION)
    path = (Path(cache) if cache is not None else cache_dir()) / \
        f"{safe_name(spec.name)}-bodies-{key}.json"
    if path.exists() and not refresh:
        return BodyInfluenceTable.from_dict(json.loads(path.read_text()))
    table = compute_body_influence(spec, size_mm=size, nz=nz)
    table.info["spec_hash"] = key
    write_json(path, table.to_dict())
    return table
