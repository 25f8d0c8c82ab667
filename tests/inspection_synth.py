"""Synthetic measured hubs with known errors, sampled on the exact flanks (test helper)."""

from __future__ import annotations

import math

import numpy as np

from gearcoupling.geometry.hub import form_radius, hub_flank_model, hub_model, tip_radius


def synthetic_hub(spec, per_flank=300, index_mm=None, thickness_mm=0.0, noise_mm=0.0,
                  teeth=None, seed=1):
    """Points on both flanks of every (or the given) tooth of the exact hub.

    ``index_mm[k]``: tooth k turned by this arc at the pitch circle toward increasing polar
    angle; ``thickness_mm``: tooth thickness change (arc at the pitch circle), applied as a
    normal offset ``thickness/2 * cos(phi)`` per flank (exact for an involute in the
    midplane); ``noise_mm``: isotropic Gaussian noise per coordinate.
    """
    m = hub_model(spec)
    rng = np.random.default_rng(seed)
    z = rng.uniform(-m.half_face, m.half_face, per_flank) * 0.98
    lo, hi = form_radius(m, z), tip_radius(m, z)
    r = lo + (hi - lo) * rng.uniform(0.02, 0.98, per_flank)
    out = []
    for flank in ("cw", "ccw"):
        p, n, _ = hub_flank_model(m, flank, z, r)
        p = p + 0.5 * thickness_mm * math.cos(m.phi) * n
        for k in range(m.teeth) if teeth is None else teeth:
            a = 2 * math.pi * k / m.teeth + (index_mm or {}).get(k, 0.0) / m.R
            c, s = math.cos(a), math.sin(a)
            out.append(p @ np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]))
    pts = np.concatenate(out)
    return pts + noise_mm * rng.standard_normal(pts.shape)


def random_placement(points, seed=3):
    """Random rotation and translation; returns the moved points and ``(R, t)``."""
    from scipy.spatial.transform import Rotation

    R = Rotation.random(random_state=seed).as_matrix()
    t = np.random.default_rng(seed).uniform(-50, 50, 3)
    return points @ R.T + t, R


def label_map(report, R_place, teeth):
    """Reported label of each original tooth, and whether the axis came out flipped."""
    Rc = report.registration.rotation @ R_place
    k = np.arange(teeth)
    a = 2 * np.pi * k / teeth
    d = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=-1) @ Rc.T
    labels = np.rint(np.arctan2(d[:, 1], d[:, 0]) * teeth / (2 * np.pi)).astype(int) % teeth
    return labels, bool(Rc[2, 2] < 0)
