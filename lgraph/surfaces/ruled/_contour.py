"""Ruled surfaces: contour and edges (docs/mathematics.rst, "Ruled surfaces,
general cylinders and cones", contour).

With ``W = w`` (parallel view, toward the viewer) or ``W = eye - y(u1)``
(central view; ``eye - x`` differs from it by a multiple of ``z``, which drops
out) the contour condition is *linear* in ``u2``::

    det(x1, x2, W) = A(u1) + u2 B(u1),   A = (y' x z) . W,   B = (z' x z) . W,

so ``u2* = -A/B``: the contour is cut into pieces where it crosses the ``u2``
edges (roots of ``A + u2 B`` for the edge values, refined by
:func:`lgraph._roots.bracketed_roots`).  Cylinders (``B = 0``), cones
(``A = r B``) and tangent surfaces (``A = 0``) are developable: their contour
consists of whole rulings, at the roots of ``A`` resp. ``B``.  *Limitation*:
the contour crossing a ``u2`` edge twice within one grid cell can be missed.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from ..._own import CONTOUR
from ..._roots import bracketed_roots
from ...curves import CurveBatch
from ...geometry.vectors import dot as _dot
from ._geometry import _flips, _RuledGeometry


class _RuledContour(_RuledGeometry):
    """:meth:`contour` and :meth:`boundary` of the ruled surfaces."""

    #: "general", "A" (rulings at roots of A) or "B" (rulings at roots of B)
    _contour_kind = "general"

    def _AB(self, u: np.ndarray, projector: Any) -> tuple[np.ndarray, np.ndarray]:
        """``A(u1)`` and ``B(u1)`` of ``det(x1, x2, W) = A + u2 B``."""
        y, y1, _, z, z1, _ = self._rul(u, 1)
        W = self._view(projector, y)
        return _dot(np.cross(y1, z), W), _dot(np.cross(z1, z), W)

    @staticmethod
    def _view(projector: Any, y: np.ndarray) -> np.ndarray:
        from ...scene.projectors import CentralProjector

        if isinstance(projector, CentralProjector):
            return projector.eye - y
        return np.broadcast_to(projector.frame[2], np.shape(y))

    def _roots(self, func: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """All sign changes of a function of ``u1`` on the grid, refined."""
        grid = self._grid()
        u = grid["u"]
        vals = func(u)[None, :]
        _, cols = _flips(vals)
        if not len(cols):
            return np.empty(0)
        return bracketed_roots(
            lambda x, s: func(x),
            u[cols],
            u[cols + 1],
            vals[0, cols],
            vals[0, cols + 1],
            grid["xtol"],
        )

    def _edges(self) -> list[CurveBatch]:
        """The patch boundary (``u2`` ends; ``u1`` ends unless periodic), without
        edges that collapse to a point (a cone's vertex)."""
        c = self.directrix
        lo, hi = self.u2_range
        t = np.linspace(c.t0, c.t1, 33)
        keep = []
        for v in (lo, hi):
            p = self.point(t, v)
            if np.ptp(p, axis=0).max() > 1e-9 * self.size:
                keep.append(v)
        out = [self._u2_line_batch(np.array(keep), "boundary")] if keep else []
        if not c.closed:
            out.append(self._ruling_batch(np.array([c.t0, c.t1]), "boundary"))
        return out

    def contour(self, projector: Any) -> list[CurveBatch]:
        """Contour of the drawn patch for ``projector`` (local frame): the curve
        ``u2 = -A/B`` (whole rulings for developable surfaces)."""
        out: list[CurveBatch] = []
        if self._contour_kind == "general":
            out.extend(self._contour_general(projector))
        else:
            pick = 0 if self._contour_kind == "A" else 1
            roots = self._roots(lambda x: self._AB(x, projector)[pick])
            if len(roots):
                out.append(self._ruling_batch(roots, "contour"))
        out.extend(self._extra_contour())
        return [attrs.evolve(b, own=CONTOUR) for b in out]

    def boundary(self) -> list[CurveBatch]:
        """The patch edges (with ``edges=True``, the default; none otherwise)."""
        return self._edges() if self.edges else []

    def _extra_contour(self) -> list[CurveBatch]:
        return []

    def _contour_general(self, projector: Any) -> list[CurveBatch]:
        c = self.directrix
        lo, hi = self.u2_range

        def edge(u2: float) -> Callable[[np.ndarray], np.ndarray]:
            def f(x: np.ndarray) -> np.ndarray:
                A, B = self._AB(x, projector)
                return A + u2 * B

            return f

        br = np.concatenate([[c.t0, c.t1], self._roots(edge(lo)), self._roots(edge(hi))])
        br = np.unique(br)
        br = br[(br >= c.t0) & (br <= c.t1)]
        if len(br) < 2:
            return []
        mid = 0.5 * (br[1:] + br[:-1])
        A, B = self._AB(mid, projector)
        inside = (A + lo * B) * (A + hi * B) <= 0
        # merge neighbouring inside intervals into pieces
        starts, ends = [], []
        for k in np.nonzero(inside)[0]:
            if ends and ends[-1] == br[k]:
                ends[-1] = br[k + 1]
            else:
                starts.append(br[k])
                ends.append(br[k + 1])
        if not starts:
            return []
        closed = c.closed and len(starts) == 1 and starts[0] == c.t0 and ends[0] == c.t1

        def uv(_idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            A, B = self._AB(t, projector)
            with np.errstate(divide="ignore", invalid="ignore"):
                u2 = np.where(B != 0, -A / np.where(B != 0, B, 1.0), 0.5 * (lo + hi))
            return np.column_stack([t, np.clip(u2, lo, hi)])

        return [CurveBatch.from_uv(self, "contour", starts, ends, uv, closed=closed)]
