"""Mass-elastic data of the whole coupling (docs/coupling.md, Data sheet): each half as
AGMA 9009 lumps it at its shaft end, the floating member, the torsional stiffness of the
chain of parts, the floating member's first lateral frequency, each mesh's 6 x 6 under
load, and the pieces of a ROSS train.

Mass properties in the aligned coupling frame (origin ``O_A``, ``z`` along the axis, hub
B's midplane at the span): the hubs and sleeve rings from their closed part meshes
(:func:`gearcoupling.rotordynamics.mass_properties`), the flanges, spacer and one-piece
tube in closed form (annuli). Half A is hub A with the floating parts on A's side of the
coupling's centre plane (the spacer or tube cut there), half B the rest: for a symmetric
coupling each half is its hub plus half the floating member. The floating parts take the
sleeve's material (spec A's ``[material.sleeve]``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..errors import ArgumentError
from ..loading import (
    annulus_twist_rad,
    body_windup_rad,
    load,
    resolve_model,
    resolve_torque_Nm,
)
from ..rotordynamics import (
    MassProperties,
    StiffnessMatrix,
    check_inputs,
    combine,
    default_rotations,
    mass_properties,
    pitch_rotations,
    stiffness_matrix,
    windup_beyond_touch,
)
from ..spec import CouplingSpec
from .beam import Segment, annulus_EI_Nm2, beam_frequencies_Hz, pinned_pinned_Hz
from .geometry import Annulus, CouplingGeometry, coupling_geometry
from .layout import CouplingLayout, ShaftAlignment
from .loads import mesh_torque_Nm
from .ross import RossPieces, ross_pieces

MM_TO_M = 1e-3


def annulus_mass(part: Annulus, density_kg_per_m3: float,
                 name: str | None = None) -> MassProperties:
    """Closed-form mass properties of an annulus along the axis (aligned coupling frame)."""
    a, b, L = part.inner_mm, part.outer_mm, part.length_mm
    volume = math.pi * (b * b - a * a) * L
    m = density_kg_per_m3 * volume * 1e-9
    polar = 0.5 * m * (a * a + b * b) * 1e-6
    across = m * (3.0 * (a * a + b * b) + L * L) / 12.0 * 1e-6
    return MassProperties(name or part.name, m, np.array([0.0, 0.0, 0.5 * (part.z0_mm +
                                                                          part.z1_mm)]),
                          np.diag([across, across, polar]), volume)


def moved(mp: MassProperties, dz_mm: float, name: str) -> MassProperties:
    """``mp`` moved ``dz_mm`` along the axis and renamed."""
    return replace(mp, name=name, centre_of_gravity_mm=mp.centre_of_gravity_mm
                   + np.array([0.0, 0.0, dz_mm]))


def part_masses(geom: CouplingGeometry, tolerance_mm: float | None = None
                ) -> dict[str, MassProperties]:
    """Every part's mass properties in the aligned coupling frame, from A to B."""
    rho = geom.spec_a.material.sleeve.mass_density_kg_per_m3()
    a = mass_properties(geom.spec_a, tolerance_mm)
    b = a if geom.spec_b is geom.spec_a else mass_properties(geom.spec_b, tolerance_mm)
    S = geom.span_mm
    out = {"hub A": moved(a["hub"], 0.0, "hub A"), "sleeve A": moved(a["sleeve"], 0.0,
                                                                       "sleeve A")}
    out.update({p.name: annulus_mass(p, rho) for p in geom.annuli})
    out["sleeve B"] = moved(b["sleeve"], S, "sleeve B")
    out["hub B"] = moved(b["hub"], S, "hub B")
    return out


def split_masses(geom: CouplingGeometry, parts: dict[str, MassProperties]
                 ) -> dict[str, MassProperties]:
    """``{"A", "B", "floating", "coupling"}``: the halves (module docstring), the floating
    member and the whole."""
    rho = geom.spec_a.material.sleeve.mass_density_kg_per_m3()
    centre = 0.5 * geom.span_mm
    sides: dict[str, list[MassProperties]] = {"A": [parts["hub A"], parts["sleeve A"]],
                                              "B": [parts["hub B"], parts["sleeve B"]]}
    for p in geom.annuli:
        for side, piece in (("A", p.below(centre, f"{p.name} A")),
                            ("B", p.above(centre, f"{p.name} B"))):
            if piece is not None:
                sides[side].append(annulus_mass(piece, rho))
    floating = [v for k, v in parts.items() if not k.startswith("hub")]
    return {"A": combine(sides["A"], "half A"), "B": combine(sides["B"], "half B"),
            "floating": combine(floating, "floating member"),
            "coupling": combine(list(parts.values()), "coupling")}


@dataclass(frozen=True, eq=False)
class WholeTorsion:
    """The coupling's torsion: its parts in series, shaft A's bore to shaft B's.

    ``secant_rad_per_Nm`` and ``tangent_rad_per_Nm`` hold each part's compliance (rad per
    N·m) from A to B: the meshes' from the load model (the wind-up beyond first touch over
    the torque, and ``d chi / d T``, each the mean over one pitch), the hub bodies' and
    sleeve rings' annulus torsion (:func:`gearcoupling.body_windup_rad`), the flanges'
    (annular disks from the sleeve ring to where the torque leaves them: the spacer's
    mean radius, or halfway between the sleeve and flange outside diameters where they
    are bolted together) and the spacer's or tube's ``L / (G J)``, ``J = pi (D^4 -
    d^4) / 32``; the bodies are linear, so their tangent is their secant.
    """

    torque_Nm: float
    secant_rad_per_Nm: dict[str, float]
    tangent_rad_per_Nm: dict[str, float]

    @property
    def secant_Nm_per_rad(self) -> float:
        return 1.0 / sum(self.secant_rad_per_Nm.values())

    @property
    def tangent_Nm_per_rad(self) -> float:
        return 1.0 / sum(self.tangent_rad_per_Nm.values())

    def side_Nm_per_rad(self, mesh: str, tangent: bool = True) -> float:
        """The stiffness of the parts on one side of the spacer or tube: a ROSS coupling
        element's torsion (hub body, mesh, sleeve ring and flange of ``mesh``)."""
        parts = self.tangent_rad_per_Nm if tangent else self.secant_rad_per_Nm
        return 1.0 / sum(v for k, v in parts.items() if k.split()[-1] == mesh)

    def summary(self) -> dict[str, Any]:
        return {"torque_Nm": self.torque_Nm, "secant_Nm_per_rad": self.secant_Nm_per_rad,
                "tangent_Nm_per_rad": self.tangent_Nm_per_rad,
                "secant_compliance_rad_per_Nm": dict(self.secant_rad_per_Nm),
                "tangent_compliance_rad_per_Nm": dict(self.tangent_rad_per_Nm)}


def tube_compliance_rad_per_Nm(inner_mm: float, outer_mm: float, length_mm: float,
                               shear_modulus_MPa: float) -> float:
    """``L / (G J)`` of a tube (rad per N·m), ``J = pi (D^4 - d^4) / 32``."""
    J = math.pi * ((2 * outer_mm) ** 4 - (2 * inner_mm) ** 4) / 32.0  # mm^4
    return length_mm / (shear_modulus_MPa * J) * 1e3


def whole_torsion(geom: CouplingGeometry, torque_Nm: float, *, model: str,
                  rotations: int | None = None) -> WholeTorsion:
    """:class:`WholeTorsion` at ``torque_Nm`` (signed, not zero)."""
    T = abs(float(torque_Nm))
    G = geom.spec_a.material.sleeve.shear_modulus_MPa
    mesh: dict[str, tuple[float, float]] = {}
    for m in geom.meshes:
        spec = geom.spec(m)
        psi = pitch_rotations(spec, default_rotations(model) if rotations is None
                              else rotations)
        res = load(spec, geom.misalignment_deg(m), psi,
                   torque_Nm=mesh_torque_Nm(m, float(torque_Nm)), model=model)
        mesh[m] = (abs(windup_beyond_touch(res)) / T,
                   float(np.mean(1.0 / np.asarray(res.mesh_stiffness_Nm_per_rad))))
    bodies = {m: body_windup_rad(geom.spec(m), T) for m in geom.meshes}
    linear: dict[str, float] = {}
    for m in geom.meshes:
        linear[f"hub body {m}"] = bodies[m]["hub_rad"] / T
        linear[f"sleeve ring {m}"] = bodies[m]["sleeve_rad"] / T
    for p in geom.annuli:
        linear[p.name] = (_flange_compliance(geom, p, G) if p.name.startswith("flange")
                          else tube_compliance_rad_per_Nm(p.inner_mm, p.outer_mm,
                                                          p.length_mm, G))
    order = ["mesh A", "hub body A", "sleeve ring A", "flange A", "spacer", "tube",
             "flange B", "sleeve ring B", "hub body B", "mesh B"]
    secant = {**{f"mesh {m}": v[0] for m, v in mesh.items()}, **linear}
    tangent = {**{f"mesh {m}": v[1] for m, v in mesh.items()}, **linear}
    return WholeTorsion(float(torque_Nm), {k: secant[k] for k in order if k in secant},
                        {k: tangent[k] for k in order if k in tangent})


def _flange_compliance(geom: CouplingGeometry, flange: Annulus, G: float) -> float:
    """An annular disk's twist per torque from the sleeve ring's outside radius to where
    the torque leaves it (:class:`WholeTorsion`)."""
    spec = geom.spec(flange.name[-1])
    a = 0.5 * spec.sleeve.outer_diameter
    spacer = [p for p in geom.annuli if p.name == "spacer"]
    b = (0.5 * (spacer[0].inner_mm + spacer[0].outer_mm) if spacer else
         0.5 * (a + flange.outer_mm))
    inner, outer = min(a, b), max(a, b)
    return annulus_twist_rad(1e3, inner, outer, flange.length_mm, G) if outer > inner else 0.0


def floating_segments(geom: CouplingGeometry, parts: dict[str, MassProperties]
                      ) -> list[Segment]:
    """The floating member as beam segments from ring A's outboard face to ring B's (SI):
    each sleeve ring with its mass spread over its face width and the bending stiffness of
    its rim (major to outside diameter; the teeth add mass, not stiffness), then the
    flanges and the spacer or tube."""
    E = geom.spec_a.material.sleeve.youngs_modulus_MPa
    rings = []
    for m, z in (("A", 0.0), ("B", geom.span_mm)):
        s = geom.spec(m).sleeve
        rings.append(Annulus(f"sleeve {m}", 0.5 * s.major_diameter, 0.5 * s.outer_diameter,
                             z - 0.5 * s.face_width, z + 0.5 * s.face_width))
    out = []
    for p in [rings[0], *geom.annuli, rings[1]]:
        if p.name.startswith("sleeve"):
            mass_per_m = parts[p.name].mass_kg / (p.length_mm * MM_TO_M)
        else:
            mass_per_m = annulus_mass(p, geom.spec_a.material.sleeve.mass_density_kg_per_m3()
                                      ).mass_kg / (p.length_mm * MM_TO_M)
        out.append(Segment(p.z0_mm * MM_TO_M, p.z1_mm * MM_TO_M,
                           annulus_EI_Nm2(p.inner_mm, p.outer_mm, E), mass_per_m))
    return out


def lateral_frequency_Hz(geom: CouplingGeometry, parts: dict[str, MassProperties]) -> float:
    """The floating member's first bending frequency, pinned at the two mesh centres
    (API 671's check of a spacer), by finite elements (:mod:`.beam`)."""
    return float(beam_frequencies_Hz(floating_segments(geom, parts),
                                     [0.0, geom.span_mm * MM_TO_M])[0])


def spacer_formula_Hz(geom: CouplingGeometry) -> float | None:
    """The spacer's (or tube's) pinned-pinned frequency alone over the span, Euler-Bernoulli
    closed form: the hand check beside :func:`lateral_frequency_Hz`; None without one."""
    tubes = [p for p in geom.annuli if p.name in ("spacer", "tube")]
    if not tubes:
        return None
    p = tubes[0]
    rho = geom.spec_a.material.sleeve.mass_density_kg_per_m3()
    EI = annulus_EI_Nm2(p.inner_mm, p.outer_mm, geom.spec_a.material.sleeve.youngs_modulus_MPa)
    area = math.pi * (p.outer_mm**2 - p.inner_mm**2) * 1e-6
    return pinned_pinned_Hz(geom.span_mm * MM_TO_M, EI, rho * area)


@dataclass(frozen=True, eq=False)
class WholeCouplingData:
    """The data sheet of the whole coupling (module docstring).

    Attributes
    ----------
    geometry : CouplingGeometry
    torque_Nm : float
    model : str
    parts : dict of str -> MassProperties
        Hub A, sleeve A, flanges, spacer or tube, sleeve B, hub B (aligned coupling frame).
    halves : dict of str -> MassProperties
        ``"A"``, ``"B"``: each half as AGMA 9009 lumps it at its shaft end.
    floating, whole : MassProperties
    torsion : WholeTorsion
    lateral_frequency_Hz : float
        The floating member pinned at the meshes (finite elements).
    spacer_formula_Hz : float or None
        The spacer or tube alone, Euler-Bernoulli closed form over the span.
    matrices : dict of str -> StiffnessMatrix
        Each mesh's 6 x 6 in its own mesh frame (``x`` its tilt axis); empty if not asked.
    seconds : float
    """

    geometry: CouplingGeometry = field(repr=False)
    torque_Nm: float
    model: str
    parts: dict[str, MassProperties] = field(repr=False)
    halves: dict[str, MassProperties] = field(repr=False)
    floating: MassProperties = field(repr=False)
    whole: MassProperties = field(repr=False)
    torsion: WholeTorsion = field(repr=False)
    lateral_frequency_Hz: float
    spacer_formula_Hz: float | None
    matrices: dict[str, StiffnessMatrix] = field(repr=False)
    seconds: float = 0.0

    def cg_from_shaft_end_mm(self, mesh: str) -> float:
        """Half ``mesh``'s centre of gravity from its hub's outboard face (the shaft end),
        into the coupling."""
        spec, cg = self.geometry.spec(mesh), float(self.halves[mesh].centre_of_gravity_mm[2])
        end = -0.5 * spec.hub.body.length if mesh == "A" else (
            self.geometry.span_mm + 0.5 * spec.hub.body.length)
        return cg - end if mesh == "A" else end - cg

    def summary(self) -> dict[str, Any]:
        """Plain data, units in the keys."""
        out: dict[str, Any] = {"torque_Nm": self.torque_Nm, "model": self.model,
                               **self.geometry.summary()}
        out["mass"] = {k: v.as_dict() for k, v in (*self.parts.items(),
                                                   *(("half " + k, v) for k, v in
                                                     self.halves.items()),
                                                   ("floating", self.floating),
                                                   ("coupling", self.whole))}
        for m in self.geometry.meshes:
            out["mass"]["half " + m]["cg_from_shaft_end_mm"] = self.cg_from_shaft_end_mm(m)
        out["torsion"] = self.torsion.summary()
        out["lateral_frequency_Hz"] = self.lateral_frequency_Hz
        out["spacer_formula_Hz"] = self.spacer_formula_Hz
        out["stiffness"] = {f"mesh_{m}": K.as_dict() for m, K in self.matrices.items()}
        out["seconds"] = self.seconds
        return out

    def to_ross(self, n: int = 0, *, held_torque: bool = False) -> RossPieces:
        """The pieces of a ROSS train (the ``rotordynamics`` extra), from element number
        ``n``: :class:`~.ross.RossPieces`."""
        return ross_pieces(self, n, held_torque=held_torque)


def default_alignment(geom: CouplingGeometry) -> ShaftAlignment:
    """The parallel offset that puts each mesh at spec A's design misalignment."""
    return ShaftAlignment(offset_mm=geom.span_mm * math.tan(geom.spec_a.design_misalignment))


def whole_coupling_data(spec: CouplingSpec, layout: CouplingLayout,
                        alignment: ShaftAlignment | None = None,
                        torque_Nm: float | None = None, *, model: str | None = None,
                        rotations: int | None = None, matrices: bool = True,
                        tolerance_mm: float | None = None) -> WholeCouplingData:
    """The whole coupling's data sheet (module docstring).

    Parameters
    ----------
    spec, layout : CouplingSpec, CouplingLayout
        Two engagements.
    alignment : ShaftAlignment, optional
        The operating alignment (the meshes' angles for the torsion and the matrices);
        default the offset that puts each mesh at the spec's design angle.
    torque_Nm : float, optional
        Signed, not zero; default the spec's ``[load]`` torque.
    model : str, optional
        Load model of the meshes; default the spec's.
    rotations : int, optional
        Rotations over one pitch of the meshes' torsion and matrices (accuracy knob).
    matrices : bool
        Each mesh's 6 x 6 (a ROSS train needs them; they cost most).
    tolerance_mm : float, optional
        Chordal tolerance of the hub and sleeve meshes (default module / 200).
    """
    t0 = time.perf_counter()
    probe = coupling_geometry(spec, layout, ShaftAlignment() if alignment is None else
                              alignment)
    if probe.layout.engagements != 2:
        raise ArgumentError("engagements", probe.layout.engagements, "2: one engagement's "
                            "data sheet is gc.coupling_data")
    geom = probe if alignment is not None else coupling_geometry(spec, layout,
                                                                 default_alignment(probe))
    T = resolve_torque_Nm(geom.spec_a, torque_Nm)
    for s in (geom.spec_a, geom.spec_b):
        check_inputs(s, T)
    model = resolve_model(geom.spec_a, model)
    parts = part_masses(geom, tolerance_mm)
    split = split_masses(geom, parts)
    torsion = whole_torsion(geom, T, model=model, rotations=rotations)
    K = ({m: stiffness_matrix(geom.spec(m), geom.misalignment_deg(m), mesh_torque_Nm(m, T),
                              model=model, rotations=rotations) for m in geom.meshes}
         if matrices else {})
    return WholeCouplingData(geom, T, model, parts, {"A": split["A"], "B": split["B"]},
                             split["floating"], split["coupling"], torsion,
                             lateral_frequency_Hz(geom, parts), spacer_formula_Hz(geom), K,
                             time.perf_counter() - t0)


__all__ = ["WholeCouplingData", "WholeTorsion", "annulus_mass", "default_alignment",
           "floating_segments", "lateral_frequency_Hz", "part_masses", "spacer_formula_Hz",
           "split_masses", "tube_compliance_rad_per_Nm", "whole_coupling_data",
           "whole_torsion"]
