"""Seeded random specs over the documented range, stratified by crown kind, generation and
tip (used by ``tests/test_random_specs.py`` and ``benchmarks/bench_random_specs.py``).

The documented range: 6-300 teeth, module 0.2-60 mm (log-uniform), pressure angle
14.5-30°, misalignment 0-6°. Face width, backlash and crown are drawn in proportions a
designer would use (face 4-20 modules, at most R/2; crown radius 0.7-1.5 R with a
spherical tip, 0.5-5 R with a cylindrical one, whose crown need not follow a sphere);
everything else is left to the defaults, which must then always validate.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

KINDS = ("none", "circular", "vari_crown", "end_round", "table")
GENERATIONS = ("enveloped", "revolved")
TIPS = ("sphere", "cylinder")
STRATA = tuple(itertools.product(KINDS, GENERATIONS, TIPS))


def random_spec_data(rng: np.random.Generator, kind: str, generation: str, tip: str) -> dict:
    """Spec data (mm, degrees) of one random coupling of the given stratum."""
    teeth = int(rng.integers(6, 301))
    module = float(np.exp(rng.uniform(math.log(0.2), math.log(60.0))))
    R = 0.5 * module * teeth
    face = min(float(rng.uniform(4.0, 20.0)) * module, 0.5 * R)
    rc = R * float(rng.uniform(0.7, 1.5) if tip == "sphere" else rng.uniform(0.5, 5.0))
    crown: dict = {"kind": kind, "generation": generation}
    if kind == "circular":
        crown["radius"] = rc
    elif kind == "vari_crown":
        crown.update(radius=rc, end_radius=rc * float(rng.uniform(1.1, 4.0)))
    elif kind == "end_round":
        crown.update(radius=rc, end_radius=rc * float(rng.uniform(0.3, 0.9)),
                     start_z=float(rng.uniform(0.0, 0.8)) * 0.5 * face)
    elif kind == "table":  # a drop like a circular crown's, scaled, sampled 3-6 times
        z = np.linspace(0.0, 0.5 * face, int(rng.integers(3, 7)))
        crown.update(z=z.tolist(), drop=(float(rng.uniform(0.5, 1.5)) * z**2 / (2 * rc)).tolist())
    return {
        "name": f"random-{kind}-{generation}-{tip}",
        "design_misalignment_deg": float(rng.choice([0.0, 0.25, 1.0, 3.0, 6.0])),
        "tooth": {"teeth": teeth, "module": module,
                  "pressure_angle_deg": float(rng.uniform(14.5, 30.0))},
        "hub": {"face_width": face, "backlash": float(rng.uniform(0.0, 0.3)) * module,
                "tip": {"kind": tip}, "crowning": crown},
    }
