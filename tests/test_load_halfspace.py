"""Half-space contact kernel against theory: Love, Hertz, the square-root edge singularity."""

import math

import numpy as np
import pytest

from gearcoupling.errors import ArgumentError
from gearcoupling.loading.kernels import halfspace
from gearcoupling.loading.kernels.halfspace import (
    composite_modulus,
    half_space,
    hertz_ellipse,
    influence,
    load_split,
    solve_contact,
)

E_STAR = composite_modulus(206000.0, 0.3, 206000.0, 0.3)


def test_composite_modulus_of_steel():
    assert E_STAR == pytest.approx(206000.0 / (2 * (1 - 0.09)), rel=1e-15)
    with pytest.raises(ArgumentError, match="poisson_ratio"):
        composite_modulus(2e5, 0.5, 2e5, 0.3)


def test_love_centre_of_square_cell():
    # Johnson eq. 3.25: centre of a square 2a x 2a: u = 8 a ln(1 + sqrt 2) p / (pi E*)
    a = 0.3
    u = influence(0.0, 0.0, 2 * a, 2 * a, E_STAR)
    assert float(u) == pytest.approx(8 * a * math.log(1 + math.sqrt(2)) / (math.pi * E_STAR),
                                     rel=1e-14)
    # far away the cell acts as a point load: u -> area / (pi E* rho)
    rho = 100.0
    far = influence(rho, 0.0, 2 * a, 2 * a, E_STAR)
    assert float(far) == pytest.approx(4 * a * a / (math.pi * E_STAR * rho), rel=1e-5)


def test_dc_fft_equals_direct_sum():
    hs = half_space((13, 9), 0.1, 0.17, E_STAR)
    p = np.random.default_rng(1).random((2, 13, 9))
    direct = hs.direct(p)
    assert np.max(np.abs(hs.displacement(p) - direct)) <= 1e-12 * np.max(np.abs(direct))


def _hertz_grid(n, W, rx, ry, span=2.5):
    h = hertz_ellipse(W, rx, ry, E_STAR)
    dx, dy = span * h["a_mm"] / n, span * h["b_mm"] / n
    x = (np.arange(n) - (n - 1) / 2) * dx
    y = (np.arange(n) - (n - 1) / 2) * dy
    gap = x[:, None] ** 2 / (2 * rx) + y[None, :] ** 2 / (2 * ry)
    return h, half_space((n, n), dx, dy, E_STAR), gap, x, y


def _semi_axis(p, coord):
    """Semi-axis from a least-squares fit of p^2 = p0^2 (1 - s^2/a^2) along the axis."""
    keep = p > 0.3 * p.max()
    slope, icpt = np.polyfit(coord[keep] ** 2, p[keep] ** 2, 1)
    return math.sqrt(-icpt / slope)


@pytest.mark.parametrize("ratio", [1.0, 2.0, 5.0, 10.0, 20.0])
def test_hertz_elliptic_contact_within_2_percent(ratio):
    """p_max and both semi-axes within 2 % of Hertz (curvature ratio 1-20) on a 65 x 65
    grid over 2.5 semi-axes; the error falls under refinement (33 -> 65 cells)."""
    W, ry = 200.0, 15.0
    errs = []
    for n in (33, 65):
        h, hs, gap, x, y = _hertz_grid(n, W, ratio * ry, ry)
        sol = solve_contact(hs, gap, load_N=W, tolerance=1e-10)
        p = sol.pressure_MPa
        c = n // 2
        a = _semi_axis(p[:, c], x)
        b = _semi_axis(p[c, :], y)
        err = max(abs(p.max() / h["p0_MPa"] - 1), abs(a / h["a_mm"] - 1),
                  abs(b / h["b_mm"] - 1))
        errs.append(err)
        assert sol.load_N.sum() == pytest.approx(W, rel=1e-12)
        assert sol.approach_mm == pytest.approx(h["delta_mm"], rel=0.02)
        assert np.all(sol.gap_mm >= -1e-6 * h["delta_mm"])
    assert errs[1] <= 0.02
    assert errs[1] < errs[0]


def test_given_approach_and_spring_agree_with_given_load():
    W = 150.0
    h, hs, gap, _, _ = _hertz_grid(41, W, 30.0, 10.0)
    by_load = solve_contact(hs, gap, load_N=W, tolerance=1e-11)
    by_approach = solve_contact(hs, gap, approach_mm=by_load.approach_mm, tolerance=1e-11)
    assert by_approach.load_N == pytest.approx(W, rel=1e-6)
    # a rigid spring c in series moves the approach by c W and leaves the pressure alone
    c = 2e-5
    spring = solve_contact(hs, gap, load_N=W, spring_mm_per_N=c, tolerance=1e-11)
    assert spring.approach_mm == pytest.approx(by_load.approach_mm + c * W, rel=1e-8)
    assert np.max(np.abs(spring.pressure_MPa - by_load.pressure_MPa)) <= 1e-6 * h["p0_MPa"]
    # two grids sharing one approach, one with the spring: loads split so approaches match
    both = solve_contact(hs, np.stack([gap, gap]), load_N=2 * W,
                         spring_mm_per_N=np.array([0.0, c]), tolerance=1e-11)
    free = solve_contact(hs, gap, approach_mm=both.approach_mm, tolerance=1e-11)
    sprung = solve_contact(hs, gap, approach_mm=both.approach_mm - c * both.load_N[1],
                           tolerance=1e-11)
    assert both.load_N[0] > both.load_N[1]
    assert both.load_N[0] == pytest.approx(free.load_N.sum(), rel=1e-6)
    assert both.load_N[1] == pytest.approx(sprung.load_N.sum(), rel=1e-6)


def test_edge_peak_grows_as_inverse_sqrt_cell_while_intensity_converges():
    """A quadratic gap cut by a straight edge inside the Hertz circle: the pressure next to
    the edge is singular like 1/sqrt(distance), so the cell next to the edge grows as
    1/sqrt(cell size) (ratio -> sqrt 2 per halving) while p sqrt(cell) converges."""
    W, R = 100.0, 20.0
    a = hertz_ellipse(W, R, R, E_STAR)["a_mm"]
    peaks, intensity = [], []
    for n in (32, 64, 128):
        dx = 2.6 * a / n
        x = -1.3 * a + (np.arange(n) + 0.5) * dx
        gap = (x[:, None] ** 2 + x[None, :] ** 2) / (2 * R)
        mask = np.broadcast_to((x <= 0.4 * a)[:, None], gap.shape)
        p = solve_contact(half_space((n, n), dx, dx, E_STAR), gap, load_N=W, mask=mask,
                          tolerance=1e-9).pressure_MPa
        peaks.append(p.max())
        intensity.append(p.max() * math.sqrt(dx))
    growth = [peaks[i + 1] / peaks[i] for i in range(2)]
    assert growth[-1] == pytest.approx(math.sqrt(2), rel=0.03)
    change = [abs(intensity[i + 1] / intensity[i] - 1) for i in range(2)]
    assert change[1] < change[0] and change[1] < 0.03


def test_bad_input_is_refused():
    hs = half_space((4, 4), 0.1, 0.1, E_STAR)
    gap = np.zeros((4, 4))
    with pytest.raises(ArgumentError, match="exactly one"):
        solve_contact(hs, gap)
    with pytest.raises(ArgumentError, match="load_N"):
        solve_contact(hs, gap, load_N=-1.0)
    with pytest.raises(ArgumentError, match="gap0_mm"):
        solve_contact(hs, np.zeros((3, 4)), load_N=1.0)
    with pytest.raises(ArgumentError, match="cell size"):
        half_space((4, 4), 0.0, 0.1, E_STAR)
    # an approach that does not close the gap carries nothing (no NaN)
    sol = solve_contact(hs, gap + 1.0, approach_mm=0.5)
    assert sol.load_N.sum() == 0 and np.all(np.isfinite(sol.gap_mm))


def test_single_precision_search_ends_on_the_double_precision_answer():
    """Grids sharing a load with springs: the search at tolerance 1e-6 runs its
    transforms in single precision and is checked in double; it lands on the answer of a
    double-precision search at 1e-11 within 1e-5 (loads) relative."""
    W = 300.0
    _, hs, gap, _, _ = _hertz_grid(41, W, 30.0, 10.0)
    gaps = np.stack([gap, gap + 1e-4, gap + 3e-4])
    c = np.array([1e-5, 2e-5, 0.5e-5])
    loose = solve_contact(hs, gaps, load_N=W, spring_mm_per_N=c, tolerance=1e-6)
    tight = solve_contact(hs, gaps, load_N=W, spring_mm_per_N=c, tolerance=1e-11)
    assert np.max(np.abs(loose.load_N - tight.load_N)) <= 1e-5 * W
    assert loose.approach_mm == pytest.approx(tight.approach_mm, rel=1e-6)
    assert float(np.sum(loose.load_N)) == pytest.approx(W, rel=1e-12)


def test_load_split_from_laws_sums_to_the_load():
    """The law-based split of a shared load (a warm start's first split) carries the
    load, loads the grid that touches first most and leaves one beyond the approach out."""
    law = np.array([[1e-4, 1e-4, 1e-4], [0.9, 0.9, 0.9], [1e-5, 1e-5, 1e-5]])
    split = load_split([0.0, 1e-3, 1.0], law, 500.0)
    assert float(np.sum(split)) == pytest.approx(500.0, rel=1e-12)
    assert split[0] > split[1] > 0 and split[2] == 0


def test_load_split_of_a_vanishing_load_is_finite_and_carried():
    # 6e-13 N on laws whose loads underflow (mill-spindle's surface capacity search at
    # 5.23° reached it): the first-touching grids share the load, no division by zero
    law = np.array([[1.27e-6, 1.27e-6], [0.9, 0.9], [4.5e-6, 4.5e-6]])
    split = load_split([-0.17336792, -0.17336792], law, 5.7e-13)
    assert np.all(np.isfinite(split))
    assert float(np.sum(split)) == pytest.approx(5.7e-13, rel=1e-12)
    assert split[0] == pytest.approx(split[1], rel=1e-12)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_compiled_small_grid_solver_equals_the_batched_transforms(seed, monkeypatch):
    """Grids of at most COMPILED_MAX_CELLS cells take the compiled per-grid search (direct
    sum over the contact, double precision); the batched path (DC-FFT) solves the same
    problem: crowned gaps with a cut edge, springs behind, five grids sharing one load.
    Loads, approach and pressure agree within 1e-8 relative at tolerance 1e-11."""
    rng = np.random.default_rng(seed)
    n1, n2 = 14, 9
    assert n1 * n2 <= halfspace.COMPILED_MAX_CELLS
    hs = half_space((n1, n2), 0.4, 0.15, E_STAR)
    x = (np.arange(n1) - n1 / 2) * 0.4
    y = (np.arange(n2) - n2 / 2) * 0.15
    gaps, masks = [], []
    for _ in range(5):
        rx, ry = rng.uniform(20, 200), rng.uniform(5, 50)
        gaps.append((x[:, None] - rng.normal(0, 1)) ** 2 / (2 * rx) + y[None, :] ** 2 / (2 * ry)
                    + rng.uniform(0, 2e-3) + rng.normal(0, 1e-4, (n1, n2)))
        masks.append(np.broadcast_to((x < rng.uniform(1, 3))[:, None], (n1, n2)))
    springs = rng.uniform(0, 3e-5, 5)
    W = float(rng.uniform(50, 3000))
    args = dict(load_N=W, mask=np.stack(masks), spring_mm_per_N=springs, tolerance=1e-11)
    fast = solve_contact(hs, np.stack(gaps), **args)
    monkeypatch.setattr(halfspace, "COMPILED_MAX_CELLS", 0)
    batched = solve_contact(hs, np.stack(gaps), **args)
    assert np.max(np.abs(fast.load_N - batched.load_N)) <= 1e-8 * W
    assert fast.approach_mm == pytest.approx(batched.approach_mm, rel=1e-8)
    p_max = np.max(batched.pressure_MPa)
    assert np.max(np.abs(fast.pressure_MPa - batched.pressure_MPa)) <= 1e-8 * p_max


def test_a_compiled_search_that_does_not_settle_hands_over_to_the_batched_one(monkeypatch):
    """A compiled grid search that has not converged in COMPILED_MAX_ITER iterations (a cell
    going in and out of contact at the tolerance: industrial-m2's load study did) is solved
    by the batched search instead: here every one (limit 1), and the answer is the batched
    path's own."""
    x = (np.arange(12) - 6) * 0.3
    gap = x[:, None] ** 2 / 40 + x[None, :8] ** 2 / 10
    hs = half_space((12, 8), 0.3, 0.3, E_STAR)
    gaps = np.stack([gap, gap + 2e-4])
    monkeypatch.setattr(halfspace, "COMPILED_MAX_ITER", 1)
    handed = solve_contact(hs, gaps, load_N=400.0, spring_mm_per_N=[1e-5, 2e-5],
                           tolerance=1e-10)
    monkeypatch.setattr(halfspace, "COMPILED_MAX_CELLS", 0)
    batched = solve_contact(hs, gaps, load_N=400.0, spring_mm_per_N=[1e-5, 2e-5],
                            tolerance=1e-10)
    np.testing.assert_array_equal(handed.pressure_MPa, batched.pressure_MPa)
    assert handed.approach_mm == batched.approach_mm
