"""Shared fixtures: templates and small helpers for the geometry tests."""

from __future__ import annotations

import numpy as np
import pytest

import gearcoupling as gc


@pytest.fixture(scope="session")
def renzo():
    return gc.load_spec("renzo-1967")


@pytest.fixture(scope="session", params=gc.template_names())
def template(request):
    return gc.load_spec(request.param)


def flank_grid(model, nz: int = 9, nr: int = 7, margin: float = 0.02):
    """(z, r) grid strictly inside the flank of a hub model: face, form radius and tip."""
    from gearcoupling.geometry.hub import form_radius, tip_radius

    z = np.linspace(-model.half_face, model.half_face, nz) * (1 - margin)
    lo, hi = form_radius(model, z), tip_radius(model, z)
    f = np.linspace(margin, 1 - margin, nr)
    r = lo[:, None] + (hi - lo)[:, None] * f[None, :]
    return np.broadcast_to(z[:, None], r.shape).copy(), r
