"""Lines of self-intersection: where a surface passes through itself.

A point of self-intersection has two parameter pairs, ``x(a) = x(b)`` with
``a != b``.  :class:`SelfIntersection` finds them numerically:

1. **Candidates**: the padded boxes of the surface's parameter-grid patches
   (the hierarchy the numeric ray test uses,
   :mod:`lgraph.surfaces.parametric._boxes`) are intersected with each other level by
   level; overlapping leaf pairs that are not neighbours in the parameter
   plane (periodic seams included) may hold a piece of the curve.
2. **Crossings**: the curve's preimage crosses the edges of the traced cells
   (the patch grid shifted by a generic fraction of a cell; each pair tests
   the four traced cells overlapping its patch).  On every edge, Newton's
   method solves the three equations ``x(edge(s)) = x(b)`` for
   ``(s, b1, b2)`` from the partner patch's centre; solutions on the edge and
   near the partner patch are kept, so both preimages are found.
3. **Curves**: crossings are joined cell by cell (like marching squares)
   into polylines in the parameter plane.  Of the two preimages of each
   point one is drawn: a polyline whose partners lie on one already taken is
   dropped (it is that one's other preimage, or the same curve seen from a
   neighbouring cell column); along a polyline that holds partners of its own
   points (a Whitney umbrella's segment, mirrored about the pinch point; Boy's
   surface, where one closed preimage covers the three loops through the
   triple point twice) the points met before their partners are kept, each
   run carried on to where the partner changes sheets.  Wherever the renderer
   evaluates a curve, its spline (and its partner's) is projected onto
   ``x(a) = x(b)`` by minimal-norm Gauss-Newton steps in the four parameters,
   so drawn points lie on both sheets to rounding level.

Curves end a patch or two short of points where the preimages meet (the
pinch point of a Whitney umbrella), where the two sheets become tangent.
Tested on the Whitney umbrella, a tube piercing itself, the Klein bottles,
the Roman surface, the cross-cap and Boy's surface.

>>> import numpy as np
>>> import lgraph as lg
>>> umbrella = lg.ParametricSurface(
...     lambda u, v: np.stack(np.broadcast_arrays(u * v, u, v * v), -1), (-1, 1), (-1, 1))
>>> (b,) = SelfIntersection().batches(umbrella, None)
>>> xyz, uv = b.evaluate(np.zeros(3, int), np.linspace(b.t0[0], b.t1[0], 3))
>>> bool(np.abs(xyz[:, :2]).max() < 1e-12), bool(np.abs(uv[:, 0]).max() < 1e-12)
(True, True)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from ..curves import CurveBatch
from . import Family, register_family
from ._preimages import one_preimage

if TYPE_CHECKING:
    from ..scene.projectors import Projector
    from ..surfaces._base import Surface

__all__ = ["SelfIntersection", "self_intersection_points"]

#: Newton iterations for an edge crossing
EDGE_NEWTON_STEPS = 12
#: edge Newton gives up on a row that strays this many cells from its edge or
#: from its partner's patch
WANDER = 1.0
#: leaf pairs this close in the parameter grid (in cells) are neighbours, not
#: candidates (padded boxes of nearby patches always overlap)
NEAR_CELLS = 2
#: the traced grid is the leaf grid shifted by this fraction of a cell
GRID_SHIFT = 0.3819660112501051
#: Gauss-Newton steps projecting evaluated points onto the curve
PROJECT_STEPS = 4
#: crossings in one cell whose partners are more than this fraction of the grid
#: apart lie on different pairs of sheets (a triple point): they are not joined
#: (partners of one branch move up to about 1/6 of the grid a cell, on a tube
#: crossing itself; the Roman surface's triple point 1/2)
PARTNER_FRACTION = 0.25
#: branches reaching less far than this (relative to the surface size: invisible) are
#: dropped: pieces at a triple or pinch point where a preimage is a pole
MIN_EXTENT = 1e-4
#: accepted crossing: |x(a) - x(b)| below this, relative to the surface size
ACCEPT_RTOL = 1e-11


def _leaf_pairs(surface: Surface) -> tuple[np.ndarray, np.ndarray, int]:
    """Index pairs ``(p, q)`` (flat, ``p < q``) of overlapping leaves more than
    ``NEAR_CELLS`` apart."""
    from ..surfaces.parametric._boxes import _hierarchy

    H = _hierarchy(surface)
    n = H.n
    pairs = np.zeros((1, 2), int)  # flat indices at the current level (root: 0, 0)
    di = np.array([0, 1, 0, 1])
    dj = np.array([0, 0, 1, 1])
    for lvl in range(1, len(H.flat)):
        m = 1 << (lvl - 1)  # boxes per row at the parent level
        i1, j1 = pairs[:, 0] // m, pairs[:, 0] % m
        i2, j2 = pairs[:, 1] // m, pairs[:, 1] % m
        c1 = ((2 * i1)[:, None] + di) * (2 * m) + (2 * j1)[:, None] + dj  # (k, 4)
        c2 = ((2 * i2)[:, None] + di) * (2 * m) + (2 * j2)[:, None] + dj
        a = np.repeat(c1, 4, axis=1).ravel()
        b = np.tile(c2, (1, 4)).ravel()
        # children of one box: each unordered pair once; children of two boxes:
        # all 16 pairs (a child of the first may have the larger index)
        keep = (a <= b) | np.repeat(pairs[:, 0] != pairs[:, 1], 16)
        a, b = np.minimum(a[keep], b[keep]), np.maximum(a[keep], b[keep])
        lo, hi = H.flat[lvl]
        ov = np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)
        pairs = np.stack([a[ov], b[ov]], axis=1)
    d = surface.domain
    i1, j1, i2, j2 = pairs[:, 0] // n, pairs[:, 0] % n, pairs[:, 1] // n, pairs[:, 1] % n
    di_ = np.abs(i1 - i2)
    dj_ = np.abs(j1 - j2)
    if d.periodic[0] is True:
        di_ = np.minimum(di_, n - di_)
    if d.periodic[1] is True:
        dj_ = np.minimum(dj_, n - dj_)
    far = (di_ > NEAR_CELLS) | (dj_ > NEAR_CELLS)
    if any(d.twisted):  # neighbours across a twisted seam, in cells
        far &= _cell_gap(d, np.stack([i1, j1], 1), np.stack([i2, j2], 1), n) > NEAR_CELLS
    return pairs[far, 0], pairs[far, 1], n


def _cell_gap(d: Any, c1: np.ndarray, c2: np.ndarray, n: int) -> np.ndarray:
    """Distance in cells (max norm) of cells ``c1`` and ``c2`` of an ``n x n``
    grid, across glued seams."""
    lo = np.array([d.u1[0], d.u2[0]])
    h = np.array([d.span(0), d.span(1)]) / n
    p, q = (c1 + 0.5) * h + lo, (c2 + 0.5) * h + lo
    return np.abs((d.nearest_image(p, q) - p) / h).max(axis=1)


def _plain(d: Any) -> tuple[bool, bool]:
    """Which parameters wrap plainly (a twisted one is traced as an interval)."""
    return (d.periodic[0] is True, d.periodic[1] is True)


def _solve_edges(surface: Surface, a0, a1, bc, h, size: float):  # noqa: ANN001, ANN202
    """Newton on ``x(a0 + s (a1 - a0)) = x(b)`` for ``(s, b)``, all edges at once
    (rows leaving the neighbourhood of their edge and patch are dropped).
    Returns ``(s, b, ok)``."""
    m = len(a0)
    d = surface.domain
    s = np.full(m, 0.5)
    b = bc.copy()
    e = a1 - a0
    ok = np.ones(m, bool)
    act = np.arange(m)
    for _ in range(EDGE_NEWTON_STEPS):
        if not len(act):
            break
        # iterates past an edge that is not glued are evaluated on the edge
        # (the caller drops the rows that end outside)
        a = d.clip(a0[act] + s[act, None] * e[act])
        bb = b[act]
        g = surface.points(a) - surface.points(bb)
        xa1, xa2 = surface.derivatives(a[:, 0], a[:, 1])
        xb1, xb2 = surface.derivatives(bb[:, 0], bb[:, 1])
        ea = e[act]
        J = np.stack([xa1 * ea[:, :1] + xa2 * ea[:, 1:], -xb1, -xb2], axis=2)  # (n, 3, 3)
        with np.errstate(all="ignore"):
            det = np.linalg.det(J)
            good = np.isfinite(det) & (np.abs(det) > 1e-300) & np.all(np.isfinite(g), axis=1)
            step = np.zeros((len(act), 3))
            if good.any():
                step[good] = np.linalg.solve(J[good], -g[good][:, :, None])[:, :, 0]
        s[act] += step[:, 0]
        b[act] = d.clip(b[act] + step[:, 1:])
        ok[act] &= good
        # rows that wander from their edge or from their partner's patch are lost
        # causes (a crossing past the edge, or with a partner in another patch, is
        # found from that edge's cell, or from a pair with that patch)
        far = np.abs((d.nearest_image(bc[act], b[act]) - bc[act]) / h).max(axis=1)
        near = (s[act] > -WANDER) & (s[act] < 1 + WANDER) & (far < 1 + WANDER)
        ok[act] &= near
        moving = np.abs(step).max(axis=1) > 1e-15 * (1 + np.abs(s[act]))
        act = act[good & near & moving]
    a = d.clip(a0 + s[:, None] * e)
    res = np.full(m, np.inf)
    res[ok] = np.linalg.norm(surface.points(a[ok]) - surface.points(b[ok]), axis=1)
    ok &= np.isfinite(res) & (res <= ACCEPT_RTOL * size)
    return s, b, ok


def self_intersection_points(surface: Surface) -> dict:
    """All crossings of the self-intersection's preimages with the edges of the
    traced cells: ``{"a": (m, 2), "b": (m, 2), "cells": (m, 2)}`` (the partner
    parameters ``b`` with ``x(a) = x(b)``, and the two cells each crossing's
    edge borders, as flat ids)."""
    d = surface.domain
    per = _plain(d)
    p, q, n = _leaf_pairs(surface)
    lo = np.array([d.u1[0], d.u2[0]])
    h = np.array([d.span(0), d.span(1)]) / n
    size = surface.size
    A, B, C = [], [], []
    # traced cells: the leaves shifted by a generic fraction of a cell (a curve
    # along a grid line, u = 0 say, must still cross edges)
    for first, second in ((p, q), (q, p)):
        # the four traced cells overlapping each leaf (one before the first leaf
        # where a parameter does not wrap), each once per partner leaf
        i, j = first // n, first % n
        ci = np.concatenate([i, i - 1, i, i - 1])
        cj = np.concatenate([j, j, j - 1, j - 1])
        if per[0]:
            ci %= n
        if per[1]:
            cj %= n
        ci, cj, partner = np.unique(np.stack([ci, cj, np.tile(second, 4)]), axis=1)
        cb = (np.stack([partner // n, partner % n], axis=1) + 0.5) * h + lo
        corner = (np.stack([ci, cj], axis=1) + GRID_SHIFT) * h + lo
        # edges: along u1 at cj and cj + 1, along u2 at ci and ci + 1; each
        # borders the cell (ci, cj) and the neighbour across it
        for off0, off1, nb in (
            ((0, 0), (1, 0), (0, -1)),
            ((0, 1), (1, 1), (0, 1)),
            ((0, 0), (0, 1), (-1, 0)),
            ((1, 0), (1, 1), (1, 0)),
        ):
            a0 = corner + np.array(off0) * h
            a1 = corner + np.array(off1) * h
            for ax in (0, 1):  # cells overhanging the patch end at its edge
                if not per[ax]:
                    a0[:, ax] = np.clip(a0[:, ax], *d.range(ax))
                    a1[:, ax] = np.clip(a1[:, ax], *d.range(ax))
            s, b, ok = _solve_edges(surface, a0, a1, cb, h, size)
            ok &= (s >= 0) & (s <= 1)
            pa = a0 + s[:, None] * (a1 - a0)
            for ax in (0, 1):  # on the drawn patch (a shifted cell may overhang it)
                if not per[ax]:
                    ok &= (pa[:, ax] >= d.range(ax)[0]) & (pa[:, ax] <= d.range(ax)[1])
            # the partner must be another point of the patch, not the trivial b = a
            gap = np.abs(b - pa)
            for ax in (0, 1):
                if per[ax]:
                    gap[:, ax] = np.abs(
                        np.mod(gap[:, ax] + 0.5 * n * h[ax], n * h[ax]) - 0.5 * n * h[ax]
                    )
            ok &= np.any(gap > NEAR_CELLS * h, axis=1)
            if any(d.twisted):  # nor the same point across a twisted seam
                ok &= np.abs((d.nearest_image(pa, b) - pa) / h).max(axis=1) > NEAR_CELLS
            bw = d.wrap(b, clip=False)
            for ax in (0, 1):
                if not d.glued[ax]:
                    lo_, hi_ = d.range(ax)
                    ok &= (bw[:, ax] >= lo_ - 1e-9 * h[ax]) & (bw[:, ax] <= hi_ + 1e-9 * h[ax])
            b = bw
            if not ok.any():
                continue
            own = np.stack([ci[ok], cj[ok]], axis=1)
            other = own + np.array(nb)
            A.append(d.wrap(pa[ok], clip=False))
            B.append(b[ok])
            C.append(np.stack([_cell_id(own, n, d), _cell_id(other, n, d)], axis=1))
    if not A:
        empty = np.empty((0, 2))
        return {"a": empty, "b": empty, "cells": np.empty((0, 2), int), "n": n}
    a, b, c = np.concatenate(A), np.concatenate(B), np.concatenate(C)
    # the same crossing found from two cells: one copy (cells and position)
    key = np.round(np.column_stack([np.sort(c, axis=1), a / h, b / h]), 6)
    _, first = np.unique(key, axis=0, return_index=True)
    first = np.sort(first)
    return {"a": a[first], "b": b[first], "cells": c[first], "n": n}


def _cell_id(cell: np.ndarray, n: int, d: Any) -> np.ndarray:
    """Flat ids of traced cells ``(i, j)``, ``-1 <= i, j <= n`` (wrapped where periodic)."""
    i, j = cell[:, 0].copy(), cell[:, 1].copy()
    if d.periodic[0] is True:
        i %= n
    if d.periodic[1] is True:
        j %= n
    return (i + 1) * (n + 2) + (j + 1)


def _trace(points: dict, surface: Surface) -> list[tuple[np.ndarray, bool]]:
    """Crossings joined into polylines: ``(index order, closed)`` per curve."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components, depth_first_order

    a = points["a"]
    m = len(a)
    if m < 2:
        return []
    cells = points["cells"].T.ravel()
    pts = np.concatenate([np.arange(m), np.arange(m)])
    order = np.argsort(cells, kind="stable")
    cells, pts = cells[order], pts[order]
    # join the crossings on the edges of each cell (two: a segment; more: nearest pairs)
    rows, cols = [], []
    starts = np.flatnonzero(np.r_[True, cells[1:] != cells[:-1]])
    ends = np.r_[starts[1:], len(cells)]
    d = surface.domain
    h = np.array([d.span(0), d.span(1)]) / points["n"]
    b_all = points["b"]

    def partners_apart(i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """Crossings whose partners lie on different sheets (as at a triple
        point): more than ``PARTNER_FRACTION`` of the grid apart, across seams."""
        bi, bj = b_all[i], b_all[j]
        gap = np.abs((d.nearest_image(bi, bj) - bi) / h).max(axis=-1)
        return gap > PARTNER_FRACTION * points["n"]

    for s0, s1 in zip(starts.tolist(), ends.tolist()):  # one step per crossed cell
        k = pts[s0:s1]
        if len(k) == 2:
            if not partners_apart(k[:1], k[1:])[0]:
                rows.append(k[0])
                cols.append(k[1])
        elif len(k) > 2:
            dist = np.linalg.norm(a[k][:, None] - a[k][None], axis=2)
            dist[partners_apart(k[:, None], k[None, :])] = np.inf
            np.fill_diagonal(dist, np.inf)
            used: set[int] = set()
            for flat in np.argsort(dist, axis=None).tolist():
                x, y = divmod(flat, len(k))
                if x in used or y in used or x >= y or not np.isfinite(dist[x, y]):
                    continue
                used |= {x, y}
                rows.append(k[x])
                cols.append(k[y])
    if not rows:
        return []
    G = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(m, m)).tocsr()
    G = G + G.T
    ncomp, labels = connected_components(G, directed=False)
    deg = np.asarray((G > 0).sum(axis=1)).ravel()
    out = []
    for c in range(ncomp):
        members = np.flatnonzero(labels == c)
        if len(members) < 3:
            continue
        ends_ = members[deg[members] == 1]
        start = int(ends_[0]) if len(ends_) else int(members[0])
        order = depth_first_order(G, start, directed=False, return_predecessors=False)
        out.append((order, len(ends_) == 0))
    return out


def _project(surface: Surface, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Minimal-norm Gauss-Newton steps onto ``x(a) = x(b)`` (4 unknowns, 3
    equations), the iterates kept in the rectangle."""
    d = surface.domain
    a, b = d.clip(a), d.clip(b)
    for _ in range(PROJECT_STEPS):
        g = surface.points(a) - surface.points(b)
        xa1, xa2 = surface.derivatives(a[:, 0], a[:, 1])
        xb1, xb2 = surface.derivatives(b[:, 0], b[:, 1])
        J = np.stack([xa1, xa2, -xb1, -xb2], axis=2)  # (n, 3, 4)
        JJ = J @ np.swapaxes(J, 1, 2)
        with np.errstate(all="ignore"):
            # pinv: JJ is singular where the sheets are tangent (a pinch or triple point)
            JJ = np.where(np.isfinite(JJ), JJ, 0.0)
            y = np.linalg.pinv(JJ) @ np.where(np.isfinite(g), -g, 0.0)[:, :, None]
        step = (np.swapaxes(J, 1, 2) @ y)[:, :, 0]
        step = np.where(np.isfinite(step), step, 0.0)
        a = d.clip(a + step[:, :2])
        b = d.clip(b + step[:, 2:])
    return a, b


class _Branch:
    """One self-intersection curve: splines of both preimages over chord length."""

    def __init__(self, surface: Surface, a: np.ndarray, b: np.ndarray, closed: bool) -> None:
        from scipy.interpolate import CubicSpline, make_interp_spline

        d = surface.domain
        scale = np.array([d.span(0), d.span(1)])
        if closed:
            a, b = np.vstack([a, a[:1]]), np.vstack([b, b[:1]])
        # both preimages continuous in the cover (either may cross a seam)
        a, b = d.continuous(a), d.continuous(b)
        if closed and any(d.twisted):
            # closing through a twist: not a loop of the cover, drawn open
            # (its two ends are one point of the surface)
            closed = bool((d.deck(a[-1], a[0])[0] > 0).all() and (d.deck(b[-1], b[0])[0] > 0).all())
        t = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(a / scale, axis=0), axis=1))])
        keep = np.concatenate([[True], np.diff(t) > 1e-9 * max(t[-1], 1e-300)])
        a, b, t = a[keep], b[keep], t[keep]
        self.length = float(t[-1])
        self.closed = closed and len(t) >= 4
        k = min(3, len(t) - 1)
        if self.closed:
            self.da, self.db = a[-1] - a[0], b[-1] - b[0]
            ramp = (t / t[-1])[:, None]
            self.sa = CubicSpline(t, a - ramp * self.da, bc_type="periodic")
            self.sb = CubicSpline(t, b - ramp * self.db, bc_type="periodic")
        else:
            self.da = self.db = np.zeros(2)
            self.sa = make_interp_spline(t, a, k=k)
            self.sb = make_interp_spline(t, b, k=k)

    def __call__(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        ramp = (t / self.length)[:, None]
        return self.sa(t) + ramp * self.da, self.sb(t) + ramp * self.db


def _extent(surface: Surface, br: _Branch) -> float:
    """How far a branch reaches in space, relative to the surface's size (16
    points; about 0 for one that stays at a triple point, whose preimage is a
    pole's row of parameters)."""
    x = surface.points(surface.domain.wrap(br(np.linspace(0, br.length, 16))[0], clip=False))
    with np.errstate(invalid="ignore"):
        return float(np.nan_to_num(np.nanmax(np.ptp(x, axis=0)))) / surface.size


@attrs.frozen
class SelfIntersection(Family):
    """The curves where the surface meets itself (family ``"self_intersection"``).

    Numeric for every surface (see the module docstring); the stroke's ``uv``
    are one of the two parameter pairs of each point.
    """

    view_dependent: ClassVar[bool] = False  # cached per surface (lgraph.families.cache)

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        pts = self_intersection_points(surface)
        lines = _trace(pts, surface)
        if not lines:
            return []
        d = surface.domain
        h = np.array([d.span(0), d.span(1)]) / pts["n"]
        branches = [
            _Branch(surface, a, b, closed) for a, b, closed in one_preimage(lines, pts, h, d)
        ]
        branches = [br for br in branches if br.length > 0 and _extent(surface, br) > MIN_EXTENT]
        if not branches:
            return []

        def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            a = np.empty((len(t), 2))
            b = np.empty((len(t), 2))
            for k in np.unique(idx).tolist():  # one call per curve present
                sel = idx == k
                a[sel], b[sel] = branches[k](t[sel])
            a, b = _project(surface, a, b)
            a = d.wrap(a, clip=False)
            return surface.points(a), a

        return [
            CurveBatch(
                "self_intersection",
                np.zeros(len(branches)),
                [br.length for br in branches],
                evaluate,
                closed=[br.closed for br in branches],
                surface=surface,
            )
        ]


register_family("self_intersection", SelfIntersection, replace=True)
