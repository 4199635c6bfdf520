"""The ring Dupin cyclide: exact contour, quartic ray hits, circles of curvature.

Standard form (``0 <= c < mu < a``, ``b^2 = a^2 - c^2``)::

    x = (mu (c - a cos u cos v) + b^2 cos u) / D
    y = b sin u (a - mu cos v) / D                 D = a - c cos u cos v
    z = b sin v (c cos u - mu) / D

It is the envelope of the spheres with centres ``m(u) = (a cos u, b sin u, 0)``
on an ellipse and radii ``r(u) = mu - c cos u``; the lines ``u = const`` are
the circles where those spheres touch it, so the unit normal there is
``(x - m(u)) / r(u)``.  Both families of parameter lines are circles and lines
of curvature.  ``c = 0`` gives the torus with radii ``a`` and ``mu``.

Implicit equation: ``(|x|^2 + b^2 - mu^2)^2 - 4 (a x - c mu)^2 - 4 b^2 y^2 = 0``.

>>> import numpy as np
>>> cy = DupinCyclide(5, 2, 3)
>>> p = cy.point(np.array([0.3, 2.0]), np.array([1.0, -0.4]))
>>> bool(np.all(np.abs(cy.implicit(p)) < 1e-10))
True
>>> DupinCyclide(5, 3, 2)
Traceback (most recent call last):
...
ValueError: DupinCyclide: need 0 <= c < mu < a (a ring cyclide), got a=5, c=3, mu=2
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np
from scipy.optimize import brentq

from lgraph import CurveBatch, Domain, Surface
from lgraph._own import CONTOUR, ON
from lgraph._tolerance import SELF_HIT_RTOL
from lgraph.families import parameter_line_batches
from lgraph.surfaces.classical._polyroots import has_root_in

__all__ = ["DupinCyclide"]

_TWO_PI = 2 * np.pi
#: grid of u on which the contour's existence intervals are found
_CONTOUR_GRID = 1440


def _number(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ValueError(f"DupinCyclide: parameters must be finite numbers, got {value!r}")
    return float(value)


@attrs.frozen
class DupinCyclide(Surface):
    """Ring Dupin cyclide with ellipse semi-axis ``a``, eccentricity ``c`` and
    radius parameter ``mu`` (``0 <= c < mu < a``); ``u, v`` in ``[0, 2 pi)``."""

    a: float = attrs.field(converter=_number)
    c: float = attrs.field(converter=_number)
    mu: float = attrs.field(converter=_number)

    def __attrs_post_init__(self) -> None:
        a, c, mu = self.a, self.c, self.mu
        if not (np.isfinite([a, c, mu]).all() and 0 <= c < mu < a):
            raise ValueError(
                f"DupinCyclide: need 0 <= c < mu < a (a ring cyclide), got a={a:g}, c={c:g}, "
                f"mu={mu:g}"
            )

    @property
    def b(self) -> float:
        return float(np.sqrt(self.a**2 - self.c**2))

    @property
    def domain(self) -> Domain:
        return Domain((0.0, _TWO_PI), (0.0, _TWO_PI), periodic=(True, True))

    # -- geometry ---------------------------------------------------------------
    def _terms(self, u: Any, v: Any) -> tuple[np.ndarray, ...]:
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        return np.cos(u), np.sin(u), np.cos(v), np.sin(v)

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        a, b, c, mu = self.a, self.b, self.c, self.mu
        cu, su, cv, sv = self._terms(u1, u2)
        den = a - c * cu * cv
        x = mu * (c - a * cu * cv) + b * b * cu
        y = b * su * (a - mu * cv)
        z = b * sv * (c * cu - mu)
        return np.stack([x, y, z], axis=-1) / den[..., None]

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        a, b, c, mu = self.a, self.b, self.c, self.mu
        cu, su, cv, sv = self._terms(u1, u2)
        den = a - c * cu * cv
        num = np.stack([mu * (c - a * cu * cv) + b * b * cu, b * su * (a - mu * cv),
                        b * sv * (c * cu - mu)], axis=-1)  # fmt: skip
        n_u = np.stack([mu * a * su * cv - b * b * su, b * cu * (a - mu * cv),
                        -b * c * sv * su], axis=-1)  # fmt: skip
        n_v = np.stack([mu * a * cu * sv, b * mu * su * sv, b * cv * (c * cu - mu)], axis=-1)
        d_u, d_v = (c * su * cv)[..., None], (c * cu * sv)[..., None]
        d2 = (den * den)[..., None]
        return (n_u * den[..., None] - num * d_u) / d2, (n_v * den[..., None] - num * d_v) / d2

    def sphere(self, u: Any) -> tuple[np.ndarray, np.ndarray]:
        """Centre ``m(u)`` and radius ``r(u)`` of the sphere touching along ``u = const``."""
        u = np.asarray(u, float)
        m = np.stack([self.a * np.cos(u), self.b * np.sin(u), np.zeros_like(u)], axis=-1)
        return m, self.mu - self.c * np.cos(u)

    def implicit(self, points: Any) -> np.ndarray:
        """The quartic ``F(x)``; zero on the cyclide, negative inside."""
        p = np.asarray(points, float)
        a, b, c, mu = self.a, self.b, self.c, self.mu
        q = np.einsum("...i,...i", p, p) + b * b - mu * mu
        return q * q - 4 * (a * p[..., 0] - c * mu) ** 2 - 4 * b * b * p[..., 1] ** 2

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Exact box of the union of the touching spheres."""
        a, c, mu = self.a, self.c, self.mu
        lo = np.array([-(a + c) - mu, -(a + mu), -(c + mu)])
        hi = np.array([a - c + mu, a + mu, c + mu])
        return lo, hi

    @property
    def size(self) -> float:
        lo, hi = self.bounds()
        return float(np.linalg.norm(hi - lo))

    # -- what it draws ------------------------------------------------------------
    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        """Both families are circles: the parameter lines ``u = const``, ``v = const``."""
        d = self.domain
        return parameter_line_batches(
            self, d.lines(0, n1), d.lines(1, n2), "curvature", "curvature"
        )

    def _contour_coefficients(self, u: np.ndarray, projector: Any) -> tuple[np.ndarray, ...]:
        """``A + B cos v + C sin v = 0`` on circle ``u`` is the contour condition.

        On circle ``u`` the normal is ``(x - m)/r``; the contour is
        ``(x - m) . p = k`` with ``p = w, k = 0`` (parallel view ``w``) or
        ``p = e - m, k = r^2`` (eye ``e``).  With ``x = (P0 + P1 cos v +
        P2 sin v) / (a - c cos u cos v)`` this is linear in ``cos v, sin v``.
        """
        from lgraph import CentralProjector

        a, b, c, mu = self.a, self.b, self.c, self.mu
        cu, su = np.cos(u), np.sin(u)
        m, r = self.sphere(u)
        if isinstance(projector, CentralProjector):
            p = projector.eye - m
            k = r * r
        else:
            p = np.broadcast_to(projector.frame[2], m.shape)
            k = np.zeros_like(u)
        mpk = np.einsum("...i,...i", m, p) + k
        p0 = p[..., 0] * (mu * c + b * b * cu) + p[..., 1] * b * a * su
        p1 = -p[..., 0] * mu * a * cu - p[..., 1] * b * mu * su
        p2 = p[..., 2] * b * (c * cu - mu)
        return p0 - a * mpk, p1 + c * cu * mpk, p2

    def contour(self, projector: Any) -> list[CurveBatch]:
        """Exact contour: per circle ``u`` the closed-form roots ``v`` of
        ``A + B cos v + C sin v = 0``; where a circle stops meeting the contour
        (``A^2 = B^2 + C^2``, found by brentq) the two roots join, and each
        closed contour curve is parametrized smoothly through those folds."""

        def h(u: Any) -> Any:
            A, B, C = self._contour_coefficients(np.asarray(u, float), projector)
            return B * B + C * C - A * A

        grid = np.linspace(0.0, _TWO_PI, _CONTOUR_GRID, endpoint=False)
        hv = h(grid)
        if np.all(hv > 0):  # every circle meets the contour twice: two closed loops
            return [self._loops(projector)]
        if np.all(hv <= 0):
            return []
        start = int(np.argmax(hv <= 0))  # begin where no circle meets the contour
        us = np.concatenate([grid[start:], grid[:start] + _TWO_PI, [grid[start] + _TWO_PI]])
        hs = np.concatenate([hv[start:], hv[:start], [hv[start]]])
        sign = hs > 0
        ups = np.nonzero(~sign[:-1] & sign[1:])[0]
        downs = np.nonzero(sign[:-1] & ~sign[1:])[0]
        intervals = []
        for i0, i1 in zip(ups, downs):
            u0 = brentq(h, us[i0], us[i0 + 1], xtol=1e-15, rtol=1e-15)
            u1 = brentq(h, us[i1], us[i1 + 1], xtol=1e-15, rtol=1e-15)
            intervals.append((u0, u1))
        mid = np.array([(u0 + u1) / 2 for u0, u1 in intervals])
        half = np.array([(u1 - u0) / 2 for u0, u1 in intervals])
        return [self._folded(projector, mid, half)]

    def _roots(self, u: np.ndarray, side: np.ndarray, projector: Any) -> np.ndarray:
        A, B, C = self._contour_coefficients(u, projector)
        R = np.hypot(B, C)
        with np.errstate(invalid="ignore", divide="ignore"):
            rho = np.clip(-A / R, -1.0, 1.0)
        return np.arctan2(C, B) + side * np.arccos(rho)

    def _uv_batch(self, t0: Any, t1: Any, uv: Any) -> CurveBatch:
        def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            p = uv(idx, t)
            return self.point(p[:, 0], p[:, 1]), np.mod(p, _TWO_PI)

        return CurveBatch("contour", t0, t1, evaluate, closed=True, surface=self, own=CONTOUR)

    def _loops(self, projector: Any) -> CurveBatch:
        sides = np.array([1.0, -1.0])

        def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            return np.column_stack([t, self._roots(t, sides[idx], projector)])

        return self._uv_batch([0.0, 0.0], [_TWO_PI, _TWO_PI], uv)

    def _folded(self, projector: Any, mid: np.ndarray, half: np.ndarray) -> CurveBatch:
        """One closed curve per interval ``mid +- half``: ``u = mid - half cos t``
        and the ``+`` root for ``sin t > 0``, the ``-`` root otherwise."""

        def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            u = mid[idx] - half[idx] * np.cos(t)
            side = np.where(np.sin(t) >= 0, 1.0, -1.0)
            return np.column_stack([u, self._roots(u, side, projector)])

        n = len(mid)
        return self._uv_batch(np.zeros(n), np.full(n, _TWO_PI), uv)

    # -- what it hides --------------------------------------------------------------
    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Roots of the quartic ``F(o + s v)`` in ``(eps, smax)``.

        A point on the cyclide has the root ``s = 0`` (double on the contour):
        it is divided out exactly, leaving a cubic (quadratic); roots come from
        companion-matrix eigenvalues polished by Newton steps.  Rays missing
        the bounding sphere ``|x| <= a + c + mu`` are culled first.
        """
        o = np.asarray(origins, float).reshape(-1, 3)
        v = np.asarray(directions, float).reshape(-1, 3)
        n = len(o)
        smax = np.broadcast_to(np.asarray(smax, float), (n,)).copy()
        own = np.zeros(n, np.int8) if own is None else np.asarray(own).reshape(-1)
        out = np.zeros(n, bool)
        vn = np.linalg.norm(v, axis=1)
        ok = vn > 0
        # cull: closest point of the segment to the centre outside the bounding sphere
        rad = self.a + self.c + self.mu
        with np.errstate(invalid="ignore", divide="ignore"):
            s_star = np.clip(-np.einsum("ij,ij->i", o, v) / vn**2, 0.0, smax)
        near = np.linalg.norm(o + np.nan_to_num(s_star)[:, None] * v, axis=1) <= rad * (1 + 1e-9)
        idx = np.nonzero(ok & near)[0]
        if not len(idx):
            return out.reshape(np.shape(origins)[:-1])
        # unit directions: s in length units
        vu = v[idx] / vn[idx, None]
        oo = o[idx]
        smx = smax[idx] * vn[idx]
        coef = self._quartic(oo, vu)
        eps = SELF_HIT_RTOL * self.size
        hit = np.zeros(len(idx), bool)
        kinds = own[idx]
        for kind, drop in ((0, 0), (ON, 1), (CONTOUR, 2)):
            sel = (kinds == kind) if kind else ((kinds != ON) & (kinds != CONTOUR))
            if sel.any():
                c = coef[sel][:, : 5 - drop]  # highest power first; drop the s^0 (s^1) terms
                hit[sel] = has_root_in(c, eps, smx[sel], self.size)
        out[idx] = hit
        return out.reshape(np.shape(origins)[:-1])

    def _quartic(self, o: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Coefficients (s^4 .. s^0) of ``F(o + s v)`` for unit ``v``."""
        a, b, c, mu = self.a, self.b, self.c, self.mu
        A2 = np.einsum("ij,ij->i", v, v)
        A1 = 2 * np.einsum("ij,ij->i", o, v)
        A0 = np.einsum("ij,ij->i", o, o) + b * b - mu * mu
        l0, l1 = a * o[:, 0] - c * mu, a * v[:, 0]
        m0, m1 = b * o[:, 1], b * v[:, 1]
        return np.column_stack([
            A2 * A2,
            2 * A2 * A1,
            A1 * A1 + 2 * A2 * A0 - 4 * (l1 * l1 + m1 * m1),
            2 * A1 * A0 - 8 * (l0 * l1 + m0 * m1),
            A0 * A0 - 4 * (l0 * l0 + m0 * m0),
        ])  # fmt: skip
