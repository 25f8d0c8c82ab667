"""What the viewer draws, as plain arrays: no viser here (the server and the HTML writer
turn these into scene nodes).

- :func:`build_scene_meshes` meshes hub and sleeve once per level of detail and splits
  the hub into a body and one patch per (flank, tooth), so a pose change only recolours
  patches and moves the hub node;
- :func:`hub_rotation` / :func:`quaternion_wxyz` pose the hub (docs/conventions.md, Frames: a hub
body
  point ``p`` lies in the sleeve frame at ``Rz(-psi) Rx(i) Rz(psi) p``);
- :func:`pose_state` evaluates the exact clearance of every tooth and flank at one pose
  (one :func:`gearcoupling.clearance.sweep` call), the contact points and interfering teeth;
- :func:`clearance_colors` and :func:`legend` map clearance (mm) to colours;
- :func:`clearance_curve` and :func:`plot_series` give the clearance-vs-θ plot;
- :func:`interference_mesh` is the hub ∩ sleeve volume at a pose (manifold3d);
- :func:`cut_sleeve` removes part of the sleeve so the teeth can be seen.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..arguments import flag, real
from ..clearance import sweep
from ..errors import ArgumentError, SpecError
from ..geometry import FLANKS, hub_flank_model, hub_model, hub_to_sleeve, rot_z
from ..interference import PreparedPart, affine, flank_index, nearest_tooth
from ..loading import load_from_sweep
from ..parts import SURFACE_KINDS, build_part, check_tolerance
from ..spec import CouplingSpec, as_spec, check_misalignment_deg

if TYPE_CHECKING:
    import trimesh

LOD_DIVISORS = {"coarse": 20.0, "medium": 100.0, "fine": 400.0}
"""Levels of detail: chordal tolerance = module / divisor."""
CUTAWAYS = ("none", "quarter", "half", "midplane")
"""Sleeve cutaways: nothing removed; the quadrant x < 0, y < 0 (facing the default
camera); the half y < 0 (the section through the tilt axis shows the pivot teeth); the
half z > 0 (the midplane section shows every tooth in its space)."""
INTERFERENCE_RGB = (220, 20, 20)
NO_CONTACT_RGB = (150, 150, 150)
# clearance colour stops from 0 (touching) to the colour scale (free)
_STOPS = np.array([[0.0, 255, 215, 0], [0.35, 120, 200, 60], [0.7, 40, 170, 170],
                   [1.0, 40, 80, 200]])
COLOR_MODES = ("clearance", "separation", "pressure")
"""What the flank colours show: the clearance itself, or Renzo's separation (clearance
minus the smallest of its flank at this pose: 0 on the teeth that touch first when torque
closes the backlash), or the contact pressure at the spec's torque (the ``surface`` load
model's interior pressure of each tooth, against the allowable contact stress)."""
_PRESSURE_STOPS = np.array([[0.0, 40, 80, 200], [0.5, 40, 170, 170], [0.8, 255, 215, 0],
                            [1.0, 220, 20, 20]])
DEFAULT_PLOT_SAMPLES = 720
VIEW_SWEEP_TOLERANCE_MM = 1e-5
"""Accuracy of the clearance minima the viewer shows (mm), far below what colours show."""


# ------------------------------------------------------------------ meshes


@dataclass(frozen=True)
class Patch:
    """A triangle mesh: ``vertices (n, 3) float32`` (mm), ``faces (m, 3) uint32``."""

    vertices: NDArray[np.float32]
    faces: NDArray[np.uint32]


def submesh(vertices: NDArray, faces: NDArray) -> Patch:
    """The faces ``(m, 3)`` with only the vertices they use, re-indexed."""
    used, inverse = np.unique(faces.ravel(), return_inverse=True)
    return Patch(np.asarray(vertices[used], dtype=np.float32),
                 inverse.reshape(-1, 3).astype(np.uint32))


@dataclass(frozen=True)
class HubPieces:
    """The hub mesh split for colouring: ``body`` (every face but the flanks) and
    ``flanks[f][k]``, the flank ``f`` (0 cw, 1 ccw) of tooth ``k``, in the hub frame."""

    body: Patch
    flanks: tuple[tuple[Patch, ...], tuple[Patch, ...]]


def split_hub(mesh) -> HubPieces:
    """Split a hub mesh from :func:`gearcoupling.parts.build_part` by its face labels.

    Parameters
    ----------
    mesh : trimesh.Trimesh
        With ``face_attributes["kind"]`` (codes into ``SURFACE_KINDS``) and
        ``face_attributes["tooth"]``.
    """
    verts = np.asarray(mesh.vertices)
    faces = np.asarray(mesh.faces)
    kind = np.asarray(mesh.face_attributes["kind"])
    tooth = np.asarray(mesh.face_attributes["tooth"])
    teeth = int(tooth.max()) + 1
    codes = [SURFACE_KINDS.index(f"flank_{f}") for f in FLANKS]
    flank = np.isin(kind, codes)
    body = submesh(verts, faces[~flank])
    pieces = []
    for code in codes:
        sel = np.flatnonzero(kind == code)
        order = sel[np.argsort(tooth[sel], kind="stable")]
        bounds = np.searchsorted(tooth[order], np.arange(teeth + 1))
        pieces.append(tuple(submesh(verts, faces[order[bounds[k]:bounds[k + 1]]])
                            for k in range(teeth)))
    return HubPieces(body, (pieces[0], pieces[1]))


def lod_tolerance(spec: CouplingSpec, lod: str) -> float:
    """Chordal tolerance (mm) of a level of detail (:data:`LOD_DIVISORS`)."""
    if lod not in LOD_DIVISORS:
        raise ArgumentError(f"lod = {lod!r}: must be one of {tuple(LOD_DIVISORS)}")
    return spec.tooth.module / LOD_DIVISORS[lod]


@dataclass(eq=False)
class SceneMeshes:
    """Hub and sleeve meshed once at one chordal tolerance, with what the viewer derives
    from them (hub pieces, sleeve cutaways, manifolds for the interference volume)."""

    spec: object
    tolerance_mm: float
    hub: trimesh.Trimesh  # hub frame
    sleeve: trimesh.Trimesh  # sleeve frame
    _cuts: dict = field(default_factory=dict)

    @cached_property
    def hub_pieces(self) -> HubPieces:
        return split_hub(self.hub)

    @cached_property
    def hub_manifold(self):
        return _manifold(self.hub)

    @cached_property
    def sleeve_manifold(self):
        return _manifold(self.sleeve)

    def sleeve_cut(self, cutaway: str) -> Patch:
        """The sleeve with a cutaway (:data:`CUTAWAYS`), cached."""
        if cutaway not in self._cuts:
            self._cuts[cutaway] = cut_sleeve(self.sleeve_manifold, cutaway)
        return self._cuts[cutaway]

    @property
    def triangles(self) -> int:
        return len(self.hub.faces) + len(self.sleeve.faces)


def view_tolerance(spec: CouplingSpec, tolerance_mm: float | None = None) -> float:
    """The meshes' chordal tolerance (mm; default ``coarse``), or :class:`SpecError`."""
    tol = lod_tolerance(spec, "coarse") if tolerance_mm is None else tolerance_mm
    try:
        return check_tolerance(spec, tol)
    except ValueError as err:
        raise ArgumentError("tolerance_mm", tolerance_mm, str(err).split(": ", 1)[-1]) from err


def build_scene_meshes(spec: CouplingSpec, tolerance_mm: float | None = None) -> SceneMeshes:
    """Mesh hub and sleeve for viewing (default: the ``coarse`` level of detail)."""
    tol = view_tolerance(spec, tolerance_mm)
    return SceneMeshes(spec, tol, build_part(spec, "hub", tolerance_mm=tol),
                       build_part(spec, "sleeve", tolerance_mm=tol))


def _manifold(mesh):
    """The closed solid of a part mesh (manifold3d, checked), via the interference stage."""
    return PreparedPart.from_trimesh(mesh, ()).manifold


def _patch_from_manifold(man) -> Patch:
    out = man.to_mesh()
    verts = np.asarray(out.vert_properties, dtype=np.float32)[:, :3]
    return Patch(np.ascontiguousarray(verts),
                 np.asarray(out.tri_verts, dtype=np.uint32).reshape(-1, 3))


_CUT_PLANES = {
    "none": [],
    "quarter": None,  # union of two trims, below
    "half": [((0.0, 1.0, 0.0), 0.0)],
    "midplane": [((0.0, 0.0, -1.0), 0.0)],
}


def cut_sleeve(sleeve_manifold, cutaway: str) -> Patch:
    """The sleeve solid with the :data:`CUTAWAYS` region removed, closed at the cuts.

    Parameters
    ----------
    sleeve_manifold : manifold3d.Manifold
        The sleeve in its frame.
    cutaway : {"none", "quarter", "half", "midplane"}
    """
    if cutaway not in CUTAWAYS:
        raise ArgumentError(f"cutaway = {cutaway!r}: must be one of {CUTAWAYS}")
    man = sleeve_manifold
    planes = _CUT_PLANES[cutaway]
    if planes is None:  # quarter: keep x >= 0 or y >= 0
        man = man.trim_by_plane((1.0, 0.0, 0.0), 0.0) + man.trim_by_plane((0.0, 1.0, 0.0), 0.0)
    else:
        for normal, offset in planes:
            man = man.trim_by_plane(normal, offset)
    return _patch_from_manifold(man)


# ------------------------------------------------------------------ pose


def check_pose(misalignment_deg: float, psi_deg: float,
               names: tuple[str, str] = ("misalignment_deg", "psi_deg")) -> tuple[float, float]:
    """Misalignment (0-6°) and rotation (within a million degrees) as floats, or an
    :class:`ArgumentError` naming the bad one by its entry in ``names``."""
    return (check_misalignment_deg(misalignment_deg, names[0], ArgumentError),
            real(psi_deg, names[1], -1e6, 1e6, unit="degrees"))


def hub_rotation(misalignment_deg: float, psi_deg: float) -> NDArray[np.float64]:
    """Rotation ``(3, 3)`` taking hub-frame points into the sleeve frame at a pose."""
    return hub_to_sleeve(math.radians(misalignment_deg), math.radians(psi_deg))


def quaternion_wxyz(rotation: ArrayLike) -> NDArray[np.float64]:
    """Unit quaternion ``(w, x, y, z)`` with ``w >= 0`` of a rotation matrix ``(3, 3)``."""
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(np.asarray(rotation, dtype=float)).as_quat()
    q = np.array([w, x, y, z])
    return -q if w < 0 else q


@dataclass(frozen=True)
class PoseState:
    """Everything that changes with the pose (arrays ``(flank, tooth)`` use ``(cw, ccw)``).

    Attributes
    ----------
    clearance_mm : (2, N)
    float
        Circumferential clearance (docs/conventions.md, Frames) of each flank and tooth; ``inf``
        where no
        point of the flank faces the sleeve flank.
    normal_clearance_mm : (2, N) float
    theta_deg : (N,) float
        Turning angle of each tooth in ``[0, 360)``.
    contact_points : (n, 3) float
        Hub-frame points of first touch of the teeth in contact (within ``band_mm`` of
        their flank's smallest normal clearance, or interfering).
    contact_flank, contact_tooth : (n,) int
    interfering : (2, N) bool
        Negative clearance.
    backlash_mm : float
        Free turning at the pitch radius (both flanks) at this pose.
    """

    misalignment_deg: float
    psi_deg: float
    band_mm: float
    clearance_mm: NDArray[np.float64]
    normal_clearance_mm: NDArray[np.float64]
    theta_deg: NDArray[np.float64]
    contact_points: NDArray[np.float64]
    contact_flank: NDArray[np.intp]
    contact_tooth: NDArray[np.intp]
    interfering: NDArray[np.bool_]
    backlash_mm: float
    pressure_MPa: NDArray[np.float64] | None = None  # (2, N) with pressure=True

    @property
    def min_clearance_mm(self) -> NDArray[np.float64]:
        """Smallest clearance of each flank, ``(2,)``."""
        return np.min(self.clearance_mm, axis=1)

    def summary(self) -> str:
        """One line per flank for the GUI: smallest clearance, its tooth, contacts."""
        lines = []
        for f, name in enumerate(FLANKS):
            c = self.clearance_mm[f]
            k = int(np.argmin(c))
            n_contact = int(np.sum(self.contact_flank == f))
            n_int = int(np.sum(self.interfering[f]))
            lines.append(f"{name}: min {c[k]:+.4f} mm (tooth {k}, θ = {self.theta_deg[k]:.1f}°)"
                         f", {n_contact} in contact, {n_int} interfering")
        lines.append(f"backlash {self.backlash_mm:.4f} mm at the pitch radius")
        return "\n".join(lines)


def pose_state(spec: CouplingSpec,
               misalignment_deg: float, psi_deg: float, *, band_mm: float = 0.005,
               tolerance_mm: float = VIEW_SWEEP_TOLERANCE_MM,
               pressure: bool = False) -> PoseState:
    """Exact clearances, contact points and interference at one pose.

    Parameters
    ----------
    spec : CouplingSpec
    misalignment_deg, psi_deg : float
        Misalignment ``i`` (0-6°) and rotation ``psi`` (degrees).
    band_mm : float
        A tooth counts as in contact when its normal clearance is within this of the
        smallest on its flank (Renzo's separation ``z`` below the band), or negative.
    tolerance_mm : float
        Accuracy of the clearance minima (see :func:`gearcoupling.clearance.sweep`).
    pressure : bool
        Also solve the contact pressure at the spec's ``[load]`` torque (the ``surface``
        model, about a second): ``pressure_MPa``.
    """
    spec = as_spec(spec)
    mis, psi = check_pose(misalignment_deg, psi_deg)
    real(band_mm, "band_mm", 0.0, unit="mm")
    flag(pressure, "pressure")
    res = sweep(spec, mis, [psi], tolerance_mm=tolerance_mm)
    clear = res.clearance_mm[:, :, 0]
    normal = res.normal_clearance_mm[:, :, 0]
    interfering = clear < 0
    low = np.min(normal, axis=1, keepdims=True)
    touching = (np.isfinite(normal) & (normal <= low + band_mm)) | interfering
    flank_idx, tooth_idx = np.nonzero(touching)
    z = res.contact_z_mm[:, :, 0][touching]
    r = res.contact_r_mm[:, :, 0][touching]
    points = np.zeros((flank_idx.size, 3))
    m = hub_model(spec)
    for f, name in enumerate(FLANKS):
        sel = flank_idx == f
        if np.any(sel):
            p, _, _ = hub_flank_model(m, name, z[sel], r[sel], check=False)
            rot = rot_z(2.0 * np.pi * tooth_idx[sel] / spec.tooth.teeth)
            points[sel] = np.einsum("nij,nj->ni", rot, p)
    backlash = float(res.backlash_mm[0])
    return PoseState(mis, psi, float(band_mm), clear, normal, res.theta_deg[:, 0], points,
                     flank_idx, tooth_idx, interfering, backlash if math.isfinite(backlash)
                     else 0.0, _pressure(spec, res) if pressure else None)


def _pressure(spec: CouplingSpec, res) -> NDArray[np.float64]:
    """Interior contact pressure ``(2, N)`` of the loaded flank's teeth at the spec's torque
    (the ``surface`` load model; 0 on the other flank and on unloaded teeth)."""
    loads = load_from_sweep(res, model="surface")
    p = np.zeros((2, res.teeth))
    p[FLANKS.index(loads.loaded_flank)] = loads.interior_pressure_MPa[:, 0]
    return p


# ------------------------------------------------------------------ colours


def flank_values(state: PoseState, mode: str = "clearance") -> NDArray[np.float64]:
    """The ``(2, N)`` values the flank colours show (:data:`COLOR_MODES`): the clearance,
    or the separation ``clearance - max(0, smallest clearance of the flank)``;
    interfering flanks stay negative (red) and unfaced ones infinite (grey) in both."""
    if mode not in COLOR_MODES:
        raise ArgumentError(f"color mode = {mode!r}: must be one of {COLOR_MODES}")
    c = state.clearance_mm
    if mode == "clearance":
        return c
    low = np.min(np.where(np.isfinite(c), c, np.inf), axis=1, keepdims=True)
    low = np.where(np.isfinite(low), np.maximum(low, 0.0), 0.0)  # 0 where it interferes
    with np.errstate(invalid="ignore"):
        sep = np.where(np.isfinite(c), c - low, np.inf)
    return np.where(state.interfering, c, np.maximum(sep, 0.0))


def flank_colors(state: PoseState, mode: str, scale_mm: float,
                 spec: CouplingSpec) -> NDArray[np.uint8]:
    """RGB ``(2, N, 3)`` of the flanks in a colour mode (:data:`COLOR_MODES`)."""
    if mode != "pressure":
        return clearance_colors(flank_values(state, mode), scale_mm)
    if state.pressure_MPa is None:
        raise ArgumentError(f"mode = {mode!r}: needs a state from pose_state(..., pressure=True)")
    return pressure_colors(state.pressure_MPa,
                           spec.material.hub.allowable_contact_stress_MPa)


def pressure_colors(pressure_MPa: ArrayLike, allowable_MPa: float) -> NDArray[np.uint8]:
    """RGB ``(..., 3) uint8``: grey without load, then blue through cyan and yellow to red
    at the allowable contact stress and above."""
    p = np.asarray(pressure_MPa, dtype=float)
    t = np.clip(p / allowable_MPa, 0.0, 1.0)
    rgb = np.stack([np.interp(t, _PRESSURE_STOPS[:, 0], _PRESSURE_STOPS[:, j])
                    for j in (1, 2, 3)], axis=-1)
    rgb = np.where((p <= 0)[..., None], np.asarray(NO_CONTACT_RGB, dtype=float), rgb)
    return np.rint(rgb).astype(np.uint8)


def default_color_scale_mm(spec: CouplingSpec) -> float:
    """Clearance shown at the free end of the colour scale: half the aligned backlash
    (the clearance of every flank when aligned)."""
    return 0.5 * float(spec.derived["aligned_backlash_mm"])


def clearance_colors(clearance_mm: ArrayLike, scale_mm: float) -> NDArray[np.uint8]:
    """RGB ``(..., 3) uint8`` of clearances: red below 0 (interference), yellow at 0
    (touching) through green and cyan to blue at ``scale_mm`` and above, grey where
    infinite (no sleeve flank faces the hub flank)."""
    if not (math.isfinite(scale_mm) and scale_mm > 0):
        raise SpecError("color_scale_mm", scale_mm, "must be a positive finite length (mm)")
    c = np.asarray(clearance_mm, dtype=float)
    t = np.clip(np.where(np.isfinite(c), c, 0.0) / scale_mm, 0.0, 1.0)
    rgb = np.stack([np.interp(t, _STOPS[:, 0], _STOPS[:, j]) for j in (1, 2, 3)], axis=-1)
    rgb = np.where((c < 0)[..., None], np.asarray(INTERFERENCE_RGB, dtype=float), rgb)
    rgb = np.where(np.isinf(c)[..., None], np.asarray(NO_CONTACT_RGB, dtype=float), rgb)
    return np.rint(rgb).astype(np.uint8)


def legend(scale_mm: float, steps: int = 4,
           mode: str = "clearance") -> list[tuple[str, tuple[int, int, int]]]:
    """Legend entries ``(label, rgb)``: interference, then ``steps + 1`` values from 0 to
    ``scale_mm``, then no contact."""
    if mode == "pressure":
        frac = np.linspace(0.0, 1.0, steps + 1)[1:]
        cols = pressure_colors(frac, 1.0)
        return ([(f"{f:.2f} x allowable contact stress" + (" and above" if f == 1 else ""),
                  _rgb(c)) for f, c in zip(frac, cols, strict=True)]
                + [("no load", NO_CONTACT_RGB)])
    values = np.linspace(0.0, scale_mm, steps + 1)
    cols = clearance_colors(values, scale_mm)
    out = [("< 0 mm (interference)", INTERFERENCE_RGB)]
    zero = " (touching)" if mode == "clearance" else " (first contact)"
    for v, c in zip(values, cols, strict=True):
        label = f"{v:.4f} mm" + (zero if v == 0 else "") + \
            (" and above" if v == scale_mm else "")
        out.append((label, _rgb(c)))
    out.append(("no sleeve flank opposite", NO_CONTACT_RGB))
    return out


def _rgb(c: NDArray[np.uint8]) -> tuple[int, int, int]:
    r, g, b = (int(x) for x in c)
    return r, g, b


def legend_title(mode: str = "clearance") -> str:
    if mode == "pressure":
        return "interior contact pressure at the spec's torque (surface model)"
    return ("flank clearance (circumferential)" if mode == "clearance" else
            "flank separation z (clearance minus the flank's smallest)")


def legend_markdown(scale_mm: float, mode: str = "clearance") -> str:
    """The legend as HTML-coloured markdown for the GUI."""
    rows = [f'<span style="color:rgb{rgb}">■■</span> {label}'
            for label, rgb in legend(scale_mm, mode=mode)]
    return f"**{legend_title(mode)}**<br/>" + "<br/>".join(rows)


# ------------------------------------------------------------------ plot


@dataclass(frozen=True)
class ClearanceCurve:
    """Clearance of one tooth against its turning angle at one misalignment.

    Attributes
    ----------
    theta_deg : (n,) float
        Sorted turning angles in ``[0, 360)``.
    clearance_mm : (2, n) float
        Circumferential clearance of the cw and ccw flank.
    """

    misalignment_deg: float
    theta_deg: NDArray[np.float64]
    clearance_mm: NDArray[np.float64]


def clearance_curve(spec: CouplingSpec,
                    misalignment_deg: float, samples: int = DEFAULT_PLOT_SAMPLES, *,
                    tolerance_mm: float = VIEW_SWEEP_TOLERANCE_MM) -> ClearanceCurve:
    """Clearance against θ from one sweep over one pitch (every tooth gives its θ).

    ``samples`` turning angles over 360° (rounded up to a multiple of the tooth count).
    """
    if not (isinstance(samples, int | np.integer) and samples >= 8):
        raise ArgumentError("samples", samples, "must be a whole number >= 8")
    mis, _ = check_pose(misalignment_deg, 0.0)
    n = spec.tooth.teeth
    per_pitch = max(1, math.ceil(samples / n))
    psi = np.arange(per_pitch) * (360.0 / n / per_pitch)
    res = sweep(spec, mis, psi, tolerance_mm=tolerance_mm)
    theta = res.theta_deg.ravel()
    order = np.argsort(theta, kind="stable")
    clear = res.clearance_mm.reshape(2, -1)[:, order]
    return ClearanceCurve(mis, theta[order], clear)


def plot_series(curve: ClearanceCurve, state: PoseState) -> tuple[NDArray, ...]:
    """Plot data ``(x, cw, ccw, cw_now, ccw_now, tooth0)`` on one shared x axis (degrees).

    ``x`` merges the curve's θ with the current θ of every tooth; ``cw``/``ccw`` are the
    curve (interpolated at the merged points, periodic in θ); ``*_now`` hold the exact
    clearance of each tooth at the current pose where ``x`` is that tooth's θ, NaN
    elsewhere (drawn as markers); ``tooth0`` is the smaller of tooth 0's two clearances
    at its θ = ψ (the current angle), NaN elsewhere. Infinite clearances (no contact)
    become NaN (gaps).
    """
    now = np.mod(state.theta_deg, 360.0)
    x = np.concatenate([curve.theta_deg, now])
    order = np.argsort(x, kind="stable")
    x = x[order]
    xp = np.concatenate([curve.theta_deg - 360.0, curve.theta_deg, curve.theta_deg + 360.0])
    out = [x]
    for f in range(2):
        c = curve.clearance_mm[f]
        fp = np.concatenate([c, c, c])
        finite = np.isfinite(fp)
        y = np.interp(x, xp[finite], fp[finite]) if np.any(finite) else np.full(x.shape, np.nan)
        out.append(y)
    blank = np.full(curve.theta_deg.size, np.nan)
    for f in range(2):
        out.append(np.concatenate([blank, state.clearance_mm[f]])[order])
    first = np.full(now.size, np.nan)
    first[0] = np.min(state.clearance_mm[:, 0])
    out.append(np.concatenate([blank, first])[order])
    return tuple(np.where(np.isfinite(a), a, np.nan) for a in out)


def plot_range(series: tuple[NDArray, ...], pad: float = 0.08) -> tuple[float, float]:
    """A fixed y range ``(lo, hi)`` (mm) covering every finite value of the y series.

    The plot sets it explicitly: uPlot's automatic range breaks on a NaN first sample,
    which the marker series have.
    """
    ys = np.concatenate([np.asarray(a, dtype=float).ravel() for a in series[1:]])
    ys = ys[np.isfinite(ys)]
    if ys.size == 0:
        return -1.0, 1.0
    lo, hi = float(ys.min()), float(ys.max())
    span = hi - lo if hi > lo else max(abs(hi), 1e-3)
    return lo - pad * span, hi + pad * span


# ------------------------------------------------------------------ interference


def interference_mesh(meshes: SceneMeshes, rotation: ArrayLike,
                      interfering: ArrayLike | None = None) -> tuple[Patch, float]:
    """Hub ∩ sleeve at a pose: the overlap solid in the sleeve frame and its volume (mm³).

    Parameters
    ----------
    meshes : SceneMeshes
    rotation : (3, 3) float
        Hub pose (:func:`hub_rotation`).
    interfering : (2, N) bool, optional
        The (flank, tooth) pairs the exact sweep finds interfering
        (:attr:`PoseState.interfering`). The meshes' chords lie inside the convex hub
        flanks but outside the concave flanks of the internal sleeve teeth, so a coarse
        mesh shows overlap up to about its chordal tolerance deep where the exact
        surfaces are still apart. Given this mask, a piece is kept when the sweep finds
        its tooth and flank (nearest its centroid) interfering, or when it is thicker on
        average (``2 V / A``) than the chordal tolerance, which no chord error makes: an
        overlap outside the flank pairs the sweep models (e.g. a sleeve chamfer corner in
        a hub root fillet).
    """
    rot = np.asarray(rotation, dtype=float)
    overlap = meshes.hub_manifold.transform(affine(rot)) ^ meshes.sleeve_manifold
    if interfering is not None:
        mask = np.asarray(interfering, dtype=bool)
        teeth = mask.shape[1]
        keep = []
        for piece in overlap.decompose():
            verts = np.asarray(piece.to_mesh().vert_properties, dtype=float)[:, :3]
            if verts.size == 0:
                continue
            c = rot.T @ verts.mean(axis=0)  # hub frame
            k = int(nearest_tooth(c, teeth)) % teeth
            flank = int(flank_index(c, k, teeth))
            thick = 2.0 * piece.volume() / max(piece.surface_area(), 1e-300)
            if mask[flank, k] or thick > meshes.tolerance_mm:
                keep.append(piece)
        overlap = type(overlap).compose(keep) if keep else type(overlap)()
    volume = float(overlap.volume())
    return _patch_from_manifold(overlap), max(volume, 0.0)


__all__ = [
    "COLOR_MODES",
    "CUTAWAYS",
    "LOD_DIVISORS",
    "ClearanceCurve",
    "HubPieces",
    "Patch",
    "PoseState",
    "SceneMeshes",
    "build_scene_meshes",
    "check_pose",
    "clearance_colors",
    "clearance_curve",
    "cut_sleeve",
    "default_color_scale_mm",
    "flank_colors",
    "flank_values",
    "hub_rotation",
    "interference_mesh",
    "legend",
    "legend_markdown",
    "legend_title",
    "lod_tolerance",
    "plot_range",
    "plot_series",
    "pose_state",
    "pressure_colors",
    "quaternion_wxyz",
    "split_hub",
    "submesh",
    "view_tolerance",
]
