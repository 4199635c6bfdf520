"""Ruled surfaces: which rays the patch hides (docs/mathematics.rst, "Ruled
surfaces, general cylinders and cones", ray test).

The ray ``P + s v`` meets the ruling through ``y(u1)`` iff
``g(u1) = det(y(u1) - P, z(u1), v) = 0``.  ``g`` is linear in ``P`` and ``v``,
so it is evaluated for all rays on the ``u1`` grid by two matrix products;
pairs of roots within one cell are separated at the extremum of ``g``
between them, the brackets refined all at once
(:func:`lgraph._roots.bracketed_roots`), and ``(u2, s)`` follow from
``y + u2 z = P + s v``.  *Limitation*: a ray that meets more than two rulings
within one grid cell can be missed.
"""

from __future__ import annotations

import numpy as np

from ..._own import CONTOUR
from ..._roots import bracketed_roots
from ..._tolerance import RULED_CHUNK as _CHUNK
from ..._tolerance import RULED_CONTOUR_SELF_RTOL as _CONTOUR_SELF_RTOL
from ..._tolerance import SELF_HIT_RTOL
from ...geometry.vectors import dot as _dot
from ._geometry import _flips, _RuledGeometry


class _RuledHits(_RuledGeometry):
    """:meth:`hits` of the ruled surfaces."""

    hit_cost = 17.0
    hit_call_cost = 5000.0

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Rays ``P + s v`` (``0 < s < smax``) meeting the drawn patch.

        Solves ``det(y(u1) - P, z(u1), v) = 0`` for all rays at once (grid scan,
        pairs of close roots found at the extrema of ``g``, bracketed refinement),
        then ``y + u2 z = P + s v`` for ``(u2, s)``.
        """
        o = np.asarray(origins, float).reshape(-1, 3)
        v = np.asarray(directions, float).reshape(-1, 3)
        m = len(o)
        smax = np.broadcast_to(np.asarray(smax, float), (m,))
        own = np.zeros(m, np.int8) if own is None else np.broadcast_to(np.asarray(own), (m,))
        out = np.zeros(m, bool)
        if not m:
            return out
        grid = self._grid()
        step = max(1, _CHUNK // len(grid["u"]))
        for k in range(0, m, step):
            sl = slice(k, k + step)
            out[sl] = self._hits_chunk(grid, o[sl], v[sl], smax[sl], own[sl])
        return out

    def _g(self, u: np.ndarray, P: np.ndarray, V: np.ndarray) -> np.ndarray:
        y, _, _, z, _, _ = self._rul(u, 0)
        return _dot(np.cross(y - P, z), V)

    def _dg(self, u: np.ndarray, P: np.ndarray, V: np.ndarray) -> np.ndarray:
        y, y1, _, z, z1, _ = self._rul(u, 1)
        return _dot(np.cross(y1, z) + np.cross(y - P, z1), V)

    def _hits_chunk(self, grid, P, V, smax, own) -> np.ndarray:  # noqa: ANN001
        u = grid["u"]
        VxP = np.cross(V, P)
        G = V @ grid["YxZ"].T - VxP @ grid["Z"].T
        rows, cols = _flips(G)
        ra, ua, ub = rows, u[cols], u[cols + 1]
        ga, gb = G[rows, cols], G[rows, cols + 1]
        # two roots within one cell: g has an extremum there that crosses zero
        D = V @ grid["dYxZ"].T - VxP @ grid["Z1"].T
        Ga, Gb, Da, Db = G[:, :-1], G[:, 1:], D[:, :-1], D[:, 1:]
        h = np.diff(u)
        cand = ((Ga > 0) & (Gb > 0) & (Da < 0) & (Db > 0)) | (
            (Ga < 0) & (Gb < 0) & (Da > 0) & (Db < 0)
        )
        cand &= np.minimum(np.abs(Ga), np.abs(Gb)) <= (np.abs(Da) + np.abs(Db)) * h
        er, ec = np.nonzero(cand)
        if len(er):
            a, b = u[ec], u[ec + 1]
            mid = bracketed_roots(
                lambda x, s: self._dg(x, P[er[s]], V[er[s]]),
                a,
                b,
                D[er, ec],
                D[er, ec + 1],
                1e-9 * (u[-1] - u[0]),  # g is flat at its extremum
            )
            gm = self._g(mid, P[er], V[er])
            two = (gm >= 0) != (G[er, ec] >= 0)
            er, ec, mid, gm = er[two], ec[two], mid[two], gm[two]
            ra = np.concatenate([ra, er, er])
            ua = np.concatenate([ua, u[ec], mid])
            ub = np.concatenate([ub, mid, u[ec + 1]])
            ga = np.concatenate([ga, G[er, ec], gm])
            gb = np.concatenate([gb, gm, G[er, ec + 1]])
        out = np.zeros(len(P), bool)
        if not len(ra):
            return out
        # drop brackets whose (u2, s) at both ends lie clearly outside the
        # accepted ranges (the margin is the change over the cell)
        keep = self._plausible(grid, P, V, smax, ra, ua, ub)
        ra, ua, ub, ga, gb = ra[keep], ua[keep], ub[keep], ga[keep], gb[keep]
        if not len(ra):
            return out
        # rounding level of g = det(y - P, z, v)
        ftol = 2e-15 * (self.size + np.linalg.norm(P[ra], axis=-1)) * grid["zmax"]
        ftol = ftol * np.linalg.norm(V[ra], axis=-1)
        root = bracketed_roots(
            lambda x, s: self._g(x, P[ra[s]], V[ra[s]]), ua, ub, ga, gb, grid["xtol"], ftol
        )
        y, _, _, z, _, _ = self._rul(root, 0)
        z = np.broadcast_to(z, y.shape)
        p, v = P[ra], V[ra]
        zv = np.cross(z, v)
        zv2 = _dot(zv, zv)
        ok = zv2 > 1e-24 * _dot(z, z) * _dot(v, v)
        zv2 = np.where(ok, zv2, 1.0)
        u2 = _dot(np.cross(p - y, v), zv) / zv2
        s = -_dot(np.cross(y - p, z), zv) / zv2
        lo, hi = self.u2_range
        rtol = np.where(own[ra] == CONTOUR, _CONTOUR_SELF_RTOL, SELF_HIT_RTOL)
        eps = rtol * self.size / np.linalg.norm(v, axis=-1)
        ok &= (u2 >= lo) & (u2 <= hi) & (s > eps) & (s < smax[ra])
        out[ra[ok]] = True
        return out

    def _plausible(self, grid, P, V, smax, ra, ua, ub) -> np.ndarray:  # noqa: ANN001
        """Whether a bracket ``[ua, ub]`` of ray ``ra`` may hold an accepted hit."""
        lo, hi = self.u2_range
        ends = []
        for x in (ua, ub):
            y, _, _, z, _, _ = self._rul(x, 0)
            z = np.broadcast_to(z, y.shape)
            p, v = P[ra], V[ra]
            zv = np.cross(z, v)
            zv2 = _dot(zv, zv)
            with np.errstate(divide="ignore", invalid="ignore"):
                u2 = _dot(np.cross(p - y, v), zv) / zv2
                s = -_dot(np.cross(y - p, z), zv) / zv2
            ends.append((u2, s))
        (ua2, sa), (ub2, sb) = ends
        with np.errstate(invalid="ignore"):
            m2 = np.abs(ub2 - ua2) + 1e-6 * (hi - lo)
            ms = np.abs(sb - sa) + 1e-6 * self.size / np.linalg.norm(V[ra], axis=-1)
            out = (np.minimum(ua2, ub2) - m2 <= hi) & (np.maximum(ua2, ub2) + m2 >= lo)
            out &= (np.maximum(sa, sb) + ms >= 0) & (np.minimum(sa, sb) - ms <= smax[ra])
        return out | ~np.isfinite(m2) | ~np.isfinite(ms)
