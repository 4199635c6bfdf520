"""Certain real-root counting of many univariate polynomials on intervals.

Each polynomial ``p(s) = sum_j q_j s^j`` is mapped onto ``t`` in ``[0, 1]``
(``s = lo + (hi - lo) t``) and written in the Bernstein basis of its degree
``d``: ``p = sum_i b_i C(d, i) t^i (1 - t)^(d - i)``.  By Descartes' rule of
signs for the Bernstein form, the number of roots in ``(0, 1)`` is at most
the number ``V`` of sign changes of ``b_0, ..., b_d`` and has its parity:
``V = 0`` proves there is none, ``V = 1`` that there is exactly one.  Rows
with ``V >= 2`` are split at ``t = 1/2`` (de Casteljau, exact convex
combinations) and both halves examined, all rows of one round together.
After ``MAX_DEPTH`` halvings (an interval ``2**-40`` of the original) a row
still undecided holds a cluster of roots closer together than that; it
counts ``1`` if ``p`` has opposite signs at its ends, else ``0``.

So the count is that of the crossings (roots of odd multiplicity): a double
root (a ray tangent to the surface) counts 0, as it should for hidden
lines.  It is exact for the floating-point coefficients whenever the roots
are more than ``2**-40 (hi - lo)`` apart and no Bernstein coefficient is
within rounding error of zero (a root within rounding error of an end of
the interval or of a split point).  Two simple roots closer than about
``1e-8`` of the interval are a case of the latter: between them ``|p|`` is
below the coefficients' rounding, and the floating-point polynomial may
well have a complex pair there instead (then it is counted as such).

>>> import numpy as np
>>> q = np.array([[2.0, -3.0, 1.0]])  # (s - 1)(s - 2)
>>> count_roots(q, np.array([0.0]), np.array([3.0])).tolist()
[2]
>>> count_roots(q, np.array([1.5]), np.array([3.0])).tolist()
[1]
>>> count_roots(np.array([[1.0, -2.0, 1.0]]), np.array([0.0]), np.array([3.0])).tolist()
[0]
"""

from __future__ import annotations

from math import comb

import numpy as np

from ..._tolerance import BERNSTEIN_MAX_DEPTH as MAX_DEPTH

__all__ = ["count_roots", "to_bernstein", "MAX_DEPTH"]


def _shift_matrix(d: int) -> np.ndarray:
    """``C(j, m)`` for ``j, m <= d``."""
    return np.array([[comb(j, m) for m in range(d + 1)] for j in range(d + 1)], float)


def to_bernstein(q: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Bernstein coefficients ``(n, d + 1)`` on ``[lo, hi]`` of the polynomials
    with power coefficients ``q`` (``(n, d + 1)``, ascending powers of ``s``).

    >>> to_bernstein(np.array([[0.0, 1.0]]), np.array([2.0]), np.array([4.0])).tolist()
    [[2.0, 4.0]]
    """
    q = np.asarray(q, float)
    n, d1 = q.shape
    d = d1 - 1
    w = hi - lo
    C = _shift_matrix(d)
    j = np.arange(d1)
    # r_m = sum_j q_j C(j, m) lo^(j - m) w^m  (p(lo + w t) in powers of t)
    expo = j[:, None] - j[None, :]
    with np.errstate(all="ignore"):
        lp = np.where(expo >= 0, lo[:, None, None] ** np.maximum(expo, 0), 0.0)
    r = np.einsum("nj,jm,njm->nm", q, C, lp) * w[:, None] ** j
    # b_i = sum_{m <= i} C(i, m) / C(d, m) r_m
    B = np.array(
        [[comb(i, m) / comb(d, m) if m <= i else 0.0 for i in range(d1)] for m in range(d1)]
    )
    return r @ B


def _variations(b: np.ndarray) -> np.ndarray:
    s = np.where(b < 0, -1, 1)
    return (s[:, 1:] != s[:, :-1]).sum(axis=1)


def _split(b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """de Casteljau at ``t = 1/2``: the Bernstein coefficients of both halves."""
    d = b.shape[1] - 1
    left, right = np.empty_like(b), np.empty_like(b)
    work = b.copy()
    left[:, 0], right[:, d] = work[:, 0], work[:, d]
    for k in range(1, d + 1):
        work = 0.5 * (work[:, :-1] + work[:, 1:])
        left[:, k] = work[:, 0]
        right[:, d - k] = work[:, -1]
    return left, right


def count_roots(q: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The number of crossings (roots of odd multiplicity) of each polynomial
    (rows of ``q``, ascending powers) in ``(lo, hi)`` (module docstring);
    rows with ``lo >= hi`` or non-finite data count 0."""
    q = np.asarray(q, float)
    n = len(q)
    out = np.zeros(n, dtype=np.int64)
    ok = (hi > lo) & np.isfinite(lo) & np.isfinite(hi) & np.isfinite(q).all(axis=1)
    rows = np.flatnonzero(ok)
    if not len(rows) or q.shape[1] < 2:
        return out
    b = to_bernstein(q[rows], lo[rows], hi[rows])
    scale = np.abs(b).max(axis=1, keepdims=True)
    b = b / np.where(scale > 0, scale, 1.0)  # the signs are what counts
    for depth in range(MAX_DEPTH + 1):
        if not len(rows):
            break
        v = _variations(b)
        one = v == 1
        np.add.at(out, rows[one], 1)
        more = v >= 2
        if depth == MAX_DEPTH:
            ends = np.sign(b[more, 0]) != np.sign(b[more, -1])
            np.add.at(out, rows[more][ends], 1)
            break
        rows, b = rows[more], b[more]
        left, right = _split(b)
        rows = np.concatenate([rows, rows])
        b = np.concatenate([left, right])
    return out
