"""The ray test of a general implicit surface: sign changes of F along each ray.

``F`` is sampled at ``RAY_SAMPLES`` points of each ray's interval ``(lo,
hi)`` (inside the clip region, past the self-hit tolerance, before the
eye); each sign change between neighbours is a crossing.  With a Lipschitz
bound ``L`` (``|F(x) - F(y)| <= L |x - y|`` in the region) an interval
``[a, b]`` without a sign change is free of roots when ``|F(a)| + |F(b)| >
L |v| (b - a)`` (a root ``r`` between would give ``|F(a)| <= L |v| (r - a)``
and ``|F(b)| <= L |v| (b - r)``); the others are bisected until they are
proved free or show a sign change (two crossings), for at most
``LIPSCHITZ_ROUNDS`` rounds: only a tangency within ``2**-48`` of a sample
interval can then be missed.

>>> import numpy as np
>>> f = lambda p: np.sum(p * p, axis=-1) - 1.0
>>> o, v = np.array([[0.0, 0.0, -3.0]]), np.array([[0.0, 0.0, 1.0]])
>>> sampled_crossings(f, o, v, np.array([1e-9]), np.array([10.0]), None).tolist()
[2]
>>> # a ray grazing the sphere at distance 1 - 1e-6: two roots 2.8e-3 apart,
>>> # missed between samples, found with a Lipschitz bound
>>> o2 = np.array([[1 - 1e-6, 0.0, -3.0]])
>>> sampled_crossings(f, o2, v, np.array([0.0]), np.array([6.0]), None).tolist()
[0]
>>> sampled_crossings(f, o2, v, np.array([0.0]), np.array([6.0]), 8.0).tolist()
[2]
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..._tolerance import IMPLICIT_LIPSCHITZ_ROUNDS as LIPSCHITZ_ROUNDS
from ..._tolerance import IMPLICIT_RAY_SAMPLES as RAY_SAMPLES

__all__ = ["sampled_crossings", "RAY_SAMPLES", "LIPSCHITZ_ROUNDS"]

#: points of F evaluated in one call
CHUNK = 1_000_000


def _eval(F: Callable[[np.ndarray], np.ndarray], x: np.ndarray) -> np.ndarray:
    out = np.empty(x.shape[:-1])
    flat, res = x.reshape(-1, 3), out.reshape(-1)
    with np.errstate(all="ignore"):
        for i in range(0, len(flat), CHUNK):
            res[i : i + CHUNK] = F(flat[i : i + CHUNK])
    return out


def sampled_crossings(
    F: Callable[[np.ndarray], np.ndarray],
    o: np.ndarray,
    v: np.ndarray,
    lo: np.ndarray,
    hi: np.ndarray,
    lipschitz: float | None,
    start: np.ndarray | None = None,
) -> np.ndarray:
    """How many times ``F`` (of points ``(..., 3)``) changes sign along each
    ray ``o + s v``, ``lo < s < hi`` (module docstring).

    ``start`` (optional, per ray): the sign of ``F`` just after ``lo`` where
    it is known better than ``F(lo)`` tells (a ray from a point on the
    surface: ``F(o)`` is rounding noise; 0 where unknown).  The first
    interval of those rays is then not bisected."""
    n = len(o)
    count = np.zeros(n, dtype=np.int64)
    rays = np.flatnonzero(hi > lo)
    if not len(rays):
        return count
    m = RAY_SAMPLES
    frac = np.linspace(0.0, 1.0, m)
    s = lo[rays, None] + (hi - lo)[rays, None] * frac  # (k, m)
    f = _eval(F, o[rays, None, :] + s[..., None] * v[rays, None, :])
    sign = np.sign(f)
    known = np.zeros(len(rays), bool)
    if start is not None:
        known = start[rays] != 0
        sign[known, 0] = start[rays][known]
    change = sign[:, :-1] * sign[:, 1:] < 0
    count[rays] = change.sum(axis=1) + (sign[:, 1:-1] == 0).sum(axis=1)
    if lipschitz is None:
        return count
    speed = np.linalg.norm(v[rays], axis=1)
    a, b = s[:, :-1], s[:, 1:]
    fa, fb = f[:, :-1], f[:, 1:]
    lip = lipschitz * speed[:, None]
    open_ = ~change & (sign[:, :-1] != 0) & (np.abs(fa) + np.abs(fb) <= lip * (b - a))
    open_[known, 0] = False
    r, j = np.nonzero(open_)
    ray, a, b, fa, fb = rays[r], a[r, j], b[r, j], fa[r, j], fb[r, j]
    L = lipschitz * np.linalg.norm(v[ray], axis=1)
    for _ in range(LIPSCHITZ_ROUNDS):
        if not len(ray):
            break
        c = 0.5 * (a + b)
        fc = _eval(F, o[ray] + c[:, None] * v[ray])
        flip = np.sign(fc) != np.sign(fa)  # both halves change sign: two crossings
        np.add.at(count, ray[flip], 2)
        left = ~flip & (np.abs(fa) + np.abs(fc) <= L * (c - a))
        right = ~flip & (np.abs(fc) + np.abs(fb) <= L * (b - c))
        ray = np.concatenate([ray[left], ray[right]])
        L = np.concatenate([L[left], L[right]])
        a, b = np.concatenate([a[left], c[right]]), np.concatenate([c[left], b[right]])
        fa, fb = np.concatenate([fa[left], fc[right]]), np.concatenate([fc[left], fb[right]])
    return count
