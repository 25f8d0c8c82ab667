"""The bodies' influence between teeth (``loading.body``): the circulant kernel, its
harmonics, the periodic fold, the z-dependent matrix and the per-tooth deflection, against
direct sums on kernels with known answers (no FE: a table stand-in)."""

from types import SimpleNamespace

import numpy as np
import pytest

from gearcoupling import load_spec
from gearcoupling.errors import ArgumentError
from gearcoupling.loading.body import (
    body_deflection_mm,
    body_influence_matrix,
    convolve_loads,
    influence_matrix,
    kernel_harmonics,
    kernel_matrix,
    periodic_kernel,
)


def ring_kernel(n: int, decay: float = 2.5) -> np.ndarray:
    """A symmetric kernel decaying with the distance round a ring of ``n`` teeth."""
    m = np.arange(n)
    return np.exp(-np.minimum(m, n - m) / decay) + 0.1


def test_matrix_convolution_and_harmonics_agree():
    b = ring_kernel(38)
    W = np.random.default_rng(1).uniform(0, 900, (38, 3))
    B = kernel_matrix(b)
    np.testing.assert_allclose(convolve_loads(b, W), B @ W, rtol=1e-12)
    np.testing.assert_allclose(convolve_loads(b, W[:, 0]), B @ W[:, 0], rtol=1e-12)
    assert np.allclose(B, B.T)  # reciprocity: a symmetric kernel
    # the harmonics are the eigenvalues: cos(2 pi n k / N) loads are eigenvectors
    lam = kernel_harmonics(b)
    k = np.arange(38)
    for n in (0, 1, 2, 19):
        v = np.cos(2 * np.pi * n * k / 38)
        np.testing.assert_allclose(B @ v, lam[n] * v, atol=1e-12)
    assert lam[0] == pytest.approx(b.sum())


def test_periodic_kernel_folds_the_ring_and_keeps_the_uniform_torsion():
    b = ring_kernel(38)
    np.testing.assert_array_equal(periodic_kernel(b, 38), b)
    for K in (1, 5, 7, 19):
        bk = periodic_kernel(b, K)
        assert bk.shape == (K,)
        assert bk.sum() == pytest.approx(b.sum(), rel=1e-12)  # equal loads: same twist
        np.testing.assert_allclose(bk[1:], bk[1:][::-1], rtol=1e-12)  # still symmetric
    # a period that divides the ring: the loads repeated round the ring, summed directly
    b36 = ring_kernel(36)
    pattern = np.tile([300.0, 0.0, 0.0, 100.0], 9)
    np.testing.assert_allclose(convolve_loads(periodic_kernel(b36, 4), pattern[:4]),
                               (kernel_matrix(b36) @ pattern)[:4], rtol=1e-12)
    # a kernel that ends within half the ring: the fold is the sum over the chain
    short = np.zeros(38)
    short[[0, 1, 2, 36, 37]] = [5.0, 2.0, 1.0, 1.0, 2.0]
    np.testing.assert_allclose(periodic_kernel(short, 5), [5.0, 2.0, 1.0, 1.0, 2.0])
    np.testing.assert_allclose(periodic_kernel(short, 3), [5.0, 3.0, 3.0])


def test_influence_matrix_is_the_kernel_at_each_pair_mean_z():
    b0, b1 = ring_kernel(12), 2.0 * ring_kernel(12)
    kernel = np.stack([b0, b1])
    np.testing.assert_array_equal(influence_matrix(kernel, [0.0, 4.0]), kernel_matrix(b0))
    z = np.where(np.arange(12) < 6, 4.0, -4.0)  # |z| 4 everywhere: the second row
    np.testing.assert_allclose(influence_matrix(kernel, [0.0, 4.0], z), kernel_matrix(b1))
    z = np.zeros(12)
    z[3] = 2.0  # tooth 3 at 2 mm: its pairs at 1 mm (a quarter on), its own term at 2 mm
    B = influence_matrix(kernel, [0.0, 4.0], z)
    assert B[3, 3] == pytest.approx(1.5 * b0[0])
    assert B[3, 5] == pytest.approx(1.25 * b0[(3 - 5) % 12])
    assert np.allclose(B, B.T)
    far = influence_matrix(kernel, [0.0, 4.0], np.full(12, 9.0))  # held beyond the grid
    np.testing.assert_allclose(far, kernel_matrix(b1))


def test_body_deflection_per_rotation_and_period():
    spec = load_spec("industrial-m2")
    N = spec.tooth.teeth
    table = SimpleNamespace(kernel_mm_per_N=np.stack([ring_kernel(N), 1.5 * ring_kernel(N)]),
                            z_mm=np.array([0.0, 6.4]), ring_mm_per_N=np.zeros((2, 2, N)))
    W = np.random.default_rng(2).uniform(0, 1000, (N, 2))
    z = np.random.default_rng(3).uniform(-6, 6, (N, 2))
    v = body_deflection_mm(spec, W, z, table=table)
    assert v.shape == (N, 2)
    for j in range(2):
        np.testing.assert_allclose(v[:, j], body_influence_matrix(spec, z[:, j], table=table)
                                   @ W[:, j], rtol=1e-12)
    B5 = body_influence_matrix(spec, np.zeros(5), period=5, table=table)
    np.testing.assert_allclose(B5, kernel_matrix(periodic_kernel(ring_kernel(N), 5)))
    with pytest.raises(ArgumentError, match="loads"):
        body_deflection_mm(spec, W[:5], table=table)
    with pytest.raises(ArgumentError, match="period"):
        body_influence_matrix(spec, period=0, table=table)


@pytest.mark.parametrize("bad", [np.array([1.0, np.nan]), np.zeros((2, 2, 2)), np.array([])])
def test_bad_kernels_are_refused(bad):
    with pytest.raises(ArgumentError, match="kernel"):
        kernel_matrix(bad)
