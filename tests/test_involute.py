"""Involute function and its inverse against series, identities and round trips."""

import numpy as np
import pytest

from gearcoupling import inv, inv_inverse


def test_inv_matches_definition_and_series():
    a = np.linspace(0.02, 1.5, 200)
    assert np.allclose(inv(a), np.tan(a) - a, rtol=1e-14, atol=0)
    small = np.array([1e-8, 1e-5, 1e-3, 9.9e-3])
    # series to a^11 against mpmath-free high-precision identity: tan - a via float128-free
    # reference: the next series term 1382 a^11 / 155925 bounds the error
    ref = small**3 / 3 + 2 * small**5 / 15 + 17 * small**7 / 315 + 62 * small**9 / 2835
    assert np.allclose(inv(small), ref, rtol=1e-15)
    assert np.all(1382 * small**11 / 155925 < 1e-15 * ref)


def test_inv_is_odd_and_continuous_at_series_switch():
    a = np.array([0.01 - 1e-12, 0.01 + 1e-12])
    assert abs(inv(a[1]) - inv(a[0])) < 1e-15
    assert np.allclose(inv(-a), -inv(a), rtol=0, atol=0)


@pytest.mark.parametrize("a", [1e-6, 1e-3, 0.1, 0.35, 0.7, 1.2, 1.5, 1.57])
def test_inverse_round_trip(a):
    y = inv(a)
    assert inv_inverse(y) == pytest.approx(a, rel=1e-13)
    assert inv_inverse(-y) == pytest.approx(-a, rel=1e-13)


def test_inverse_vectorised_and_exact_zero():
    y = np.geomspace(1e-15, 1e3, 500)
    a = inv_inverse(y)
    assert np.all(np.isfinite(a)) and np.all((a > 0) & (a < np.pi / 2))
    assert np.allclose(inv(a), y, rtol=1e-12)
    assert inv_inverse(0.0) == 0.0


def test_inverse_rejects_non_finite():
    with pytest.raises(ValueError):
        inv_inverse(np.array([0.1, np.nan]))
