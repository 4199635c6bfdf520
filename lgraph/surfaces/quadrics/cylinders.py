"""The elliptic, hyperbolic and parabolic cylinders, on bounded patches.

``x^2/a^2 + y^2/b^2 = 1``, ``x^2/a^2 - y^2/b^2 = 1`` (both branches) and
``z = x^2/a^2``, each of bounded length along its rulings.  Their lines of
curvature are their parameter lines, cross-sections and rulings
(docs/mathematics.rst, "Ruled surfaces, general cylinders and cones (paper
§4)", Example 4.1), the rulings spread evenly by arc length.
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from ...curves import CurveBatch
from .._base import Domain
from ._unbounded import _angle, _optional_positive, _PatchQuadric, _piece_lines, _set_default
from .quadric import _positive

__all__ = ["EllipticCylinder", "HyperbolicCylinder", "ParabolicCylinder"]


def _ruled_loc(surface: Any, n1: int, n2: int) -> list[CurveBatch]:
    """Cylinders (paper Example 4.1): the parameter lines are the lines of
    curvature -- ``n1`` cross-sections ``u1 = const``, ``n2`` rulings spread
    evenly by arc length along the cross-section, on every piece."""
    return _piece_lines(surface, n1, n2, ("c1", "c2"), even=True)


@attrs.frozen
class EllipticCylinder(_PatchQuadric):
    """Elliptic cylinder ``x^2/a^2 + y^2/b^2 = 1``, ``|z| <= height`` (default
    ``max(a, b)``); ``x = (a cos u2, b sin u2, u1)``.  Lines of curvature: the
    cross-sections and the rulings."""

    a: float = _positive("EllipticCylinder")
    b: float = _positive("EllipticCylinder")
    height: float = _optional_positive("EllipticCylinder")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", max(self.a, self.b))

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, self.b**-2, 0.0]), np.zeros(3), -1.0

    @property
    def domain(self) -> Domain:
        return Domain((-self.height, self.height), (0.0, 2 * np.pi), periodic=(False, True))

    def _pieces(self) -> list[tuple]:
        return [(self.domain.u1, self.domain.u2, "periodic", None)]

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * np.cos(u2), self.b * np.sin(u2), u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        z = np.zeros_like(u1)
        x1 = np.stack([z, z, np.ones_like(u1)], axis=-1)
        x2 = np.stack([-self.a * np.sin(u2), self.b * np.cos(u2), z], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x[..., 2], _angle(x[..., 1] / self.b, x[..., 0] / self.a)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        hi = np.array([self.a, self.b, self.height])
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        return self.height - np.abs(np.asarray(points, float)[..., 2])

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return _ruled_loc(self, n1, n2)


@attrs.frozen
class HyperbolicCylinder(_PatchQuadric):
    """Hyperbolic cylinder ``x^2/a^2 - y^2/b^2 = 1``, both branches, on
    ``|y| <= width`` (default ``2 b``) and ``|z| <= height`` (default ``max(a, b)``).

    ``u1 = z``; ``u2`` in ``[-2V, 2V]`` (``V = asinh(width/b)``) encodes the
    branch: ``u2 >= 0`` is the branch ``x > 0`` with ``v = u2 - V``, ``u2 < 0``
    the branch ``x < 0`` with ``v = u2 + V``; ``x = (+-a cosh v, b sinh v, u1)``.
    Parameter lines are drawn per branch (:meth:`!parameter_lines`).
    """

    a: float = _positive("HyperbolicCylinder")
    b: float = _positive("HyperbolicCylinder")
    height: float = _optional_positive("HyperbolicCylinder")
    width: float = _optional_positive("HyperbolicCylinder")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "height", max(self.a, self.b))
        _set_default(self, "width", 2 * self.b)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, -(self.b**-2), 0.0]), np.zeros(3), -1.0

    @property
    def _V(self) -> float:
        return float(np.arcsinh(self.width / self.b))

    @property
    def domain(self) -> Domain:
        return Domain((-self.height, self.height), (-2 * self._V, 2 * self._V))

    def _pieces(self) -> list[tuple]:
        V, r1 = self._V, self.domain.u1
        return [(r1, (0.0, 2 * V), "ends", (1, 1.0)), (r1, (-2 * V, 0.0), "ends", (1, -1.0))]

    def _branch(self, u2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        sg = np.where(np.signbit(u2), -1.0, 1.0)  # -0.0 belongs to the branch x < 0
        return sg, u2 - sg * self._V

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        sg, v = self._branch(u2)
        return np.stack([sg * self.a * np.cosh(v), self.b * np.sinh(v), u1], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        sg, v = self._branch(u2)
        z = np.zeros_like(u1)
        x1 = np.stack([z, z, np.ones_like(u1)], axis=-1)
        x2 = np.stack([sg * self.a * np.sinh(v), self.b * np.cosh(v), z], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        sg = np.where(x[..., 0] < 0, -1.0, 1.0)
        u2 = np.arcsinh(x[..., 1] / self.b) + sg * self._V
        return np.stack([x[..., 2], np.copysign(u2, sg)], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        hi = np.array([self.a * np.cosh(self._V), self.width, self.height])
        return -hi, hi

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.minimum(self.width - np.abs(x[..., 1]), self.height - np.abs(x[..., 2]))

    def parameter_lines(self, n1: int, n2: int) -> list[CurveBatch]:
        """``n1`` cross-sections and ``n2`` rulings on each branch."""
        return _piece_lines(self, n1, n2, ("u1", "u2"), even=False)

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return _ruled_loc(self, n1, n2)


@attrs.frozen
class ParabolicCylinder(_PatchQuadric):
    """Parabolic cylinder ``z = x^2/a^2`` on ``|x| <= a extent`` (default
    ``extent = 1``), ``|y| <= length`` (default ``a``).

    ``x = (a u2, u1, u2^2)``: ``u1 = y`` runs along the rulings.
    """

    a: float = _positive("ParabolicCylinder")
    extent: float = _optional_positive("ParabolicCylinder")
    length: float = _optional_positive("ParabolicCylinder")

    def __attrs_post_init__(self) -> None:
        _set_default(self, "extent", 1.0)
        _set_default(self, "length", self.a)

    @property
    def coefficients(self) -> tuple[np.ndarray, np.ndarray, float]:
        return np.diag([self.a**-2, 0.0, 0.0]), np.array([0.0, 0.0, -1.0]), 0.0

    @property
    def domain(self) -> Domain:
        return Domain((-self.length, self.length), (-self.extent, self.extent))

    def _pieces(self) -> list[tuple]:
        return [(self.domain.u1, self.domain.u2, "ends", None)]

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        return np.stack([self.a * u2, u1, u2 * u2], axis=-1)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
        z = np.zeros_like(u1)
        x1 = np.stack([z, np.ones_like(u1), z], axis=-1)
        x2 = np.stack([self.a * np.ones_like(u1), z, 2 * u2], axis=-1)
        return x1, x2

    def uv_of(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.stack([x[..., 1], x[..., 0] / self.a], -1)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = self.extent
        return np.array([-self.a * r, -self.length, 0.0]), np.array(
            [self.a * r, self.length, r * r]
        )

    def patch_margin(self, points: Any) -> np.ndarray:
        x = np.asarray(points, float)
        return np.minimum(self.extent - np.abs(x[..., 0]) / self.a, self.length - np.abs(x[..., 1]))

    def lines_of_curvature(self, n1: int, n2: int) -> list[CurveBatch]:
        return _ruled_loc(self, n1, n2)
