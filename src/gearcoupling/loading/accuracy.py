"""What the accuracy ladder (docs/load.md, "Accuracy ladder") measured for each load model
and tooth spring: the one table that load summaries, the report and the data sheet quote.

Two measurements: the wind-up against the CalculiX contact reference (aligned, each
spec's torque and half of it, bodies included; renzo-1967, industrial-m2, mill-spindle
and the random springs-24-circular over three meshes, the random springs-12-end_round the
finer of two; industrial-m2, mill-spindle and springs-24-circular solved with the deck
meshed at first touch, renzo-1967 and springs-12-end_round with the previous one, within
0.25 % of it there; ``python benchmarks/bench_fea_contact.py --from-golden``), and the
most loaded tooth against a CalculiX sector at 1° and 2° at equal wind-up (renzo-1967,
industrial-m2, and springs-24-circular at 2°; FE / model; ``python
benchmarks/bench_fea_sector.py``), for the FE springs with the bodies as the sector has
them (its cyclic cuts repeat its loads round the ring; ``python benchmarks/bench_bodies.py
--stored``, docs/load.md "The bodies"; the uniform body of the coupling's torque gave
0.67–1.00), both springs read held at 0.8 of the half face as the load models read them
(docs/load.md, "The face end").
A model and spring not on the ladder are named as such, never given a borrowed figure.
"""

from __future__ import annotations

from .models.registry import load_model

#: (model, springs) -> (lowest, highest) wind-up error in % against the CalculiX contact
#: reference (positive: the model is more compliant); springs ``template C`` is the
#: linear model with the spec's own ``mesh_stiffness``
WINDUP_ERROR_PCT: dict[tuple[str, str], tuple[float, float]] = {
    ("linear", "template C"): (-57.0, -54.0),
    ("linear", "fe-fit"): (15.0, 66.0),
    ("linear", "cantilever"): (19.0, 51.0),
    ("compliance", "cantilever"): (53.0, 82.0),
    ("surface", "cantilever"): (71.0, 108.0),
    ("compliance", "fe"): (-10.1, -0.4),
    ("surface", "fe"): (-7.0, 4.1),
    ("compliance", "fe-fit"): (-11.0, -0.4),
    ("surface", "fe-fit"): (-7.9, 4.0),
}

#: (model, springs) -> (lowest, highest) CalculiX-sector / model load on the most loaded
#: teeth at 1° and 2° (below 1: the model carries more than the sector); the ``fe`` and
#: ``fe-fit`` rows with the sector's own bodies, the others with the uniform body
TOOTH_LOAD_RATIO: dict[tuple[str, str], tuple[float, float]] = {
    ("linear", "template C"): (0.18, 0.27),
    ("linear", "cantilever"): (1.23, 1.24),
    ("compliance", "cantilever"): (1.53, 1.57),
    ("surface", "cantilever"): (1.69, 1.78),
    ("compliance", "fe"): (0.80, 1.00),
    ("surface", "fe"): (0.89, 1.00),
    ("compliance", "fe-fit"): (0.80, 1.00),
    ("surface", "fe-fit"): (0.89, 1.00),
}


def springs_name(spec, model: str) -> str:
    """The tooth springs a model used: ``template C`` for a model that takes the spec's
    ``mesh_stiffness`` where it is set (the linear model), else the spec's ``[load] stiffness``."""
    if load_model(model).takes_mesh_stiffness and spec.load.mesh_stiffness_N_per_mm is not None:
        return "template C"
    return str(spec.load.stiffness)


def windup_error(model: str, spring: str) -> str:
    """The ladder's aligned wind-up error of a model and spring, as a sentence."""
    band = WINDUP_ERROR_PCT.get((model, spring))
    if band is None:
        return (f"the {model} model with {spring} springs is not on the accuracy ladder "
                "(docs/load.md): no measured error")
    lo, hi = band
    return (f"{model} model, {spring} springs: wind-up {lo:+.1f} to {hi:+.1f} % against the "
            "CalculiX contact reference (aligned; positive = too compliant, so stiffnesses "
            "are low by about as much)")


def tooth_load_error(model: str, spring: str) -> str:
    """The ladder's misaligned tooth-load ratio of a model and spring, as a sentence."""
    band = TOOTH_LOAD_RATIO.get((model, spring))
    if band is None:
        return (f"the {model} model with {spring} springs has no misaligned measurement on "
                "the accuracy ladder (docs/load.md)")
    lo, hi = band
    return (f"{model} model, {spring} springs: the most loaded teeth carry {lo:.2f} to "
            f"{hi:.2f} times the model's load in a CalculiX sector at 1° and 2° (equal "
            "wind-up)")
