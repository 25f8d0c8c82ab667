"""The sweep's critical and binding angles per template, pinned .

The values and their source are in ``tests/golden/<template>.json`` under ``"sweep"``
(regenerate with ``python tests/golden_values.py --sweep`` after an intended change and
review the diff). Each angle is root-found to 1e-4°, so two correct runs may differ by
twice that.
"""

from __future__ import annotations

import json

import pytest

import gearcoupling as gc
from gearcoupling.clearance.design import binding_angle_deg, critical_misalignment_deg

from golden_values import GOLDEN, engagement_templates

NAMES = engagement_templates()


def _want(name: str) -> dict:
    return json.loads((GOLDEN / f"{name}.json").read_text())["sweep"]


@pytest.mark.parametrize("name", NAMES)
def test_critical_and_binding_angles_match_golden(name):
    want = _want(name)
    assert want["source"]
    spec = gc.load_spec(name)
    tol = 2 * want["tolerance_deg"]
    for key, fn in (("critical_misalignment_deg", critical_misalignment_deg),
                    ("binding_angle_deg", binding_angle_deg)):
        got = fn(spec)
        if want[key] is None:
            assert got is None, key
        else:
            assert got == pytest.approx(want[key], abs=tol), key
