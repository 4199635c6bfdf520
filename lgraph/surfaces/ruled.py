"""Ruled surfaces ``x(u1, u2) = y(u1) + u2 z(u1)`` (paper §4).

A ruled surface is swept by the straight lines (rulings) through the points of
a directrix ``y`` in the directions of a director ``z``.  Everything the
renderer asks reduces to one-dimensional problems in ``u1``:

* derivatives: ``x1 = y' + u2 z'``, ``x2 = z``, ``x11 = y'' + u2 z''``,
  ``x12 = z'``, ``x22 = 0``;
* contour: with ``W = w`` (parallel view, toward the viewer) or
  ``W = eye - y(u1)`` (central view; ``eye - x`` differs from it by a multiple
  of ``z``, which drops out) the contour condition is *linear* in ``u2``::

      det(x1, x2, W) = A(u1) + u2 B(u1),   A = (y' x z) . W,   B = (z' x z) . W,

  so ``u2* = -A/B``.  Cylinders (``B = 0``), cones (``A = r B``) and tangent
  surfaces (``A = 0``) are developable: their contour consists of whole
  rulings, at the roots of ``A`` resp. ``B``;
* hits: the ray ``P + s v`` meets ruling ``u1`` iff
  ``g(u1) = det(y(u1) - P, z(u1), v) = 0``.  ``g`` is linear in ``P`` and ``v``,
  so it is evaluated for all rays on a grid of ``u1`` by two matrix products;
  brackets are refined all at once (:func:`lgraph._roots.bracketed_roots`) and ``(u2, s)``
  follow from ``y + u2 z = P + s v``;
* lines of curvature (developable surfaces): the rulings and the curves
  ``u2 = d - S(u1)`` with ``S = integral of y' . z`` (paper (4.2)): for
  cylinders ``S = c . y``, for cones ``S = |y - apex|`` (spheres about the
  vertex), for tangent surfaces ``S`` = arc length (involutes).

The ``u1`` grid is chosen from the curve: its nodes are equidistributed in the
total turning of ``z`` and of the tangent of ``y`` plus the arc length of the
patch's edges (about 8 cells per radian and per patch diameter).  *Limitation*:
a ray that meets more than two rulings within one grid cell, or the contour
curve crossing a ``u2`` edge twice within one cell, can be missed.

>>> import numpy as np
>>> import lgraph as lg
>>> circle = lg.Curve(lambda t: np.stack([np.cos(t), np.sin(t), 0 * t], -1), 0, 2 * np.pi,
...                   closed=True)
>>> cyl = GeneralCylinder(circle, (0, 0, 1), u2_range=(0, 2))
>>> cyl.point(0.0, 1.5).tolist()
[1.0, 0.0, 1.5]
>>> cone = GeneralCone(circle, apex=(0, 0, 1))
>>> cone.domain.u2  # from the directrix up to the vertex
(-1.414213562373095, 0.0)
>>> bool(np.allclose(cone.point(1.0, cone.domain.u2[0]), [0, 0, 1]))
True
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from .._own import CONTOUR
from .._roots import bracketed_roots
from .._tolerance import (
    RULED_CELLS_PER_UNIT as _CELLS_PER_UNIT,
)
from .._tolerance import (
    RULED_CHUNK as _CHUNK,
)
from .._tolerance import (
    RULED_CONTOUR_SELF_RTOL as _CONTOUR_SELF_RTOL,
)
from .._tolerance import (
    RULED_DEVELOPABLE_RTOL as _DEVELOPABLE_RTOL,
)
from .._tolerance import (
    RULED_MAX_CELLS as _MAX_CELLS,
)
from .._tolerance import (
    RULED_MIN_CELLS as _MIN_CELLS,
)
from .._tolerance import (
    RULED_PRE_SAMPLES as _PRE_SAMPLES,
)
from .._tolerance import (
    RULED_XTOL as _XTOL,
)
from .._tolerance import SELF_HIT_RTOL
from .._validate import interval, vector3
from ..curves import Curve, CurveBatch
from ._base import Domain, Surface

__all__ = ["RuledSurface", "GeneralCylinder", "GeneralCone", "TangentSurface"]

#: the name surfaces/revolution.py and surfaces/_revolution_contour.py import
_illinois = bracketed_roots

_GL_X, _GL_W = np.polynomial.legendre.leggauss(10)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", a, b)


def _flips(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(row, cell) of every sign change between neighbouring columns."""
    s = values >= 0
    return np.nonzero(s[:, 1:] != s[:, :-1])


def _curve(owner: str, name: str, value: Any) -> Curve:
    if not isinstance(value, Curve):
        raise TypeError(f"{owner}: {name} must be an lg.Curve, got {type(value).__name__}")
    return value


def _u2_range(owner: str) -> Any:
    return attrs.field(
        default=None,
        kw_only=True,
        converter=lambda v: None if v is None else interval(owner, "u2_range", v),
    )


class _Ruled(Surface):
    """The machinery shared by all ruled surfaces (not instantiated directly).

    Subclasses supply :meth:`_raw`: the directrix, an (unnormalized) director
    ``d`` and their derivatives; ``z = d/|d|`` unless ``_unit`` is False.
    """

    hit_cost = 17.0
    hit_call_cost = 5000.0

    _unit = True
    #: "general", "A" (rulings at roots of A) or "B" (rulings at roots of B)
    _contour_kind = "general"
    default_families = ("parameter_lines",)

    # -- to be supplied -----------------------------------------------------
    def _raw(self, u: np.ndarray, order: int) -> list[Any]:  # pragma: no cover
        """``[y, y', y'', d, d', d'']`` at ``u`` (entries above ``order`` may be None)."""
        raise NotImplementedError

    def _default_u2(self) -> tuple[float, float]:
        return (0.0, self._directrix_diameter())

    # -- set-up -------------------------------------------------------------
    def _setup(self) -> None:
        curve = self.directrix
        probe = self._raw(np.linspace(curve.t0, curve.t1, 257), 0)
        dn = np.linalg.norm(probe[3], axis=-1)
        if not np.all(np.isfinite(dn)) or not np.all(dn > 1e-12 * (dn.max() + 1e-300)):
            raise ValueError(
                f"{type(self).__name__}: the ruling direction must be a non-zero finite vector "
                "for every parameter value (does the directrix pass through the apex, or "
                "have a zero derivative?)"
            )
        if self.u2_range is None:
            object.__setattr__(self, "u2_range", self._default_u2())

    def _directrix_diameter(self) -> float:
        c = self.directrix
        y = c(np.linspace(c.t0, c.t1, 257))
        d = float(np.linalg.norm(y.max(axis=0) - y.min(axis=0)))
        return d if d > 0 else 1.0

    @property
    def domain(self) -> Domain:
        c = self.directrix
        return Domain((c.t0, c.t1), self.u2_range, periodic=(c.closed, False))

    # -- evaluation -----------------------------------------------------------
    def _rul(self, u: Any, order: int = 0) -> list[Any]:
        """``[y, y', y'', z, z', z'']`` at the flat array ``u``."""
        u = np.asarray(u, float)
        y, y1, y2, d, d1, d2 = self._raw(u, order)
        d = np.broadcast_to(d, u.shape + (3,))
        if not self._unit:
            z1 = None if order < 1 else np.broadcast_to(d1, d.shape)
            z2 = None if order < 2 else np.broadcast_to(d2, d.shape)
            return [y, y1, y2, d, z1, z2]
        rho = np.linalg.norm(d, axis=-1, keepdims=True)
        z = d / rho
        z1 = z2 = None
        if order >= 1:
            rho1 = _dot(d1, z)[..., None]
            z1 = (d1 - z * rho1) / rho
            if order >= 2:
                rho2 = (_dot(d2, z) + _dot(d1, z1))[..., None]
                z2 = (d2 - 2 * z1 * rho1 - z * rho2) / rho
        return [y, y1, y2, z, z1, z2]

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        """``y(u1) + u2 z(u1)``, broadcasting."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        y, _, _, z, _, _ = self._rul(u1.ravel(), 0)
        x = y + u2.reshape(-1, 1) * z
        return x.reshape(u1.shape + (3,))

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        """``x1 = y' + u2 z'`` and ``x2 = z``."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        y, y1, _, z, z1, _ = self._rul(u1.ravel(), 1)
        x1 = y1 + u2.reshape(-1, 1) * z1
        x2 = np.broadcast_to(z, x1.shape)
        return x1.reshape(u1.shape + (3,)), np.array(x2).reshape(u1.shape + (3,))

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``x11 = y'' + u2 z''``, ``x12 = z'``, ``x22 = 0``."""
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        _, _, y2, _, z1, z2 = self._rul(u1.ravel(), 2)
        x11 = y2 + u2.reshape(-1, 1) * z2
        shape = u1.shape + (3,)
        z1 = np.broadcast_to(z1, x11.shape)
        return x11.reshape(shape), np.array(z1).reshape(shape), np.zeros(shape)

    # -- the u1 grid (computed once) --------------------------------------------
    def _grid(self) -> dict[str, Any]:
        cache = self._cache
        if "grid" in cache:
            return cache["grid"]
        c = self.directrix
        lo, hi = self.u2_range
        u = np.linspace(c.t0, c.t1, _PRE_SAMPLES)
        y, y1, y2, z, z1, _ = self._rul(u, 2)
        y1 = np.broadcast_to(y1, y.shape)
        y2 = np.broadcast_to(y2, y.shape)
        z1 = np.broadcast_to(z1, y.shape)
        edges = np.concatenate([y + lo * z, y + hi * z])
        box_lo, box_hi = edges.min(axis=0), edges.max(axis=0)
        diam = float(np.linalg.norm(box_hi - box_lo)) or 1.0
        zz = _dot(z, z)
        turn_z = np.linalg.norm(np.cross(z, z1), axis=-1) / zz
        sp = _dot(y1, y1)
        with np.errstate(divide="ignore", invalid="ignore"):
            turn_t = np.linalg.norm(np.cross(y1, y2), axis=-1) / sp
        turn_t = np.where(sp > 1e-24 * (sp.max() + 1e-300), turn_t, 0.0)
        speed = np.linalg.norm(y1 + lo * z1, axis=-1) + np.linalg.norm(y1 + hi * z1, axis=-1)
        span = c.t1 - c.t0
        dens = turn_z + np.minimum(turn_t, 1e3 / span) + speed / diam + 4.0 / span
        mu = np.concatenate([[0.0], np.cumsum(0.5 * (dens[1:] + dens[:-1]) * np.diff(u))])
        n = int(np.clip(math.ceil(_CELLS_PER_UNIT * mu[-1]), _MIN_CELLS, _MAX_CELLS))
        nodes = np.interp(np.linspace(0.0, mu[-1], n + 1), mu, u)
        nodes[0], nodes[-1] = c.t0, c.t1
        Y, Y1, _, Z, Z1, _ = self._rul(nodes, 1)
        Y1 = np.broadcast_to(Y1, Y.shape)
        Z = np.broadcast_to(Z, Y.shape)
        Z1 = np.broadcast_to(Z1, Y.shape)
        # bounds: the patch lies in the hull of its u2 edges (rulings are straight);
        # pad by the chord error of the sampled edges
        chord = max(
            float(np.abs(e[:-2] - 2 * e[1:-1] + e[2:]).max()) for e in (y + lo * z, y + hi * z)
        )
        pad = 0.01 * diam + chord
        grid = {
            "u": nodes,
            "Y": np.array(Y),
            "Y1": np.array(Y1),
            "Z": np.array(Z),
            "Z1": np.array(Z1),
            "YxZ": np.cross(Y, Z),
            "dYxZ": np.cross(Y1, Z) + np.cross(Y, Z1),
            "bounds": (box_lo - pad, box_hi + pad),
            "xtol": _XTOL * max(abs(c.t0), abs(c.t1), span),
            "zmax": float(np.linalg.norm(Z, axis=-1).max()),
        }
        cache["grid"] = grid
        return grid

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self._grid()["bounds"]
        return lo.copy(), hi.copy()

    @property
    def size(self) -> float:
        lo, hi = self._grid()["bounds"]
        return float(np.linalg.norm(hi - lo))

    # -- hits ------------------------------------------------------------------
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

    # -- contour ---------------------------------------------------------------
    def _AB(self, u: np.ndarray, projector: Any) -> tuple[np.ndarray, np.ndarray]:
        """``A(u1)`` and ``B(u1)`` of ``det(x1, x2, W) = A + u2 B``."""
        y, y1, _, z, z1, _ = self._rul(u, 1)
        W = self._view(projector, y)
        return _dot(np.cross(y1, z), W), _dot(np.cross(z1, z), W)

    @staticmethod
    def _view(projector: Any, y: np.ndarray) -> np.ndarray:
        from ..projectors import CentralProjector

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

    def _ruling_batch(self, values: np.ndarray, family: str) -> CurveBatch:
        lo, hi = self.u2_range
        c1 = np.asarray(values, float)
        return CurveBatch.from_uv(
            self,
            family,
            np.full(len(c1), lo),
            np.full(len(c1), hi),
            lambda idx, t: np.column_stack([c1[idx], t]),
        )

    def _u2_line_batch(self, values: np.ndarray, family: str) -> CurveBatch:
        c = self.directrix
        c2 = np.asarray(values, float)
        return CurveBatch.from_uv(
            self,
            family,
            np.full(len(c2), c.t0),
            np.full(len(c2), c.t1),
            lambda idx, t: np.column_stack([t, c2[idx]]),
            closed=c.closed,
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

    # -- lines of curvature -------------------------------------------------------
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

    def describe(self) -> str:
        return repr(self)


def _director_curve(owner: str, value: Any, directrix: Curve, derivative: Any) -> Curve:
    if isinstance(value, Curve):
        return value
    if not callable(value):
        raise TypeError(
            f"{owner}: director must be a callable t -> (n, 3) or an lg.Curve, "
            f"got {type(value).__name__}"
        )
    return Curve(value, directrix.t0, directrix.t1, derivative_func=derivative)


@attrs.frozen(eq=False)
class RuledSurface(_Ruled):
    """Ruled surface ``x(u1, u2) = y(u1) + u2 z(u1)`` (paper (4.1)).

    Parameters
    ----------
    directrix : Curve
        The curve ``y``; ``u1`` runs over its parameter interval (periodic if
        the curve is ``closed``).
    director : callable or Curve
        ``t -> (n, 3)``: the ruling directions, normalized to unit vectors ``z``.
    u2_range : (lo, hi), optional
        The drawn part of each ruling; default ``(0, diameter of the directrix)``.
    director_derivative : callable, optional
        Analytic derivative of ``director`` (numeric otherwise).
    edges : bool
        Draw the patch's edges with its contour (default True).

    >>> import numpy as np
    >>> y = lambda t: np.stack([4 * np.cos(t), 4 * np.sin(t), 0 * t], -1)
    >>> z = lambda t: np.stack([np.cos(t) * np.sin(4 * t), np.sin(t) * np.sin(4 * t),
    ...                         np.cos(4 * t)], -1)
    >>> s = RuledSurface(Curve(y, 0, 2 * np.pi, closed=True), z, u2_range=(0, 3))
    >>> s.point(0.0, 3.0).round(12).tolist()
    [4.0, 0.0, 3.0]
    >>> RuledSurface(Curve(y, 0, 1), lambda t: 0 * y(t))
    Traceback (most recent call last):
    ...
    ValueError: RuledSurface: the ruling direction must be a non-zero finite vector ...
    """

    directrix: Curve = attrs.field(converter=lambda v: _curve("RuledSurface", "directrix", v))
    director: Any = attrs.field(default=None)
    u2_range: tuple[float, float] = _u2_range("RuledSurface")
    director_derivative: Any = attrs.field(default=None, kw_only=True, repr=False)
    edges: bool = attrs.field(default=True, kw_only=True)
    _cache: dict = attrs.field(init=False, factory=dict, repr=False)

    def __attrs_post_init__(self) -> None:
        self._cache["d"] = _director_curve(
            type(self).__name__, self.director, self.directrix, self.director_derivative
        )
        self._setup()

    def _raw(self, u: np.ndarray, order: int) -> list[Any]:
        c, d = self.directrix, self._cache["d"]
        return [
            c(u),
            c.derivative(u) if order >= 1 else None,
            c.second_derivative(u) if order >= 2 else None,
            d(u),
            d.derivative(u) if order >= 1 else None,
            d.second_derivative(u) if order >= 2 else None,
        ]


@attrs.frozen(eq=False)
class GeneralCylinder(RuledSurface):
    """General cylinder ``x = y(u1) + u2 c`` over ``directrix`` with constant
    unit ``direction`` ``c``.

    Lines of curvature (paper (4.3)): the rulings and the curves
    ``u2 = d - c . y(u1)`` (plane sections perpendicular to ``c``); the contour
    consists of the rulings where ``(y' x c) . W = 0``.

    >>> import numpy as np
    >>> GeneralCylinder(Curve(lambda t: np.stack([t, t, t], -1), 0, 1), (0, 0, 0))
    Traceback (most recent call last):
    ...
    ValueError: GeneralCylinder: direction must be a non-zero vector, got (0, 0, 0)
    """

    director: Any = attrs.field(init=False, default=None, repr=False)
    director_derivative: Any = attrs.field(init=False, default=None, repr=False)
    direction: np.ndarray = attrs.field(
        default=(0.0, 0.0, 1.0),
        converter=lambda v: vector3("GeneralCylinder", "direction", v, nonzero=True),
        eq=attrs.cmp_using(eq=np.array_equal),
    )
    _contour_kind = "A"

    def __attrs_post_init__(self) -> None:
        self._cache["c"] = self.direction / np.linalg.norm(self.direction)
        self._setup()

    def _raw(self, u: np.ndarray, order: int) -> list[Any]:
        c = self.directrix
        zero = np.zeros(3)
        return [
            c(u),
            c.derivative(u) if order >= 1 else None,
            c.second_derivative(u) if order >= 2 else None,
            self._cache["c"],
            zero,
            zero,
        ]

    def _S(self, u: np.ndarray) -> np.ndarray:
        return self.directrix(np.asarray(u, float)) @ self._cache["c"]


@attrs.frozen(eq=False)
class GeneralCone(RuledSurface):
    """General cone over ``directrix`` with vertex ``apex``.

    By default (paper (4.1), (4.4)) ``x = y(u1) + u2 z(u1)`` with the unit
    vector ``z = (y - apex)/|y - apex|``: ``u2`` is the signed distance from the
    directrix along the ruling and the vertex is at ``u2 = -|y(u1) - apex|``;
    the default ``u2_range`` runs from the directrix to the vertex (reached
    where ``y`` is closest to the apex).  With ``scaled=True`` the cone is
    ``x = apex + u2 (y(u1) - apex)`` (the paper's (4.6)): ``u2 = 0`` is the
    vertex, ``u2 = 1`` the directrix, negative ``u2`` the second nappe; the
    default range is ``(0, 1)``.

    Lines of curvature: the rulings and the sections by spheres about the
    vertex (``|x - apex| = const``); the contour consists of the rulings where
    ``(z' x z) . W = 0``.  The vertex is a singular point (no normal there).
    """

    director: Any = attrs.field(init=False, default=None, repr=False)
    director_derivative: Any = attrs.field(init=False, default=None, repr=False)
    apex: np.ndarray = attrs.field(
        default=(0.0, 0.0, 0.0),
        converter=lambda v: vector3("GeneralCone", "apex", v),
        eq=attrs.cmp_using(eq=np.array_equal),
    )
    scaled: bool = attrs.field(default=False, kw_only=True)
    _contour_kind = "B"

    def __attrs_post_init__(self) -> None:
        self._setup()

    @property
    def _unit(self) -> bool:  # type: ignore[override]
        return not self.scaled

    def _default_u2(self) -> tuple[float, float]:
        if self.scaled:
            return (0.0, 1.0)
        c = self.directrix
        r = np.linalg.norm(c(np.linspace(c.t0, c.t1, _PRE_SAMPLES)) - self.apex, axis=-1)
        return (-float(r.min()), 0.0)

    def _raw(self, u: np.ndarray, order: int) -> list[Any]:
        c = self.directrix
        y = c(u)
        y1 = c.derivative(u) if order >= 1 else None
        y2 = c.second_derivative(u) if order >= 2 else None
        if self.scaled:
            zero = np.zeros(3)
            return [np.broadcast_to(self.apex, y.shape), zero, zero, y - self.apex, y1, y2]
        return [y, y1, y2, y - self.apex, y1, y2]

    def _r(self, u: np.ndarray) -> np.ndarray:
        u = np.asarray(u, float)
        return np.linalg.norm(self.directrix(u.ravel()) - self.apex, axis=-1).reshape(u.shape)

    def _S(self, u: np.ndarray) -> np.ndarray:
        return self._r(u)

    def _level_u2(self, u1: np.ndarray, d: np.ndarray) -> np.ndarray:
        # distance from the vertex: r + u2 (unit) or u2 r (scaled) equals d
        if self.scaled:
            return d / self._r(u1)
        return d - self._r(u1)

    def _levels(self, n: int) -> np.ndarray:
        if not self.scaled:
            return super()._levels(n)
        lo, hi = self.u2_range
        r = self._r(self._grid()["u"])
        ends = np.concatenate([lo * r, hi * r])
        lvl = np.linspace(ends.min(), ends.max(), n + 2)[1:-1]
        return lvl[np.abs(lvl) > 1e-9 * (ends.max() - ends.min())]  # not the vertex

    def _check_developable(self) -> None:
        return None


def _third_derivative(c: Curve, u: np.ndarray) -> np.ndarray:
    """``y'''`` by eighth-order central differences of ``y''``."""
    h = 2e-3 * (c.t1 - c.t0)
    w = (4 / 5, -1 / 5, 4 / 105, -1 / 280)
    acc = 0.0
    for k, wk in enumerate(w, start=1):
        acc = acc + wk * (c.second_derivative(u + k * h) - c.second_derivative(u - k * h))
    return acc / h


@attrs.frozen(eq=False)
class TangentSurface(RuledSurface):
    """Tangent surface (tangent developable) of ``curve``:
    ``x = y(u1) + u2 y'(u1)/|y'(u1)|``.

    ``u2`` is the distance along the tangent; the curve itself (``u2 = 0``) is
    the edge of regression, a cuspidal edge drawn with the contour.  Lines of
    curvature (paper (4.5)): the rulings and the involutes
    ``u2 = d - s(u1)``, ``s`` the arc length.  Default ``u2_range``:
    ``(0, diameter/2)``.
    """

    director: Any = attrs.field(init=False, default=None, repr=False)
    director_derivative: Any = attrs.field(init=False, default=None, repr=False)
    _contour_kind = "B"

    def __attrs_post_init__(self) -> None:
        self._setup()

    def _default_u2(self) -> tuple[float, float]:
        return (0.0, 0.5 * self._directrix_diameter())

    def _raw(self, u: np.ndarray, order: int) -> list[Any]:
        c = self.directrix
        y1 = c.derivative(u)
        y2 = c.second_derivative(u) if order >= 1 else None
        y3 = _third_derivative(c, u) if order >= 2 else None
        return [c(u), y1 if order >= 1 else None, y2, y1, y2, y3]

    def _extra_contour(self) -> list[CurveBatch]:
        lo, hi = self.u2_range
        if lo <= 0.0 <= hi and not (self.edges and 0.0 in (lo, hi)):
            return [self._u2_line_batch(np.array([0.0]), "contour")]
        return []
