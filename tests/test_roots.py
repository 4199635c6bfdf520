"""The shared bracketing root finder (lgraph._roots, on scipy's elementwise
find_root), checked against roots polished independently (bisection to the last
bit, then Newton), and the numeric zero sets that use it."""

from __future__ import annotations

import numpy as np
import pytest

import lgraph as lg
from lgraph._roots import bracketed_roots
from lgraph.surfaces.parametric._zero_set import _edge_roots, zero_set

EPS = np.finfo(float).eps


def _reference(c: np.ndarray) -> np.ndarray:
    """Roots of cos(x) - c x in [0, 2]: bisection to the last bit, then Newton."""
    lo, hi = np.zeros(len(c)), np.full(len(c), 2.0)
    for _ in range(200):
        m = 0.5 * (lo + hi)
        pos = np.cos(m) - c * m > 0
        lo, hi = np.where(pos, m, lo), np.where(pos, hi, m)
    x = 0.5 * (lo + hi)
    for _ in range(3):
        x -= (np.cos(x) - c * x) / (-np.sin(x) - c)
    return x


def test_roots_match_an_independent_reference_and_f_sees_only_active_brackets():
    c = np.random.default_rng(1).uniform(0.5, 3.0, 500)
    a, b = np.zeros(len(c)), np.full(len(c), 2.0)
    seen = []

    def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
        assert x.shape == sel.shape and sel.dtype.kind == "i"
        assert np.all((x >= a[sel]) & (x <= b[sel]))
        seen.append(len(sel))
        return np.cos(x) - c[sel] * x

    x = bracketed_roots(f, a, b, np.cos(a) - c * a, np.cos(b) - c * b, xtol=2e-15)
    ref = _reference(c)
    assert np.abs(x - ref).max() <= 2e-15 + 4 * EPS * 2
    # brackets drop out as they converge: the last calls see fewer of them
    assert seen[-1] < len(c) and len(seen) < 20


def test_zero_ends_are_roots_and_the_ends_are_not_evaluated():
    a, b = np.array([0.0, 0.0, -1.0]), np.array([1.0, 2.0, 1.0])
    calls = []

    def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
        calls.append((x.copy(), sel.copy()))
        return x - 0.25

    # the given end values are used as they are, even where f would differ:
    # bracket 0 has a root at its left end, bracket 1 at its right end
    x = bracketed_roots(f, a, b, np.array([0.0, -1.0, -1.25]), np.array([0.75, 0.0, 0.75]), 1e-15)
    assert x[0] == 0.0 and x[1] == 2.0
    assert abs(x[2] - 0.25) <= 1e-15
    for xs, sel in calls:  # f is never called at the ends of a bracket
        assert np.all((xs != a[sel]) & (xs != b[sel]))


def test_ftol_per_bracket_stops_at_the_rounding_level():
    c = np.array([1.0, 1.0])
    a, b = np.zeros(2), np.full(2, 2.0)
    fa, fb = np.cos(a) - c * a, np.cos(b) - c * b
    ftol = np.array([1e-3, 1e-300])

    def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
        return np.cos(x) - c[sel] * x

    x = bracketed_roots(f, a, b, fa, fb, 0.0, ftol)
    ref = _reference(c)
    assert abs(np.cos(x[0]) - x[0]) <= 1e-3
    assert abs(x[0] - ref[0]) > 1e-12  # stopped early: only |f| <= 1e-3 was asked
    assert abs(x[1] - ref[1]) <= 4 * EPS


def test_a_jump_without_a_root_is_located_to_the_tolerance():
    a, b = np.array([0.0]), np.array([1.0])

    def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
        return np.where(x > 1 / 3, 1.0, -1.0)

    x = bracketed_roots(f, a, b, np.array([-1.0]), np.array([1.0]), 1e-14)
    assert abs(x[0] - 1 / 3) <= 1e-14 + 4 * EPS


def test_no_brackets_and_bad_tolerances():
    def f(x: np.ndarray, sel: np.ndarray) -> np.ndarray:
        return x

    e = np.empty(0)
    assert bracketed_roots(f, e, e, e, e, 1e-15).shape == (0,)
    one = np.array([-1.0]), np.array([1.0]), np.array([-1.0]), np.array([1.0])
    with pytest.raises(ValueError, match="xtol"):
        bracketed_roots(f, *one, np.array([1e-15]))
    with pytest.raises(ValueError, match="xtol"):
        bracketed_roots(f, *one, -1.0)
    with pytest.raises(ValueError, match="ftol"):
        bracketed_roots(f, *one, 1e-15, np.array([0.0]))
    with pytest.raises(ValueError, match="ftol"):
        bracketed_roots(f, *one, 1e-15, -1.0)


def test_edge_roots_lie_on_the_zero_set():
    # the unit circle crossing segments of the plane
    rng = np.random.default_rng(2)
    ang = rng.uniform(0, 2 * np.pi, 300)
    p = np.column_stack([np.cos(ang), np.sin(ang)])
    t = rng.uniform(0.05, 0.95, 300)
    d = rng.normal(size=(300, 2)) * 0.1
    a, b = p - t[:, None] * d, p + (1 - t)[:, None] * d

    def fun(q: np.ndarray) -> np.ndarray:
        return np.einsum("ij,ij->i", q, q) - 1.0

    fa, fb = fun(a), fun(b)
    ok = fa * fb < 0
    x = _edge_roots(fun, a[ok], b[ok], fa[ok], fb[ok])
    assert np.abs(np.linalg.norm(x, axis=1) - 1).max() < 1e-14
    # the root lies on its segment
    s = np.einsum("ij,ij->i", x - a[ok], b[ok] - a[ok]) / np.einsum("ij,ij->i", d[ok], d[ok])
    assert np.all((s >= 0) & (s <= 1))


def test_zero_set_drops_a_zero_at_a_single_grid_node():
    # fun vanishes at one grid node and is negative around it: the crossings on
    # the four edges at that node are all the node itself, which is no curve
    s = lg.ParametricSurface(lambda u, v: np.stack([u, v, 0 * u], -1), (0.0, 1.0), (0.0, 1.0))
    node = np.linspace(0.0, 1.0, 193)[96]

    def fun(u1: np.ndarray, u2: np.ndarray) -> np.ndarray:
        return -(np.abs(u1 - node) + np.abs(u2 - node))

    assert zero_set(s, fun) == []

    # a circle through the same machinery is found, to the rounding level
    def circle(u1: np.ndarray, u2: np.ndarray) -> np.ndarray:
        return (u1 - 0.5) ** 2 + (u2 - 0.5) ** 2 - 0.09

    (pts, closed), *rest = zero_set(s, circle)
    assert closed and not rest
    assert np.abs(np.hypot(pts[:, 0] - 0.5, pts[:, 1] - 0.5) - 0.3).max() < 1e-14
