"""Ruled surfaces: lines of curvature of the developable ones (paper (4.2)-(4.5);
docs/mathematics.rst, "Ruled surfaces, general cylinders and cones", lines of
curvature).

On a developable surface (``det(y', z, z') = 0``) the lines of curvature are
the rulings and the curves ``u2 = d - S(u1)`` orthogonal to them, with
``S = integral of y' . z`` (10-point Gauss-Legendre per grid cell): for
cylinders ``S = c . y`` (plane sections), for cones ``S = |y - apex|``
(spheres about the vertex), for tangent surfaces ``S`` = arc length
(involutes).  The curves are clipped to the drawn ``u2`` range where they
cross its ends (:func:`lgraph._roots.bracketed_roots`).
"""

from __future__ import annotations

import numpy as np

from ..._roots import bracketed_roots
from ..._tolerance import RULED_DEVELOPABLE_RTOL as _DEVELOPABLE_RTOL
from ...curves import CurveBatch
from ...geometry.vectors import dot as _dot
from ._geometry import _flips, _RuledGeometry

_GL_X, _GL_W = np.polynomial.legendre.leggauss(10)


class _RuledCurvature(_RuledGeometry):
    """:meth:`lines_of_curvature` of the developable ruled surfaces."""

    def _S(self, u: np.ndarray) -> np.ndarray:
        """``S(u1) = integral of y' . z`` from ``t0`` (10-point Gauss-Legendre per
        grid cell; the cell sums are computed once)."""
        grid = self._grid()
        nodes = grid["u"]
        if "S" not in self._cache:
            self._cache["S"] = np.concatenate([[0.0], np.cumsum(self._gl(nodes[:-1], nodes[1:]))])
        S = self._cache["S"]
        u = np.asarray(u, float)
        k = np.clip(np.searchsorted(nodes, u, side="right") - 1, 0, len(nodes) - 2)
        return S[k] + self._gl(nodes[k], u)

    def _gl(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        half = 0.5 * (b - a)
        x = (0.5 * (a + b))[:, None] + half[:, None] * _GL_X
        _, y1, _, z, _, _ = self._rul(x.ravel(), 1)
        f = _dot(np.broadcast_to(y1, z.shape), z).reshape(x.shape)
        return half * (f @ _GL_W)

    def _level_u2(self, u1: np.ndarray, d: np.ndarray) -> np.ndarray:
        """``u2`` of the line of curvature with constant ``d`` (second family)."""
        u1 = np.asarray(u1, float)
        return d - self._S(u1.ravel()).reshape(u1.shape)

    def _levels(self, n: int) -> np.ndarray:
        u = self._grid()["u"]
        lo, hi = self.u2_range
        S = self._S(u)
        lvl = np.linspace(lo + S.min(), hi + S.max(), n + 2)[1:-1]
        return lvl

    def _check_developable(self) -> None:
        g = self._grid()
        y, y1, _, z, z1, _ = self._rul(g["u"], 1)
        det = np.abs(_dot(np.cross(np.broadcast_to(y1, z.shape), z), np.broadcast_to(z1, z.shape)))
        scale = (
            np.linalg.norm(y1, axis=-1) * np.linalg.norm(z1, axis=-1) * np.linalg.norm(z, axis=-1)
        )
        if np.any(det > _DEVELOPABLE_RTOL * (scale.max() + 1e-300)):
            raise ValueError(
                f"{type(self).__name__}: lines of curvature by the paper's (4.2) need a "
                "developable surface (det(y', z, z') = 0: a general cylinder, cone or "
                "tangent surface); this one is not"
            )

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """The rulings (``n1``) and ``n2`` curves of the second principal family,
        clipped to the drawn ``u2`` range (paper (4.2)-(4.5))."""
        self._check_developable()
        out = []
        if n1:
            out.append(self._ruling_batch(self.domain.lines(0, n1), "curvature"))
        if n2:
            b = self._clipped_levels(self._levels(n2))
            if b is not None:
                out.append(b)
        return out

    def _clipped_levels(self, d: np.ndarray) -> CurveBatch | None:
        """Pieces of the curves ``u2 = _level_u2(u1, d_k)`` inside the drawn range."""
        c = self.directrix
        grid = self._grid()
        u = grid["u"]
        lo, hi = self.u2_range
        U2 = self._level_u2(u[None, :], d[:, None])
        rows, a = [], []
        for bound in (lo, hi):
            r, cols = _flips(U2 - bound)
            if len(r):
                rows.append(r)
                a.append(
                    bracketed_roots(
                        lambda x, s, r=r, bound=bound: self._level_u2(x, d[r[s]]) - bound,
                        u[cols],
                        u[cols + 1],
                        U2[r, cols] - bound,
                        U2[r, cols + 1] - bound,
                        grid["xtol"],
                    )
                )
        rows = np.concatenate(rows) if rows else np.empty(0, int)
        cuts = np.concatenate(a) if a else np.empty(0)
        # per curve: sorted break points, keep the sub-intervals whose middle is inside
        n = len(d)
        allr = np.concatenate([np.arange(n), np.arange(n), rows])
        allt = np.concatenate([np.full(n, c.t0), np.full(n, c.t1), cuts])
        order = np.lexsort((allt, allr))
        allr, allt = allr[order], allt[order]
        same = allr[1:] == allr[:-1]
        s0, s1, rr = allt[:-1][same], allt[1:][same], allr[:-1][same]
        keep = s1 > s0
        s0, s1, rr = s0[keep], s1[keep], rr[keep]
        mid_u2 = self._level_u2(0.5 * (s0 + s1), d[rr])
        inside = (mid_u2 >= lo) & (mid_u2 <= hi)
        s0, s1, rr = s0[inside], s1[inside], rr[inside]
        if not len(rr):
            return None
        # merge neighbouring pieces of the same curve
        join = np.concatenate([[False], (rr[1:] == rr[:-1]) & (s0[1:] == s1[:-1])])
        first = np.nonzero(~join)[0]
        last = np.concatenate([first[1:] - 1, [len(rr) - 1]])
        t0, t1, dk = s0[first], s1[last], d[rr[first]]
        periodic = c.closed and abs(
            float(self._level_u2(np.array([c.t1]), np.array([0.0]))[0])
            - float(self._level_u2(np.array([c.t0]), np.array([0.0]))[0])
        ) <= 1e-9 * (hi - lo)
        closed = periodic & (t0 == c.t0) & (t1 == c.t1)

        def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            return np.column_stack([t, self._level_u2(t, dk[idx])])

        return CurveBatch.from_uv(self, "curvature", t0, t1, uv, closed=closed)
