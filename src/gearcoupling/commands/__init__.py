"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import (
    capacity,
    charts,
    check,
    compare,
    datasheet,
    fea,
    fea_contact,
    generate,
    hob,
    load,
    report,
    run,
    sections,
    spec,
    stiffness,
    study,
    sweep,
    templates,
    view,
)
from .common import CREATED, WRITING

COMMANDS = [
    spec,
    sections,
    run,
    templates,
    check,
    view,
    generate,
    sweep,
    load,
    capacity,
    datasheet,
    fea,
    fea_contact,
    stiffness,
    study,
    hob,
    charts,
    compare,
    report,
]

__all__ = ["COMMANDS", "CREATED", "WRITING"]
