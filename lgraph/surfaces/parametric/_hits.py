"""The numeric ray test of a parametrized surface: the default of
:meth:`Surface.hits <lgraph.surfaces._base.Surface.hits>`.

The bounding boxes of :mod:`~lgraph.surfaces.parametric._boxes` select
candidate leaf patches; their facets
(:mod:`~lgraph.surfaces.parametric._facets`) give Newton's method on
``x(u1, u2) - (o + s v) = 0`` its starts, drop the patches that hold no
root and mark those where roots may hide, which are split in four (up to
``HIT_MAX_DEPTH`` levels; see docs/mathematics.rst, "The numeric ray
test").  A ray from a point on the surface (``own == ON``) never counts its
own root ``s = 0``; a second root close to it (near the surface's own
contour) is found from the local quadratic approximation of the surface:
``s = 2 (v . N) / II(a)`` with ``J a`` the tangential part of ``v``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..._own import CONTOUR, OFF, ON
from ..._tolerance import HIT_CHUNK_RAYS, SELF_HIT_RTOL
from ...geometry.vectors import cross as _cross
from ._boxes import _candidates, _cell_pad, _Hierarchy, _hierarchy
from ._facets import Ring, facet_test, fold_free

if TYPE_CHECKING:
    from .._domain import Parametrized

__all__ = ["hits", "nearest_roots"]

#: extra subdivision levels where Newton's method fails in a leaf
HIT_MAX_DEPTH = 3
#: Newton iterations from the centre of a patch still ambiguous at the finest level
HIT_NEWTON_STEPS = 30
#: Newton iterations from a start on a facet (within the padding of the root):
#: converging quadratically, it needs 3 or 4; one that has not converged by
#: then (a root nearly double, at a grazing ray) splits its patch
HIT_FACET_STEPS = 10
#: roots of one ray closer than this (relative to the surface size) along it
#: are one root found from neighbouring patches: a grazing ray's double root
#: is found to about the square root of Newton's tolerance, 1e-5 of the
#: surface, in every patch around it (clusters of up to 16 "roots" within
#: 2e-5 on a torus at 1e-7 made sheet counts of 5 to 10)
DISTINCT_RTOL = 1e-5
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
    # both neighbours in one call of the user's function
    y = surface.point(np.concatenate([u1 + s1, u1]), np.concatenate([u2, u2 + s2]))
    m = len(u1)
    return (y[:m] - x) / s1[:, None], (y[m:] - x) / s2[:, None]


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
        act, f = act[good], f[good]
        uv[act, 0] += f * d1[good]
        uv[act, 1] += f * d2[good]
        s[act] += f * d3[good]
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
    nearest: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Numeric :meth:`Surface.hits` (see there); with ``count``, the number
    of distinct roots of each ray instead (:meth:`Surface.hit_count`); with
    ``nearest`` (and ``count``), the parameters and ``s`` of each ray's root
    nearest to its origin are written into those arrays
    (:func:`nearest_roots`).

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
    view = _common_view(H, o, v, smax)
    free = None if view is None else fold_free(H.grid, *view)  # (n, n) leaves
    for a in range(0, nray, HIT_CHUNK_RAYS):
        b = slice(a, a + HIT_CHUNK_RAYS)
        near = None if nearest is None else (nearest[0][b], nearest[1][b])
        out[b] = _hits_chunk(surface, H, o[b], v[b], smax[b], own[b], count, view, free, near)
    return out


def nearest_roots(
    surface: Parametrized,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The root of each ray ``origins + s * directions``, ``0 < s < smax``,
    nearest to its origin (arguments as :func:`hits`; a ray's own root left
    out): its parameters ``(n, 2)`` and ``s`` ``(n,)``, NaN where the ray
    meets the patch nowhere."""
    n = len(np.asarray(origins).reshape(-1, 3))
    uv, s = np.full((n, 2), np.nan), np.full(n, np.nan)
    hits(surface, origins, directions, smax, own, True, (uv, s))
    return uv, s


def _common_view(H: _Hierarchy, o: np.ndarray, v: np.ndarray, smax: np.ndarray) -> Any:
    """``(eye, None)`` when all rays end at one eye (a central view), ``(None,
    direction)`` when all run one way to infinity (a parallel view), else None."""
    if np.isfinite(smax).all():
        ends = o + smax[:, None] * v
        if np.ptp(ends, axis=0).max() <= 1e-9 * H.size:
            return ends[0], None
    elif np.isinf(smax).all():
        w = v / np.linalg.norm(v, axis=1, keepdims=True)
        if np.ptp(w, axis=0).max() <= 1e-12:
            return None, w[0]
    return None


def _hits_chunk(
    surface: Parametrized,
    H: _Hierarchy,
    o: np.ndarray,
    v: np.ndarray,
    smax: np.ndarray,
    own: Any,
    count: bool = False,
    view: Any = None,
    free: np.ndarray | None = None,
    nearest: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Hits of one chunk of rays; with ``count``, every patch is searched
    (not only until a ray's first root) and the distinct roots are counted;
    with ``nearest`` (and ``count``), the parameters and ``s`` of each ray's
    root nearest to its origin are written into those arrays instead.

    Each (ray, leaf patch) pair the boxes let through is judged by its facets
    (:func:`~lgraph.surfaces.parametric._facets.facet_test`, no evaluation of
    the surface): Newton's method starts where a facet lies around the ray;
    ambiguous patches, and those where Newton failed or left the patch, are
    split in four (up to ``HIT_MAX_DEPTH`` levels); at the last level an
    ambiguous patch is searched by Newton's method from its centre."""
    nray = len(o)
    out = np.zeros(nray, bool)
    roots_r, roots_s, roots_uv = [], [], []
    d = surface.domain
    size = H.size
    vnorm = np.linalg.norm(v, axis=1)
    vnorm = np.where(vnorm > 0, vnorm, 1.0)
    s_eps = SELF_HIT_RTOL * size / vnorm
    s_self = np.where(own == CONTOUR, CONTOUR_SELF_RTOL * size / vnorm, s_eps)
    near_self = CONTOUR_SELF_RTOL * size
    tol = 1e-10 * size
    r, i, j, _, _ = _candidates(H, o, v, smax)
    leaf = i * H.n + j
    c0 = np.stack([H.lo1 + i * H.h1, H.lo2 + j * H.h2], axis=1)
    c1 = c0 + np.array([H.h1, H.h2])
    S = np.take(H.leaf_samples, leaf, axis=0)
    pad = H.leaf_pad[leaf]
    own_uv = np.full((nray, 2), np.nan)

    def newton(pr: np.ndarray, uv: np.ndarray, s: np.ndarray, steps: int) -> np.ndarray:
        """Newton's method for pairs ``pr`` from ``(uv, s)``; records the roots
        and returns which pairs failed (did not converge inside their patch)."""
        rr = r[pr]
        a, b = c0[pr], c1[pr]
        uv, s, conv = _newton(surface, o[rr], v[rr], uv, s, 2.0 * (b - a), tol, steps, (a, b))
        x_off = np.linalg.norm(surface.point(uv[:, 0], uv[:, 1]) - o[rr], axis=1)
        # the own root: at the ray's origin, or (a ray grazing the surface there,
        # where Newton creeps to it) within CONTOUR_SELF_RTOL of it; a true
        # second root that close is found from the local quadratic form below
        selfroot = conv & (own[rr] != OFF) & ((s < s_self[rr]) | (x_off < near_self))
        valid = conv & ~selfroot & (s > s_eps[rr]) & (s < smax[rr])
        out[rr[valid]] = True
        if count:
            roots_r.append(rr[valid])
            roots_s.append(s[valid])
            roots_uv.append(uv[valid])
        m = selfroot & (own[rr] == ON)
        own_uv[rr[m]] = uv[m]
        return ~valid & ~(conv & _in_cell(surface, uv, a, b, 1.5))

    ring = Ring(H.grid, 2 * i, 2 * j, H.periodic, None, free)  # the leaves' neighbours
    for depth in range(HIT_MAX_DEPTH + 1):
        if not count:
            keep = ~out[r]
            r, c0, c1, S, pad = r[keep], c0[keep], c1[keep], S[keep], pad[keep]
            ring = ring.take(keep)
        if not len(r):
            break
        pair, uv, s, near, redo = facet_test(S, pad, o[r], v[r], smax[r], c0, c1, ring)
        if count and depth < HIT_MAX_DEPTH:
            # a patch to be split is searched in its quarters: no start here
            go = ~redo[pair]
            pair, uv, s, near = pair[go], uv[go], s[go], near[go]
        if len(pair):
            failed = newton(pair, uv, s, HIT_FACET_STEPS)
            # split where a start inside a facet failed, or every near miss's
            redo[pair[failed & ~near]] = True
            missed = np.zeros(len(r), dtype=bool)
            missed[pair[near]] = True
            missed[pair[near & ~failed]] = False
            redo |= missed
        if not count:
            redo &= ~out[r]
        if depth == HIT_MAX_DEPTH:
            # still ambiguous at the finest level: Newton from the patch's centre
            pr = np.flatnonzero(redo)
            if len(pr):
                q = S[pr] - o[r[pr], None, :]
                z = np.einsum("pkc,pc->pk", q, v[r[pr]]) / (vnorm[r[pr]] ** 2)[:, None]
                z = np.where(np.isfinite(z), z, np.nan)
                z[np.isnan(z).all(1)] = 0.0  # no finite sample: start at the origin
                s_mid = np.nanmean(z, 1)
                newton(
                    pr, 0.5 * (c0[pr] + c1[pr]), np.clip(s_mid, 0.0, smax[r[pr]]), HIT_NEWTON_STEPS
                )
            break
        pr = np.flatnonzero(redo)
        if not len(pr):
            break
        parent_free = ring.patch_free()
        r, c0, c1, S, pad, quarter_free, G = _split(surface, r[pr], c0[pr], c1[pr], size, view)
        q = np.tile(np.arange(4), len(pr))  # quarter 2 a + b, the order of _split
        sib = None
        if parent_free is not None:  # a patch without contour: its quarters too
            sib = parent_free[pr, None, None] | quarter_free
        ring = Ring(
            G, 2 * (q // 2), 2 * (q % 2), (False, False), np.repeat(np.arange(len(pr)), 4), sib
        )
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
                roots_uv.append(uv[ok])
    if not count:
        return out
    if nearest is not None:  # the root nearest to each origin
        if roots_r:
            r, s, uv = (np.concatenate(x) for x in (roots_r, roots_s, roots_uv))
            order = np.lexsort((s, r))
            r, s, uv = r[order], s[order], uv[order]
            first = np.ones(len(r), dtype=bool)
            first[1:] = r[1:] != r[:-1]
            nearest[0][r[first]], nearest[1][r[first]] = uv[first], s[first]
        return np.zeros(nray, dtype=np.int64)
    if not roots_r:  # no ray met a patch box
        return np.zeros(nray, dtype=np.int64)
    return _distinct(
        np.concatenate(roots_r), np.concatenate(roots_s), DISTINCT_RTOL * size / vnorm, nray
    )


def _split(
    surface: Parametrized, r: np.ndarray, c0: np.ndarray, c1: np.ndarray, size: float, view: Any
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, Any, np.ndarray]:
    """The four quarters of patches ``[c0, c1]`` (of rays ``r``): their rays,
    corners, 3 x 3 samples, paddings, (with a common ``view``) which of them
    hold no contour (``(m, 2, 2)``), and the ``5 x 5`` grid of samples of every patch."""
    f = np.linspace(0.0, 1.0, 5)
    u1 = c0[:, 0, None] + (c1[:, 0] - c0[:, 0])[:, None] * f
    u2 = c0[:, 1, None] + (c1[:, 1] - c0[:, 1])[:, None] * f
    G = surface.point(u1[:, :, None], u2[:, None, :])  # (m, 5, 5, 3)
    a = np.array([0, 0, 1, 1])
    b = np.array([0, 1, 0, 1])
    rows = 2 * a[:, None] + np.arange(3)  # (4, 3)
    cols = 2 * b[:, None] + np.arange(3)
    Q = G[:, rows[:, :, None], cols[:, None, :]]  # (m, 4, 3, 3, 3)
    m = len(r)
    Q = Q.reshape(4 * m, 3, 3, 3)
    with np.errstate(invalid="ignore"):
        pad = _cell_pad(Q) + 1e-9 * size
    half = 0.5 * (c1 - c0)
    n0 = (c0[:, None, :] + np.stack([a, b], 1)[None] * half[:, None, :]).reshape(4 * m, 2)
    free = None if view is None else fold_free(G, *view)  # (m, 2, 2)
    corners = n0, n0 + np.repeat(half, 4, axis=0)
    return np.repeat(r, 4), *corners, Q.reshape(4 * m, 9, 3), pad, free, G


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
