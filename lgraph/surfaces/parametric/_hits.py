"""The numeric ray test of a parametrized surface: the default of
:meth:`Surface.hits <lgraph.surfaces._base.Surface.hits>`.

The bounding boxes of :mod:`~lgraph.surfaces.parametric._boxes` select candidate patches;
Newton's method on ``x(u1, u2) - (o + s v) = 0`` starts in each; patches where
it fails or leaves the patch are subdivided (up to ``HIT_MAX_DEPTH`` levels).
A ray from a point on the surface (``own == ON``) never counts its own root
``s = 0``; a second root close to it (near the surface's own contour) is
found from the local quadratic approximation of the surface:
``s = 2 (v . N) / II(a)`` with ``J a`` the tangential part of ``v``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..._own import CONTOUR, OFF, ON
from ..._tolerance import HIT_CHUNK_RAYS, SELF_HIT_RTOL
from ...geometry.vectors import cross as _cross
from ._boxes import _candidates, _Hierarchy, _hierarchy, _inverse, _slab, _sub_boxes

if TYPE_CHECKING:
    from .._domain import Parametrized

__all__ = ["hits"]

#: extra subdivision levels where Newton's method fails in a leaf
HIT_MAX_DEPTH = 3
#: Newton iterations per candidate patch
HIT_NEWTON_STEPS = 30
#: a contour point's ray counts a root within this distance (relative to the
#: surface size) of its origin as its own (double) root
CONTOUR_SELF_RTOL = 1e-5


def _analytic_derivatives(surface: Parametrized) -> bool:
    # the base class marks its finite-difference default (no import of _base here)
    if getattr(type(surface).derivatives, "finite_differences", False):
        return False
    return getattr(surface, "derivatives_func", True) is not None


def _fast_derivatives(surface: Parametrized, u1: np.ndarray, u2: np.ndarray, x: np.ndarray) -> Any:
    """Derivatives for Newton's method: analytic if the class has them, else
    forward differences (accurate enough for Newton, 3 times cheaper)."""
    if _analytic_derivatives(surface):
        return surface.derivatives(u1, u2)
    d = surface.domain
    h1, h2 = 1e-7 * d.span(0), 1e-7 * d.span(1)
    lo1, hi1 = d.u1
    lo2, hi2 = d.u2
    # step inward at the upper end of parameters that are not glued
    s1 = np.where((not d.glued[0]) & (u1 + h1 > hi1), -h1, h1)
    s2 = np.where((not d.glued[1]) & (u2 + h2 > hi2), -h2, h2)
    x1 = (surface.point(u1 + s1, u2) - x) / s1[:, None]
    x2 = (surface.point(u1, u2 + s2) - x) / s2[:, None]
    return x1, x2


def _newton(
    surface: Parametrized,
    o: np.ndarray,
    v: np.ndarray,
    uv: np.ndarray,
    s: np.ndarray,
    maxstep: np.ndarray,
    tol: float,
    steps: int = HIT_NEWTON_STEPS,
    cell: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newton on ``x(u) - o - s v = 0``; returns (uv, s, converged).

    With ``cell = (c0, c1)``, iterates that wander more than 1.5 patch widths
    from the patch ``[c0, c1]`` are given up (the caller subdivides)."""
    d = surface.domain
    uv = uv.copy()
    s = s.copy()
    conv = np.zeros(len(s), bool)
    act = np.arange(len(s))
    prev = np.full(len(s), np.inf)
    for _ in range(steps):
        if not len(act):
            break
        p = uv[act]
        x = surface.point(p[:, 0], p[:, 1])
        F = x - o[act] - s[act, None] * v[act]
        res = np.linalg.norm(F, axis=1)
        # polish to rounding level: stop when tiny, or when close and stagnating
        ok = res <= tol
        conv[act] = ok
        done = (res <= 1e-4 * tol) | (ok & (res > 0.5 * prev[act]))
        prev[act] = res
        keep = ~done & np.isfinite(res)
        act, p, F = act[keep], p[keep], F[keep]
        if not len(act):
            break
        x1, x2 = _fast_derivatives(surface, p[:, 0], p[:, 1], x[keep])
        w = -v[act]
        # solve [x1 x2 w] dz = -F by Cramer's rule
        c23 = _cross(x2, w)
        det = np.einsum("ij,ij->i", x1, c23)
        good = np.abs(det) > 1e-300
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            d1 = -np.einsum("ij,ij->i", F, c23) * inv
            d2 = -np.einsum("ij,ij->i", x1, _cross(F, w)) * inv
            d3 = -np.einsum("ij,ij->i", x1, _cross(x2, F)) * inv
        # limit the parameter step
        lim = maxstep[act]
        big = np.maximum(np.abs(d1) / lim[:, 0], np.abs(d2) / lim[:, 1])
        f = np.where(big > 1, 1.0 / np.where(big > 1, big, 1.0), 1.0)
        good &= np.isfinite(d1) & np.isfinite(d2) & np.isfinite(d3)
        act = act[good]
        uv[act, 0] += (f * d1)[good]
        uv[act, 1] += (f * d2)[good]
        s[act] += (f * d3)[good]
        uv[act] = d.wrap(uv[act])
        if cell is not None:
            act = act[_in_cell(surface, uv[act], cell[0][act], cell[1][act], 1.5)]
    return uv, s, conv


def _in_cell(
    surface: Parametrized, uv: np.ndarray, c0: np.ndarray, c1: np.ndarray, margin: float = 0.05
) -> np.ndarray:
    d = surface.domain
    inside = np.ones(len(uv), bool)
    for i in (0, 1):
        w = c1[:, i] - c0[:, i]
        lo, hi = c0[:, i] - margin * w, c1[:, i] + margin * w
        x = uv[:, i]
        if d.periodic[i] is True:
            span = d.span(i)
            x = lo + np.mod(x - lo, span)
        inside &= (x >= lo) & (x <= hi)
    return inside


def _local_second_root(
    surface: Parametrized, o: np.ndarray, v: np.ndarray, uv0: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Start of Newton for the root next to the own root ``(uv0, 0)``: the local
    quadratic approximation gives ``s = 2 (v . N) / II(a)`` with ``J a`` the
    tangential part of ``v``."""
    x1, x2 = surface.derivatives(uv0[:, 0], uv0[:, 1])
    x11, x12, x22 = surface.second_derivatives(uv0[:, 0], uv0[:, 1])
    n = _cross(x1, x2)
    with np.errstate(divide="ignore", invalid="ignore"):
        n /= np.linalg.norm(n, axis=1, keepdims=True)
    vn = np.einsum("ij,ij->i", v, n)
    g11 = np.einsum("ij,ij->i", x1, x1)
    g12 = np.einsum("ij,ij->i", x1, x2)
    g22 = np.einsum("ij,ij->i", x2, x2)
    b1 = np.einsum("ij,ij->i", x1, v)
    b2 = np.einsum("ij,ij->i", x2, v)
    g = g11 * g22 - g12 * g12
    with np.errstate(divide="ignore", invalid="ignore"):  # g = 0: a pole or pinch point (NaN)
        a1 = (g22 * b1 - g12 * b2) / g
        a2 = (g11 * b2 - g12 * b1) / g
        L11 = np.einsum("ij,ij->i", n, x11)
        L12 = np.einsum("ij,ij->i", n, x12)
        L22 = np.einsum("ij,ij->i", n, x22)
        II = L11 * a1 * a1 + 2 * L12 * a1 * a2 + L22 * a2 * a2
        s = 2 * vn / II
    return uv0 + s[:, None] * np.stack([a1, a2], axis=1), s


def hits(
    surface: Parametrized,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray | None = None,
    count: bool = False,
) -> np.ndarray:
    """Numeric :meth:`Surface.hits` (see there); with ``count``, the number
    of distinct roots of each ray instead (:meth:`Surface.hit_count`).

    Rays are tested in chunks of ``HIT_CHUNK_RAYS`` so that memory stays
    bounded; a chunk whose rays meet more than ``HIT_MAX_CANDIDATES`` patch
    boxes in all (a surface winding over itself very many times) is refused
    with a ValueError before any Newton step.
    """
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    v = np.asarray(directions, dtype=float).reshape(-1, 3)
    nray = len(o)
    smax = np.broadcast_to(np.asarray(smax, dtype=float), (nray,)).copy()
    own = np.zeros(nray, np.int8) if own is None else np.asarray(own).reshape(-1)
    out = np.zeros(nray, np.int64 if count else bool)
    if not nray:
        return out
    H = _hierarchy(surface)
    for a in range(0, nray, HIT_CHUNK_RAYS):
        b = slice(a, a + HIT_CHUNK_RAYS)
        out[b] = _hits_chunk(surface, H, o[b], v[b], smax[b], own[b], count)
    return out


def _hits_chunk(
    surface: Parametrized,
    H: _Hierarchy,
    o: np.ndarray,
    v: np.ndarray,
    smax: np.ndarray,
    own: Any,
    count: bool = False,
) -> np.ndarray:
    """Hits of one chunk of rays; with ``count``, every patch is searched
    (not only until a ray's first root) and the distinct roots are counted."""
    nray = len(o)
    out = np.zeros(nray, bool)
    roots_r, roots_s = [], []
    d = surface.domain
    size = H.size
    vnorm = np.linalg.norm(v, axis=1)
    vnorm = np.where(vnorm > 0, vnorm, 1.0)
    s_eps = SELF_HIT_RTOL * size / vnorm
    s_self = np.where(own == CONTOUR, CONTOUR_SELF_RTOL * size / vnorm, s_eps)
    tol = 1e-10 * size
    r, i, j, s0, s1 = _candidates(H, o, v, smax)
    c0 = np.stack([H.lo1 + i * H.h1, H.lo2 + j * H.h2], axis=1)
    c1 = c0 + np.array([H.h1, H.h2])
    own_uv = np.full((nray, 2), np.nan)
    for depth in range(HIT_MAX_DEPTH + 1):
        if not count:
            keep = ~out[r]
            r, c0, c1, s0, s1 = r[keep], c0[keep], c1[keep], s0[keep], s1[keep]
        if not len(r):
            break
        uv = 0.5 * (c0 + c1)
        s = 0.5 * (s0 + s1)
        s = np.where(np.isfinite(s), s, s0)
        maxstep = 2.0 * (c1 - c0)
        uv, s, conv = _newton(surface, o[r], v[r], uv, s, maxstep, tol, cell=(c0, c1))
        x_off = np.linalg.norm(surface.point(uv[:, 0], uv[:, 1]) - o[r], axis=1)
        selfroot = conv & (own[r] != OFF) & ((s < s_self[r]) | (x_off < s_self[r] * vnorm[r]))
        valid = conv & ~selfroot & (s > s_eps[r]) & (s < smax[r])
        out[r[valid]] = True
        if count:
            roots_r.append(r[valid])
            roots_s.append(s[valid])
        m = selfroot & (own[r] == ON)
        own_uv[r[m]] = uv[m]
        if depth == HIT_MAX_DEPTH:
            break
        # subdivide patches where Newton failed or left the patch
        redo = ~valid & (count | ~out[r]) & ~(conv & _in_cell(surface, uv, c0, c1, 1.5))
        if not redo.any():
            break
        r, c0, c1 = r[redo], c0[redo], c1[redo]
        mid = 0.5 * (c0 + c1)
        nr = np.repeat(r, 4)
        q0 = np.repeat(c0, 4, axis=0)
        q1 = np.repeat(c1, 4, axis=0)
        m4 = np.repeat(mid, 4, axis=0)
        a = np.tile([0, 1, 0, 1], len(r)).astype(bool)
        b = np.tile([0, 0, 1, 1], len(r)).astype(bool)
        n0 = np.stack([np.where(a, m4[:, 0], q0[:, 0]), np.where(b, m4[:, 1], q0[:, 1])], 1)
        n1 = np.stack([np.where(a, q1[:, 0], m4[:, 0]), np.where(b, q1[:, 1], m4[:, 1])], 1)
        blo, bhi = _sub_boxes(surface, n0, n1, size)
        ok, t0, t1 = _slab(o[nr], _inverse(v[nr]), blo, bhi, smax[nr])
        r, c0, c1, s0, s1 = nr[ok], n0[ok], n1[ok], t0[ok], t1[ok]
    # rays from points on the surface: the root next to the own root
    cand = np.nonzero((own == ON) & ~out & np.isfinite(own_uv[:, 0]))[0]
    if count:  # the root next to the own one may be missing while others were found
        cand = np.nonzero((own == ON) & np.isfinite(own_uv[:, 0]))[0]
    if len(cand):
        uv, s = _local_second_root(surface, o[cand], v[cand], own_uv[cand])
        ok = np.isfinite(s) & (s > 0) & np.isfinite(uv).all(axis=1)
        cand, uv, s = cand[ok], uv[ok], s[ok]
        if len(cand):
            uv = surface.domain.wrap(uv)
            step = np.tile([[d.span(0) / 8, d.span(1) / 8]], (len(cand), 1))
            uv, s, conv = _newton(surface, o[cand], v[cand], uv, s, step, tol)
            ok = conv & (s > s_eps[cand]) & (s < smax[cand])
            out[cand[ok]] = True
            if count:
                roots_r.append(cand[ok])
                roots_s.append(s[ok])
    if not count:
        return out
    if not roots_r:  # no ray met a patch box
        return np.zeros(nray, dtype=np.int64)
    return _distinct(np.concatenate(roots_r), np.concatenate(roots_s), 1e-7 * size / vnorm, nray)


def _distinct(r: np.ndarray, s: np.ndarray, gap: np.ndarray, nray: int) -> np.ndarray:
    """Number of distinct roots ``s`` of every ray (roots of one ray closer
    than ``gap[r]`` are one: the same root found from neighbouring patches).

    >>> r, s = np.array([0, 0, 0, 2]), np.array([1.0, 1.0 + 1e-12, 2.0, 5.0])
    >>> _distinct(r, s, np.full(3, 1e-9), 3).tolist()
    [2, 0, 1]
    """
    order = np.lexsort((s, r))
    r, s = r[order], s[order]
    first = np.ones(len(r), dtype=bool)
    first[1:] = (r[1:] != r[:-1]) | (s[1:] - s[:-1] > gap[r[1:]])
    return np.bincount(r[first], minlength=nray)
