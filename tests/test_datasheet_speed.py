"""Issue 42's data-sheet work: the wind-up curve's placed points, the warm start of a pose
next to a solved one (the matrix's shifted poses), and the allowable misalignment's search
without the top of the range where a known capacity brackets it."""

from __future__ import annotations

import numpy as np
import pytest

import gearcoupling as gc
from gearcoupling.loading import load_from_sweep
from gearcoupling.loading.models.surface import start_from
from gearcoupling.rotordynamics.allowable import capacity_limit_deg
from gearcoupling.rotordynamics.stiffness import pitch_rotations
from gearcoupling.rotordynamics.torsion import DEFAULT_POINTS, windup_torques


def _interpolation_error(torques, law, dense):
    """Largest gap between ``law`` drawn straight through ``torques`` and ``law`` itself
    at ``dense``, over its value at the end."""
    return float(np.max(np.abs(np.interp(dense, torques, law(torques)) - law(dense))
                        / law(dense[-1])))


def test_the_curves_default_points_draw_a_contact_law_closer_than_eleven_even_ones():
    """The default torques lie at (i / (n - 1))^2 of the end, the operating torque among
    them, signed like it; drawn straight through them, a wind-up law like the contact's
    (chi ~ T^0.8, steepest at zero) is closer than through 11 evenly placed torques."""
    T, cap = -700.0, 2000.0
    grid = windup_torques(T, cap)
    share = np.linspace(0.0, 1.0, DEFAULT_POINTS) ** 2
    assert np.allclose(np.sort(np.abs(grid)), np.unique(np.append(share * cap, 700.0)),
                       rtol=0, atol=1e-9)
    assert np.all(grid <= 0)
    dense = np.linspace(0.0, cap, 4001)

    def law(t):
        return np.abs(t) ** 0.8

    placed = _interpolation_error(np.sort(np.abs(grid)), law, dense)
    even = _interpolation_error(np.linspace(0.0, cap, 11), law, dense)
    assert DEFAULT_POINTS <= 6 and placed < even


@pytest.fixture(scope="module")
def renzo():
    return gc.load_spec("renzo-1967")


def test_a_pose_started_from_its_neighbour_gives_the_cold_answer(renzo):
    """A load on a one-rotation sweep started from the pose solved at that rotation of
    another sweep (the matrix's shifted poses) agrees with the same load solved cold, to
    the contact solver's tolerance; a sweep that kept no such pose gives no start."""
    T = renzo.load.torque_Nm
    sw = gc.sweep(renzo, 1.0, pitch_rotations(renzo, 3))
    load_from_sweep(sw, torque_Nm=T, model="surface")
    psi = [float(sw.angles_deg[1])]
    warm_sweep, cold_sweep = gc.sweep(renzo, 1.0, psi), gc.sweep(renzo, 1.0, psi)
    assert start_from(warm_sweep, sw, 1, "ccw")
    assert not start_from(cold_sweep, gc.sweep(renzo, 1.0, psi), 0, "ccw")
    offsets = np.linspace(0.0, 2e-6, renzo.tooth.teeth)  # a shifted pose: gaps moved
    warm = load_from_sweep(warm_sweep, torque_Nm=T, model="surface", gap_offset_rad=offsets)
    cold = load_from_sweep(cold_sweep, torque_Nm=T, model="surface", gap_offset_rad=offsets)
    scale = float(np.max(cold.normal_force_N))
    assert np.max(np.abs(warm.normal_force_N - cold.normal_force_N)) <= 1e-4 * scale
    assert warm.windup_rad == pytest.approx(cold.windup_rad, rel=1e-6)


def test_a_known_capacity_below_the_torque_spares_the_top_of_the_range(renzo):
    """With a known capacity below the torque (the operating point's, as the data sheet
    has it) the search solves no capacity at the top of the range: as many capacities as
    with the top's capacity known too, and the same angle."""
    model, T = "compliance", renzo.load.torque_Nm
    here = gc.capacity(renzo, 1.0, model=model)
    top = gc.critical_misalignment_deg(renzo) or 6.0
    assert here.capacity_Nm < T  # renzo-1967 does not carry its torque at 1°
    counts, found = [], []
    for known in ([here], [here, gc.capacity(renzo, top, model=model)]):
        steps: list[int] = []
        found.append(capacity_limit_deg(renzo, T, top, model=model, known=known,
                                        step=lambda steps=steps: steps.append(1)))
        counts.append(len(steps))
    assert counts[0] == counts[1] and found[0] == found[1]
    assert found[0][0] is not None and 0.0 < found[0][0] < 1.0
