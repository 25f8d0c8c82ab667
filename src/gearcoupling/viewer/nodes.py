"""The coupling's scene nodes in a viser server, shared by the live viewer and the HTML
export.

Node tree (sleeve frame = world; ``+z`` up is the sleeve axis)::

    /sleeve                       sleeve mesh (with the chosen cutaway)
    /hub                          frame posed by Rz(-psi) Rx(i) Rz(psi)
    /hub/body                     hub without its flanks
    /hub/flanks/cw/007 ...        one patch per flank and tooth, coloured by clearance
    /hub/contacts                 points of first touch (point cloud)
    /interference                 hub ∩ sleeve solid in red (only while interfering)
    /legend/...                   colour legend (static HTML only)

Meshes are sent once per level of detail; :meth:`CouplingScene.set_pose` only changes the
hub node's orientation, the patch colours, the contact points and the interference
solid.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

import numpy as np

from ..errors import ArgumentError, BackendError
from ..geometry import FLANKS, rot_z
from ..interrupts import reraise as reraise_interrupt
from ..loading import LoadResult, load
from ..spec import CouplingSpec
from .scene import (
    COLOR_MODES,
    CUTAWAYS,
    INTERFERENCE_RGB,
    VIEW_SWEEP_TOLERANCE_MM,
    Patch,
    PoseState,
    SceneMeshes,
    build_scene_meshes,
    check_pose,
    default_color_scale_mm,
    flank_colors,
    hub_rotation,
    interference_mesh,
    legend,
    legend_title,
    pose_state,
    quaternion_wxyz,
)

HUB_RGB = (190, 160, 110)
SLEEVE_RGB = (120, 140, 175)
CONTACT_RGB = (230, 0, 200)
FRAMES = ("sleeve", "ground")
"""``sleeve``: the sleeve body frame stays still and the hub wobbles by
``Rz(-psi) Rx(i) Rz(psi)``; ``ground``: both members turn, the sleeve by ``Rz(psi)`` and
the hub by ``Rx(i) Rz(psi)`` about its tilted axis (the tilt axis stays on screen ``x``)."""


def import_viser():
    """``viser``, or :class:`BackendError` naming the extra to install."""
    try:
        return importlib.import_module("viser")
    except ImportError as err:
        reraise_interrupt(err)  # a signal during the import
        raise BackendError("the 3D viewer needs viser: pip install 'gearcoupling[viewer]'"
                           ) from err


@dataclass
class ViewSettings:
    """What the viewer shows; the GUI edits these and the CLI sets their start values."""

    misalignment_deg: float
    psi_deg: float = 0.0
    cutaway: str = "quarter"
    show_hub: bool = True
    show_sleeve: bool = True
    hub_opacity: float = 1.0
    sleeve_opacity: float = 1.0
    color_scale_mm: float | None = None  # None: default_color_scale_mm(spec)
    color_mode: str = "clearance"  # scene.COLOR_MODES
    band_mm: float = 0.005
    show_contacts: bool = True
    show_interference: bool = True
    frame: str = "sleeve"  # FRAMES: what stays still on screen

    def __post_init__(self):
        if self.cutaway not in CUTAWAYS:
            raise ArgumentError("cutaway", self.cutaway, f"one of {CUTAWAYS}")
        if self.frame not in FRAMES:
            raise ArgumentError("frame", self.frame, f"one of {FRAMES}")
        if self.color_mode not in COLOR_MODES:
            raise ArgumentError("color_mode", self.color_mode, f"one of {COLOR_MODES}")
        for name in ("hub_opacity", "sleeve_opacity"):
            v = getattr(self, name)
            if not 0.0 <= v <= 1.0:
                raise ArgumentError(name, v, "from 0 to 1")


def pose_loads(spec: CouplingSpec, misalignment_deg: float, psi_deg: float) -> LoadResult:
    """The loads the pressure colours show: :func:`gearcoupling.load` at the pose and the
    spec's torque with the ``surface`` model (about a second), on the viewer's sweep
    accuracy."""
    return load(spec, misalignment_deg, [psi_deg], model="surface",
                tolerance_mm=VIEW_SWEEP_TOLERANCE_MM)


class CouplingScene:
    """Hub and sleeve of one spec as viser scene nodes.

    Parameters
    ----------
    server : viser.ViserServer
    spec : CouplingSpec
    settings : ViewSettings
    tolerance_mm : float, optional
        Chordal tolerance of the meshes (default: the ``coarse`` level of detail).
    legend_in_scene : bool
        Draw the colour legend as boxes and labels in the 3D scene (for the static HTML,
        which has no GUI panel).
    """

    def __init__(self, server, spec: CouplingSpec,
                 settings: ViewSettings, tolerance_mm: float | None = None,
                 *, legend_in_scene: bool = False):
        self.server = server
        self.spec = spec
        self.settings = settings
        self.state: PoseState | None = None
        self.interference_volume_mm3 = 0.0
        self.interference_patch: Patch | None = None  # sleeve frame
        self._interference = None
        self._flanks: list[list] = [[], []]
        self._legend_in_scene = legend_in_scene
        self.meshes: SceneMeshes = build_scene_meshes(spec, tolerance_mm)
        R = spec.tooth.pitch_radius
        server.scene.set_up_direction("+z")
        server.initial_camera.position = (-1.0 * R, -1.45 * R, 1.0 * R)
        server.initial_camera.look_at = (0.0, 0.0, 0.0)
        server.initial_camera.up = (0.0, 0.0, 1.0)
        self.hub_frame = server.scene.add_frame("/hub", show_axes=False)
        self._add_meshes()
        self._contacts = server.scene.add_point_cloud(
            "/hub/contacts", np.zeros((1, 3), np.float32), CONTACT_RGB,
            point_size=0.5 * spec.tooth.module, point_shape="circle", precision="float32",
            visible=False)
        if legend_in_scene:
            self._add_legend()
        self.set_pose(settings.misalignment_deg, settings.psi_deg)

    # ---------------------------------------------------------------- meshes

    @property
    def color_scale_mm(self) -> float:
        s = self.settings.color_scale_mm
        return default_color_scale_mm(self.spec) if s is None else s

    def _add_meshes(self) -> None:
        scene, st, pieces = self.server.scene, self.settings, self.meshes.hub_pieces
        cut = self.meshes.sleeve_cut(st.cutaway)
        self.sleeve = scene.add_mesh_simple(
            "/sleeve", cut.vertices, cut.faces, color=SLEEVE_RGB,
            opacity=_opacity(st.sleeve_opacity), side="double", visible=st.show_sleeve)
        self.hub_body = scene.add_mesh_simple(
            "/hub/body", pieces.body.vertices, pieces.body.faces, color=HUB_RGB,
            opacity=_opacity(st.hub_opacity), visible=st.show_hub)
        self._flanks = [[], []]
        for f, name in enumerate(FLANKS):
            for k, patch in enumerate(pieces.flanks[f]):
                self._flanks[f].append(scene.add_mesh_simple(
                    f"/hub/flanks/{name}/{k:03d}", patch.vertices, patch.faces, color=HUB_RGB,
                    opacity=_opacity(st.hub_opacity), side="double", visible=st.show_hub))

    def set_tolerance(self, tolerance_mm: float) -> None:
        """Re-mesh at another chordal tolerance (level of detail) and resend the meshes."""
        meshes = build_scene_meshes(self.spec, tolerance_mm)
        with self.server.atomic():
            self.sleeve.remove()
            self.hub_body.remove()
            for handles in self._flanks:
                for h in handles:
                    h.remove()
            self.meshes = meshes
            self._add_meshes()
        self.set_pose(self.settings.misalignment_deg, self.settings.psi_deg)

    def set_cutaway(self, cutaway: str) -> None:
        """Show the sleeve with another cutaway (the cut meshes are cached)."""
        if cutaway not in CUTAWAYS:
            raise ArgumentError("cutaway", cutaway, f"one of {CUTAWAYS}")
        self.settings.cutaway = cutaway
        cut = self.meshes.sleeve_cut(cutaway)
        st = self.settings
        self.sleeve.remove()
        self.sleeve = self.server.scene.add_mesh_simple(
            "/sleeve", cut.vertices, cut.faces, color=SLEEVE_RGB,
            opacity=_opacity(st.sleeve_opacity), side="double", visible=st.show_sleeve,
            wxyz=self._ground_wxyz())

    def ground(self) -> np.ndarray:
        """Sleeve body frame to screen: ``Rz(psi)`` in the ground frame, else identity."""
        if self.settings.frame == "ground":
            return rot_z(np.radians(self.settings.psi_deg))
        return np.eye(3)

    def _ground_wxyz(self) -> np.ndarray:
        return quaternion_wxyz(self.ground())

    def set_display(self) -> None:
        """Apply visibility and opacity from the settings to the existing nodes."""
        st = self.settings
        with self.server.atomic():
            self.sleeve.visible = st.show_sleeve
            self.sleeve.opacity = _opacity(st.sleeve_opacity)
            for h in [self.hub_body, *self._flanks[0], *self._flanks[1]]:
                h.visible = st.show_hub
                h.opacity = _opacity(st.hub_opacity)
            self._contacts.visible = (st.show_contacts and self.state is not None
                                      and self.state.contact_points.shape[0] > 0)
            if self._interference is not None:
                self._interference.visible = st.show_interference

    # ---------------------------------------------------------------- pose

    def set_pose(self, misalignment_deg: float, psi_deg: float) -> PoseState:
        """Move the hub to a pose and recolour: no mesh is rebuilt (the interference
        solid, which is new geometry at every pose, is the only node re-added)."""
        st = self.settings
        mis, psi = check_pose(misalignment_deg, psi_deg)
        loads = pose_loads(self.spec, mis, psi) if st.color_mode == "pressure" else None
        state = pose_state(self.spec, mis, psi, band_mm=st.band_mm, loads=loads)
        st.misalignment_deg, st.psi_deg = state.misalignment_deg, state.psi_deg
        rot = hub_rotation(state.misalignment_deg, state.psi_deg)
        colors = flank_colors(state, st.color_mode, self.color_scale_mm, self.spec)
        patch = None
        volume = 0.0
        # the boolean runs only when some flank comes within the chordal tolerance: farther
        # apart, the meshes cannot overlap by more than chord error at the flanks
        if np.min(state.clearance_mm) < self.meshes.tolerance_mm:
            patch, volume = interference_mesh(self.meshes, rot, state.interfering)
        ground = self.ground()
        with self.server.atomic():
            self.hub_frame.wxyz = quaternion_wxyz(ground @ rot)
            self.sleeve.wxyz = quaternion_wxyz(ground)
            for f in range(2):
                for k, handle in enumerate(self._flanks[f]):
                    handle.color = tuple(int(c) for c in colors[f, k])
            n = state.contact_points.shape[0]
            if n:
                self._contacts.points = state.contact_points.astype(np.float32)
                self._contacts.colors = np.broadcast_to(np.asarray(CONTACT_RGB, np.uint8),
                                                        (n, 3)).copy()
            self._contacts.visible = bool(n) and st.show_contacts
            if self._interference is not None:
                self._interference.remove()
                self._interference = None
            if patch is not None and patch.faces.shape[0]:
                self._interference = self.server.scene.add_mesh_simple(
                    "/interference", patch.vertices, patch.faces, color=INTERFERENCE_RGB,
                    side="double", visible=st.show_interference,
                    wxyz=quaternion_wxyz(ground))
        self.state = state
        self.interference_volume_mm3 = volume
        self.interference_patch = patch
        return state

    def recolor(self) -> None:
        """Recolour the flanks after a colour-scale change (same pose)."""
        if self.state is None:
            return
        st = self.settings
        if st.color_mode == "pressure" and self.state.pressure_MPa is None:
            self.set_pose(st.misalignment_deg, st.psi_deg)  # computes the loads
            return
        colors = flank_colors(self.state, st.color_mode, self.color_scale_mm, self.spec)
        with self.server.atomic():
            for f in range(2):
                for k, handle in enumerate(self._flanks[f]):
                    handle.color = tuple(int(c) for c in colors[f, k])

    # ---------------------------------------------------------------- legend

    def _add_legend(self) -> None:
        """Colour legend above the coupling, right of the axis (for the static HTML, which
        has no GUI panel)."""
        bounds = self.meshes.sleeve.bounds
        add_legend(self.server.scene, self.spec, self.settings.color_mode,
                   self.color_scale_mm, 0.9 * bounds[1][0], bounds[1][2])


def add_legend(scene, spec: CouplingSpec, mode: str, scale_mm: float, x: float,
               z_bottom: float) -> None:
    """The colour legend of ``mode`` as boxes with labels in a viser ``scene``, from
    ``z_bottom`` up at ``x`` (sized by the module)."""
    add_legend_entries(scene, spec, legend_title(mode), legend(scale_mm, mode=mode), x,
                       z_bottom)


def add_legend_entries(scene, spec: CouplingSpec, title: str,
                       entries: list[tuple[str, tuple[int, int, int]]], x: float,
                       z_bottom: float) -> None:
    """A legend ``title`` over ``entries`` ``(label, rgb)`` as boxes with labels in a viser
    ``scene``, from ``z_bottom`` up at ``x`` (sized by the module)."""
    size = 1.5 * spec.tooth.module
    step = 1.6 * size
    z_top = z_bottom + (len(entries) + 1) * step
    scene.add_label("/legend/title", title,
                    position=(x - 0.5 * size, 0.0, z_top + step), anchor="bottom-left")
    for j, (label, rgb) in enumerate(entries):
        z = z_top - j * step
        scene.add_box(f"/legend/box{j}", color=rgb, dimensions=(size, size, size),
                      position=(x, 0.0, z))
        scene.add_label(f"/legend/label{j}", label, position=(x + size, 0.0, z),
                        anchor="center-left")


def _opacity(value: float) -> float | None:
    return None if value >= 1.0 else float(value)
