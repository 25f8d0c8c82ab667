"""The aligned contact reference: one tooth pitch of hub and sleeve in frictionless
CalculiX contact, loaded by the torque, with cyclic-symmetry equations on the cut faces.

At misalignment 0 every tooth carries the same load, so one pitch with rotationally
periodic cuts is the whole coupling. The hub and sleeve sectors of one pitch are meshed
by gmsh with node-for-node periodic cuts (:func:`~gearcoupling.fea.mesh_part`,
``periodic=True``); every node of a ccw cut face follows its cw partner turned by the
pitch angle (``*EQUATION``, three per node). The hub bore is fixed; the sleeve outside
diameter is a rigid body whose rotation node carries the moment ``T / N``. The hub is
meshed turned to the sweep's exact first touch (a rotation of its nodes), and step 1 turns
the sleeve (displacement control) on to just past it, so the contact is closed when step 2
releases it and applies the moment. The hub ccw flank (slave) meets the sleeve ccw flank
(master) through a stiff linear penalty law. The analysis is linear (small strain): a
finite turn of the rigid surface by ``theta`` reads as a compression of about
``theta**2 / 2`` that shrinks the sleeve and moves its flanks toward the hub: step 1
turning by the whole first touch would move the wind-up beyond it by 0.15-0.24 % on
renzo-1967 and 1.6-3.2 % on industrial-m2 (docs/fea.md); meshing the pose leaves only the
small remainder.

Measured per run: the wind-up (the sleeve's rotation against the fixed bore) and the part
beyond the exact first touch, the tooth's tangential load (its contact moment / pitch
radius; equilibrium says ``T / (N R)``), the peak and interior contact pressure, the patch
extent across the face and along the profile, and solver time and memory. The load curve
(the end of step 1, half and the whole torque) also gives the mesh's own first touch: the
parabola through its points, at zero torque. Its distance from the exact
first touch is the error of the meshed flanks, in the one measure that matters here; the
solid is therefore built to a tight chordal tolerance (``tolerance_mm``).
"""

from __future__ import annotations

import math
import resource
from dataclasses import asdict, dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..arguments import is_real, resolve_torque_Nm
from ..clearance import min_backlash_rad
from ..errors import ArgumentError, GeometryError
from ..geometry import developed_arc, rot_z
from ..io import inp_id_lines, inp_number
from ..spec import CouplingSpec, as_spec
from .ccx import run_ccx, solver_dir
from .contact import merge
from .mesh import check_size, mesh_part
from .stiffness import material
from .volume import VolumeMesh
from .write import inp_mesh_lines

TOLERANCE_MODULES = 2e-4  # chordal tolerance of the solid: module x this (0.5 µm at m 2.54)
PENALTY_FACTOR = 50.0  # penalty stiffness = factor * E / element size (MPa/mm)
TOUCH_MARGIN = 0.03  # step 1 turns on by margin x first touch, to close the contact
MIN_PATCH_ELEMENTS = 1.5  # contact elements across the patch along the face, at least
#: cut-face partners may lie this share of the face's node spacing apart (one to one, so no
#: node can take a wrong partner): gmsh's periodic copy leaves them up to 4 µm apart on a
#: 256-tooth hub of module 0.69 (93 of 246 nodes over 1 µm), against a spacing of 92 µm
MATCH_SHARE = 0.1
#: ccx's equation solver for the contact decks: its preconditioned conjugate gradients gave
#: renzo-1967's default reference (26 265 nodes) to the 7 digits ccx prints, in as many
#: contact iterations, with less CPU and memory than SPOOLES (docs/fea.md has the figures)
CONTACT_SOLVER = "ITERATIVE CHOLESKY"
#: ccx's contact-change tolerance (``*CONTROLS, PARAMETERS=CONTACT``, first value; its
#: default 0.001): an iteration's contact set counts as settled when the number of contact
#: elements changes by at most this share. On renzo-1967's default reference 0.01 saves
#: three of 24 iterations with the printed answers unchanged; 0.05 once settled on a wrong
#: contact set
CONTACT_CHANGE_TOLERANCE = 0.01


@dataclass(frozen=True)
class FEContactResult:
    """One aligned contact reference pose (module docstring). Lengths mm, angles rad;
    ``windup_curve`` the ``(torque_Nm, windup_from_first_touch_rad)`` of every load
    increment (at most half the torque apart) and of the end of step 1;
    ``mesh_first_touch_rad`` the mesh's own first touch (module docstring)."""

    spec: str
    torque_Nm: float
    size_mm: float
    windup_rad: float
    first_touch_rad: float
    windup_from_first_touch_rad: float
    windup_curve: list[tuple[float, float]]
    mesh_first_touch_rad: float
    tooth_load_N: float
    equilibrium_tooth_load_N: float
    peak_pressure_MPa: float
    interior_pressure_MPa: float
    patch_face_mm: float
    patch_profile_mm: float
    nodes: int
    solve_seconds: float
    max_rss_MB: float
    settings: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """Plain values, for ``fea_contact.json``."""
        return asdict(self)


def fe_contact(spec: CouplingSpec, *, torque_Nm: float | None = None,
               misalignment_deg: float = 0.0, size_mm: float | None = None,
               contact_size_mm: float | None = None, tolerance_mm: float | None = None,
               workdir=None) -> FEContactResult:
    """Solve the aligned contact reference of ``spec`` at ``torque_Nm`` (module docstring).

    Parameters
    ----------
    spec : CouplingSpec
    torque_Nm : float, optional
        Positive torque (N m); default the spec's load torque.
    misalignment_deg : float
        Only 0: a misaligned pose needs a sector of several pitches
        (:func:`~gearcoupling.fea.sector.fe_contact_sector`).
    size_mm : float, optional
        Element size on the teeth (default module / 4).
    contact_size_mm : float, optional
        Element size on the loaded flanks near mid-face, where the patch lies (the accuracy
        knob; default ``size_mm``); refused when fewer than 1.5 elements span the patch.
    tolerance_mm : float, optional
        Chordal tolerance of the solids (default module x 2e-4).
    workdir : path, optional
        Keep the deck, log and printout here (default: a temporary folder, kept on failure).
    """
    spec = as_spec(spec)
    if not (is_real(misalignment_deg) and misalignment_deg == 0.0):
        raise ArgumentError("misalignment_deg", misalignment_deg,
                            "0 only: the one-pitch cyclic reference holds for aligned shafts; "
                            "a misaligned pose is a sector (fe_contact_sector, sector_check)")
    T = resolve_torque_Nm(spec, torque_Nm, zero=False)
    if T < 0:
        raise ArgumentError("torque_Nm" if torque_Nm is not None else "load.torque_Nm", T,
                            "a torque above 0 N·m: the reference loads the ccw flanks")
    size = min(check_size(spec, "hub", size_mm), check_size(spec, "sleeve", size_mm))
    c = size if contact_size_mm is None else check_size(spec, "hub", contact_size_mm)
    tol = TOLERANCE_MODULES * spec.tooth.module if tolerance_mm is None else tolerance_mm
    touch = 0.5 * min_backlash_rad(spec, 0.0)
    if not touch > 0:
        raise ArgumentError("spec", spec.name, "aligned backlash above 0: these teeth touch or "
                            "bind at no load, which the reference's first step cannot start from")
    hub, sleeve = (mesh_part(spec, part, sector=1, size_mm=size, periodic=True,
                             tolerance_mm=tol, contact=(c, 0.25 * spec.hub.face_width))
                   for part in ("hub", "sleeve"))
    pair = merge(hub, sleeve, rot_z(touch))
    E, _ = material(spec, "hub")
    deck = torque_deck(pair, spec, moment_Nmm=1e3 * T / spec.tooth.teeth,
                       preturn_rad=TOUCH_MARGIN * touch, penalty=PENALTY_FACTOR * E / size)
    with solver_dir(workdir) as work:
        res = run_ccx(deck, work, "fe_contact")
        pressure = frd_nodal(res.job.with_suffix(".frd").read_text(), "CONTACT")
    out = _result(spec, T, c, touch, pair, res, pressure)
    if out.patch_face_mm < MIN_PATCH_ELEMENTS * c:
        raise ArgumentError("contact_size_mm", c, f"at most "
                            f"{out.patch_face_mm / MIN_PATCH_ELEMENTS:.3g} mm: "
                            f"the patch is {out.patch_face_mm:.3g} mm long across the face and "
                            f"needs {MIN_PATCH_ELEMENTS:g} elements at least")
    return out


def cyclic_equations(vm: VolumeMesh, cw: str, ccw: str, rotation: NDArray[np.float64],
                     skip: NDArray[np.int64]) -> list[str]:
    """``*EQUATION`` lines tying every node of the ``ccw`` cut to its ``cw`` partner turned
    by ``rotation (3, 3)`` (u_ccw = R u_cw; the partner lies at R x_cw), except nodes in
    ``skip`` (0-based). The partners must pair one to one, each within :data:`MATCH_SHARE`
    of the cut face's smallest node spacing."""
    from scipy.spatial import cKDTree

    a, b = vm.node_set(cw), vm.node_set(ccw)
    rot = np.asarray(rotation, dtype=float)
    tree = cKDTree(vm.nodes[b])
    dist, idx = tree.query(vm.nodes[a] @ rot.T)
    spacing = tree.query(vm.nodes[b], k=2)[0][:, 1].min() if len(b) > 1 else 0.0
    if (len(a) != len(b) or len(np.unique(idx)) != len(idx)
            or dist.max() > MATCH_SHARE * spacing):
        raise GeometryError(f"the cut faces of the {vm.part} sector do not match node for "
                            f"node ({len(a)} and {len(b)} nodes, worst {dist.max():.3g} mm "
                            f"against a node spacing of {spacing:.3g} mm); "
                            "mesh it with periodic=True")
    lines = ["*EQUATION"]
    skipped = set(skip.tolist())
    for i, j in zip(a + 1, b[idx] + 1, strict=True):
        if j - 1 in skipped:
            continue
        for d in range(3):
            terms = [f"{j}, {d + 1}, 1.0"] + [f"{i}, {e + 1}, {inp_number(-rot[d, e])}"
                                             for e in range(3) if abs(rot[d, e]) > 1e-15]
            lines += [str(len(terms)), ", ".join(terms)]
    return lines


def torque_deck(pair: VolumeMesh, spec: CouplingSpec, *, moment_Nmm: float, preturn_rad: float,
                penalty: float, increment: float = 0.5) -> str:
    """The deck (module docstring) of a ``pair`` meshed at first touch: step 1 turns the
    sleeve on by ``-preturn_rad`` in one increment, step 2 applies ``-moment_Nmm`` about z
    to it instead, in increments of at most ``increment`` of the moment (each one printed:
    the wind-up curve); ccx's equation solver :data:`CONTACT_SOLVER`, its contact-change
    tolerance :data:`CONTACT_CHANGE_TOLERANCE`."""
    E, nu = material(spec, "hub")
    ref, rot = len(pair.nodes) + 1, len(pair.nodes) + 2
    bore, outer = pair.node_set("H_BORE"), pair.node_set("S_OUTER")
    turn = rot_z(2 * math.pi / spec.tooth.teeth)
    lines = inp_mesh_lines(pair)
    lines += ["*NODE", f"{ref}, 0.0, 0.0, 0.0", f"{rot}, 0.0, 0.0, 0.0",
              "*NSET, NSET=ROTN", f"{rot}", "*NSET, NSET=SRIGID", *inp_id_lines(outer + 1),
              "*NSET, NSET=HFIX", *inp_id_lines(bore + 1)]
    lines += cyclic_equations(pair, "H_CUT_CW", "H_CUT_CCW", turn, bore)
    lines += cyclic_equations(pair, "S_CUT_CW", "S_CUT_CCW", turn, outer)
    controls = ["*CONTROLS, PARAMETERS=CONTACT", inp_number(CONTACT_CHANGE_TOLERANCE)]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{inp_number(E)}, {inp_number(nu)}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
              f"*RIGID BODY, NSET=SRIGID, REF NODE={ref}, ROT NODE={rot}",
              "*SURFACE INTERACTION, NAME=SI",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{inp_number(penalty)}",
              "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE",
              "S_H_T0_FLANK_CCW, S_S_T0_FLANK_CCW",
              "*BOUNDARY", "HFIX, 1, 3, 0.0", f"{ref}, 1, 3, 0.0", f"{rot}, 1, 2, 0.0",
              "*STEP, INC=100", f"*STATIC, SOLVER={CONTACT_SOLVER}", "1.0, 1.0", *controls,
              "*BOUNDARY",
              f"{rot}, 3, 3, {inp_number(-preturn_rad)}",
              "*NODE PRINT, NSET=ROTN", "U, RF", "*END STEP",
              "*STEP, INC=200", f"*STATIC, SOLVER={CONTACT_SOLVER}",
              f"{increment}, 1.0, 1e-4, {increment}", *controls,
              "*BOUNDARY, OP=NEW", "HFIX, 1, 3, 0.0", f"{ref}, 1, 3, 0.0", f"{rot}, 1, 2, 0.0",
              "*CLOAD", f"{rot}, 3, {inp_number(-moment_Nmm)}",
              "*NODE PRINT, NSET=ROTN", "U, RF",
              "*CONTACT PRINT, SLAVE=S_H_T0_FLANK_CCW, MASTER=S_S_T0_FLANK_CCW", "CF",
              "*CONTACT FILE", "CSTR", "*END STEP"]
    return "\n".join(lines) + "\n"


def _result(spec, T, size, touch, pair, res, pressure) -> FEContactResult:
    R = spec.tooth.pitch_radius
    curve = load_curve(res, T, spec.tooth.teeth, meshed_at_rad=touch)
    windup = curve[-1][1]
    torques, turns = np.array(curve).T
    mesh_touch = float(np.polyfit(torques, turns, min(2, len(curve) - 1))[-1])
    stats = res.get("statistics", "S_H_T0_FLANK_CCW")[-1][0, :6]
    load = abs(float(stats[5])) / R
    peak, interior, face, profile = patch_figures(spec, pair, pressure, size)
    return FEContactResult(
        spec=spec.name, torque_Nm=float(T), size_mm=size, windup_rad=windup,
        first_touch_rad=touch, windup_from_first_touch_rad=windup - touch,
        windup_curve=[(t, w - touch) for t, w in curve], mesh_first_touch_rad=mesh_touch,
        tooth_load_N=load, equilibrium_tooth_load_N=1e3 * T / (spec.tooth.teeth * R),
        peak_pressure_MPa=peak, interior_pressure_MPa=interior, patch_face_mm=face,
        patch_profile_mm=profile, nodes=len(pair.nodes), solve_seconds=res.seconds,
        max_rss_MB=resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,
        settings={"penalty_factor": PENALTY_FACTOR, "touch_margin": TOUCH_MARGIN,
                  "element": "C3D10", "cuts": "cyclic equations, one pitch",
                  "solver": CONTACT_SOLVER, "pose": "hub meshed turned to first touch",
                  "contact_change_tolerance": CONTACT_CHANGE_TOLERANCE})


def load_curve(res, T: float, teeth: int, meshed_at_rad: float) -> list[tuple[float, float]]:
    """``(torque_Nm, windup_rad)`` at the end of step 1 (its reaction moment) and at every
    increment of step 2 (time 1 + share of ``T``); the wind-up from the unturned pose, of a
    pair meshed turned by ``meshed_at_rad``."""
    rows = {t: r for k, name, t, r in res.blocks if k == "displacements" and name == "ROTN"}
    forces = {t: r for k, name, t, r in res.blocks if k == "forces" and name == "ROTN"}
    out = []
    for t in sorted(t for t in rows if t >= 1.0):  # the end of step 1, then step 2
        torque = (-float(forces[t][0, 3]) * teeth * 1e-3 if t <= 1.0 and t in forces
                  else T * (t - 1.0))
        out.append((torque, meshed_at_rad - float(rows[t][0, 3])))
    return out


def frd_nodal(text: str, block: str) -> dict[int, NDArray[np.float64]]:
    """Node -> values of the last ``block`` (e.g. ``"CONTACT"``) of a ccx ``.frd`` text
    (fixed columns: ``-1``, node I10, values E12)."""
    found: dict[int, NDArray[np.float64]] = {}
    current: dict[int, NDArray[np.float64]] | None = None
    for line in text.splitlines():
        if line.startswith(" -4"):
            current = {} if line.split()[1] == block else None
        elif line.startswith(" -3") and current is not None:
            found, current = current, None
        elif line.startswith(" -1") and current is not None:
            vals = [float(line[i:i + 12]) for i in range(13, len(line.rstrip()), 12)]
            current[int(line[3:13])] = np.array(vals)
    return found


def patch_figures(spec: CouplingSpec, pair: VolumeMesh, pressure: dict, size: float
                  ) -> tuple[float, float, float, float]:
    """Peak and interior pressure (MPa), patch extent across the face and along the
    developed profile (mm) of the slave flank's nodal pressure ``node id -> CPRESS``.

    Interior: the mean over the nodes within half an element ``size`` of the patch's centre
    line across the face (its load-weighted ``z``) and at least a tenth of the active depth
    from the ends of the depth both flanks share (the surface model's interior distance).
    Quadratic elements' nodal contact pressures alternate between corner and mid-side nodes;
    the mean along the centre line smooths that out (it still moves with the mesh: docs/fea.md),
    the peak grows with refinement at the depth ends."""
    rb = spec.tooth.base_radius
    hub, sleeve = pair.node_set("H_T0_FLANK_CCW"), pair.node_set("S_T0_FLANK_CCW")
    r_of = np.hypot(pair.nodes[:, 0], pair.nodes[:, 1])
    s_lo, s_hi = developed_arc(np.array([max(r_of[hub].min(), r_of[sleeve].min()),
                                        min(r_of[hub].max(), r_of[sleeve].max())]), rb)
    p = np.array([pressure.get(int(n) + 1, np.zeros(4))[3] for n in hub])
    s, z = developed_arc(r_of[hub], rb), pair.nodes[hub, 2]
    peak = float(p.max(initial=0.0))
    on = p > 1e-3 * peak
    if not on.any():
        return 0.0, 0.0, 0.0, 0.0
    d = 0.1 * (s_hi - s_lo)
    z_c = float(np.sum(p * z) / np.sum(p))
    line = (np.abs(z - z_c) <= 0.5 * size) & (s >= s_lo + d) & (s <= s_hi - d)
    interior = float(np.mean(p[line])) if line.any() else peak
    return peak, interior, float(np.ptp(z[on])), float(np.ptp(s[on]))
