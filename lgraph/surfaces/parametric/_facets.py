"""Rays against the facets of patches: where the numeric ray test starts Newton.

A patch sampled on a 3 x 3 grid is covered by 8 triangles (two in each of its
four quarters, all facing one way in the parameter plane); the surface strays
from them by at most the patch's padding ``pad`` (the second-difference
bound of :func:`~lgraph.surfaces.parametric._boxes._cell_pad`).  Seen along a
ray, each triangle is a 2-D triangle in the plane perpendicular to the ray,
where the ray is the origin (its *trace*).  Then, for every (ray, patch)
pair, without evaluating the surface (:func:`facet_test`):

* a triangle *around* the trace gives a start for Newton's method: its
  barycentric coordinates give the parameters and the distance along the
  ray, from where Newton converges in a few steps;
* a patch none of whose triangles comes within ``pad`` of the trace (with
  the depths in range) holds no root: it is dropped;
* a near miss (within ``pad``, outside the triangle) across an inner edge
  whose two triangles face the same way lies in the other one; across the
  patch's border, in the triangle across, when the patches are leaves of one
  grid of samples (``ring``) or quarters of one patch; across the domain's
  border it gets a start of its own (from the triangle's nearest point);
* a near miss at a *fold* (the triangles on an edge's two sides face
  opposite ways), on a triangle seen edge-on (inradius below ``pad``), or a
  sample that is not finite, may hide roots: the patch is split.

Folds lie on the contour: :func:`fold_free` marks the leaves where the
contour function keeps one sign, whose image is one sheet (no fold rule).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["TRIANGLES", "Ring", "facet_test", "fold_free"]

#: the 8 triangles of a patch, as indices ``3 a + b`` of its 3 x 3 samples
#: (``a`` along ``u1``, ``b`` along ``u2``); each quarter split by its diagonal
TRIANGLES = np.array(
    [[3 * a + b, 3 * (a + 1) + b, 3 * (a + 1) + b + 1] for a in (0, 1) for b in (0, 1)]
    + [[3 * a + b, 3 * (a + 1) + b + 1, 3 * a + b + 1] for a in (0, 1) for b in (0, 1)]
)


def _neighbours(tri: np.ndarray) -> np.ndarray:
    """For triangle ``t`` and its edge ``k`` (from vertex ``k`` to vertex
    ``k + 1``), the other triangle on that edge, or -1 on the patch's border.

    >>> _neighbours(TRIANGLES)[0].tolist()  # (0, 3, 4): border, inner, diagonal
    [-1, 6, 4]
    """
    out = np.full(tri.shape, -1)
    for t, (p, q, r) in enumerate(tri):
        for k, edge in enumerate(({p, q}, {q, r}, {r, p})):
            for o, other in enumerate(tri):
                if o != t and edge <= set(other.tolist()):
                    out[t, k] = o
    return out


_NEIGHBOUR = _neighbours(TRIANGLES)


def _outer_vertices(tri: np.ndarray) -> np.ndarray:
    """For a border edge ``k`` of triangle ``t``, the sample offsets ``(a, b)``
    (from the patch's first sample, possibly -1 or 3) of the third vertex of
    the triangle across it, in the same triangulation of the grid of samples
    the patch belongs to; ``(0, 0)`` for inner edges (unused).

    >>> _outer_vertices(TRIANGLES)[0, 0].tolist()  # edge (0, 0)-(1, 0): across is (0, -1)
    [0, -1]
    """
    grid = []  # every triangle of the quads with corners in -1..3
    for a in range(-1, 3):
        for b in range(-1, 3):
            grid.append([(a, b), (a + 1, b), (a + 1, b + 1)])
            grid.append([(a, b), (a + 1, b + 1), (a, b + 1)])
    out = np.zeros(tri.shape + (2,), dtype=int)
    for t, vs in enumerate(tri):
        pts = [divmod(int(x), 3) for x in vs]
        for k in range(3):
            if _NEIGHBOUR[t, k] >= 0:
                continue
            edge = {pts[k], pts[(k + 1) % 3]}
            (other,) = [g for g in grid if edge <= set(g) and set(g) != set(pts)]
            out[t, k] = (set(other) - edge).pop()
    return out


_OUTER = _outer_vertices(TRIANGLES)


class Ring(NamedTuple):
    """Where the patches' neighbours are: the grid of samples the patches
    belong to, ``grid (N1, N2, 3)`` (the leaves), or one such grid a parent
    patch, ``grid (m, N1, N2, 3)`` with ``owner`` the parent of each patch
    (quarters); patch ``p``'s first sample is ``[gi[p], gj[p]]`` there, and
    ``periodic`` says which parameters wrap round (a sample past the grid is
    on the domain's border otherwise, or the parent's: no neighbour known)."""

    grid: np.ndarray
    gi: np.ndarray
    gj: np.ndarray
    periodic: tuple[bool, bool]
    owner: np.ndarray | None = None
    #: which patches of the grid hold no contour (``(n1, n2)``, or ``(m, 2,
    #: 2)`` with ``owner``), if known
    free: np.ndarray | None = None

    def take(self, rows: np.ndarray) -> Ring:
        """The ring of the patches ``rows``."""
        owner = None if self.owner is None else self.owner[rows]
        return self._replace(gi=self.gi[rows], gj=self.gj[rows], owner=owner)

    def patch_free(self) -> np.ndarray | None:
        """Whether each patch itself holds no contour (None if not known)."""
        if self.free is None:
            return None
        a, b = self.gi // 2, self.gj // 2
        return self.free[a, b] if self.owner is None else self.free[self.owner, a, b]


#: the sample fractions of a patch along each parameter
_F = np.array([0.0, 0.5, 1.0])


def facet_test(
    S: np.ndarray,
    pad: np.ndarray,
    o: np.ndarray,
    v: np.ndarray,
    smax: np.ndarray,
    c0: np.ndarray,
    c1: np.ndarray,
    ring: Ring | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Rays ``o + s v`` (``0 <= s <= smax``) against the facets of patches.

    ``S (P, 9, 3)`` are the 3 x 3 samples of patch ``[c0, c1]`` (``(P, 2)``)
    of pair ``p``, ``pad (P,)`` their padding, ``o, v (P, 3)`` and ``smax (P,)``
    the pair's ray.  With a :class:`Ring` (the grid of samples the patches
    belong to), a near miss across a patch's border needs no start of its
    own (the triangle across, in the neighbouring patch, holds the trace)
    unless the border is the grid's (the domain's or the parent's) or the
    triangle across faces the other way (a fold).  Patches the ring knows to
    hold no contour (:func:`fold_free`, :meth:`Ring.patch_free`) have an image
    of one sheet, with no fold to hide roots.

    Returns ``(pair, uv, s, near, fold)``: the starts of Newton's method
    (pair, parameters, distance along the ray; ``near``: from a near miss,
    not from a triangle around the trace), and per pair whether a root may
    hide in the patch (a near miss at a fold or an edge-on triangle, or a
    sample not finite): such patches are searched more finely.

    >>> u = np.linspace(0, 1, 3)
    >>> S = np.stack([*np.meshgrid(u, u, indexing="ij"), np.zeros((3, 3))], -1).reshape(1, 9, 3)
    >>> o, v = np.array([[0.3, 0.6, 1.0]]), np.array([[0.0, 0.0, -1.0]])
    >>> c0, c1 = np.zeros((1, 2)), np.ones((1, 2))
    >>> pair, uv, s, near, fold = facet_test(S, np.array([1e-3]), o, v, np.array([5.0]), c0, c1)
    >>> pair.tolist(), np.round(uv, 12).tolist(), np.round(s, 12).tolist(), near.tolist()
    ([0], [[0.3, 0.6]], [1.0], [False])
    >>> fold.tolist()
    [False]
    """
    P = len(S)
    vn = np.linalg.norm(v, axis=1)
    vn = np.where(vn > 0, vn, 1.0)
    w = v / vn[:, None]
    # a frame (e1, e2, w) per ray; e1 perpendicular to w and to its smallest axis
    ax = np.argmin(np.abs(w), axis=1)
    e = np.zeros_like(w)
    e[np.arange(P), ax] = 1.0
    e1 = np.cross(w, e)
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(w, e1)
    q = S - o[:, None, :]
    X = np.einsum("pkc,pc->pk", q, e1)
    Y = np.einsum("pkc,pc->pk", q, e2)
    Z = np.einsum("pkc,pc->pk", q, w)
    finite = np.isfinite(X).all(1) & np.isfinite(Y).all(1) & np.isfinite(Z).all(1)
    # first the pairs whose trace lies in the padded box of the patch's samples
    # (in the ray's frame) and whose depths are in range: the others hold no root
    with np.errstate(invalid="ignore"):
        keep = (
            (X.min(1) - pad <= 0)
            & (X.max(1) + pad >= 0)
            & (Y.min(1) - pad <= 0)
            & (Y.max(1) + pad >= 0)
            & (Z.min(1) - pad <= smax * vn)
            & (Z.max(1) + pad >= 0)
        )
    kept = np.flatnonzero(keep)
    X, Y, Z, S, o, e1, e2 = (x[kept] for x in (X, Y, Z, S, o, e1, e2))
    pad, c0, c1, smax, vn = pad[kept], c0[kept], c1[kept], smax[kept], vn[kept]
    free = None
    if ring is not None:
        ring = ring.take(kept)
        free = ring.patch_free()
    P = len(kept)
    A, B, C = (TRIANGLES[:, i] for i in range(3))
    ax_, ay_, bx, by, cx, cy = X[:, A], Y[:, A], X[:, B], Y[:, B], X[:, C], Y[:, C]
    # twice the signed area of the triangle (trace, edge start, edge end), per edge
    W = np.stack([ax_ * by - ay_ * bx, bx * cy - by * cx, cx * ay_ - cy * ax_], -1)
    L = np.stack(
        [np.hypot(bx - ax_, by - ay_), np.hypot(cx - bx, cy - by), np.hypot(ax_ - cx, ay_ - cy)], -1
    )
    two_a = W.sum(-1)  # (P, 8)
    pd = pad[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        d = W / L  # signed distances of the trace from the edge lines
    sign = np.sign(two_a)
    # depths in range: the triangle's depths, padded, meet [0, smax |v|]
    zt = Z[:, TRIANGLES]  # (P, 8, 3)
    zok = (zt.min(-1) - pd <= (smax * vn)[:, None]) & (zt.max(-1) + pd >= 0)
    # the trace within the triangle's box, padded
    xt, yt = X[:, TRIANGLES], Y[:, TRIANGLES]
    boxok = (
        (xt.min(-1) - pd <= 0)
        & (xt.max(-1) + pd >= 0)
        & (yt.min(-1) - pd <= 0)
        & (yt.max(-1) + pd >= 0)
    )
    flat = np.abs(two_a) <= pd * L.max(-1)  # seen (nearly) edge-on: inradius below pad
    inside = (two_a != 0) & (((W >= 0).all(-1)) | ((W <= 0).all(-1))) & zok
    near = ((d >= -pd[..., None]).all(-1) | (d <= pd[..., None]).all(-1)) & boxok & zok & ~inside
    # a near miss across a fold or on an edge-on triangle may hide roots; one
    # across the patch's border may be a root just beyond it
    nb_sign = sign[:, np.maximum(_NEIGHBOUR, 0)]  # (P, 8, 3)
    violated = near[..., None] & (sign[..., None] * d < 0)
    fold_edge = (_NEIGHBOUR >= 0) & (nb_sign != sign[..., None])
    border = violated & (_NEIGHBOUR < 0)
    if ring is not None:
        pp, tt, kk = np.nonzero(border)
        if len(pp):
            edge, folded, across_free = _across(ring, pp, tt, kk, sign, S, o, e1, e2)
            border[pp, tt, kk] = edge | ~across_free
            fold_edge[pp, tt, kk] = folded
    fold_t = near & (flat | (sign == 0) | (violated & fold_edge).any(-1))
    if free is not None:
        # no contour in the patch: its image is one sheet, and a near miss
        # inside the domain lies in a neighbouring triangle (here or across)
        fold_t &= ~free[:, None]
    fold = np.array(~finite)  # a sample not finite: the patch is searched more finely
    fold[kept] = fold_t.any(1)
    # near starts: a pair's triangle nearest to the trace, of each facing
    # (at a fold, one on either sheet)
    cand = fold_t | border.any(-1)
    closeness = (sign[..., None] * d).min(-1)
    start = inside.copy()
    rows = np.arange(P)
    for facing in (1.0, -1.0):
        c = cand & (sign == facing)
        best = np.argmax(np.where(c, closeness, -np.inf), axis=1)
        start[rows, best] |= c[rows, best]
    pair, tri = np.nonzero(start)
    near_start = ~inside[pair, tri]
    with np.errstate(divide="ignore", invalid="ignore"):
        # barycentric coordinates: A opposite edge BC (index 1), B opposite CA, C opposite AB
        lam = W[pair, tri][:, [1, 2, 0]] / two_a[pair, tri][:, None]
        # a near miss starts from the nearest point of its triangle (roughly)
        lam = np.where(near_start[:, None], np.maximum(lam, 0.0), lam)
        lam /= lam.sum(1, keepdims=True)
    lam = np.where(np.isfinite(lam).all(1, keepdims=True), lam, 1.0 / 3.0)
    ia, ib = np.divmod(TRIANGLES[tri], 3)  # (m, 3) sample rows and columns
    span = c1[pair] - c0[pair]
    fu = np.einsum("mk,mk->m", lam, _F[ia])
    fv = np.einsum("mk,mk->m", lam, _F[ib])
    uv = c0[pair] + span * np.stack([fu, fv], 1)
    s = np.einsum("mk,mk->m", lam, Z[pair[:, None], TRIANGLES[tri]]) / vn[pair]
    return kept[pair], uv, s, near_start, fold


def _across(
    ring: Ring,
    pp: np.ndarray,
    tt: np.ndarray,
    kk: np.ndarray,
    sign: np.ndarray,
    S: np.ndarray,
    o: np.ndarray,
    e1: np.ndarray,
    e2: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For border edge ``kk`` of triangle ``tt`` of pair ``pp``: is it the
    grid's border (no triangle across), does the triangle across face the
    other way (a fold), and is the patch across known to hold no contour?"""
    grid, gi, gj, periodic, owner, _ = ring
    m = grid.shape[-3] - 1, grid.shape[-2] - 1
    ga = gi[pp] + _OUTER[tt, kk, 0]
    gb = gj[pp] + _OUTER[tt, kk, 1]
    ok = np.ones(len(pp), dtype=bool)
    for g, n, wrap in ((ga, m[0], periodic[0]), (gb, m[1], periodic[1])):
        if wrap:
            g %= n
        else:
            ok &= (g >= 0) & (g <= n)
            np.clip(g, 0, n, out=g)
    r3 = (grid[ga, gb] if owner is None else grid[owner[pp], ga, gb]) - o[pp]
    a = np.take_along_axis(S[pp], TRIANGLES[tt, kk][:, None, None], 1)[:, 0] - o[pp]
    b = np.take_along_axis(S[pp], TRIANGLES[tt, (kk + 1) % 3][:, None, None], 1)[:, 0] - o[pp]
    f1, f2 = e1[pp], e2[pp]

    def xy(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.einsum("ij,ij->i", q, f1), np.einsum("ij,ij->i", q, f2)

    (ax, ay), (bx, by), (rx, ry) = xy(a), xy(b), xy(r3)
    # the triangle across, (b, a, r3), in the patch's orientation
    across = np.sign((ax - bx) * (ry - by) - (ay - by) * (rx - bx))
    folded = ok & ~((across == sign[pp, tt]) & np.isfinite(across))
    # the patch across (it holds the triangle's centroid): known to hold no
    # contour?  Only then does its own start find a root beside the border
    # (a patch with a fold is split, and its quarters no longer meet this
    # patch's triangles)
    if ring.free is None:
        return ~ok, folded, np.zeros(len(pp), dtype=bool)
    va, vb = np.divmod(TRIANGLES[tt, kk], 3)
    wa, wb = np.divmod(TRIANGLES[tt, (kk + 1) % 3], 3)
    ca = (gi[pp] * 3 + va + wa + _OUTER[tt, kk, 0]) / 3.0
    cb = (gj[pp] * 3 + vb + wb + _OUTER[tt, kk, 1]) / 3.0
    n1, n2 = ring.free.shape[-2:]
    pa, pb = np.floor(ca / 2).astype(int), np.floor(cb / 2).astype(int)
    pa = pa % n1 if periodic[0] else np.clip(pa, 0, n1 - 1)
    pb = pb % n2 if periodic[1] else np.clip(pb, 0, n2 - 1)
    nb_free = ring.free[pa, pb] if owner is None else ring.free[owner[pp], pa, pb]
    return ~ok, folded, ok & nb_free


def fold_free(grid: np.ndarray, eye: np.ndarray | None, toward: np.ndarray | None) -> np.ndarray:
    """Which leaves of sample grids ``grid (..., 2 n + 1, 2 n + 1, 3)`` hold
    no point of the contour seen from ``eye`` (central) or along ``toward``
    (parallel): the contour function ``(x_1 x x_2) . (x - eye)`` (or ``.
    toward``, the derivatives by differences on the grid) keeps one sign on
    the leaf's nine samples, with a margin of its second differences (as the
    patches' padding).  ``(..., n, n)`` flags.

    >>> u = np.linspace(-1, 1, 5)
    >>> U, V = np.meshgrid(u, u, indexing="ij")
    >>> plane = np.stack([U, V, 0 * U], -1)
    >>> fold_free(plane, None, np.array([0.0, 0.0, 1.0])).tolist()
    [[True, True], [True, True]]
    >>> fold_free(plane, None, np.array([1.0, 0.0, 0.0])).tolist()  # seen edge-on
    [[False, False], [False, False]]
    """
    with np.errstate(invalid="ignore"):
        x1 = np.gradient(grid, axis=-3)
        x2 = np.gradient(grid, axis=-2)
        dirs = grid - eye if toward is None else np.broadcast_to(toward, grid.shape)
        g = np.einsum("...c,...c->...", np.cross(x1, x2), dirs)
        m = (grid.shape[-3] - 1) // 2, (grid.shape[-2] - 1) // 2
        ia = 2 * np.arange(m[0])[:, None] + np.arange(3)
        ib = 2 * np.arange(m[1])[:, None] + np.arange(3)
        G = g[..., ia[:, None, :, None], ib[None, :, None, :]]  # (..., n, n, 3, 3)
        d1 = np.abs(G[..., 0, :] - 2 * G[..., 1, :] + G[..., 2, :]).max(-1)
        d2 = np.abs(G[..., :, 0] - 2 * G[..., :, 1] + G[..., :, 2]).max(-1)
        d12 = np.abs(G[..., 0, 0] - G[..., 2, 0] - G[..., 0, 2] + G[..., 2, 2])
        margin = 0.5 * (d1 + d2) + 0.25 * d12
        lo, hi = G.min(axis=(-2, -1)), G.max(axis=(-2, -1))
        return (lo > margin) | (hi < -margin)
