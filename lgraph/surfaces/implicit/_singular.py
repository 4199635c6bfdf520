"""Singular points of algebraic surfaces (``F = 0``, ``grad F = 0``), found
by subdivision with certain bounds and Newton's method.

The clip box is split into octants, level by level.  On every box the
polynomials ``F, F_x, F_y, F_z`` are written in the tensor Bernstein basis
of the box; their coefficients bound the polynomials there (the convex-hull
property), so a box where one of the four bounds excludes 0 holds no
singular point and is dropped -- a certain decision, up to the rounding of
the coefficients (the bounds are widened by ``1e-12`` of their size).  The
boxes left after ``LEVELS`` halvings (``2**-LEVELS`` of the clip box) seed
Newton's method on ``grad F = 0``; a limit point is kept when ``F``
vanishes there to rounding error (``1e-10`` of ``F``'s terms in absolute
value) and its Hessian is invertible (an ordinary node, ``A1``); points on
curves of singular points (the double lines of the Roman surface), whose
Hessian is singular, are not reported.  More than ``MAX_BOXES`` boxes on
one level (a singular curve) stops the subdivision there.

>>> import lgraph as lg
>>> p = singular_points(lg.CayleyCubic())
>>> sorted(map(tuple, np.round(p).astype(int).tolist()))
[(-1, -1, 1), (-1, 1, -1), (1, -1, -1), (1, 1, 1)]
"""

from __future__ import annotations

from math import comb
from typing import Any

import numpy as np

from ..._tolerance import SINGULAR_LEVELS as LEVELS
from ..._tolerance import SINGULAR_MAX_BOXES as MAX_BOXES
from ._polynomial import Polynomial

__all__ = ["singular_points", "LEVELS", "MAX_BOXES"]

#: Newton steps from each remaining box
NEWTON_STEPS = 30


def _axis_maps(d: int, lo: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Per box and axis, the matrix taking power coefficients in ``x`` to
    Bernstein coefficients on ``[lo, lo + w]``: ``(m, 3, d + 1, d + 1)``."""
    j = np.arange(d + 1)
    C = np.array([[comb(a, b) for b in j] for a in j], float)
    expo = j[:, None] - j[None, :]
    lp = np.where(expo >= 0, lo[..., None, None] ** np.maximum(expo, 0), 0.0)
    T = C * lp * w[..., None, None] ** j  # T[j, a] = C(j, a) lo^(j - a) w^a
    B = np.array([[comb(i, a) / comb(d, a) if a <= i else 0.0 for i in j] for a in j])
    return T @ B


def _enclosures(cs: np.ndarray, lo: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper bounds ``(m, k)`` of polynomials ``cs`` (``(k, d+1, d+1,
    d+1)``) on the boxes ``[lo, lo + w]``."""
    d = cs.shape[1] - 1
    M = _axis_maps(d, lo, w)
    t = np.einsum("kabc,mci->mkabi", cs, M[:, 2])
    t = np.einsum("mkabi,mbh->mkahi", t, M[:, 1])
    t = np.einsum("mkahi,mag->mkghi", t, M[:, 0])
    t = t.reshape(len(lo), len(cs), -1)
    lo_b, hi_b = t.min(axis=2), t.max(axis=2)
    pad = 1e-12 * np.abs(t).max(axis=2)
    return lo_b - pad, hi_b + pad


def singular_points(surface: Any) -> np.ndarray:
    """The isolated ordinary singular points ``(n, 3)`` of an
    :class:`~lgraph.AlgebraicSurface` inside its clip region (module docstring)."""
    poly = surface.poly
    clip = surface.clip
    cs = np.stack([poly.c, *poly.d1])
    lo = clip.lo[None, :].copy()
    w = (clip.hi - clip.lo)[None, :].copy()
    corners = np.array([[a, b, c] for a in (0, 1) for b in (0, 1) for c in (0, 1)], float)
    for _ in range(LEVELS):
        blo, bhi = _enclosures(cs, lo, w)
        keep = ((blo <= 0) & (bhi >= 0)).all(axis=1)
        lo, w = lo[keep], w[keep]
        if not len(lo) or 8 * len(lo) > MAX_BOXES:
            break
        w = w / 2
        lo = (lo[:, None, :] + corners[None] * w[:, None, :]).reshape(-1, 3)
        w = np.repeat(w, 8, axis=0)
    if not len(lo):
        return np.empty((0, 3))
    x = lo + w / 2
    for _ in range(NEWTON_STEPS):
        g, H = poly.gradient(x), poly.hessian(x)
        with np.errstate(all="ignore"):
            ok = np.abs(np.linalg.det(H)) > 1e-300
            dx = np.zeros_like(x)
            if ok.any():
                dx[ok] = np.linalg.solve(H[ok], g[ok][..., None])[..., 0]
        x = x - np.where(np.isfinite(dx), dx, 0.0)
    absf = Polynomial(np.abs(poly.c)).value(np.abs(x))
    good = np.abs(poly.value(x)) <= 1e-10 * np.maximum(absf, 1e-300)
    g = poly.gradient(x)
    H = poly.hessian(x)
    scale = np.linalg.norm(H, axis=(1, 2))
    good &= np.linalg.norm(g, axis=1) <= 1e-9 * np.maximum(scale, 1e-300) * clip.size
    with np.errstate(all="ignore"):
        cond = np.linalg.cond(H)
    good &= np.isfinite(cond) & (cond < 1e8)
    good &= np.linalg.norm(x - (lo + w / 2), axis=1) < 2 * np.linalg.norm(w, axis=1)
    good &= clip.excess(x)[0] <= 1e-9 * clip.size
    x = x[good]
    out: list[np.ndarray] = []
    for p in x:  # a few points: keep one of each cluster
        if all(np.linalg.norm(p - q) > 1e-7 * clip.size for q in out):
            out.append(p)
    return np.array(out).reshape(-1, 3)
