"""One-sided and self-intersecting surfaces: Moebius strip, Klein bottle, Boy's,
Roman and cross-cap surfaces, with their gluings.

Each is a parametrization over a rectangle whose edges are glued
(:class:`~lgraph.surfaces._domain.Domain`): the Moebius strip has one twisted
parameter, the Klein bottle one twisted and one periodic; the three models
of the projective plane are images of the unit sphere under an even map
``F(p) = F(-p)``, over the chart ``p = (sin u cos v, sin u sin v, cos u)``,
``u`` in ``[0, pi]`` (poles at both ends), ``v`` in ``[0, pi]`` twisted:
``p(u, pi) = -p(pi - u, 0)``.  Everything else (contour, hits, lines of
curvature, the self-intersection with :class:`~lgraph.SelfIntersection`) is
numeric.  Formulas and their gluings: ``docs/gluings.rst``.

>>> import lgraph as lg
>>> lg.MoebiusStrip().domain.periodic
('twisted', False)
>>> lg.KleinBottle(form="figure8").domain.periodic
('twisted', True)
>>> lg.RomanSurface().domain.periodic
(False, 'twisted')
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np

from ..._validate import as_number, finite_positive, one_of
from .._base import Domain, Surface
from ..parametric import ParametricSurface

__all__ = ["MoebiusStrip", "KleinBottle", "BoySurface", "RomanSurface", "CrossCap"]

_PI = np.pi


class _Formulas(Surface):
    """A surface drawn from an inner :class:`ParametricSurface` of formulas
    (exact derivatives); subclasses set ``_inner`` in ``__attrs_post_init__``."""

    _inner: Any

    @property
    def domain(self) -> Domain:
        return self._inner.domain

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        return self._inner.point(u1, u2)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        return self._inner.derivatives(u1, u2)

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return self._inner.second_derivatives(u1, u2)

    def _set(self, x: str, y: str, z: str, u: Any, v: Any, periodic: Any,
             poles: Any = False, **constants: float) -> None:  # fmt: skip
        inner = ParametricSurface.from_formulas(
            x, y, z, u, v, constants=constants, periodic=periodic, poles=poles
        )
        object.__setattr__(self, "_inner", inner)


def _inner_field() -> Any:
    return attrs.field(init=False, default=None, repr=False, eq=False)


@attrs.frozen
class MoebiusStrip(_Formulas):
    """Moebius strip ``((R + v cos(u/2)) cos u, (R + v cos(u/2)) sin u, v sin(u/2))``,
    ``u`` in ``[0, 2 pi]`` twisted, ``|v| <= width / 2``.

    Its parameter lines ``v = c`` close after two turns (through ``v = -c``);
    its boundary is one closed curve.

    >>> s = MoebiusStrip(width=0.8)
    >>> bool(np.allclose(s.point(0.0, 0.3), s.point(2 * np.pi, -0.3)))
    True
    >>> MoebiusStrip(width=0)
    Traceback (most recent call last):
    ...
    ValueError: MoebiusStrip: width must be a positive finite number, got 0
    """

    radius: float = attrs.field(
        default=1.0, converter=as_number, validator=finite_positive("MoebiusStrip")
    )
    width: float = attrs.field(
        default=1.0, converter=as_number, validator=finite_positive("MoebiusStrip")
    )
    _inner: Any = _inner_field()

    def __attrs_post_init__(self) -> None:
        r = "(R + v*cos(u/2))"
        self._set(f"{r}*cos(u)", f"{r}*sin(u)", "v*sin(u/2)", (0, "2*pi"),
                  (-self.width / 2, self.width / 2), ("twisted", False), R=self.radius)  # fmt: skip


#: the classical bottle (a surface of the Wikipedia/"Klein bottle" family):
#: x, y, z as polynomials in cos u, sin u, cos v, sin v over u in [0, pi]
_BOTTLE = (
    "-2/15*cos(u)*(3*cos(v) - 30*sin(u) + 90*cos(u)^4*sin(u) - 60*cos(u)^6*sin(u)"
    " + 5*cos(u)*cos(v)*sin(u))",
    "-1/15*sin(u)*(3*cos(v) - 3*cos(u)^2*cos(v) - 48*cos(u)^4*cos(v) + 48*cos(u)^6*cos(v)"
    " - 60*sin(u) + 5*cos(u)*cos(v)*sin(u) - 5*cos(u)^3*cos(v)*sin(u)"
    " - 80*cos(u)^5*cos(v)*sin(u) + 80*cos(u)^7*cos(v)*sin(u))",
    "2/15*(3 + 5*cos(u)*sin(u))*sin(v)",
)


@attrs.frozen
class KleinBottle(_Formulas):
    """Klein bottle: ``form="bottle"`` (the classical bottle whose neck passes
    through its side; ``u`` in ``[0, pi]`` twisted, ``v`` in
    ``[-pi/2, 3 pi/2]`` periodic: ``x(0, t) = x(pi, pi - t)``) or
    ``form="figure8"`` (the figure-8 immersion
    ``((r + cos(u/2) sin v - sin(u/2) sin 2v) cos u, (...) sin u,
    sin(u/2) sin v + cos(u/2) sin 2v)``, ``u`` in ``[0, 2 pi]`` twisted, ``v``
    in ``[0, 2 pi]`` periodic, ``radius`` ``r``; it meets itself in the
    circle of radius ``r`` in the plane ``z = 0``).

    >>> k = KleinBottle()
    >>> bool(np.allclose(k.point(0.0, 0.4), k.point(np.pi, np.pi - 0.4)))
    True
    >>> KleinBottle(form="torus")
    Traceback (most recent call last):
    ...
    ValueError: KleinBottle: form must be one of 'bottle', 'figure8', got 'torus'
    """

    form: str = attrs.field(
        default="bottle", validator=one_of("KleinBottle", ("bottle", "figure8"))
    )
    radius: float = attrs.field(
        default=2.0, converter=as_number, validator=finite_positive("KleinBottle")
    )
    _inner: Any = _inner_field()

    def __attrs_post_init__(self) -> None:
        if self.form == "bottle":
            self._set(*_BOTTLE, (0, "pi"), ("-pi/2", "3*pi/2"), ("twisted", True))
            return
        rho = "(r + cos(u/2)*sin(v) - sin(u/2)*sin(2*v))"
        self._set(f"{rho}*cos(u)", f"{rho}*sin(u)", "sin(u/2)*sin(v) + cos(u/2)*sin(2*v)",
                  (0, "2*pi"), (0, "2*pi"), ("twisted", True), r=self.radius)  # fmt: skip


# the chart of the projective plane: the unit sphere's point p(u, v)
_PX, _PY, _PZ = "(sin(u)*cos(v))", "(sin(u)*sin(v))", "cos(u)"
_RP2 = dict(u=(0, "pi"), v=("pi/24", "25*pi/24"), periodic=(False, "twisted"), poles=(True, False))


@attrs.frozen
class RomanSurface(_Formulas):
    """Steiner's Roman surface ``size * (yz, zx, xy)`` of the unit sphere's
    point ``(x, y, z)``; implicit equation ``X^2 Y^2 + Y^2 Z^2 + Z^2 X^2 =
    size * XYZ``.  It meets itself in three segments of the axes
    (``|X| <= size / 2``) through a triple point at the origin.

    >>> s = RomanSurface()
    >>> X, Y, Z = s.point(0.7, 0.4)
    >>> bool(abs(X*X*Y*Y + Y*Y*Z*Z + Z*Z*X*X - X*Y*Z) < 1e-15)
    True
    """

    size: float = attrs.field(
        default=1.0, converter=as_number, validator=finite_positive("RomanSurface")
    )
    _inner: Any = _inner_field()

    def __attrs_post_init__(self) -> None:
        a = "a*"
        self._set(f"{a}{_PY}*{_PZ}", f"{a}{_PZ}*{_PX}", f"{a}{_PX}*{_PY}", **_RP2, a=self.size)


@attrs.frozen
class CrossCap(_Formulas):
    """The cross-cap ``size * (yz, 2xy, x^2 - y^2)`` of the unit sphere's point
    ``(x, y, z)``.  Implicit equation (``size = 1``; derived in
    ``docs/gluings.rst``): ``(2X^2 + Y^2 + Z^2 + Z)^2 = (Y^2 + Z^2)(1 + Z)^2``.
    It meets itself in the segment ``X = Y = 0``, ``0 <= Z <= size``, with
    pinch points at its ends.

    >>> X, Y, Z = CrossCap().point(0.7, 0.4)
    >>> bool(abs((2*X*X + Y*Y + Z*Z + Z)**2 - (Y*Y + Z*Z) * (1 + Z)**2) < 1e-14)
    True
    """

    size: float = attrs.field(
        default=1.0, converter=as_number, validator=finite_positive("CrossCap")
    )
    _inner: Any = _inner_field()

    def __attrs_post_init__(self) -> None:
        self._set(f"a*{_PY}*{_PZ}", f"2*a*{_PX}*{_PY}", f"a*({_PX}^2 - {_PY}^2)", **_RP2,
                  a=self.size)  # fmt: skip


def _bryant_kusner(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Bryant and Kusner's Boy surface at the unit sphere's point ``p(u, v)``:
    ``w`` is the stereographic image of ``p`` or of ``-p`` (the map is even),
    whichever lies in the closed unit disk."""
    u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
    px, py, pz = np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u)
    s = np.where(pz >= 0, 1.0, -1.0)
    w = s * (px + 1j * py) / (1 + s * pz)
    w3 = w**3
    w6 = w3 * w3
    den = w6 + np.sqrt(5) * w3 - 1
    g1 = -1.5 * np.imag(w * (1 - w3 * w) / den)
    g2 = -1.5 * np.real(w * (1 + w3 * w) / den)
    g3 = np.imag((1 + w6) / den) - 0.5
    r2 = g1 * g1 + g2 * g2 + g3 * g3
    return np.stack([g1 / r2, g2 / r2, g3 / r2], axis=-1)


@attrs.frozen
class BoySurface(Surface):
    """Boy's surface (Bryant and Kusner's parametrization, a minimal
    immersion of the projective plane after an inversion), ``size`` times,
    over the chart of the projective plane (``u`` in ``[0, pi]`` with poles,
    ``v`` in ``[0, pi]`` twisted).  It meets itself in a curve of three
    loops through one triple point.

    >>> s = BoySurface()
    >>> bool(np.allclose(s.point(0.4, np.pi), s.point(np.pi - 0.4, 0.0)))
    True
    """

    size: float = attrs.field(
        default=1.0, converter=as_number, validator=finite_positive("BoySurface")
    )

    @property
    def domain(self) -> Domain:
        return Domain((0.0, _PI), (0.0, _PI), periodic=(False, "twisted"), poles=(True, False))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        return self.size * _bryant_kusner(u1, u2)
