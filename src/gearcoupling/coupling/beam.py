"""Lateral bending of the floating member: an Euler-Bernoulli beam of finite elements
(cubic Hermite, two degrees of freedom a node: deflection and slope), pinned where the
gear meshes hold it, and its first natural frequency.

Units: SI inside (m, kg, N). The member is a chain of segments, each of constant bending
stiffness ``E I`` and mass per length; point masses (kg) sit at nodes. The closed form of a
uniform pinned-pinned beam, ``f1 = pi / (2 L²) sqrt(E I / (rho A))``
(:func:`pinned_pinned_Hz`), is what the elements converge to on one segment.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ArgumentError

MIN_ELEMENTS = 40  # over the whole beam; every segment gets at least two


@dataclass(frozen=True)
class Segment:
    """A length of constant section: from ``z0_m`` to ``z1_m``, bending stiffness
    ``EI_Nm2`` (N·m²) and mass per length ``mass_kg_per_m``."""

    z0_m: float
    z1_m: float
    EI_Nm2: float
    mass_kg_per_m: float


def _element(length: float, EI: float, m: float) -> tuple[NDArray, NDArray]:
    """Stiffness and consistent mass ``(4, 4)`` of one element (w1, t1, w2, t2)."""
    L = length
    LL = L * L
    k = EI / L**3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * LL, -6 * L, 2 * LL],
                              [-12, -6 * L, 12, -6 * L], [6 * L, 2 * LL, -6 * L, 4 * LL]])
    mm = m * L / 420 * np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * LL, 13 * L, -3 * LL],
                                 [54, 13 * L, 156, -22 * L], [-13 * L, -3 * LL, -22 * L, 4 * LL]])
    return k, mm


def beam_frequencies_Hz(segments: list[Segment], supports_m: ArrayLike, *,
                        point_masses: ArrayLike = (), modes: int = 1,
                        elements: int = MIN_ELEMENTS) -> NDArray[np.float64]:
    """The lowest ``modes`` bending frequencies (Hz) of a chain of ``segments`` (contiguous,
    increasing ``z``) pinned at the positions ``supports_m``, with ``point_masses``
    ``(z_m, kg)``; ``elements`` over the whole length (every segment, split at the supports
    and masses, gets at least two)."""
    from scipy.linalg import eigh  # at the call: importing the package stays light

    if not segments or any(s.z1_m <= s.z0_m or s.EI_Nm2 <= 0 or s.mass_kg_per_m < 0
                           for s in segments):
        raise ArgumentError("segments", len(segments), "contiguous lengths with EI > 0 and "
                            "mass >= 0")
    masses = np.reshape(np.asarray(point_masses, float), (-1, 2))
    supports = np.atleast_1d(np.asarray(supports_m, float))
    cuts = np.concatenate([supports, masses[:, 0]])
    total = segments[-1].z1_m - segments[0].z0_m
    z_nodes, props = [segments[0].z0_m], []
    for s in segments:
        inner = np.sort(cuts[(cuts > s.z0_m) & (cuts < s.z1_m)])
        for a, b in zip([s.z0_m, *inner], [*inner, s.z1_m], strict=True):
            n = max(2, math.ceil(elements * (b - a) / total))
            for z in np.linspace(a, b, n + 1)[1:]:
                props.append((z - z_nodes[-1], s.EI_Nm2, s.mass_kg_per_m))
                z_nodes.append(float(z))
    nodes = np.array(z_nodes)
    K = np.zeros((2 * nodes.size, 2 * nodes.size))
    M = np.zeros_like(K)
    for e, (L, EI, m) in enumerate(props):
        k, mm = _element(L, EI, m)
        K[2 * e:2 * e + 4, 2 * e:2 * e + 4] += k
        M[2 * e:2 * e + 4, 2 * e:2 * e + 4] += mm
    for z, mass in masses:
        M[2 * _node(nodes, z), 2 * _node(nodes, z)] += mass
    held = {2 * _node(nodes, z) for z in supports}
    free = [i for i in range(K.shape[0]) if i not in held]
    w2 = eigh(K[np.ix_(free, free)], M[np.ix_(free, free)], eigvals_only=True,
              subset_by_index=[0, modes - 1])
    return np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi)


def _node(nodes: NDArray, z: float) -> int:
    i = int(np.argmin(np.abs(nodes - z)))
    if abs(nodes[i] - z) > 1e-9 * max(1.0, abs(z)):
        raise ArgumentError("supports_m", z, "positions on the beam (m)")
    return i


def pinned_pinned_Hz(length_m: float, EI_Nm2: float, mass_kg_per_m: float) -> float:
    """First bending frequency of a uniform pinned-pinned Euler-Bernoulli beam (Hz)."""
    return math.pi / (2.0 * length_m**2) * math.sqrt(EI_Nm2 / mass_kg_per_m)


def annulus_EI_Nm2(inner_mm: float, outer_mm: float, youngs_modulus_MPa: float) -> float:
    """``E I`` of an annular section (N·m²): ``I = pi (R^4 - r^4) / 4``."""
    return youngs_modulus_MPa * 1e6 * math.pi * (outer_mm**4 - inner_mm**4) / 4.0 * 1e-12


__all__ = ["Segment", "annulus_EI_Nm2", "beam_frequencies_Hz", "pinned_pinned_Hz"]
