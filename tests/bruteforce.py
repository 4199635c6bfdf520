"""Independent brute-force visibility for tests: analytic ray casts against
quadrics given by (A, b, d) in local coordinates, written without lgraph's
visibility code."""

from __future__ import annotations

import numpy as np


def quadric_roots(A, b, d, o, v):
    """Both roots s of (o + s v)^T A (o + s v) + b.(o + s v) + d = 0 (NaN if none)."""
    qa = np.einsum("ni,ij,nj->n", v, A, v)
    qb = 2 * np.einsum("ni,ij,nj->n", o, A, v) + v @ b
    qc = np.einsum("ni,ij,nj->n", o, A, o) + o @ b + d
    disc = qb**2 - 4 * qa * qc
    with np.errstate(invalid="ignore", divide="ignore"):
        sq = np.sqrt(disc)
        r1 = (-qb - sq) / (2 * qa)
        r2 = (-qb + sq) / (2 * qa)
    return r1, r2, disc, qa, qb


def classify(objects, projector, points, owners, eps=1e-9, patch=None):
    """Hidden flags of world ``points``; ``objects`` is a list of (A, b, d, T, in_patch)
    with T the node transform (lgraph Transform) and in_patch a callable or None.

    A root closer than ``eps * size`` to the origin counts as the origin itself
    when the point lies on that object (owners[i] == k).
    Returns (hidden, margin): margin is small where the classification is fragile.
    """
    points = np.asarray(points, float)
    if hasattr(projector, "eye"):
        w = projector.eye - points
        smax = np.linalg.norm(w, axis=1)
        dirs = w / smax[:, None]
    else:
        dirs = np.broadcast_to(projector.frame[2], points.shape)
        smax = np.full(len(points), np.inf)
    hidden = np.zeros(len(points), bool)
    margin = np.full(len(points), np.inf)
    for k, (A, b, d, T, in_patch, size) in enumerate(objects):
        inv = T.inverse()
        o = inv.apply(points)
        v = inv.apply_vector(dirs)
        r1, r2, disc, qa, qb = quadric_roots(A, b, d, o, v)
        own = owners == k
        scale = np.abs(qb) + np.abs(qa) * size + 1e-300
        margin = np.minimum(margin, np.where(own, np.inf, np.abs(disc) / scale**2))
        # on its own surface, the root nearer to 0 is the point itself
        self_root = np.where(np.abs(r1) < np.abs(r2), 1, 2)
        for j, r in ((1, r1), (2, r2)):
            ok = np.isfinite(r) & (r < smax)
            is_self = own & (self_root == j)
            ok &= ~is_self & (r > eps * size)
            if in_patch is not None:
                q = o + np.where(np.isfinite(r), r, 0)[:, None] * v
                ok &= in_patch(q)
            hidden |= ok
            m = np.where(np.isfinite(r) & ~is_self, np.abs(r) / size, np.inf)
            m = np.minimum(m, np.where(np.isfinite(r) & ~is_self, np.abs(smax - r) / size, np.inf))
            margin = np.minimum(margin, m)
    return hidden, margin


def sign_changes(g):
    """A brute-force ray march read off samples ``g (rays, n)`` of an implicit
    function along each ray (NaN off the surface's patch): ``(hit, margin)``,
    ``hit`` where ``g`` changes sign, ``margin`` the smallest ``|g|`` at a
    turning point of ``g`` (a near-tangency, where the march is unreliable)."""
    hit = ((np.sign(g[:, 1:]) * np.sign(g[:, :-1])) < 0).any(axis=1)
    dg = np.diff(g, axis=1)
    turn = np.zeros_like(g, dtype=bool)
    turn[:, 1:-1] = dg[:, 1:] * dg[:, :-1] <= 0
    with np.errstate(invalid="ignore"):
        margin = np.nanmin(np.where(turn, np.abs(g), np.inf), axis=1)
    return hit, margin


def even_stations(xy, spacing, skip=2):
    """Indices of samples of one polyline ``xy (n, 2)`` about ``spacing`` apart
    along its length (the nearest sample at or after each station), leaving
    out ``skip`` samples at each end.  Checks then weigh a curve evenly along
    its length, however densely the renderer has sampled near contours and
    transitions."""
    if len(xy) <= 2 * skip:
        return np.empty(0, dtype=np.int64)
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
    inner = arc[skip : len(xy) - skip]
    stations = np.arange(inner[0], inner[-1] + 0.5 * spacing, spacing)
    idx = np.searchsorted(inner, stations).clip(0, len(inner) - 1) + skip
    return np.unique(idx)
