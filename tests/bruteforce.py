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


def parametric_mesh(func, r1, r2, n1, n2):
    """Triangles ``(m, 3, 3)`` of a parametric surface ``func(u, v)`` on an
    ``n1 x n2`` grid of ``r1 x r2``, and each triangle's grid cell ``(m, 2)``."""
    u = np.linspace(*r1, n1 + 1)
    v = np.linspace(*r2, n2 + 1)
    P = func(*np.meshgrid(u, v, indexing="ij"))
    i, j = np.meshgrid(np.arange(n1), np.arange(n2), indexing="ij")
    a, b, c, d = P[i, j], P[i + 1, j], P[i + 1, j + 1], P[i, j + 1]
    tris = np.concatenate(
        [np.stack([a, b, c], -2).reshape(-1, 3, 3), np.stack([a, c, d], -2).reshape(-1, 3, 3)]
    )
    cells = np.concatenate([np.stack([i, j], -1).reshape(-1, 2)] * 2)
    return tris, cells


class MeshCaster:
    """Rays toward the viewer cast against a triangle mesh of a parametric
    surface (:func:`parametric_mesh`), the triangles binned by their
    projected boxes: independent of lgraph's ray tests.  A ray from a point
    of the surface skips the triangles within ``skip`` grid cells of the
    point's own cell (its own sheet), whatever its distance."""

    def __init__(self, func, r1, r2, n1, n2, projector, periodic=(False, False), bins=256):
        self.func, self.r1, self.r2 = func, r1, r2
        self.T, self.cells = parametric_mesh(func, r1, r2, n1, n2)
        self.grid = ((r1[0], (r1[1] - r1[0]) / n1, n1), (r2[0], (r2[1] - r2[0]) / n2, n2))
        self.periodic, self.p, self.bins = periodic, projector, bins
        q = projector.project(self.T.reshape(-1, 3)).reshape(-1, 3, 2)
        self.lo = q.min(axis=(0, 1))
        self.w = (q.max(axis=(0, 1)) - self.lo) / bins * (1 + 1e-9)
        b0 = np.floor((q.min(axis=1) - self.lo) / self.w).astype(int).clip(0, bins - 1)
        b1 = np.floor((q.max(axis=1) - self.lo) / self.w).astype(int).clip(0, bins - 1)
        nj = b1[:, 1] - b0[:, 1] + 1
        cnt = (b1[:, 0] - b0[:, 0] + 1) * nj
        k = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        key = (np.repeat(b0[:, 0], cnt) + k // np.repeat(nj, cnt)) * bins
        key += np.repeat(b0[:, 1], cnt) + k % np.repeat(nj, cnt)
        order = np.argsort(key, kind="stable")
        self.tri = np.repeat(np.arange(len(self.T)), cnt)[order]
        self.start = np.searchsorted(key[order], np.arange(bins * bins + 1))

    def hidden(self, uv, skip=2):
        """Whether the points ``func(uv)`` are hidden (a ray toward the viewer
        meets the mesh, own cells left out)."""
        uv = np.asarray(uv, float)
        pts = self.func(uv[:, 0], uv[:, 1])
        d, smax = self.p.rays(pts)
        d = np.array(d, float)
        smax = np.broadcast_to(smax, len(pts))
        b = np.floor((self.p.project(pts) - self.lo) / self.w).astype(int)
        ok = ((b >= 0) & (b < self.bins)).all(axis=1)
        key = np.where(ok, b[:, 0] * self.bins + b[:, 1], 0)
        s0 = self.start[key]
        cnt = np.where(ok, self.start[key + 1] - s0, 0)
        ray = np.repeat(np.arange(len(pts)), cnt)
        idx = self.tri[
            np.repeat(s0, cnt) + np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        ]
        own = np.ones(len(ray), bool)
        for k in (0, 1):
            lo, h, n = self.grid[k]
            c = np.floor((uv[ray, k] - lo) / h).astype(int).clip(0, n - 1)
            dd = np.abs(self.cells[idx, k] - c)
            if self.periodic[k]:
                dd = np.minimum(dd, n - dd)
            own &= dd <= skip
        T, o, v = self.T[idx], pts[ray], d[ray]
        e1, e2 = T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]
        h = np.cross(v, e2)
        a = np.einsum("ij,ij->i", e1, h)
        with np.errstate(all="ignore"):
            f = 1.0 / a
            s = o - T[:, 0]
            bu = f * np.einsum("ij,ij->i", s, h)
            qq = np.cross(s, e1)
            bv = f * np.einsum("ij,ij->i", v, qq)
            t = f * np.einsum("ij,ij->i", e2, qq)
            hit = ~own & (bu >= 0) & (bv >= 0) & (bu + bv <= 1) & (t > 0) & (t < smax[ray])
        return np.bincount(ray[hit], minlength=len(pts)) > 0

    def robust_hidden(self, uv, delta):
        """``(hidden, reliable)``: :meth:`hidden` at ``uv``, reliable where the
        four neighbours at ``+-delta`` (per parameter) agree with it (not
        beside a visibility change)."""
        offs = np.array([[0, 0], [1, 0], [-1, 0], [0, 1], [0, -1]], float)
        U = (np.asarray(uv, float)[None] + offs[:, None] * np.asarray(delta)).reshape(-1, 2)
        U = np.stack([U[:, 0].clip(*self.r1), U[:, 1].clip(*self.r2)], axis=1)
        h = self.hidden(U).reshape(5, -1)
        return h[0], (h == h[0]).all(axis=0)
