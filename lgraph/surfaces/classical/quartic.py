"""Quartic surfaces with an exact ray test: the ring torus and the Dupin cyclide.

Both satisfy ``(|x|^2 + k)^2 = 4 sum_i (w_i . x + w0_i)^2``; along a ray this is
a quartic in the ray parameter, solved for all rays at once
(:func:`~lgraph.surfaces.classical._polyroots.roots_in`).

>>> import numpy as np
>>> t = Torus(3, 1)
>>> t.point(np.array([0.0]), np.array([0.0])).tolist()
[[4.0, 0.0, 0.0]]
>>> Torus(1, 2)
Traceback (most recent call last):
...
ValueError: Torus: r must be smaller than R (a ring torus), got R=1, r=2
"""

from __future__ import annotations

import functools
from typing import Any

import attrs
import numpy as np

from ..._tolerance import SELF_HIT_RTOL
from ...families._lines import parameter_line_batches
from .._base import CONTOUR, ON, Domain, Surface
from ..parametric import _TWO_PI, _positive, _stack, _uv
from ._polyroots import roots_in

__all__ = ["Torus", "DupinCyclide"]


def _quartic_implicit(points: Any, k: float, lin: np.ndarray) -> np.ndarray:
    """``(|x|^2 + k)^2 - 4 sum_i (w_i . x + w0_i)^2`` with rows ``(w_i, w0_i)``
    of ``lin``: the implicit form of the torus and of the Dupin cyclide."""
    p = np.asarray(points, dtype=float)
    q = np.einsum("...i,...i", p, p) + k
    forms = p @ lin[:, :3].T + lin[:, 3]
    return q * q - 4 * np.einsum("...i,...i", forms, forms)


def _quartic_hits(
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray | None,
    k: float,
    lin: np.ndarray,
    size: float,
    count: bool = False,
) -> np.ndarray:
    """Exact ray test for the surfaces :func:`_quartic_implicit` describes
    (with ``count``: how many times each ray crosses the surface).

    Along ``o + s v`` the implicit function is a quartic in ``s``, solved for
    all rays at once (:func:`~lgraph.surfaces.classical._polyroots.roots_in`).  A
    point on the surface (``ON``) has the root ``s = 0`` divided out (a cubic
    is left); a contour point (``CONTOUR``, the ray tangent there) has it
    twice (a quadratic).  Roots count when real and in
    ``(eps, smax)``, ``eps`` the self-hit tolerance of the surface's ``size``.
    """
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    v = np.asarray(directions, dtype=float).reshape(-1, 3)
    n = len(o)
    smax = np.broadcast_to(np.asarray(smax, dtype=float), (n,))
    own = np.zeros(n, np.int8) if own is None else np.asarray(own)
    # |x|^2 + k = qa s^2 + qb s + qc, and each linear form = la s + lb
    qa = np.einsum("ij,ij->i", v, v)
    qb = 2 * np.einsum("ij,ij->i", o, v)
    qc = np.einsum("ij,ij->i", o, o) + k
    la = v @ lin[:, :3].T
    lb = o @ lin[:, :3].T + lin[:, 3]
    coef = np.stack(
        [qa * qa, 2 * qa * qb, qb * qb + 2 * qa * qc - 4 * (la * la).sum(1),
         2 * qb * qc - 8 * (la * lb).sum(1), qc * qc - 4 * (lb * lb).sum(1)], axis=1,
    )  # fmt: skip
    speed = np.sqrt(qa)  # s is in units of |v|
    hit = np.zeros(n, dtype=np.int64)
    for degree, rows in (
        (4, np.flatnonzero((own != ON) & (own != CONTOUR))),
        (3, np.flatnonzero(own == ON)),
        (2, np.flatnonzero(own == CONTOUR)),
    ):
        if len(rows):  # the last 4 - degree coefficients vanish: s = 0 divided out
            scale = size / speed[rows]
            hit[rows] = roots_in(coef[rows, : degree + 1], SELF_HIT_RTOL * scale, smax[rows], scale)
    return hit if count else hit > 0


class _QuarticSurface(Surface):
    """A surface ``(|x|^2 + k)^2 = 4 sum_i (w_i . x + w0_i)^2`` (``_quartic``
    gives ``k`` and the rows ``(w_i, w0_i)``) with the exact ray test of
    :func:`_quartic_hits`."""

    # the quartic ray test costs about 3 us per ray and 150 us per call
    hit_cost = 10.0
    hit_call_cost = 500.0

    @property
    def _quartic(self) -> tuple[float, np.ndarray]:  # pragma: no cover - abstract
        raise NotImplementedError

    def _quartic_size(self) -> float:  # pragma: no cover - abstract
        raise NotImplementedError

    def implicit(self, points: Any) -> np.ndarray:
        """The implicit function: zero on the surface, negative inside."""
        return _quartic_implicit(points, *self._quartic)

    def _solid(self) -> Any:
        return self.implicit

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Exact ray test (:func:`_quartic_hits`)."""
        k, lin = self._quartic
        return _quartic_hits(origins, directions, smax, own, k, lin, self._quartic_size())

    def hit_count(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """The ray's crossings (up to four; a point's own root not counted):
        the real roots of the ray's quartic in ``(eps, smax)``
        (:func:`_quartic_hits`)."""
        k, lin = self._quartic
        return _quartic_hits(origins, directions, smax, own, k, lin, self._quartic_size(), True)


@attrs.frozen
class Torus(_QuarticSurface):
    """Ring torus ``((R + r cos u2) cos u1, (R + r cos u2) sin u1, r sin u2)``.

    ``u1`` runs around the axis (``z``), ``u2`` around the tube; both periodic.
    Lines of curvature are the parameter lines (meridians and parallels).  Its
    ray test is exact (a quartic in the ray parameter, :meth:`!hits`; some 20
    times faster than the numeric default); the contour is numeric.

    >>> Torus(2, 0)
    Traceback (most recent call last):
    ...
    ValueError: Torus: r must be a positive finite number, got 0
    """

    R: float = _positive("Torus")
    r: float = _positive("Torus")

    def __attrs_post_init__(self) -> None:
        if not self.r < self.R:
            raise ValueError(
                f"Torus: r must be smaller than R (a ring torus), got R={self.R}, r={self.r}"
            )

    @property
    def domain(self) -> Domain:
        return Domain((0.0, _TWO_PI), (0.0, _TWO_PI), periodic=(True, True))

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        e = self.R + self.r
        return np.array([-e, -e, -self.r]), np.array([e, e, self.r])

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = _uv(u1, u2)
        rho = self.R + self.r * np.cos(u2)
        return _stack(rho * np.cos(u1), rho * np.sin(u1), self.r * np.sin(u2))

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        rho = self.R + self.r * np.cos(u2)
        c1, s1, c2, s2 = np.cos(u1), np.sin(u1), np.cos(u2), np.sin(u2)
        x1 = _stack(-rho * s1, rho * c1, np.zeros_like(u1))
        x2 = _stack(-self.r * s2 * c1, -self.r * s2 * s1, self.r * c2)
        return x1, x2

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        rho = self.R + self.r * np.cos(u2)
        c1, s1, c2, s2 = np.cos(u1), np.sin(u1), np.cos(u2), np.sin(u2)
        z = np.zeros_like(u1)
        x11 = _stack(-rho * c1, -rho * s1, z)
        x12 = _stack(self.r * s2 * s1, -self.r * s2 * c1, z)
        x22 = _stack(-self.r * c2 * c1, -self.r * c2 * s1, -self.r * s2)
        return x11, x12, x22

    @property
    def _quartic(self) -> tuple[float, np.ndarray]:
        """``(|x|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2)``."""
        R = self.R
        return R**2 - self.r**2, np.array([[R, 0.0, 0.0, 0.0], [0.0, R, 0.0, 0.0]])

    def _quartic_size(self) -> float:
        return 2 * (self.R + self.r)

    def lines_of_curvature(self, n1: int, n2: int) -> list:
        """Meridians ``u1 = const`` and parallels ``u2 = const`` (exact)."""
        d = self.domain
        return parameter_line_batches(self, d.lines(0, n1), d.lines(1, n2))


@functools.lru_cache(maxsize=64)
def _cyclide_size(a: float, b: float, d: float) -> float:
    """Diagonal of a Dupin cyclide's bounding box (sampled once per shape)."""
    return DupinCyclide(a, b, d).size


@attrs.frozen
class DupinCyclide(_QuarticSurface):
    """Ring Dupin cyclide with parameters ``a > b > 0``, ``c = sqrt(a^2 - b^2) < d < a``.

    ``x = (d (c - a cos u1 cos u2) + b^2 cos u1, b sin u1 (a - d cos u2),
    b sin u2 (c cos u1 - d)) / (a - c cos u1 cos u2)``; both parameters periodic.
    All its lines of curvature are circles: the parameter lines.

    >>> DupinCyclide(2, 1.9, 0.5)
    Traceback (most recent call last):
    ...
    ValueError: DupinCyclide: d must lie strictly between c = sqrt(a^2 - b^2) and a ...
    """

    a: float = _positive("DupinCyclide", 2.0)
    b: float = _positive("DupinCyclide", 1.9)
    d: float = _positive("DupinCyclide", 1.0)

    def __attrs_post_init__(self) -> None:
        if not self.b < self.a:
            raise ValueError(f"DupinCyclide: b must be smaller than a, got a={self.a}, b={self.b}")
        if not self.c < self.d < self.a:
            raise ValueError(
                "DupinCyclide: d must lie strictly between c = sqrt(a^2 - b^2) and a "
                f"(ring cyclide), got a={self.a}, b={self.b}, d={self.d}"
            )

    @property
    def c(self) -> float:
        return float(np.sqrt(self.a**2 - self.b**2))

    @property
    def domain(self) -> Domain:
        return Domain((0.0, _TWO_PI), (0.0, _TWO_PI), periodic=(True, True))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = _uv(u1, u2)
        a, b, c, d = self.a, self.b, self.c, self.d
        c1, s1, c2, s2 = np.cos(u1), np.sin(u1), np.cos(u2), np.sin(u2)
        den = a - c * c1 * c2
        return _stack(
            (d * (c - a * c1 * c2) + b * b * c1) / den,
            b * s1 * (a - d * c2) / den,
            b * s2 * (c * c1 - d) / den,
        )

    @property
    def _quartic(self) -> tuple[float, np.ndarray]:
        """``(|x|^2 + b^2 - d^2)^2 - 4 (a x - c d)^2 - 4 b^2 y^2``."""
        a, b, c, d = self.a, self.b, self.c, self.d
        return b * b - d * d, np.array([[a, 0.0, 0.0, -c * d], [0.0, b, 0.0, 0.0]])

    def _quartic_size(self) -> float:
        return _cyclide_size(self.a, self.b, self.d)

    def lines_of_curvature(self, n1: int, n2: int) -> list:
        """Both families of circles: the parameter lines (exact)."""
        d = self.domain
        return parameter_line_batches(self, d.lines(0, n1), d.lines(1, n2))
