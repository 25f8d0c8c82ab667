"""CLI commands; each module has ``register(subparsers)``. Add new commands to COMMANDS."""

from . import (
    charts,
    check,
    compare,
    fea,
    generate,
    hob,
    run,
    sections,
    spec,
    stiffness,
    study,
    sweep,
    templates,
    view,
)

COMMANDS = [spec, sections, run, templates, check, view, generate, sweep,
            fea, stiffness, study, hob, charts, compare]
