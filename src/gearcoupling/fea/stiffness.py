"""Tooth compliance and mesh stiffness from CalculiX on hub and sleeve tooth sectors.

Set-up (both parts): a sector of ``sector`` teeth (default 3) meshed by
:func:`gearcoupling.fea.mesh_part`; the middle tooth is loaded. Supports: the hub bore
(``BORE``), the sleeve outside diameter (``OUTER``) and both sector cut planes (``CUT``)
fully fixed (fixed, not cyclic: the cuts lie half a pitch beyond the neighbouring teeth,
and fixing them makes the sector slightly stiffer than the whole part). A hub without a
bore is held on its body end faces instead.

Load: a force along the exact surface normal (into the tooth, no friction), spread as
equal nodal forces over the flank nodes of a small patch (``|dz|, |dr| <= patch``) around
the point ``(z, r)``, scaled so that its moment about the axis is ``1 N x R`` (a unit
tangential load at the pitch radius R). The hub is loaded on its ccw flank, the sleeve on
the ccw flank that meets it (positive torque, docs/conventions.md, Loaded analysis; sleeve regions
``T<k>_...``
bound the space of hub tooth k), each in the middle of the sector. The compliance is the work
conjugate ``sum f_i . u_i`` (mm/N): the circumferential displacement at the pitch radius
per unit tangential load there, the measure of Renzo's mesh stiffness C. It includes the
local deformation under the patch (which shrinks slowly as the patch grows); Hertzian
contact compliance is not part of it.

Far field: the load models add the local (contact) deformation themselves, from the
contact law or the half-space influence of the pressure, so the compliance they read
(:meth:`ComplianceTable.pair_compliance_mm_per_N`) is the FE value less the half-space
(Boussinesq) work of the same nodal forces (:func:`halfspace_work_mm_per_N`): the
standard hybrid of a finite-element far field and a surface-integral near field, which
counts the local part once.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ArgumentError, GeometryError
from ..io import safe_name, write_json
from ..spec import CouplingSpec
from .ccx import run_ccx, solver_dir
from .deck import LoadCase, principal_max, static_deck
from .mesh import DEFAULT_SECTOR_TEETH, check_size, mesh_part
from .volume import VolumeMesh

CACHE_ENV = "GEARCOUPLING_CACHE"
VERSION = 3  # bump when the set-up changes: old cache entries are then ignored
LOADED_FLANK = {"hub": "CCW", "sleeve": "CCW"}  # the sleeve ccw flank meets the hub ccw flank
INTO_SIGN = {"hub": -1.0, "sleeve": 1.0}  # sign of the force's polar component


SQUARE_MEAN_INVERSE_DISTANCE = 4.0 * (math.log(1.0 + math.sqrt(2.0)) - (math.sqrt(2.0) - 1.0) / 3.0)
"""Mean of ``1 / |x - y|`` over pairs of points of the unit square (2.9732)."""


def halfspace_work_mm_per_N(points: NDArray[np.float64], forces: NDArray[np.float64],
                            area_mm2: float, youngs_modulus_MPa: float,
                            poisson_ratio: float) -> float:
    """Work ``sum f_i . u_i`` of nodal forces on an elastic half-space (Boussinesq).

    Each force is spread uniformly over a square of the node's share of the loaded area;
    pairs act through ``(1 - nu²) / (pi E |x_i - x_j|)``, a node on itself through the mean
    inverse distance of its square. The normal to the plane is the forces' mean direction;
    tangential parts of the forces are left out (frictionless flank loads are normal).

    Parameters
    ----------
    points : (n, 3) float
        Node positions (mm).
    forces : (n, 3) float
        Nodal forces (N).
    area_mm2 : float
        Loaded area the ``n`` nodes share (mm²).

    Returns
    -------
    float
        Work per the forces' scale squared (mm/N when the forces are per unit load).
    """
    n = forces.sum(axis=0)
    n = n / np.linalg.norm(n)
    fn = forces @ n
    d = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=-1)
    side = math.sqrt(area_mm2 / len(points))
    inv = np.where(d > 0, 1.0 / np.where(d > 0, d, 1.0), 0.0)
    np.fill_diagonal(inv, SQUARE_MEAN_INVERSE_DISTANCE / side)
    return float((1.0 - poisson_ratio**2) / (math.pi * youngs_modulus_MPa) * fn @ inv @ fn)


def material(spec: CouplingSpec, part: str) -> tuple[float, float]:
    """``(E MPa, nu)`` of a part: ``spec.material.<part>`` when the spec has it, else steel
    (206 000 MPa, 0.3)."""
    mat = getattr(getattr(spec, "material", None), part, None)
    return (float(getattr(mat, "youngs_modulus_MPa", 206_000.0)),
            float(getattr(mat, "poisson_ratio", 0.3)))


def spec_hash(spec: CouplingSpec, **settings) -> str:
    """Hash of what the table depends on (teeth, hub, sleeve, the elastic constants) and the
    FE settings: the cache key, the same for specs differing only in their load,
    allowables, density, name or inspection."""
    elastic = [material(spec, part) for part in ("hub", "sleeve")]  # not the allowables
    solid = (spec.tooth, spec.hub, spec.sleeve, elastic)
    text = repr(solid) + json.dumps(settings, sort_keys=True) + f"v{VERSION}"
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def cache_dir() -> Path:
    """The compliance-table cache: ``$GEARCOUPLING_CACHE`` or ``$XDG_CACHE_HOME/gearcoupling``
    (default ``~/.cache/gearcoupling``), subfolder ``fea``."""
    base = os.environ.get(CACHE_ENV) or Path(
        os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "gearcoupling"
    return Path(base) / "fea"


@dataclass(frozen=True)
class ComplianceTable:
    """FE tooth compliances on a grid of load points ``(|z|, r)`` of the hub flank.

    Attributes
    ----------
    z_mm : (nz,) float
        Axial load positions ``|z|`` (hub frame; the table is even in z).
    r_mm : (nr,) float
        Load radii.
    hub_mm_per_N, sleeve_mm_per_N : (nz, nr) float
        Compliance of the hub tooth and of the sleeve tooth (see the module docstring).
    root_stress_MPa_per_N : (2, nz, nr) float
        Largest principal stress in the fillets of the loaded hub / sleeve tooth per unit
        tangential load at the pitch radius.
    pitch_radius_mm : float
    near_field_mm_per_N : (2, nz, nr) float
        Half-space work of the same loads on hub / sleeve (the local part, module
        docstring).
    info : dict
        Spec name and hash, size, sector, supports, mesh and solve figures.
    """

    z_mm: NDArray[np.float64]
    r_mm: NDArray[np.float64]
    hub_mm_per_N: NDArray[np.float64]
    sleeve_mm_per_N: NDArray[np.float64]
    root_stress_MPa_per_N: NDArray[np.float64]
    pitch_radius_mm: float
    near_field_mm_per_N: NDArray[np.float64]
    info: dict = field(default_factory=dict)

    def _interp(self, values, z_mm, r_mm) -> NDArray[np.float64]:
        from scipy.interpolate import RegularGridInterpolator

        z, r = np.broadcast_arrays(np.abs(np.asarray(z_mm, float)), np.asarray(r_mm, float))
        z = np.clip(z, self.z_mm[0], self.z_mm[-1])
        r = np.clip(r, self.r_mm[0], self.r_mm[-1])
        f = RegularGridInterpolator((self.z_mm, self.r_mm), values, method="linear")
        return f(np.stack([z.ravel(), r.ravel()], axis=1)).reshape(z.shape)

    @property
    def far_field_mm_per_N(self) -> NDArray[np.float64]:
        """Hub + sleeve compliance less the half-space near field ``(nz, nr)`` (mm/N)."""
        near = self.near_field_mm_per_N
        return self.hub_mm_per_N + self.sleeve_mm_per_N - near[0] - near[1]

    def pair_compliance_mm_per_N(self, z_mm: ArrayLike, r_mm: ArrayLike) -> NDArray:
        """Far-field hub + sleeve tooth compliance (mm/N) at hub flank points ``(z, r)``:
        bending, shear and the body under the tooth, without the local deformation the load
        models' contact adds (broadcast; bilinear in ``(|z|, r)``, held constant outside the
        table)."""
        return self._interp(self.far_field_mm_per_N, z_mm, r_mm)

    @property
    def mesh_stiffness_N_per_mm(self) -> float:
        """Renzo's C of one tooth pair: 1 / the whole FE compliance (with the local
        deformation under the patch) at mid-face and the pitch radius."""
        return float(1.0 / self._interp(self.hub_mm_per_N + self.sleeve_mm_per_N, 0.0,
                                        self.pitch_radius_mm))

    def to_dict(self) -> dict:
        d = asdict(self)
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in d.items()}

    @classmethod
    def from_dict(cls, d: dict) -> ComplianceTable:
        arrays = {k: np.asarray(d[k], dtype=float) for k in
                  ("z_mm", "r_mm", "hub_mm_per_N", "sleeve_mm_per_N", "root_stress_MPa_per_N",
                   "near_field_mm_per_N")}
        return cls(**arrays, pitch_radius_mm=float(d["pitch_radius_mm"]), info=d["info"])

    def rows(self) -> list[dict]:
        """One row per grid point (``stiffness.csv``)."""
        out = []
        for i, z in enumerate(self.z_mm):
            for j, r in enumerate(self.r_mm):
                h, s = self.hub_mm_per_N[i, j], self.sleeve_mm_per_N[i, j]
                near = self.near_field_mm_per_N[:, i, j]
                out.append({"z_mm": z, "r_mm": r, "hub_um_per_N": 1e3 * h,
                            "sleeve_um_per_N": 1e3 * s, "pair_um_per_N": 1e3 * (h + s),
                            "pair_stiffness_N_per_mm": 1.0 / (h + s),
                            "hub_near_field_um_per_N": 1e3 * near[0],
                            "sleeve_near_field_um_per_N": 1e3 * near[1],
                            "pair_far_field_um_per_N": 1e3 * self.far_field_mm_per_N[i, j],
                            "hub_root_stress_MPa_per_N": self.root_stress_MPa_per_N[0, i, j],
                            "sleeve_root_stress_MPa_per_N":
                                self.root_stress_MPa_per_N[1, i, j]})
        return out


def _fixed_sets(vm: VolumeMesh) -> list[str]:
    if vm.part == "sleeve":
        base = ["OUTER"]
    elif "BORE" in vm.regions:
        base = ["BORE"]
    else:
        base = ["END"]
    return base + (["CUT"] if vm.teeth is not None else [])


def load_grid(spec: CouplingSpec, hub: VolumeMesh, sleeve: VolumeMesh, nz: int = 3, nr: int = 3):
    """Load points: ``|z|`` from 0 to 0.8 of the hub half face; ``r`` across the radii that
    both loaded flanks cover at every such z (10 % in from each end of that band)."""
    hf = 0.5 * spec.hub.face_width
    z = np.linspace(0.0, 0.8 * hf, nz)
    lo, hi = -np.inf, np.inf
    for vm in (hub, sleeve):
        k = _loaded_tooth(vm)
        p = vm.nodes[vm.node_set(f"T{k}_FLANK_{LOADED_FLANK[vm.part]}")]
        r = np.hypot(p[:, 0], p[:, 1])
        for zi in z:
            near = np.abs(np.abs(p[:, 2]) - zi) < 0.05 * hf + 1e-9
            if near.sum() < 2:
                raise GeometryError(f"the {vm.part} flank mesh has no nodes near z = {zi:.3g}")
            lo, hi = max(lo, r[near].min()), min(hi, r[near].max())
    if not hi > lo:
        raise GeometryError("hub and sleeve flanks share no radii to load")
    pad = 0.1 * (hi - lo)
    return z, np.linspace(lo + pad, hi - pad, nr)


def loaded_fillets(vm: VolumeMesh) -> list[str]:
    """Fillet regions at the root of the loaded tooth (the sleeve tooth loaded on the ccw
    flank of space k lies between spaces k and k + 1)."""
    k = _loaded_tooth(vm)
    if vm.part == "hub":
        names = [f"T{k}_FILLET_CW", f"T{k}_FILLET_CCW"]
    else:
        names = [f"T{k}_FILLET_CCW", f"T{k + 1}_FILLET_CW"]
    return [f for f in names if f in vm.regions]


def _loaded_tooth(vm: VolumeMesh) -> int:
    return 0 if vm.teeth is None else vm.teeth[len(vm.teeth) // 2]


def load_case(vm: VolumeMesh, z: float, r: float, pitch_radius: float,
              patch_mm: float) -> tuple[LoadCase, float]:
    """Forces on the loaded flank patch around ``(z, r)`` (module docstring) and the
    patch's area (mm²: the flank triangles whose centres lie in it)."""
    k = _loaded_tooth(vm)
    region = f"T{k}_FLANK_{LOADED_FLANK[vm.part]}"
    tri = vm.regions[region]
    p = vm.nodes
    nodes = np.unique(tri.ravel())
    rn = np.hypot(p[nodes, 0], p[nodes, 1])
    zs = np.sign(z) if z != 0 else 1.0
    inside = (np.abs(p[nodes, 2] - z * zs) <= patch_mm) & (np.abs(rn - r) <= patch_mm)
    if inside.sum() < 3:
        d = np.hypot(p[nodes, 2] - z, rn - r)
        inside = d <= np.sort(d)[min(5, len(d) - 1)]
    patch = nodes[inside]
    c = p[tri[:, :3]]
    normal = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    cen = c.mean(axis=1)
    near = np.isin(tri[:, :3], patch).any(axis=1)
    e_t = np.stack([-cen[:, 1], cen[:, 0], np.zeros(len(cen))], axis=1)
    normal *= np.sign(np.einsum("ij,ij->i", normal, e_t) * INTO_SIGN[vm.part])[:, None]
    n = normal[near].sum(axis=0)
    n /= np.linalg.norm(n)
    pts = p[patch]
    moment = np.mean(pts[:, 0] * n[1] - pts[:, 1] * n[0])  # about z, per unit force
    scale = pitch_radius / abs(moment)  # total normal force for a moment of 1 N x R
    forces = np.tile(n * scale / len(patch), (len(patch), 1))
    in_box = ((np.abs(cen[:, 2] - z * zs) <= patch_mm)
              & (np.abs(np.hypot(cen[:, 0], cen[:, 1]) - r) <= patch_mm))
    area = 0.5 * float(np.linalg.norm(normal[in_box], axis=1).sum())
    return LoadCase(patch, forces), area


def part_compliance(vm: VolumeMesh, spec: CouplingSpec, z_mm, r_mm, *, patch_mm: float, workdir,
                    job: str) -> tuple[NDArray, NDArray, NDArray, dict]:
    """Compliance ``(nz, nr)`` (mm/N), its half-space near field ``(nz, nr)`` (mm/N) and
    the fillet stress per N ``(nz, nr)`` of one part."""
    R = spec.tooth.pitch_radius
    E, nu = material(spec, vm.part)
    cases, near = [], []
    for z in z_mm:
        for r in r_mm:
            case, area = load_case(vm, z, r, R, patch_mm)
            cases.append(case)
            near.append(halfspace_work_mm_per_N(vm.nodes[case.nodes], case.forces, area, E, nu))
    fillets = loaded_fillets(vm)
    prints = [(f"P{i}", c.nodes) for i, c in enumerate(cases)]
    deck = static_deck(vm, youngs_modulus_MPa=E, poisson_ratio=nu,
                       fixed=_fixed_sets(vm), cases=cases, node_print=prints,
                       stress_sets=fillets, solver="ITERATIVE CHOLESKY")
    res = run_ccx(deck, workdir, job)
    comp = np.empty(len(cases))
    stress = np.empty(len(cases))
    for i, case in enumerate(cases):
        u = res.get("displacements", f"P{i}")[i]
        order = np.argsort(u[:, 0])
        ids = np.sort(case.nodes + 1)
        if not np.array_equal(u[order, 0].astype(int), ids):
            raise GeometryError(f"ccx printed other nodes than the load patch {i}")
        f = case.forces[np.argsort(case.nodes)]
        comp[i] = float(np.sum(f * u[order, 1:4]))
        stress[i] = max(float(principal_max(res.get("stresses", name)[i][:, 2:8]).max())
                        for name in fillets)
    shape = (len(z_mm), len(r_mm))
    if not np.all(np.isfinite(comp) & (comp > 0)):
        raise GeometryError(f"non-positive {vm.part} compliance from ccx: {comp}")
    return (comp.reshape(shape), np.reshape(near, shape), stress.reshape(shape),
            {"solve_seconds": res.seconds})


def compute_compliance_table(spec: CouplingSpec, *, size_mm: float | None = None,
                             sector: int = DEFAULT_SECTOR_TEETH, nz: int = 3, nr: int = 3,
                             patch_mm: float | None = None, workdir=None,
                             progress: Callable[[int, int], None] | None = None
                             ) -> ComplianceTable:
    """Mesh hub and sleeve sectors and solve the load cases with ccx (no cache);
    ``progress(done, 4)`` after each mesh and each solve."""
    if sector is None or int(sector) < 1 or int(sector) % 2 == 0:
        raise ArgumentError("sector", sector, "an odd number of teeth (the middle one is loaded), "
                        "e.g. 3")
    t0 = time.perf_counter()
    meshes = {}
    for part in ("hub", "sleeve"):
        meshes[part] = mesh_part(spec, part, sector=sector, size_mm=size_mm)
        if progress:
            progress(len(meshes), 4)
    z, r = load_grid(spec, meshes["hub"], meshes["sleeve"], nz, nr)
    patch = (max(meshes["hub"].size_mm, spec.tooth.module / 4.0) if patch_mm is None
             else float(patch_mm))
    comp, near, stress, times = {}, {}, {}, {}
    with solver_dir(workdir) as work:
        for part, vm in meshes.items():
            comp[part], near[part], stress[part], info = part_compliance(
                vm, spec, z, r, patch_mm=patch, workdir=work, job=part)
            times[part] = info["solve_seconds"]
            if progress:
                progress(2 + len(times), 4)
    info = {
        "spec": spec.name, "size_mm": meshes["hub"].size_mm, "sector_teeth": sector,
        "patch_mm": patch, "loaded_flank": {"hub": "ccw", "sleeve": "ccw"},
        "supports": {"hub": _fixed_sets(meshes["hub"]),
                     "sleeve": _fixed_sets(meshes["sleeve"]),
                     "cut_faces": "fixed (all displacements), not cyclic"},
        "material": {p: dict(zip(("youngs_modulus_MPa", "poisson_ratio"), material(spec, p),
                                 strict=True)) for p in meshes},
        "mesh": {p: vm.quality for p, vm in meshes.items()},
        "solve_seconds": times, "total_seconds": time.perf_counter() - t0,
    }
    table = ComplianceTable(z, r, comp["hub"], comp["sleeve"],
                            np.stack([stress["hub"], stress["sleeve"]]),
                            spec.tooth.pitch_radius, np.stack([near["hub"], near["sleeve"]]),
                            info)
    if not np.all(table.far_field_mm_per_N > 0):
        raise ArgumentError(
            f"size_mm = {meshes['hub'].size_mm:g}, sector = {sector}: the FE compliance is "
            f"below its half-space part under the {patch:g} mm load patch (a mesh too coarse "
            f"for the patch, or a sector so small that its fixed cuts hold the loaded "
            f"tooth); use size_mm at most module / 4 = {spec.tooth.module / 4:g} mm and "
            f"sector at least 3")
    return table


def tooth_compliance_table(spec: CouplingSpec, *, size_mm: float | None = None,
                           sector: int = DEFAULT_SECTOR_TEETH, nz: int = 3, nr: int = 3,
                           cache: str | Path | None = None, refresh: bool = False,
                           progress: Callable[[int, int], None] | None = None
                           ) -> ComplianceTable:
    """The FE compliance table of a spec, cached per spec hash and settings.

    The cache is ``<cache>/<hash>.json`` (default :func:`cache_dir`, i.e. the user's cache
    folder ``~/.cache/gearcoupling/fea``); ``refresh`` recomputes it. Implements the tooth
    compliance protocol ``pair_compliance_mm_per_N(z_mm, r_mm)`` of the load models.
    """
    check_size(spec, "hub", size_mm)
    check_size(spec, "sleeve", size_mm)
    key = spec_hash(spec, size_mm=size_mm, sector=sector, nz=nz, nr=nr)
    path = Path(cache) if cache is not None else cache_dir()
    path = path / f"{safe_name(spec.name)}-{key}.json"  # a spec name cannot escape
    if path.exists() and not refresh:
        return ComplianceTable.from_dict(json.loads(path.read_text()))
    table = compute_compliance_table(spec, size_mm=size_mm, sector=sector, nz=nz, nr=nr,
                                     progress=progress)
    table.info["spec_hash"] = key
    write_json(path, table.to_dict())
    return table


def pitch_point_compliance(table: ComplianceTable) -> dict:
    """Hub, sleeve and pair compliance (µm/N) and C (N/mm) at mid-face, pitch radius."""
    R = table.pitch_radius_mm
    hub = float(table._interp(table.hub_mm_per_N, 0.0, R))
    sleeve = float(table._interp(table.sleeve_mm_per_N, 0.0, R))
    far = float(table.pair_compliance_mm_per_N(0.0, R))
    return {"hub_um_per_N": 1e3 * hub, "sleeve_um_per_N": 1e3 * sleeve,
            "pair_um_per_N": 1e3 * (hub + sleeve), "pair_far_field_um_per_N": 1e3 * far,
            "mesh_stiffness_N_per_mm": 1.0 / (hub + sleeve), "pitch_radius_mm": R}
