"""The elliptic and hyperbolic paraboloids, on bounded patches.

``z = x^2/a^2 + y^2/b^2`` (cut at a height) and ``z = x^2/a^2 - y^2/b^2``
(over a square of half-side ``extent``).  Lines of curvature in closed form
(:mod:`lgraph.surfaces.quadrics._curvature`): docs/mathematics.rst, "Hyperbolic paraboloid
(paper §5)" and "Elliptic paraboloid (not in the paper)" (confocal
paraboloids).  The hyperbolic paraboloid's asymptotic lines are its two
families of rulings.
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from ...curves import CurveBatch
from .._base import Domain
from ._unbounded import _angle, _optional_positive, _PatchQuadric, _set_default
from .quadric import _positive

__all__ = ["EllipticParaboloid", "HyperbolicParaboloid"]


@attrs.frozen
class EllipticParaboloid(_PatchQuadric):
    """Elliptic paraboloid ``z = x^2/a^2 + y^2/b^2``, drawn for ``z <= height``
    (default 1).

    ``x = (a u1 cos u2, b u1 sin u2, u1^2)``, ``0 <= u1 <= sqrt(height)``.
    Lines of curvature: confocal paraboloids (:mod:`!lgraph.surfaces.quadrics._curvature`),
    ``n1`` loops and ``n2`` complete curves; 2 umbilics (1 if a = b).
    """

    a: float = _positive("EllipticParaboloid")
    b: float = _positive("EllipticParaboloid")
    height: float = _optional_positive("EllipticParaboloid")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", 1.0)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, 0.0]), np.array([0.0, 0.0, -1.0]), 0.0

    @property
    def domain(self) -> Domain:
        return Domain((0.0, np.sqrt(self.height)), (0.0, 2 * np.pi), periodic=(False, True))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u1 * np.cos(u2), self.b * u1 * np.sin(u2), u1 * u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        c2, s2 = np.cos(u2), np.sin(u2)
        x1 = np.stack([self.a * c2, self.b * s2, 2 * u1], axis=-1)
        x2 = np.stack([-self.a * u1 * s2, self.b * u1 * c2, np.zeros_like(u1)], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        X, Y = x[..., 0] / self.a, x[..., 1] / self.b
        return np.stack([np.hypot(X, Y), _angle(Y, X)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = np.sqrt(self.height)
        return np.array([-self.a * r, -self.b * r, 0.0]), np.array(
            [self.a * r, self.b * r, self.height]
        )

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.asarray(points, float)[..., 2]

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._curvature import elliptic_paraboloid_lines

        return elliptic_paraboloid_lines(self, n1, n2)

    def umbilics(self) -> np.ndarray:
        """``(+-sqrt(P(Q-P)), 0, (Q-P)/2)`` with ``P, Q = a^2/2, b^2/2`` (a < b;
        on the axis of the smaller semi-axis); the vertex alone if a = b."""
        from ._curvature import elliptic_paraboloid_umbilics

        return elliptic_paraboloid_umbilics(self.a, self.b)


@attrs.frozen
class HyperbolicParaboloid(_PatchQuadric):
    """Hyperbolic paraboloid ``z = x^2/a^2 - y^2/b^2`` on the patch
    ``|x| <= a extent, |y| <= b extent`` (default ``extent = 1``).

    ``x = (a u1, b u2, u1^2 - u2^2)`` (paper §5).  Lines of curvature: the
    confocal-paraboloid parametrization ``(cosh s sinh t, sinh s cosh t)``
    (:mod:`!lgraph.surfaces.quadrics._curvature`), cut exactly to the patch.
    """

    a: float = _positive("HyperbolicParaboloid")
    b: float = _positive("HyperbolicParaboloid")
    extent: float = _optional_positive("HyperbolicParaboloid")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "extent", 1.0)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, -(self.b**-2), 0.0]), np.array([0.0, 0.0, -1.0]), 0.0

    @property
    def domain(self) -> Domain:
        r = self.extent
        return Domain((-r, r), (-r, r))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u1, self.b * u2, u1 * u1 - u2 * u2], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        one, zero = np.ones_like(u1), np.zeros_like(u1)
        return (
            np.stack([self.a * one, zero, 2 * u1], axis=-1),
            np.stack([zero, self.b * one, -2 * u2], axis=-1),
        )

    def asymptotic_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """The two families of rulings: with ``p = x/a + y/b`` and
        ``q = x/a - y/b`` the surface is ``z = p q``, so ``p = const`` and
        ``q = const`` are straight lines on it.  ``n1`` values of ``p`` and
        ``n2`` of ``q`` are spread over ``(-2 e, 2 e)``; each line is cut exactly
        to the square patch (``|p + q|, |p - q| <= 2 e``, so the free parameter
        runs over ``|c| - 2 e .. 2 e - |c|``).
        """
        e = self.extent
        out = []
        for n, swap in ((n1, False), (n2, True)):
            if n <= 0:
                continue
            c = Domain((-2 * e, 2 * e), (0.0, 1.0)).lines(0, n)
            half = 2 * e - np.abs(c)

            def uv(idx: np.ndarray, t: np.ndarray, c=c, swap=swap) -> np.ndarray:
                p, q = (t, c[idx]) if swap else (c[idx], t)
                return np.column_stack([(p + q) / 2, (p - q) / 2])

            out.append(CurveBatch.from_uv(self, "asymptotic", -half, half, uv))
        return out

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x[..., 0] / self.a, x[..., 1] / self.b], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = self.extent
        return np.array([-self.a * r, -self.b * r, -r * r]), np.array(
            [self.a * r, self.b * r, r * r]
        )

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        r = self.extent
        return np.minimum(r - np.abs(x[..., 0]) / self.a, r - np.abs(x[..., 1]) / self.b)

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        from ._curvature import hyperbolic_paraboloid_lines

        return hyperbolic_paraboloid_lines(self, n1, n2)
