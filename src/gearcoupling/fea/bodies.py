"""The bodies under the teeth: whole hub and sleeve rings in CalculiX under tooth loads.

Mesh: one pitch of the part, meshed by gmsh with node-for-node periodic cuts
(:func:`~gearcoupling.fea.mesh_part`, ``sector=1, periodic=True``). Every tooth of the
ring is this pitch turned, so the ring's response is exactly circulant, and a sector of
copies (:func:`assemble`) has the same mesh under its teeth as the ring: the local
deformation under a patch load, which dwarfs the body term and moves with the mesh,
cancels between ring and sector.

Ring (:func:`ring_deflections`): solved harmonic by harmonic (:func:`bloch_solve`). The
tooth loads' discrete Fourier transform over the teeth loads one pitch per harmonic ``n``
whose ccw cut follows its cw cut turned by a pitch times ``exp(2 pi i n / N)`` (real and
imaginary parts on two copies of the pitch, tied by ``*EQUATION``); the teeth's
displacements are the inverse transform. Exactly the whole ring's linear solution, at
the cost of ``N / 2 + 1`` small solves instead of one of N pitches (measured: the same
tooth deflections as a direct solve of the assembled ring within 1e-6). A phase
``2 pi j / K`` gives a sector of ``K`` teeth with cyclic cuts instead.

Supports: the hub bore (``BORE``; ``END`` without a bore) or the sleeve outside diameter
(``OUTER``) fixed, as for the tooth table (:mod:`~gearcoupling.fea.stiffness`); the
table's own set-up, a 3-tooth sector whose cut faces are fixed as well, is
:func:`sector_self`.

Loads and measure: the table's patch load (:func:`~gearcoupling.fea.stiffness.load_case`:
frictionless, along the flank normal, a unit tangential load at the pitch radius) on any
tooth at any ``(z, r)`` of its loaded (ccw) flank; a tooth's deflection is the work
conjugate ``sum f_i . u_i`` of its unit pattern: the circumferential displacement at the
pitch radius, the table's measure (mm per N of tangential load at the pitch radius).

Body influence (:func:`body_influence_table`, cached per spec like the tooth table): the
ring's deflection of every tooth under a unit load on one tooth, and the table sector's
own deflection on the same mesh, at a few ``|z|`` at the pitch radius; their use is
:mod:`gearcoupling.loading.body`.
"""

from __future__ import annotations

import math
import resource
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ArgumentError, GeometryError
from ..geometry import rot_z
from ..io import cache_key, cached, inp_number, package_version, safe_name, store
from ..spec import CouplingSpec
from .ccx import run_ccx, solver_dir
from .deck import LoadCase, static_deck
from .mesh import check_size, mesh_part
from .stiffness import fe_cache_folder, load_case, material, spec_hash, table_array
from .volume import VolumeMesh, tet_volumes

BODIES_VERSION = 1  # bump when the set-up changes: old cache entries are then ignored
TABLE_SECTOR_TEETH = 3  # the tooth table's sector (fixed cuts)


def default_body_size(spec: CouplingSpec) -> float:
    """Default element size of the body rings: the coarsest :func:`check_size` allows on
    both parts (module / 2, or twice the smaller root fillet radius)."""
    return min(spec.tooth.module / 2.0, 2.0 * spec.hub.root.fillet_radius,
               2.0 * spec.sleeve.root_fillet_radius)


def pitch_mesh(spec: CouplingSpec, part: str, size_mm: float | None = None) -> VolumeMesh:
    """One pitch of ``part`` (tooth or space 0) with periodic cuts (default size
    :func:`default_body_size`)."""
    size = default_body_size(spec) if size_mm is None else size_mm
    return mesh_part(spec, part, sector=1, size_mm=size, periodic=True)


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


def _check_pitch(pitch: VolumeMesh) -> None:
    if pitch.teeth != [0] or "CUT_CW" not in pitch.regions:
        raise ArgumentError("pitch", pitch.teeth, "a one-pitch mesh of tooth 0 with its cuts "
                            "(pitch_mesh)")


def assemble(pitch: VolumeMesh, teeth: int, copies: int) -> VolumeMesh:
    """``copies`` copies of a one-pitch mesh turned by ``2 pi k / teeth`` (copy ``k`` holds
    tooth ``k``), each copy's cw cut joined node for node to the previous copy's ccw cut;
    ``copies = teeth`` closes the whole ring (no ``CUT`` regions), else the first copy's
    ``CUT_CW`` and the last one's ``CUT_CCW`` remain.

    Returns
    -------
    VolumeMesh
        Regions ``T<k>_...`` of copy ``k``; ``BORE``, ``END``, ``BODY``, ``OUTER`` joined;
        ``teeth`` ``None`` for the ring, else ``[0 .. copies - 1]``.
    """
    _check_pitch(pitch)
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
    return VolumeMesh(pitch.part, nodes, tets,
                      {k: np.concatenate(v) for k, v in regions.items()},
                      {k: np.concatenate(v) for k, v in faces.items()},
                      None if ring else list(range(copies)), pitch.size_mm,
                      {"nodes": len(nodes), "elements": len(tets), "copies": copies})


def patch_load(vm: VolumeMesh, spec: CouplingSpec, tooth: int, z_mm: float, r_mm: float,
               patch_mm: float) -> LoadCase:
    """The unit patch load of ``tooth`` at ``(z_mm, r_mm)`` (1 N tangential at the pitch
    radius; module docstring)."""
    case, _, _ = load_case(vm, float(z_mm), float(r_mm), spec.tooth.pitch_radius, patch_mm,
                        tooth=tooth)
    return case


def combine(cases: list[LoadCase], loads: ArrayLike) -> LoadCase:
    """One load case: unit patterns ``cases`` scaled by ``loads (k,)`` (N), summed per node."""
    nodes = np.concatenate([c.nodes for c in cases])
    forces = np.concatenate([c.forces * w for c, w in zip(cases, np.ravel(loads), strict=True)])
    uniq, inv = np.unique(nodes, return_inverse=True)
    out = np.zeros((len(uniq), 3))
    np.add.at(out, inv, forces)
    keep = np.any(out != 0, axis=1)
    return LoadCase(uniq[keep], out[keep])


def default_patch(spec: CouplingSpec, size_mm: float) -> float:
    """The load patch half-size of the tooth table (:mod:`~gearcoupling.fea.stiffness`)."""
    return max(size_mm, spec.tooth.module / 4.0)


def _support(vm: VolumeMesh) -> str:
    """The fixed region: bore (hub; ``END`` without one) or outside diameter (sleeve)."""
    return "OUTER" if vm.part == "sleeve" else ("BORE" if "BORE" in vm.regions else "END")


def _with_equations(deck: str, equations: list[str]) -> str:
    """The deck with ``*EQUATION`` lines before its first step."""
    head, sep, tail = deck.partition("\n*STEP\n")
    return head + "\n" + "\n".join(equations) + sep + tail


def _watched(res, name: str, count: int) -> list[NDArray[np.float64]]:
    blocks = res.get("displacements", name)
    if len(blocks) != count:
        raise GeometryError(f"ccx printed {len(blocks)} displacement blocks for {count} "
                            "load cases")
    return blocks


def sector_self(pitch: VolumeMesh, spec: CouplingSpec, z_mm: ArrayLike, r_mm: ArrayLike, *,
                patch_mm: float, sector: int = TABLE_SECTOR_TEETH, workdir=None,
                job: str = "sector") -> tuple[NDArray[np.float64], float]:
    """The tooth table's measure on copies of ``pitch``: the middle tooth's own deflection
    per unit load (mm/N) in a sector of ``sector`` teeth whose cuts are fixed as well as
    its bore / outside diameter (the table's set-up), at each point ``z_mm, r_mm (q,)``;
    and the solver's time (s)."""
    vm = assemble(pitch, spec.tooth.teeth, sector)
    pats = [patch_load(vm, spec, sector // 2, z, r, patch_mm)
            for z, r in zip(np.ravel(z_mm), np.ravel(r_mm), strict=True)]
    watch = np.unique(np.concatenate([p.nodes for p in pats]))
    E, nu = material(spec, vm.part)
    deck = static_deck(vm, youngs_modulus_MPa=E, poisson_ratio=nu, fixed=[_support(vm), "CUT"],
                       cases=pats, node_print=[("WATCH", watch)])
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, job)
    out = np.empty(len(pats))
    for i, rows in enumerate(_watched(res, "WATCH", len(pats))):
        u = np.zeros((len(vm.nodes), 3))
        u[rows[:, 0].astype(np.int64) - 1] = rows[:, 1:4]
        out[i] = float(np.sum(pats[i].forces * u[pats[i].nodes]))
    return out, res.seconds


def stack(pitch: VolumeMesh, blocks: int) -> VolumeMesh:
    """``blocks`` disjoint copies of a mesh at the same place (copy ``b``'s nodes offset by
    ``b n``) with only the support region, joined."""
    n, m = len(pitch.nodes), len(pitch.tets)
    name = _support(pitch)
    tri, faces = pitch.regions[name], pitch.faces[name]
    return VolumeMesh(pitch.part, np.tile(pitch.nodes, (blocks, 1)),
                      np.concatenate([pitch.tets + b * n for b in range(blocks)]),
                      {name: np.concatenate([tri + b * n for b in range(blocks)])},
                      {name: np.concatenate([faces + np.array([b * m, 0])
                                             for b in range(blocks)])},
                      [0], pitch.size_mm, {"nodes": n * blocks, "elements": m * blocks})


def bloch_equations(cw: NDArray, ccw: NDArray, turn: NDArray, phase: float, a: int,
                    b: int | None, skip: set) -> list[str]:
    """``*EQUATION`` lines of a Bloch-periodic pitch: the ccw cut follows the cw cut turned
    by ``turn (3, 3)`` times ``exp(i phase)``; the real part lives on the copy whose nodes
    are offset by ``a``, the imaginary part on ``b`` (``None`` when the phase is 0 or pi:
    real). ``cw, ccw`` 0-based partner nodes; pairs whose ccw node is in ``skip`` (fixed)
    are left out."""
    c, s = math.cos(phase), math.sin(phase)
    parts = ([(a, [(a, c), (b, -s)]), (b, [(a, s), (b, c)])] if b is not None
             else [(a, [(a, c)])])
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


def bloch_solve(pitch: VolumeMesh, spec: CouplingSpec, phases: ArrayLike, forces: NDArray,
                watch: NDArray, *, per_run: int = 4, workdir=None, job: str = "bloch"
                ) -> tuple[NDArray[np.complex128], float]:
    """Displacements of a chain of pitches whose loads and response go as
    ``exp(i phase k)`` from pitch to pitch (module docstring).

    Each phase is one pitch mesh (two, real and imaginary part, unless the phase is 0 or
    pi) tied by :func:`bloch_equations`; ``per_run`` phases share one ccx run as disjoint
    meshes (the solver's memory grows with it), every case is a step. Phases without load
    are not solved (their response is 0).

    Parameters
    ----------
    phases : (P,) float
        Bloch phases per pitch (rad): ``2 pi n / N`` for harmonic ``n`` of the ring,
        ``2 pi j / K`` for a cyclic sector of ``K`` pitches.
    forces : (C, P, n, 3) complex
        Nodal forces on the pitch's nodes of every case and phase; imaginary parts at a
        phase of 0 or pi are ignored.
    watch : (w,) int
        Pitch nodes to return.

    Returns
    -------
    u : (C, P, w, 3) complex
    seconds : float
        The solver's time, all runs.
    """
    _check_pitch(pitch)
    phases = np.asarray(phases, dtype=float)
    forces = np.asarray(forces)
    out = np.zeros((len(forces), len(phases), len(watch), 3), dtype=complex)
    loaded = [p for p in range(len(phases)) if np.any(forces[:, p] != 0)]
    step = max(1, int(per_run))
    seconds = 0.0
    with solver_dir(workdir) as work:
        for g in range(0, len(loaded), step):
            group = loaded[g:g + step]
            cases = [c for c in range(len(forces)) if np.any(forces[c][group] != 0)]
            u, secs = _bloch_run(pitch, spec, phases[group], forces[cases][:, group], watch,
                                 work, f"{job}_{g // step}")
            out[np.ix_(cases, group)] = u
            seconds += secs
    return out, seconds


def _bloch_run(pitch: VolumeMesh, spec: CouplingSpec, phases: NDArray, forces: NDArray,
               watch: NDArray, work, job: str) -> tuple[NDArray[np.complex128], float]:
    """One ccx run of :func:`bloch_solve`: ``phases (P,)``, ``forces (C, P, n, 3)``."""
    n = len(pitch.nodes)
    offsets, k = [], 0
    for ph in phases:
        real = abs(math.sin(ph)) < 1e-12
        offsets.append((k * n, None if real else (k + 1) * n))
        k += 1 if real else 2
    mesh = stack(pitch, k)
    turn = rot_z(2 * math.pi / spec.tooth.teeth)
    cw, ccw = _cut_partners(pitch, 2 * math.pi / spec.tooth.teeth)
    skip = set(pitch.node_set(_support(pitch)).tolist())
    eqs = [line for ph, (a, b) in zip(phases, offsets, strict=True)
           for line in bloch_equations(cw, ccw, turn, float(ph), a, b, skip)]
    cases = []
    for f in forces:
        parts = []
        for p, (a, b) in enumerate(offsets):
            hit = np.flatnonzero(np.any(f[p] != 0, axis=1))
            parts.append((hit + a, f[p][hit].real))
            if b is not None:
                parts.append((hit + b, f[p][hit].imag))
        cases.append(LoadCase(np.concatenate([q for q, _ in parts]),
                              np.concatenate([v for _, v in parts])))
    E, nu = material(spec, pitch.part)
    watched = np.unique(np.concatenate([watch + a for a, _ in offsets]
                                       + [watch + b for _, b in offsets if b is not None]))
    deck = static_deck(mesh, youngs_modulus_MPa=E, poisson_ratio=nu, fixed=[_support(pitch)],
                       cases=cases, node_print=[("WATCH", watched)])
    res = run_ccx(_with_equations(deck, eqs), work, job)
    out = np.zeros((len(cases), len(phases), len(watch), 3), dtype=complex)
    for c, rows in enumerate(_watched(res, "WATCH", len(cases))):
        u = np.zeros((len(mesh.nodes), 3))
        u[rows[:, 0].astype(np.int64) - 1] = rows[:, 1:4]
        for p, (a, b) in enumerate(offsets):
            out[c, p] = u[watch + a] + (1j * u[watch + b] if b is not None else 0.0)
    return out, res.seconds


@dataclass(frozen=True)
class RingSolution:
    """A ring (or cyclic sector) solved harmonic by harmonic: ``deflection_mm (C, K)`` of
    every tooth per case; ``shell_twist_rad (C,)`` the turn of the body shell
    (:func:`body_shell`) averaged over its volume (0 unless asked for); the pitch mesh's
    ``nodes``, the ``harmonics`` solved (those with load), the solver's time and the
    largest solver memory so far (MB)."""

    deflection_mm: NDArray[np.float64]
    shell_twist_rad: NDArray[np.float64]
    nodes: int
    harmonics: int
    solve_seconds: float
    max_rss_MB: float


def body_shell(pitch: VolumeMesh) -> tuple[float, float, float, float]:
    """``(fixed radius, shell inner radius, shell outer radius, length)`` (mm) of a part's
    full-length body, read off its mesh: the hub from its bore to its root (to the shoulder
    where the body is longer than the teeth), the sleeve from its tooth root (major
    diameter) to its outside diameter, each over its length. The shell is the half away
    from the fixed radius, where the twist is largest."""
    def radii(name: str) -> NDArray[np.float64]:
        q = pitch.nodes[pitch.node_set(name)]
        return np.hypot(q[:, 0], q[:, 1])

    fixed = _support(pitch)
    if fixed == "END":
        raise ArgumentError("pitch", pitch.part, "a hub with a bore: without one the body's "
                            "twist depends on the shaft")
    a = float(np.median(radii(fixed)))
    zf = pitch.nodes[pitch.node_set(fixed), 2]
    if pitch.part == "hub":
        b = float(radii("BODY").min() if "BODY" in pitch.regions else radii("T0_ROOT").min())
        return a, 0.5 * (a + b), b, float(np.ptp(zf))
    b = float(radii("T0_ROOT").min())
    return a, b, 0.5 * (a + b), float(np.ptp(zf))


def _shell_tets(pitch: VolumeMesh) -> NDArray[np.int64]:
    """Tetrahedra of the pitch whose centroid lies in the body shell (:func:`body_shell`)."""
    _, r1, r2, _ = body_shell(pitch)
    c = pitch.nodes[pitch.tets[:, :4]].mean(axis=1)
    r = np.hypot(c[:, 0], c[:, 1])
    return np.flatnonzero((r >= r1) & (r <= r2))


def shell_twist(pitch: VolumeMesh, tets: NDArray, u: NDArray) -> NDArray[np.float64]:
    """Volume mean of the turn ``u_theta / r`` over the tetrahedra ``tets (t,)`` of the pitch
    for displacements ``u (..., n, 3)`` (quadratic interpolation at each centroid)."""
    el = pitch.tets[tets]
    w = np.array([-0.125] * 4 + [0.25] * 6)  # C3D10 shape functions at the centroid
    x = np.einsum("j,ejd->ed", w, pitch.nodes[el])  # (t, 3)
    uc = np.einsum("j,...ejd->...ed", w, u[..., el, :])  # (..., t, 3)
    turn = (x[:, 0] * uc[..., 1] - x[:, 1] * uc[..., 0]) / (x[:, 0] ** 2 + x[:, 1] ** 2)
    vol = np.abs(tet_volumes(pitch.nodes, el))
    return np.sum(turn * vol, axis=-1) / vol.sum()


def chain_deflections(pitch: VolumeMesh, spec: CouplingSpec, period: int,
                      patterns: list[list[LoadCase]], loads: ArrayLike, *,
                      shell: bool = False, per_run: int = 4, workdir=None,
                      job: str = "ring") -> RingSolution:
    """Work-conjugate deflections of ``period`` teeth repeated round a chain (``period =
    N``: the whole ring; ``K < N``: a sector of K teeth with cyclic cuts) under patch
    loads, harmonic by harmonic (:func:`bloch_solve`).

    Parameters
    ----------
    patterns : list over cases of list over the ``period`` teeth of LoadCase
        Each tooth's unit pattern on the pitch mesh (tooth 0's frame; :func:`patch_load`).
    loads : (C, period) float
        Tooth loads (N, tangential at the pitch radius).
    shell : bool
        Also the volume-mean turn of the body shell (:func:`body_shell`) per case.
    """
    loads = np.asarray(loads, dtype=float)
    C, K = loads.shape
    n = len(pitch.nodes)
    harmonics = np.arange(K // 2 + 1)
    phases = 2 * math.pi * harmonics / K
    forces = np.zeros((C, len(phases), n, 3), dtype=complex)
    for c in range(C):
        for k, pat in enumerate(patterns[c]):
            if loads[c, k] != 0:
                w = loads[c, k] * np.exp(-1j * phases * k)
                forces[c][:, pat.nodes] += w[:, None, None] * pat.forces  # nodes unique
    forces[np.abs(forces) <= 1e-12 * np.abs(forces).max(initial=0.0)] = 0.0  # rounding
    tets = _shell_tets(pitch) if shell else np.zeros(0, np.int64)
    extra = np.unique(pitch.tets[tets])
    watch = np.unique(np.concatenate([p.nodes for pats in patterns for p in pats] + [extra]))
    u, seconds = bloch_solve(pitch, spec, phases, forces, watch, per_run=per_run,
                             workdir=workdir, job=job)
    weight = np.where((harmonics == 0) | (2 * harmonics == K), 1.0, 2.0) / K
    pos = np.searchsorted(watch, np.arange(n))
    out = np.zeros((C, K))
    for c in range(C):
        for k, pat in enumerate(patterns[c]):
            turn = weight * np.exp(1j * phases * k)
            uk = np.einsum("p,pwd->wd", turn, u[c][:, pos[pat.nodes]]).real
            out[c, k] = float(np.sum(pat.forces * uk))
    twist = np.zeros(C)
    if shell:
        mean = np.zeros((C, n, 3))
        mean[:, extra] = u[:, 0, pos[extra]].real / K  # the teeth's mean: harmonic 0
        twist = shell_twist(pitch, tets, mean)
    solved = int(np.sum(np.any(forces != 0, axis=(0, 2, 3))))
    return RingSolution(out, twist, n, solved, seconds,
                        resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024)


def unit_patterns(pitch: VolumeMesh, spec: CouplingSpec, z_mm: ArrayLike, r_mm: ArrayLike,
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


def ring_deflections(pitch: VolumeMesh, spec: CouplingSpec, loads: ArrayLike, z_mm: ArrayLike,
                     r_mm: ArrayLike, *, patch_mm: float, period: int | None = None,
                     shell: bool = False, per_run: int = 4, workdir=None,
                     job: str = "ring") -> RingSolution:
    """Each tooth's deflection (work conjugate of its own unit pattern, mm) under every
    tooth's load at its own point, round the whole ring of ``pitch`` copies (``period``
    ``None``: N teeth) or a sector of ``period`` teeth with cyclic cuts.

    Parameters
    ----------
    loads : (C, K) float
        Tangential load of every tooth at the pitch radius (N), per case.
    z_mm, r_mm : (C, K) float, broadcast
        Every tooth's load point (hub frame).
    patch_mm : float
        Half-size of the load patches (:func:`default_patch`).
    shell : bool
        Also the volume-mean turn of the body shell per case (:func:`body_shell`).
    per_run : int
        Harmonics per ccx run (memory against runs).
    """
    loads = np.atleast_2d(np.asarray(loads, dtype=float))
    K = spec.tooth.teeth if period is None else period
    if not (isinstance(K, int) and 1 <= K <= spec.tooth.teeth):
        raise ArgumentError("period", period, f"a whole number of teeth from 1 to "
                            f"{spec.tooth.teeth}")
    if loads.shape[1] != K or not np.all(np.isfinite(loads)):
        raise ArgumentError("loads", loads.shape, f"finite, shaped (cases, {K}): one load "
                            "per tooth")
    z = np.broadcast_to(np.asarray(z_mm, dtype=float), loads.shape)
    r = np.broadcast_to(np.asarray(r_mm, dtype=float), loads.shape)
    pats = [unit_patterns(pitch, spec, z[c], r[c], patch_mm) for c in range(len(loads))]
    return chain_deflections(pitch, spec, K, pats, loads, shell=shell, per_run=per_run,
                             workdir=workdir, job=job)


@dataclass(frozen=True)
class BodyInfluenceTable:
    """The bodies' influence between teeth: the FE ring and the tooth table's sector.

    Attributes
    ----------
    z_mm : (nz,) float
        Axial load points ``|z|`` at the pitch radius (the ring is even in z).
    ring_mm_per_N : (2, nz, N) float
        Hub / sleeve ring: deflection of tooth ``m`` (work conjugate of its unit pattern at
        ``(z_i, R)``) under a unit tangential load on tooth 0 at the same point.
    sector_mm_per_N : (2, nz) float
        The loaded tooth's own deflection in the tooth table's 3-tooth sector with fixed
        cuts, on the same mesh and patch: the part the table already holds.
    shell_twist_rad_per_Nmm : (2,) float
        Hub / sleeve: volume-mean turn of the body shell (:func:`body_shell`) per N·mm of
        torque on every tooth alike (against the bore / the outside diameter).
    pitch_radius_mm : float
    info : dict
        Spec name and hash, element size, patch, shells, nodes, harmonics, times.
    """

    z_mm: NDArray[np.float64]
    ring_mm_per_N: NDArray[np.float64]
    sector_mm_per_N: NDArray[np.float64]
    shell_twist_rad_per_Nmm: NDArray[np.float64]
    pitch_radius_mm: float
    info: dict = field(default_factory=dict)

    @property
    def kernel_mm_per_N(self) -> NDArray[np.float64]:
        """Hub + sleeve body kernel ``(nz, N)`` (mm/N): the ring less, on the loaded tooth,
        what the 3-tooth table holds (:mod:`gearcoupling.loading.body`)."""
        k = self.ring_mm_per_N.sum(axis=0)
        k[:, 0] -= self.sector_mm_per_N.sum(axis=0)
        return k

    def to_dict(self) -> dict:
        d = asdict(self)
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in d.items()}

    @classmethod
    def from_dict(cls, d: dict) -> BodyInfluenceTable:
        """The table of :meth:`to_dict`'s data, checked (shapes as documented, values
        finite, the loaded tooth's own deflections and the pitch radius positive); else
        :class:`~gearcoupling.errors.ArgumentError` naming the field."""
        if not isinstance(d, dict):
            raise ArgumentError("table", type(d).__name__, "a dict of the table's fields")
        z = table_array(d, "z_mm", None, fewest=1)
        ring = np.asarray(d.get("ring_mm_per_N"), dtype=object)
        teeth = ring.shape[2] if ring.ndim == 3 else 0
        ring = table_array(d, "ring_mm_per_N", (2, z.size, teeth))
        if not np.all(ring[:, :, 0] > 0):
            raise ArgumentError("ring_mm_per_N", "a loaded tooth's own deflection <= 0",
                                "positive on the loaded tooth")
        info = d.get("info", {})
        if not isinstance(info, dict):
            raise ArgumentError("info", type(info).__name__, "a dict")
        return cls(z, ring, table_array(d, "sector_mm_per_N", (2, z.size), "positive"),
                   table_array(d, "shell_twist_rad_per_Nmm", (2,)),
                   float(table_array(d, "pitch_radius_mm", (), "positive")), info)


def compute_body_influence(spec: CouplingSpec, *, size_mm: float | None = None, nz: int = 3,
                           workdir=None) -> BodyInfluenceTable:
    """Solve the ring and the 3-tooth sector of hub and sleeve (no cache): unit loads at
    ``|z|`` from 0 to 0.8 of the hub half face at the pitch radius, and every tooth loaded
    alike for the shell's twist."""
    size = default_body_size(spec) if size_mm is None else float(size_mm)
    if not (isinstance(nz, int) and nz >= 1):
        raise ArgumentError("nz", nz, "a whole number of axial load points, at least 1")
    R, N = spec.tooth.pitch_radius, spec.tooth.teeth
    z = np.linspace(0.0, 0.4 * spec.hub.face_width, nz)
    patch = default_patch(spec, size)
    ring, sector, twist = [], [], []
    info: dict = {"spec": spec.name, "size_mm": size, "patch_mm": patch, "parts": {}}
    t0 = time.perf_counter()
    with solver_dir(workdir) as work:
        for part in ("hub", "sleeve"):
            pitch = pitch_mesh(spec, part, size)
            loads = np.zeros((nz + 1, N))
            loads[:nz, 0] = 1.0
            loads[nz] = 1.0
            zz = np.zeros((nz + 1, N))
            zz[:nz] = z[:, None]
            sol = ring_deflections(pitch, spec, loads, zz, R, patch_mm=patch, shell=True,
                                   workdir=work, job=f"{part}_ring")
            own, secs = sector_self(pitch, spec, z, np.full(nz, R), patch_mm=patch,
                                    workdir=work, job=f"{part}_sector")
            ring.append(sol.deflection_mm[:nz])
            sector.append(own)
            twist.append(sol.shell_twist_rad[nz] / (N * R))
            info["parts"][part] = {"pitch_nodes": sol.nodes, "harmonics": sol.harmonics,
                                   "shell_mm": list(body_shell(pitch)),
                                   "ring_seconds": sol.solve_seconds, "sector_seconds": secs,
                                   "max_rss_MB": sol.max_rss_MB}
    info["total_seconds"] = time.perf_counter() - t0
    return BodyInfluenceTable(z, np.array(ring), np.array(sector), np.array(twist), R, info)


def body_influence_table(spec: CouplingSpec, *, size_mm: float | None = None, nz: int = 3,
                         cache: str | Path | None = None, refresh: bool = False
                         ) -> BodyInfluenceTable:
    """The body influence table of a spec (:func:`compute_body_influence`), cached like the
    tooth table (:func:`~gearcoupling.fea.tooth_compliance_table`: used only when its key
    and checksum match) in ``<cache>/<name>-bodies-<hash>.json``; ``refresh`` recomputes
    it."""
    size = default_body_size(spec) if size_mm is None else size_mm
    size = min(check_size(spec, "hub", size), check_size(spec, "sleeve", size))
    key = cache_key("FE body influence table", BODIES_VERSION, size_mm=size, nz=nz,
                    spec_hash=spec_hash(spec, size_mm=size, nz=nz, kind="bodies",
                                        version=BODIES_VERSION, package=package_version()))
    path = fe_cache_folder(cache) / f"{safe_name(spec.name)}-bodies-{key['spec_hash']}.json"
    found = None if refresh else cached(path, key, BodyInfluenceTable.from_dict,
                                        f"the FE body influence table of {spec.name!r}")
    if found is not None:
        return found
    table = compute_body_influence(spec, size_mm=size, nz=nz)
    table.info["spec_hash"] = key["spec_hash"]
    store(path, key, table.to_dict())
    return table
