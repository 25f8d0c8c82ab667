"""Tooth compliance and mesh stiffness from CalculiX on hub and sleeve tooth sectors.

Set-up (both parts): a sector of ``sector`` teeth (default 3) meshed by
:func:`gearcoupling.fea.mesh_part`; the middle tooth is loaded. Supports: the hub bore
(``BORE``), the sleeve outside diameter (``OUTER``) and both sector cut planes (``CUT``)
fully fixed (fixed, not cyclic: the cuts lie half a pitch beyond the neighbouring teeth,
and fixing them makes the sector slightly stiffer than the whole part). A hub without a
bore is held on its body end faces instead.

Mesh (:func:`_loaded_sector`): the loaded tooth at the element size, its loaded flank at
:data:`FLANK_SIZE` of it where the load patches lie, the other teeth coarser; gmsh's HXT
mesher.

Load: a uniform pressure on the loaded flank within ``|dz|, |dr| <= patch`` of the point
``(z, r)``, along the patch's mean normal (into the tooth, no friction), as the consistent
nodal forces of the quadratic flank triangles (:func:`load_case`), scaled so that its
moment about the axis is ``1 N x R`` (a unit tangential load at the pitch radius R). The
hub is loaded on its ccw flank, the sleeve on the ccw flank that meets it (positive
torque, docs/conventions.md, Loaded analysis; sleeve regions ``T<k>_...`` bound the space
of hub tooth k), each in the middle of the sector. The compliance is the work conjugate
``sum f_i . u_i`` (mm/N): the circumferential displacement at the pitch radius per unit
tangential load there, the measure of Renzo's mesh stiffness C. It includes the local
deformation under the patch (which shrinks slowly as the patch grows); Hertzian contact
compliance is not part of it. Every load case of a part is one Green function of one
ccx factorisation (:func:`~gearcoupling.fea.deck.green_deck`).

Far field: the load models add the local (contact) deformation themselves, from the
contact law or the half-space influence of the pressure, so the compliance they read
(:meth:`ComplianceTable.pair_compliance_mm_per_N`) is the FE value less the half-space
(Boussinesq) work of the same uniform pressure on the patch rectangle
(:func:`rectangle_halfspace_work_mm_per_N`, closed form): the standard hybrid of a
finite-element far field and a surface-integral near field, which counts the local part
once.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import count, flag
from ..errors import ArgumentError, GeometryError
from ..io import cache_folder, cache_key, cached, package_version, safe_name, store
from ..spec import CouplingSpec, as_spec
from .backends import ccx_path, gmsh_module
from .ccx import run_ccx, solver_dir
from .deck import LoadCase, green_deck, principal_max
from .mesh import DEFAULT_SECTOR_TEETH, LoadedTooth, check_size, mesh_part, size_range
from .volume import VolumeMesh

CACHE_ENV = "GEARCOUPLING_CACHE"
VERSION = 5  # bump when the set-up changes: old cache entries are then ignored
FAR_SIZE = 3.0
"""Element size on the teeth away from the loaded one, in loaded-tooth sizes."""
FLANK_SIZE = 0.35
"""Element size on the loaded flank where the load patches lie, in loaded-tooth sizes."""
TABLE_FACE_SHARE = 0.8
"""The table's evenly spaced load rows reach this share of the hub half face; one more row
lies at the face end (:func:`load_rows_mm`)."""
LOADED_ZONE = 0.5
"""Distance (modules) from the loaded tooth's flanks and fillets kept at the tooth size."""
LOADED_FLANK = {"hub": "CCW", "sleeve": "CCW"}  # the sleeve ccw flank meets the hub ccw flank
INTO_SIGN = {"hub": -1.0, "sleeve": 1.0}  # sign of the force's polar component


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
    return _cache_base()[0] / "fea"


def _cache_base() -> tuple[Path, str, str]:
    """The cache's base folder, the variable that sets it and its value."""
    if os.environ.get(CACHE_ENV):
        return Path(os.environ[CACHE_ENV]), CACHE_ENV, os.environ[CACHE_ENV]
    if os.environ.get("XDG_CACHE_HOME"):
        xdg = os.environ["XDG_CACHE_HOME"]
        return Path(xdg) / "gearcoupling", "XDG_CACHE_HOME", xdg
    home = Path.home() / ".cache" / "gearcoupling"
    return home, "the cache folder", str(home)


def fe_cache_folder(cache: str | Path | None = None, field: str = "cache") -> Path:
    """The folder of the FE tables' cache entries, made if missing and checked before any
    work: ``cache`` (named ``field`` in an error), else :func:`cache_dir` (an error names
    ``GEARCOUPLING_CACHE`` or ``XDG_CACHE_HOME`` when one of them sets it).
    :class:`~gearcoupling.errors.ArgumentError` when it is a file, a device or a pipe, lies
    under a file or cannot be written into (:func:`gearcoupling.io.cache.cache_folder`)."""
    if cache is not None:
        return cache_folder(cache, field)
    base, name, value = _cache_base()
    cache_folder(base, name, value)
    return cache_folder(base / "fea", name, value)


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

    def interpolate(self, values, z_mm, r_mm) -> NDArray[np.float64]:
        """``values (nz, nr)`` at hub flank points ``(z, r)``: bilinear in ``(|z|, r)``,
        held constant outside the table."""
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
        return self.interpolate(self.far_field_mm_per_N, z_mm, r_mm)

    @property
    def mesh_stiffness_N_per_mm(self) -> float:
        """Renzo's C of one tooth pair: 1 / the whole FE compliance (with the local
        deformation under the patch) at mid-face and the pitch radius."""
        return float(1.0 / self.interpolate(self.hub_mm_per_N + self.sleeve_mm_per_N, 0.0,
                                        self.pitch_radius_mm))

    def to_dict(self) -> dict:
        d = asdict(self)
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in d.items()}

    @classmethod
    def from_dict(cls, d: dict) -> ComplianceTable:
        """The table of :meth:`to_dict`'s data, checked: grids increasing, every value
        finite, compliances, far field and pitch radius positive, stresses and near field
        not negative, shapes as documented; else :class:`~gearcoupling.errors.ArgumentError`
        naming the field."""
        if not isinstance(d, dict):
            raise ArgumentError("table", type(d).__name__, "a dict of the table's fields")
        z = table_array(d, "z_mm", None)
        r = table_array(d, "r_mm", None)
        grid = (z.size, r.size)
        hub = table_array(d, "hub_mm_per_N", grid, "positive")
        sleeve = table_array(d, "sleeve_mm_per_N", grid, "positive")
        stress = table_array(d, "root_stress_MPa_per_N", (2, *grid), "not negative")
        near = table_array(d, "near_field_mm_per_N", (2, *grid), "not negative")
        R = table_array(d, "pitch_radius_mm", (), "positive")
        info = d.get("info", {})
        if not isinstance(info, dict):
            raise ArgumentError("info", type(info).__name__, "a dict")
        table = cls(z, r, hub, sleeve, stress, float(R), near, info)
        if not np.all(table.far_field_mm_per_N > 0):
            raise ArgumentError("near_field_mm_per_N", near, "below the hub + sleeve "
                                "compliance at every load point (a positive far field)",
                                _shown(near))
        return table

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


def table_array(d: dict, name: str, shape: tuple[int, ...] | None, sign: str = "finite",
                fewest: int = 2) -> NDArray[np.float64]:
    """``d[name]`` (a stored table's field) as a float array of ``shape`` (``None``: 1-D,
    at least ``fewest`` values, increasing from 0 or more), every value finite and ``sign``
    (``"positive"``, ``"not negative"`` or ``"finite"``); else an
    :class:`~gearcoupling.errors.ArgumentError` naming ``name``."""
    want = (f"a list of at least {fewest} increasing numbers, the first not negative"
            if shape is None else f"numbers of shape {shape}, finite"
            + ("" if sign == "finite" else f" and {sign}"))
    try:
        a = np.asarray(d[name], dtype=float)
    except (KeyError, TypeError, ValueError):
        raise ArgumentError(name, d.get(name), want, _shown(d.get(name))) from None
    ok = a.shape == shape if shape is not None else (a.ndim == 1 and a.size >= fewest)
    ok = ok and bool(np.all(np.isfinite(a)))
    if ok and shape is None:
        ok = bool(np.all(np.diff(a) > 0) and a[0] >= 0)
    elif ok and sign != "finite":
        ok = bool(np.all(a > 0) if sign == "positive" else np.all(a >= 0))
    if not ok:
        raise ArgumentError(name, a, want, _shown(a))
    return a


def _shown(value: object) -> str:
    """A table field's value as an error shows it: an array's shape and range."""
    if isinstance(value, np.ndarray) and value.size:
        return f"array of shape {value.shape} from {np.min(value):.4g} to {np.max(value):.4g}"
    return repr(value)[:80]


def _fixed_sets(vm: VolumeMesh) -> list[str]:
    if vm.part == "sleeve":
        base = ["OUTER"]
    elif "BORE" in vm.regions:
        base = ["BORE"]
    else:
        base = ["END"]
    return base + (["CUT"] if vm.teeth is not None else [])


def default_patch_mm(spec: CouplingSpec, size_mm: float | None = None) -> float:
    """Half the side of the table's square load patch: the loaded tooth's element size
    (:func:`~gearcoupling.fea.mesh.check_size`), at least module / 4."""
    return max(check_size(spec, "hub", size_mm), spec.tooth.module / 4.0)


def load_rows_mm(spec: CouplingSpec, patch_mm: float, nz: int = 3) -> NDArray[np.float64]:
    """``|z|`` of the table's load rows ``(nz + 1,)`` or ``(nz,)`` (mm): ``nz`` evenly from
    mid-face to :data:`TABLE_FACE_SHARE` of the hub half face, and one whose patch (half
    side ``patch_mm``) is flush with the face end, where a misaligned patch runs and the
    tooth is softest. Where that lies within half a patch of the last even row (a short
    face), it replaces that row; within half a patch of the row before that too, the even
    rows stay as they are."""
    hf = 0.5 * spec.hub.face_width
    z = np.linspace(0.0, TABLE_FACE_SHARE * hf, nz)
    flush = hf - patch_mm
    if flush >= z[-1] + 0.5 * patch_mm:
        return np.append(z, flush)
    if flush > z[-2] + 0.5 * patch_mm:
        z[-1] = flush
    return z


def load_grid(spec: CouplingSpec, hub: VolumeMesh, sleeve: VolumeMesh, nz: int, nr: int,
              patch_mm: float):
    """Load points: ``|z|`` the rows of :func:`load_rows_mm`; ``r`` across the radii that
    both loaded flanks cover at every such z (10 % in from each end of that band)."""
    hf = 0.5 * spec.hub.face_width
    z = load_rows_mm(spec, patch_mm, nz)
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


def load_case(vm: VolumeMesh, z: float, r: float, pitch_radius: float, patch_mm: float,
              subdivisions: int = 8, *, tooth: int | None = None
              ) -> tuple[LoadCase, float, float]:
    """Consistent nodal forces of a uniform pressure on the loaded flank within
    ``|dz|, |dr| <= patch_mm`` of ``(z, r)``, along the patch's mean normal into the tooth
    and scaled to a moment of ``1 N x R`` about the axis, with the patch's area (mm²) and
    axial length (mm). ``z`` is signed; ``tooth`` defaults to the sector's middle tooth.

    The pressure is integrated over the quadratic flank triangles with the triangles'
    shape functions at the centroids of ``subdivisions²`` sub-triangles each, so the
    forces follow the patch's edges, not the mesh.
    """
    k = _loaded_tooth(vm) if tooth is None else tooth
    tri = vm.regions[f"T{k}_FLANK_{LOADED_FLANK[vm.part]}"]
    x = vm.nodes[tri]  # (t, 6, 3)
    N, dxi, deta = _tri6(_subcentroids(subdivisions))
    pts = np.einsum("sa,tad->tsd", N, x)
    normal = np.cross(np.einsum("sa,tad->tsd", dxi, x), np.einsum("sa,tad->tsd", deta, x))
    jac = np.linalg.norm(normal, axis=-1)
    inside = ((np.abs(pts[..., 2] - z) <= patch_mm)
              & (np.abs(np.hypot(pts[..., 0], pts[..., 1]) - r) <= patch_mm))
    w = jac * inside / (2.0 * subdivisions**2)  # area of each sub-triangle in the patch
    if not w.any():
        raise GeometryError(f"the {vm.part} flank has no area within {patch_mm:g} mm of "
                            f"z = {z:.4g}, r = {r:.4g} mm")
    e_t = np.stack([-pts[..., 1], pts[..., 0], np.zeros(pts.shape[:2])], axis=-1)
    side = np.sign(np.einsum("tsd,tsd->ts", normal, e_t) * INTO_SIGN[vm.part])
    n = np.einsum("ts,tsd->d", w * side / np.where(jac > 0, jac, 1.0), normal)
    n /= np.linalg.norm(n)
    moment = float(np.sum(w * (pts[..., 0] * n[1] - pts[..., 1] * n[0])))
    pressure = pitch_radius / abs(moment)  # a moment of 1 N x R about the axis
    nodes, index = np.unique(tri, return_inverse=True)
    load = np.bincount(index.ravel(), weights=(w @ N).ravel() * pressure, minlength=len(nodes))
    keep = np.abs(load) > 1e-12 * np.abs(load).max()  # corner loads can be negative
    length = min(z + patch_mm, x[..., 2].max()) - max(z - patch_mm, x[..., 2].min())
    return LoadCase(nodes[keep], load[keep, None] * n[None, :]), float(w.sum()), float(length)


def _subcentroids(m: int) -> NDArray[np.float64]:
    """Centroids ``(m², 2)`` of the ``m²`` equal sub-triangles of the reference triangle."""
    i, j = np.meshgrid(np.arange(m), np.arange(m), indexing="ij")
    up = i + j <= m - 1
    down = i + j <= m - 2
    return np.concatenate([np.stack([i[up] + 1 / 3, j[up] + 1 / 3], axis=1),
                           np.stack([i[down] + 2 / 3, j[down] + 2 / 3], axis=1)]) / m


def _tri6(q: NDArray[np.float64]) -> tuple[NDArray, NDArray, NDArray]:
    """Shape functions of the 6-node triangle (corners, then edges 1-2, 2-3, 3-1) and their
    derivatives, ``(s, 6)`` each, at reference points ``q (s, 2)``."""
    a, b = q[:, 0], q[:, 1]
    c = 1.0 - a - b
    N = np.stack([c * (2 * c - 1), a * (2 * a - 1), b * (2 * b - 1), 4 * c * a, 4 * a * b,
                  4 * b * c], axis=1)
    zero = np.zeros_like(a)
    da = np.stack([1 - 4 * c, 4 * a - 1, zero, 4 * (c - a), 4 * b, -4 * b], axis=1)
    db = np.stack([1 - 4 * c, zero, 4 * b - 1, -4 * a, 4 * a, 4 * (c - b)], axis=1)
    return N, da, db


def rectangle_halfspace_work_mm_per_N(force_N: float, length_mm: float, width_mm: float,
                                      youngs_modulus_MPa: float, poisson_ratio: float) -> float:
    """Work ``P w̄`` of a uniform pressure of total force ``P`` on a ``length x width``
    rectangle of an elastic half-space, ``w̄`` its mean deflection (Love 1929):
    ``(1 - nu²) / (pi E) (P / (a b))² J(a, b)`` with ``J`` the integral of ``1 / |x - y|``
    over pairs of points of the rectangle,
    ``J = 2/3 (a³ + b³ - d³) + 2 a² b asinh(b / a) + 2 a b² asinh(a / b)``,
    ``d = sqrt(a² + b²)`` (2.9732 for the unit square)."""
    a, b = float(length_mm), float(width_mm)
    d = math.hypot(a, b)
    J = (2.0 / 3.0 * (a**3 + b**3 - d**3) + 2.0 * a * a * b * math.asinh(b / a)
         + 2.0 * a * b * b * math.asinh(a / b))
    return (1.0 - poisson_ratio**2) / (math.pi * youngs_modulus_MPa) * (force_N / (a * b))**2 * J


def part_compliance(vm: VolumeMesh, spec: CouplingSpec, z_mm, r_mm, *, patch_mm: float, workdir,
                    job: str, threads: int = 2) -> tuple[NDArray, NDArray, NDArray, dict]:
    """Compliance ``(nz, nr)`` (mm/N), its half-space near field ``(nz, nr)`` (mm/N) and
    the fillet stress per N ``(nz, nr)`` of one part: one ccx run (``threads``), every
    load case a Green function of one factorisation (:func:`~.deck.green_deck`)."""
    R = spec.tooth.pitch_radius
    E, nu = material(spec, vm.part)
    cases, near = [], []
    for z in z_mm:
        for r in r_mm:
            case, area, length = load_case(vm, abs(z), r, R, patch_mm)  # the table is even in z
            cases.append(case)
            force = float(np.linalg.norm(case.forces.sum(axis=0)))
            near.append(rectangle_halfspace_work_mm_per_N(force, length, area / length, E, nu))
    fillets = loaded_fillets(vm)
    deck = green_deck(vm, youngs_modulus_MPa=E, poisson_ratio=nu, fixed=_fixed_sets(vm),
                      cases=cases, stress_sets=fillets)
    res = run_ccx(deck, workdir, job, threads=threads)
    loads = len(vm.nodes) + 1 + np.arange(len(cases))
    printed = res.get("displacements", "LOADS")
    if len(printed) != len(cases) or any(not np.array_equal(u[:, 0].astype(int), loads)
                                         for u in printed):
        raise GeometryError(f"ccx printed other Green functions than the {len(cases)} load "
                            f"cases; see {res.job}.dat")
    comp = np.empty(len(cases))
    stress = np.empty(len(cases))
    for i, u in enumerate(printed):
        comp[i] = u[i, 1]  # the work of case i's forces: its load node's displacement
        stress[i] = max(float(principal_max(res.get("stresses", name)[i][:, 2:8]).max())
                        for name in fillets)
    shape = (len(z_mm), len(r_mm))
    if not np.all(np.isfinite(comp) & (comp > 0)):
        raise GeometryError(f"non-positive {vm.part} compliance from ccx: {comp}")
    return (comp.reshape(shape), np.reshape(near, shape), stress.reshape(shape),
            {"solve_seconds": res.seconds})


def _loaded_sector(spec: CouplingSpec, part: str, sector: int, size: float,
                   z_window: tuple[float, float]) -> VolumeMesh:
    """The sector a part's load cases are solved on: ``size`` on the loaded tooth,
    :data:`FLANK_SIZE` of it on the loaded flank in ``z_window``, the largest size
    :func:`~gearcoupling.fea.mesh.check_size` allows (up to :data:`FAR_SIZE` times
    ``size``) on the other teeth, the root fillets at
    :func:`~gearcoupling.fea.mesh.fillet_size`. gmsh's HXT mesher first; its Delaunay
    mesher when HXT leaves an inverted element."""
    m = spec.tooth.module
    far = max(size, min(FAR_SIZE * size, size_range(spec)[1]))
    loaded = LoadedTooth(far_size_mm=far, flank_size_mm=FLANK_SIZE * size, z_mm=z_window,
                         zone_mm=LOADED_ZONE * m)
    try:
        return mesh_part(spec, part, sector=sector, size_mm=size, loaded=loaded,
                         algorithm="hxt")
    except GeometryError:
        return mesh_part(spec, part, sector=sector, size_mm=size, loaded=loaded)


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
    m = spec.tooth.module
    size = check_size(spec, "hub", size_mm)
    check_size(spec, "sleeve", size_mm)
    patch = default_patch_mm(spec, size) if patch_mm is None else float(patch_mm)
    z_window = (-patch, load_rows_mm(spec, patch, nz)[-1] + patch)
    meshes = {}
    for part in ("hub", "sleeve"):
        meshes[part] = _loaded_sector(spec, part, sector, size, z_window)
        if progress:
            progress(len(meshes), 4)
    z, r = load_grid(spec, meshes["hub"], meshes["sleeve"], nz, nr, patch)
    comp, near, stress, times = {}, {}, {}, {}
    # both parts at once, one solver thread each (2 cores)
    with solver_dir(workdir) as work, ThreadPoolExecutor(2) as pool:
        runs = {pool.submit(part_compliance, vm, spec, z, r, patch_mm=patch, workdir=work,
                            job=part, threads=1): part for part, vm in meshes.items()}
        for run in as_completed(runs):
            part = runs[run]
            comp[part], near[part], stress[part], info = run.result()
            times[part] = info["solve_seconds"]
            if progress:
                progress(2 + len(times), 4)
    info = {
        "spec": spec.name, "size_mm": meshes["hub"].size_mm, "sector_teeth": sector,
        "patch_mm": patch, "loaded_flank": {"hub": "ccw", "sleeve": "ccw"},
        "load": "uniform pressure on the patch, consistent nodal forces",
        "solver": "ccx *GREEN (SPOOLES): one factorisation per part, a Green function per "
                  "load case",
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
    bad = int(np.sum(table.far_field_mm_per_N <= 0))
    if bad:
        if size <= m / 4.0 and sector >= DEFAULT_SECTOR_TEETH:
            why = ("at a mesh and sector that resolve it on other specs: this spec's teeth "
                   "are too few or its face too short for the split (measured on specs of "
                   "6-14 teeth and a face width of at most 3.5 modules; on one of 11 teeth a "
                   "sector of 5 teeth too)")
        else:
            why = (f"a mesh too coarse for the patch, or a sector so small that its fixed "
                   f"cuts hold the loaded tooth; use size_mm at most module / 4 = {m / 4:g} "
                   f"mm and sector at least 3")
        raise ArgumentError(
            "size_mm, sector", (meshes["hub"].size_mm, sector), f"the FE compliance is "
            f"below its half-space part under the {patch:g} mm load patch at {bad} of the "
            f"{table.far_field_mm_per_N.size} load points, {why}")
    return table


def tooth_compliance_table(spec: CouplingSpec, *, size_mm: float | None = None,
                           sector: int = DEFAULT_SECTOR_TEETH, nz: int = 3, nr: int = 3,
                           cache: str | Path | None = None, refresh: bool = False,
                           progress: Callable[[int, int], None] | None = None
                           ) -> ComplianceTable:
    """The FE compliance table of a spec, cached per spec hash and settings.

    The cache entry is ``<cache>/<name>-<hash>.json`` (default :func:`cache_dir`, i.e. the
    user's cache folder ``~/.cache/gearcoupling/fea``), checked before any work
    (:func:`fe_cache_folder`). It is used only when it was written for the same key (the
    spec's hash, these settings, :data:`VERSION` and the package's version) and its
    checksum matches, and when the table in it is valid (:meth:`ComplianceTable.from_dict`);
    otherwise (or with ``refresh``) the table is computed again and stored, with one line
    on stderr saying why (:func:`gearcoupling.io.cache.cached`). gmsh and ccx are looked up
    before that. Implements the tooth compliance protocol
    ``pair_compliance_mm_per_N(z_mm, r_mm)`` of the load models.
    """
    spec = as_spec(spec)
    flag(refresh, "refresh")
    path, key = table_entry(spec, size_mm=size_mm, sector=sector, nz=nz, nr=nr, cache=cache)
    found = None if refresh else cached(path, key, ComplianceTable.from_dict,
                                        f"the FE tooth table of {spec.name!r}")
    if found is not None:
        return found
    gmsh_module()
    ccx_path()
    table = compute_compliance_table(spec, size_mm=size_mm, sector=sector, nz=nz, nr=nr,
                                     progress=progress)
    table.info["spec_hash"] = key["spec_hash"]
    store(path, key, table.to_dict())
    return table


def table_entry(spec: CouplingSpec, *, size_mm: float | None = None,
                sector: int = DEFAULT_SECTOR_TEETH, nz: int = 3, nr: int = 3,
                cache: str | Path | None = None) -> tuple[Path, dict]:
    """Where the cache entry of :func:`tooth_compliance_table` lies (its folder checked and
    made, :func:`fe_cache_folder`) and its key (:func:`gearcoupling.io.cache.cache_key`),
    the settings checked."""
    spec = as_spec(spec)
    check_size(spec, "hub", size_mm)
    check_size(spec, "sleeve", size_mm)
    count(nz, "nz", 2, 9)
    count(nr, "nr", 2, 9)
    count(sector, "sector", 1, spec.tooth.teeth)
    folder = fe_cache_folder(cache)
    settings = {"size_mm": size_mm, "sector": sector, "nz": nz, "nr": nr}
    key = cache_key("FE tooth compliance table", VERSION,
                    spec_hash=spec_hash(spec, **settings, package=package_version()),
                    **settings)
    return folder / f"{safe_name(spec.name)}-{key['spec_hash']}.json", key


def pitch_point_compliance(table: ComplianceTable) -> dict:
    """Hub, sleeve and pair compliance (µm/N) and C (N/mm) at mid-face, pitch radius."""
    R = table.pitch_radius_mm
    hub = float(table.interpolate(table.hub_mm_per_N, 0.0, R))
    sleeve = float(table.interpolate(table.sleeve_mm_per_N, 0.0, R))
    far = float(table.pair_compliance_mm_per_N(0.0, R))
    return {"hub_um_per_N": 1e3 * hub, "sleeve_um_per_N": 1e3 * sleeve,
            "pair_um_per_N": 1e3 * (hub + sleeve), "pair_far_field_um_per_N": 1e3 * far,
            "mesh_stiffness_N_per_mm": 1.0 / (hub + sleeve), "pitch_radius_mm": R}
