"""Real roots of many small polynomials at once (the quartic ray tests).

>>> import numpy as np
>>> coef = np.array([[1.0, 0.0, -1.0], [1.0, 0.0, 1.0]])  # s^2 - 1, s^2 + 1
>>> has_root_in(coef, 0.0, np.array([2.0, 2.0]), 1.0).tolist()
[True, False]
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["all_real_roots", "has_root_in", "real_roots", "roots_in"]


def real_roots(coef: np.ndarray, size: Any) -> np.ndarray:
    """Real roots ``(n, deg)`` of each real polynomial (rows of ``coef``,
    highest power first, leading coefficient non-zero), NaN where a root is
    complex.

    Roots of cubics and quartics are the eigenvalues of the companion
    matrices, all rows at once; of lines and quadratics, the closed forms
    (the quadratic's without cancellation).  A root counts as real when its
    imaginary part is below ``1e-7`` of ``size + |root|`` (a double root
    splits into a pair ~1e-8 apart); only real roots are then polished by
    Newton steps (small ones: a complex pair's real part must not wander off
    into a false root).  ``size`` is a scalar or one value per row.

    >>> np.sort(real_roots(np.array([[1.0, -3.0, 2.0]]), 1.0)).round(12).tolist()
    [[1.0, 2.0]]
    """
    coef = np.asarray(coef, dtype=float)
    n, deg = len(coef), coef.shape[1] - 1
    size = np.broadcast_to(np.asarray(size, float), (n,))[:, None]
    monic = coef[:, 1:] / coef[:, :1]
    if deg <= 2:
        s, imag = _low_degree(monic)
    else:
        comp = np.zeros((n, deg, deg))
        comp[:, 0, :] = -monic
        comp[:, np.arange(1, deg), np.arange(deg - 1)] = 1.0
        roots = np.linalg.eigvals(comp)
        s, imag = roots.real.copy(), roots.imag
    real = np.abs(imag) <= 1e-7 * (size + np.abs(s))
    for _ in range(3):
        f = np.zeros_like(s)
        df = np.zeros_like(s)
        for k in range(deg + 1):
            df = df * s + f
            f = f * s + coef[:, k, None]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            step = np.where(real & (df != 0), f / df, 0.0)
        s = s - np.where(np.abs(step) < 1e-3 * (size + np.abs(s)), step, 0.0)
    return np.where(real, s, np.nan)


def _low_degree(monic: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Real parts and imaginary parts ``(n, deg)`` of the roots of ``s + q`` or
    ``s^2 + p s + q`` (rows of ``monic``: ``[q]`` or ``[p, q]``)."""
    if monic.shape[1] == 1:
        return -monic.copy(), np.zeros_like(monic)
    p, q = monic[:, 0], monic[:, 1]
    disc = p * p - 4 * q
    root = np.sqrt(np.abs(disc))
    big = -0.5 * (p + np.copysign(root, p))  # the root of larger magnitude, no cancellation
    with np.errstate(invalid="ignore", divide="ignore"):
        small = np.where(big != 0, q / np.where(big != 0, big, 1.0), 0.0)
    real = disc >= 0
    re = np.where(real[:, None], np.stack([big, small], axis=1), -0.5 * p[:, None])
    im = np.where(real, 0.0, 0.5 * root)[:, None] * np.array([1.0, -1.0])
    return re, im


def all_real_roots(coef: np.ndarray, size: Any) -> np.ndarray:
    """:func:`real_roots` of polynomials whose leading coefficients may vanish:
    leading coefficients below ``1e-13`` of the row's largest are dropped
    (rows of each degree solved together); ``(n, deg)``, NaN-padded.

    >>> r = all_real_roots(np.array([[0.0, 1.0, -1.0], [1.0, 0.0, -4.0]]), 1.0)
    >>> np.sort(r, axis=1).round(12).tolist()  # the order of the roots is not specified
    [[1.0, nan], [-2.0, 2.0]]
    """
    coef = np.asarray(coef, dtype=float)
    n, deg = len(coef), coef.shape[1] - 1
    size = np.broadcast_to(np.asarray(size, float), (n,))
    out = np.full((n, deg), np.nan)
    big = np.abs(coef).max(axis=1, keepdims=True)
    negligible = np.abs(coef) <= 1e-13 * big
    lead = np.argmin(negligible, axis=1)  # index of the first coefficient that counts
    for first in range(deg):
        rows = np.flatnonzero(lead == first)
        if len(rows):
            out[rows, : deg - first] = real_roots(coef[rows, first:], size[rows])
    return out


def has_root_in(coef: np.ndarray, lower: Any, upper: Any, size: Any) -> np.ndarray:
    """Whether each polynomial of :func:`real_roots` has a real root in
    ``(lower, upper)`` (scalars or one value per row)."""
    return roots_in(coef, lower, upper, size) > 0


def roots_in(coef: np.ndarray, lower: Any, upper: Any, size: Any) -> np.ndarray:
    """How many real roots (:func:`real_roots`, with multiplicity as they
    split) each polynomial has in ``(lower, upper)`` (scalars or one value
    per row).

    >>> roots_in(np.array([[1.0, -6.0, 11.0, -6.0]]), 0.5, 2.5, 1.0).tolist()
    [2]
    """
    n = len(coef)
    lower, upper = (np.broadcast_to(np.asarray(x, float), (n,))[:, None] for x in (lower, upper))
    s = real_roots(coef, size)
    with np.errstate(invalid="ignore"):
        return ((s > lower) & (s < upper)).sum(axis=1)
