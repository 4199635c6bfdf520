"""Real roots of many small polynomials at once (lgraph.surfaces.classical._polyroots),
against numpy's ``np.roots`` one polynomial at a time."""

from __future__ import annotations

import numpy as np
import pytest

from lgraph.surfaces.classical._polyroots import all_real_roots, real_roots


def _reference(row: np.ndarray, size: float) -> np.ndarray:
    r = np.roots(row)
    return np.sort(r[np.abs(r.imag) <= 1e-7 * (size + np.abs(r.real))].real)


@pytest.mark.parametrize("degree", [1, 2, 3, 4])
def test_real_roots_agree_with_numpy_root_by_root(degree: int) -> None:
    rng = np.random.default_rng(degree)
    n = 3000
    coef = rng.normal(size=(n, degree + 1)) * np.exp(3 * rng.normal(size=(n, 1)))
    if degree == 2:  # exact double roots (s - r)^2 and pairs 1e-9 apart
        r = rng.normal(size=200)
        coef[:100] = np.column_stack([np.ones(100), -2 * r[:100], r[:100] ** 2])
        gap = 1e-9
        coef[100:200] = np.column_stack(
            [np.ones(100), -2 * r[100:] - gap, r[100:] * (r[100:] + gap)]
        )
    got = real_roots(coef, 1.0)
    for row, g in zip(coef, got):
        want = _reference(row, 1.0)
        g = np.sort(g[np.isfinite(g)])
        assert len(g) == len(want), (row, g, want)
        scale = 1.0 + np.abs(want)
        assert np.all(np.abs(g - want) <= 2e-7 * scale), (row, g, want)


def test_quadratics_without_cancellation() -> None:
    # s^2 - 1e8 s + 1: roots 1e8 and 1e-8; the textbook formula loses the small one
    s = np.sort(real_roots(np.array([[1.0, -1e8, 1.0]]), 1.0)[0])
    assert abs(s[0] - 1e-8) <= 1e-22 and abs(s[1] - 1e8) <= 1e-6


def test_a_complex_pair_is_no_root_and_a_vanishing_lead_lowers_the_degree() -> None:
    assert np.isnan(real_roots(np.array([[1.0, 0.0, 1.0]]), 1.0)).all()
    r = all_real_roots(np.array([[0.0, 2.0, -1.0], [0.0, 0.0, 3.0]]), 1.0)
    assert r[0, 0] == 0.5 and np.isnan(r[0, 1]) and np.isnan(r[1]).all()
