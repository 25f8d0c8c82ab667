"""Seeded random specs over the documented range, stratified by crown kind, generation and
tip (used by ``tests/test_random_specs.py`` and ``benchmarks/bench_random_specs.py``; the
proportion specs ``springs-<i>-<crown>`` by ``benchmarks/bench_springs.py`` and
``benchmarks/bench_fea_contact.py``).

The documented range: 6-300 teeth, module 0.2-60 mm (log-uniform), pressure angle
14.5-30°, misalignment 0-6°. Face width, backlash and crown are drawn in proportions a
designer would use (face 4-20 modules, at most R/2; crown radius 0.7-1.5 R with a
spherical tip, 0.5-5 R with a cylindrical one, whose crown need not follow a sphere);
everything else is left to the defaults, which must then always validate.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

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


def random_proportions_data(rng: np.random.Generator) -> dict:
    """Spec data (mm, degrees) of a random coupling whose tooth proportions, fillets, rim
    and bore are drawn too (the tooth-spring data set: ``benchmarks/bench_springs.py``):
    6-300 teeth and module 0.2-60 mm log-uniform, pressure angle 14.5-30°, face 4-20
    modules (at most R/2), hub dedendum 1.1-1.35 m, hub and sleeve root fillets 0.15-0.38 m
    (at least the FE mesh's module / 8), hub rim under the root and sleeve ring over it
    2-8 m, a circular, Vari-Crown, End Round or no crown; the rest the defaults."""
    teeth = round(math.exp(rng.uniform(math.log(6), math.log(300))))
    module = float(np.exp(rng.uniform(math.log(0.2), math.log(60.0))))
    R = 0.5 * module * teeth
    face = min(float(rng.uniform(4.0, 20.0)) * module, 0.5 * R)
    kind = str(rng.choice(["circular", "circular", "vari_crown", "end_round", "none"]))
    rc = R * float(rng.uniform(0.5, 3.0))
    crown: dict = {"kind": kind}
    if kind == "circular":
        crown["radius"] = rc
    elif kind == "vari_crown":
        crown.update(radius=rc, end_radius=rc * float(rng.uniform(1.1, 3.0)))
    elif kind == "end_round":
        crown.update(radius=rc, end_radius=rc * float(rng.uniform(0.3, 0.9)),
                     start_z=float(rng.uniform(0.2, 0.8)) * 0.5 * face)
    dedendum = float(rng.uniform(1.1, 1.35)) * module
    hub_rim = float(rng.uniform(2.0, 8.0)) * module
    sleeve_ring = float(rng.uniform(2.0, 8.0)) * module
    root_dia = 2.0 * (R - dedendum)
    return {
        "name": f"springs-{kind}",
        "tooth": {"teeth": teeth, "module": module,
                  "pressure_angle_deg": float(rng.uniform(14.5, 30.0))},
        "hub": {"face_width": face, "backlash": float(rng.uniform(0.02, 0.2)) * module,
                "crowning": crown,
                "root": {"dedendum": dedendum,
                         "fillet_radius": float(rng.uniform(0.15, 0.38)) * module},
                "body": {"bore_diameter": max(0.0, root_dia - 2.0 * hub_rim)}},
        "sleeve": {"root_fillet_radius": float(rng.uniform(0.15, 0.38)) * module},
        "sleeve_ring_mm": sleeve_ring,
    }


def proportions_spec(rng: np.random.Generator, tries: int = 50):
    """A valid spec of :func:`random_proportions_data`, its sleeve ring set over the major
    diameter. Where the spec or its FE mesh size refuses the draw, the drawn proportions
    fall back to the defaults one by one (few teeth undercut a deep dedendum), then the
    whole spec is drawn again."""
    import gearcoupling as gc
    from gearcoupling.errors import GearCouplingError
    from gearcoupling.fea.mesh import check_size

    fallbacks = (("hub", "root", "dedendum"), ("hub", "root", "fillet_radius"),
                 ("sleeve", "root_fillet_radius"), ("hub", "body", "bore_diameter"))
    for _ in range(tries):
        data = random_proportions_data(rng)
        ring = data.pop("sleeve_ring_mm")
        for drop in (None, *fallbacks):
            if drop is not None:
                table = data
                for key in drop[:-1]:
                    table = table[key]
                table.pop(drop[-1], None)
            data["sleeve"].pop("outer_diameter", None)
            try:
                spec = gc.spec_from_dict(data, name=data["name"])
                data["sleeve"]["outer_diameter"] = spec.sleeve.major_diameter + 2.0 * ring
                spec = gc.spec_from_dict(data, name=data["name"])
                for part in ("hub", "sleeve"):
                    check_size(spec, part, None)
                gc.sweep(spec, 0.0, [0.0])
            except GearCouplingError:
                continue
            return spec
    raise RuntimeError("no valid spec drawn")


SPRINGS_SEED = 2026  # the seed of bench_springs.py's data set


def springs_specs(count: int, seed: int = SPRINGS_SEED) -> list:
    """The first ``count`` specs of :func:`proportions_spec` drawn with ``seed``, named
    ``springs-<i>-<crown kind>`` (the random specs of ``benchmarks/bench_springs.py``)."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(count):
        s = proportions_spec(rng)
        out.append(replace(s, name=f"springs-{i:02d}-{s.hub.crowning.kind}"))
    return out


def springs_spec(name: str, seed: int = SPRINGS_SEED):
    """The spec of :func:`springs_specs` named ``name`` (``springs-<i>-<crown kind>``)."""
    parts = name.split("-")
    if len(parts) != 3 or parts[0] != "springs" or not parts[1].isdigit():
        raise ValueError(f"{name!r}: not a name springs-<i>-<crown kind>")
    spec = springs_specs(int(parts[1]) + 1, seed)[-1]
    if spec.name != name:
        raise ValueError(f"{name!r}: spec {parts[1]} of seed {seed} is {spec.name}")
    return spec
