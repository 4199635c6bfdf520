"""The monkey saddle's ray cubic and its transition functions for the
renderer's flip search (docs/mathematics.rst, "The monkey saddle").

Along ``o + s v`` the implicit function ``F = z - c (x^3 - 3 x y^2)`` is a
cubic ``P(s)`` (:func:`ray_cubic`).  :meth:`MonkeySaddle.hits` solves the
*deflated* cubic: ``P`` itself for a point off the surface, ``P / s`` for
its own point (``ON``: the root ``s = 0`` divided out, a quadratic ``Q``),
``P / s^2`` for a contour point (``CONTOUR``, a line ``L``).  A root of the
deflated polynomial hides the point when it lies in ``(cut, smax)``
(``cut = SELF_HIT_RTOL`` of the ray's size scale) over the square
``|x|, |y| <= e'`` (``e' = extent (1 + 1e-12)``).  So that answer changes,
along a curve on the surface, exactly where a root

* crosses ``cut``: the deflated polynomial is zero at ``s = cut``
  (:func:`contour_function`; for an ``ON`` point ``Q(cut) ≈ Q(0) = ∇F.v``,
  the point crossing its own contour);
* leaves the square through one of its four sides, the plane ``x = ±e'`` or
  ``y = ±e'``: the deflated polynomial is zero where the ray meets that
  plane (:func:`rim_function`);
* meets the other root (the ray starts or stops grazing the surface): the
  quadratic ``Q`` has a double root, its discriminant -- shifted by the band
  in which :func:`~lgraph.surfaces.classical._polyroots.real_roots` counts a complex
  pair as real -- is zero (:func:`grazing_function`).

Each function is NaN where it does not apply (the plane crossing or the
double root behind the point, past ``smax`` or off the square), and scaled
to be of order 1.  The renderer root-finds on whichever changes sign across
a flip and verifies the result with :meth:`hits`.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from ..._own import CONTOUR, ON
from ..._tolerance import SELF_HIT_RTOL


class Saddle(Protocol):
    """What the transition functions read of a monkey saddle (a
    :class:`~lgraph.MonkeySaddle`): its square, its scale and its size."""

    @property
    def extent(self) -> float: ...

    @property
    def c(self) -> float: ...

    @property
    def size(self) -> float: ...


__all__ = [
    "RIM_SLACK",
    "contour_function",
    "grazing_function",
    "margins",
    "ray_cubic",
    "rim_function",
]

#: The ray test's square reaches ``extent (1 + RIM_SLACK)`` (points on the
#: rim count as inside despite rounding).
RIM_SLACK = 1e-12

#: A complex pair of roots counts as real when its imaginary part is below
#: this fraction of ``size + |root|`` (:func:`~lgraph.surfaces.classical._polyroots.real_roots`).
_REAL_BAND = 1e-7

#: Order of the sides in :func:`margins`: the planes ``x = +e``, ``x = -e``,
#: ``y = +e``, ``y = -e``.
_SIDES = ((0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0))


def ray_cubic(c: float, o: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Coefficients ``(n, 4)``, highest power first, of ``P(s) = F(o + s v)``
    for ``F = z - c (x^3 - 3 x y^2)``."""
    ox, oy, oz = o.T
    vx, vy, vz = v.T
    return np.stack(
        [-c * (vx**3 - 3 * vx * vy * vy),
         -c * (3 * ox * vx * vx - 3 * (ox * vy * vy + 2 * oy * vx * vy)),
         vz - c * (3 * ox * ox * vx - 3 * (2 * ox * oy * vy + vx * oy * oy)),
         oz - c * (ox**3 - 3 * ox * oy * oy)], axis=1,
    )  # fmt: skip


def _deflated(coef: np.ndarray, own: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The polynomial the ray test solves, as a cubic ``(n, 4)`` with leading
    zeros (``P``, ``P / s`` or ``P / s^2`` by ``own``), and the number of
    roots ``s = 0`` divided out (0, 1 or 2)."""
    m = np.where(own == CONTOUR, 2, np.where(own == ON, 1, 0))
    out = np.zeros_like(coef)
    for k in (0, 1, 2):
        rows = np.flatnonzero(m == k)
        out[rows, k:] = coef[rows, : 4 - k]
    return out, m


def _horner(d: np.ndarray, s: np.ndarray) -> np.ndarray:
    return ((d[:, 0] * s + d[:, 1]) * s + d[:, 2]) * s + d[:, 3]


class _Rays:
    """What every transition function of one batch of rays needs."""

    def __init__(
        self, surface: Saddle, o: np.ndarray, v: np.ndarray, smax: np.ndarray, own: np.ndarray
    ) -> None:
        self.o, self.v = o, v
        n = len(o)
        self.smax = np.broadcast_to(np.asarray(smax, dtype=float), (n,))
        self.size = surface.size
        self.speed = np.sqrt(np.einsum("ij,ij->i", v, v))
        self.scale = self.size / self.speed  # the ray test's length scale in s
        self.cut = SELF_HIT_RTOL * self.scale
        self.e = surface.extent * (1 + RIM_SLACK)
        self.d, m = _deflated(ray_cubic(surface.c, o, v), np.asarray(own))
        # the deflated polynomial at s, divided by this, is dimensionless
        self.norm = self.size / self.scale**m

    def value(self, s: np.ndarray) -> np.ndarray:
        return _horner(self.d, s) / self.norm

    def inside(self, s: np.ndarray) -> np.ndarray:
        """Whether ``s`` lies in ``(cut, smax)`` and its point over the square."""
        x = self.o[:, 0] + s * self.v[:, 0]
        y = self.o[:, 1] + s * self.v[:, 1]
        with np.errstate(invalid="ignore"):
            return (s > self.cut) & (s < self.smax) & (np.abs(x) <= self.e) & (np.abs(y) <= self.e)


def contour_function(r: _Rays, own: np.ndarray) -> np.ndarray:
    """The deflated polynomial at ``s = cut`` (zero where a root crosses it;
    for a point on the surface ``≈ ∇F.v / |v|``, zero on its own contour);
    NaN for points off the surface."""
    out = r.value(r.cut)
    return np.where((own == ON) | (own == CONTOUR), out, np.nan)


def rim_function(r: _Rays, axis: int, sign: float) -> np.ndarray:
    """The deflated polynomial where the ray meets the plane
    ``x[axis] = sign e'`` (zero where a root leaves the square through that
    side); NaN where the ray misses that side within ``(cut, smax)``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (sign * r.e - r.o[:, axis]) / r.v[:, axis]
        other = np.abs(r.o[:, 1 - axis] + s * r.v[:, 1 - axis])
        ok = (s > r.cut) & (s < r.smax) & (other <= r.e)
    return np.where(ok, r.value(np.where(ok, s, 0.0)), np.nan)


def grazing_function(r: _Rays, own: np.ndarray) -> np.ndarray:
    """For a point on the surface, ``A2^2 - 4 A1 A3 + 4 b^2 (|A3| + |A2|/2)^2``
    with ``Q(s) = A3 σ^2 + A2 σ + A1`` in ``σ = s / scale`` and ``b`` the band
    of :func:`~lgraph.surfaces.classical._polyroots.real_roots`: non-negative exactly
    where the ray test counts ``Q``'s roots as real.  NaN for other points, and
    where the double root ``-A2 / (2 A3)`` is not in ``(cut, smax)`` over the
    square."""
    n = len(r.o)
    out = np.full(n, np.nan)
    rows = np.flatnonzero(own == ON)
    if not len(rows):
        return out
    d, sc = r.d[rows], r.scale[rows]
    a3, a2, a1 = d[:, 1] * sc * sc, d[:, 2] * sc, d[:, 3]
    norm = r.norm[rows]
    a3, a2, a1 = a3 / norm, a2 / norm, a1 / norm
    g = a2 * a2 - 4 * a1 * a3 + 4 * _REAL_BAND**2 * (np.abs(a3) + 0.5 * np.abs(a2)) ** 2
    # the ray test drops a leading coefficient below 1e-13 of the largest
    # (then Q is a line: no double root)
    big = np.abs(d[:, 1:]).max(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        s2 = np.where(np.abs(d[:, 1]) > 1e-13 * big, -d[:, 2] / (2 * d[:, 1]), np.nan)
    full = np.full(n, np.nan)
    full[rows] = s2
    ok = r.inside(full)[rows]
    out[rows[ok]] = g[ok]
    return out


def margins(
    surface: Saddle,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray,
    which: int | None = None,
) -> np.ndarray:
    """The six transition functions ``(6, n)`` (only row ``which`` when given,
    ``(1, n)``): the contour function, the four rims (``x = +e, -e``, ``y =
    +e, -e``) and the grazing function (module docstring)."""
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    v = np.asarray(directions, dtype=float).reshape(-1, 3)
    own = np.broadcast_to(np.asarray(own), (len(o),))
    r = _Rays(surface, o, v, smax, own)

    def row(k: int) -> np.ndarray:
        if k == 0:
            return contour_function(r, own)
        if k <= len(_SIDES):
            return rim_function(r, *_SIDES[k - 1])
        return grazing_function(r, own)

    if which is not None:
        return row(which)[None]
    return np.stack([row(k) for k in range(len(_SIDES) + 2)])
