"""Ruled surfaces ``x(u1, u2) = y(u1) + u2 z(u1)`` (paper §4): the public classes.

A ruled surface is swept by the straight lines (rulings) through the points of
a directrix ``y`` in the directions of a director ``z``.  Everything the
renderer asks reduces to one-dimensional problems in ``u1``, solved on a grid
of ``u1`` and refined by :func:`lgraph._roots.bracketed_roots`
(docs/mathematics.rst, "Ruled surfaces, general cylinders and cones").  The
machinery shared by the classes of this module is split by question:

* :mod:`~lgraph.surfaces.ruled._geometry`: evaluation and derivatives, the ``u1`` grid, bounds;
* :mod:`~lgraph.surfaces.ruled._hits`: which rays the patch hides, ``det(y - P, z, v) = 0``;
* :mod:`~lgraph.surfaces.ruled._contour`: the contour ``u2 = -A(u1)/B(u1)`` (whole rulings on
  developable surfaces) and the patch's edges;
* :mod:`~lgraph.surfaces.ruled._curvature`: the lines of curvature of developable surfaces,
  the rulings and ``u2 = d - S(u1)`` (paper (4.2)-(4.5)).

This module holds the classes (:class:`RuledSurface`,
:class:`GeneralCylinder`, :class:`GeneralCone`, :class:`TangentSurface`):
each supplies its directrix and director and, where it has them, closed forms
of ``S``.

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

from typing import Any

import attrs
import numpy as np

from ..._tolerance import RULED_PRE_SAMPLES as _PRE_SAMPLES
from ..._validate import interval, vector3
from ...curves import Curve, CurveBatch
from ._contour import _RuledContour
from ._curvature import _RuledCurvature
from ._hits import _RuledHits

__all__ = ["RuledSurface", "GeneralCylinder", "GeneralCone", "TangentSurface"]


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


class _Ruled(_RuledHits, _RuledContour, _RuledCurvature):
    """The machinery shared by all ruled surfaces (not instantiated directly):
    evaluation and grid (:mod:`~lgraph.surfaces.ruled._geometry`), hits
    (:mod:`~lgraph.surfaces.ruled._hits`), contour and edges
    (:mod:`~lgraph.surfaces.ruled._contour`), lines of curvature
    (:mod:`~lgraph.surfaces.ruled._curvature`).

    Subclasses supply :meth:`_raw`: the directrix, an (unnormalized) director
    ``d`` and their derivatives; ``z = d/|d|`` unless ``_unit`` is False.
    """


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
