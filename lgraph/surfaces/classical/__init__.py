"""Classical parametric surfaces with analytic derivatives: the monkey saddle
(with an exact cubic ray test), the helicoid, the catenoid and Enneper's
surface.

Beside them in this folder: ``quartic.py`` the torus and the Dupin cyclide
(exact quartic ray tests), ``onesided.py`` the one-sided surfaces with glued
edges (Moebius strip, Klein bottle, Boy's, Roman and cross-cap surfaces),
``_saddle_margins.py`` the monkey saddle's ray cubic and transition functions,
``_polyroots.py`` the real roots of many small polynomials at once; all are
importable from here.
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
from ._polyroots import all_real_roots
from ._saddle_margins import RIM_SLACK, margins, ray_cubic
from .onesided import BoySurface, CrossCap, KleinBottle, MoebiusStrip, RomanSurface
from .quartic import DupinCyclide, Torus

__all__ = ["MonkeySaddle", "Helicoid", "Catenoid", "Enneper", "Torus", "DupinCyclide"]
__all__ += ["MoebiusStrip", "KleinBottle", "BoySurface", "RomanSurface", "CrossCap"]


@attrs.frozen
class MonkeySaddle(Surface):
    """Monkey saddle ``z = u1^3 - 3 u1 u2^2`` over ``[-extent, extent]^2``, scaled by ``c``.

    The origin is a flat umbilic.

    >>> MonkeySaddle(extent=-1)
    Traceback (most recent call last):
    ...
    ValueError: MonkeySaddle: extent must be a positive finite number, got -1
    """

    extent: float = _positive("MonkeySaddle", 1.0)
    c: float = _positive("MonkeySaddle", 1.0)

    @property
    def domain(self) -> Domain:
        return Domain((-self.extent, self.extent), (-self.extent, self.extent))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = _uv(u1, u2)
        return _stack(u1, u2, self.c * (u1**3 - 3 * u1 * u2**2))

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        o, z = np.ones_like(u1), np.zeros_like(u1)
        return (
            _stack(o, z, self.c * (3 * u1**2 - 3 * u2**2)),
            _stack(z, o, self.c * (-6 * u1 * u2)),
        )

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        z = np.zeros_like(u1)
        return (
            _stack(z, z, self.c * 6 * u1),
            _stack(z, z, self.c * (-6 * u2)),
            _stack(z, z, self.c * (-6 * u1)),
        )

    def fundamental_forms(self, u1: Any, u2: Any) -> tuple[np.ndarray, ...]:
        """``(g11, g12, g22, L11, L12, L22)`` in closed form: the graph of
        ``f`` has ``g_ik = delta_ik + f_i f_k`` and ``L_ik = f_ik / W`` with
        ``W = sqrt(1 + f_1^2 + f_2^2)`` (normal ``x1 x x2``).  What the
        numeric lines of curvature evaluate (``lgraph.families.fieldlines``).

        >>> s = MonkeySaddle()
        >>> from lgraph.curvature import fundamental_forms
        >>> bool(np.allclose(s.fundamental_forms(0.3, -0.2), fundamental_forms(s, 0.3, -0.2)))
        True
        """
        if not (type(u1) is type(u2) is np.ndarray and u1.shape == u2.shape):
            u1, u2 = _uv(u1, u2)  # (the tracer's rows need no broadcasting)
        c = self.c
        f1, f2 = 3 * c * (u1 * u1 - u2 * u2), -6 * c * u1 * u2
        g12 = f1 * f2
        g11, g22 = 1 + f1 * f1, 1 + f2 * f2
        w = 6 * c / np.sqrt(g11 + f2 * f2)
        L11 = w * u1
        return g11, g12, g22, L11, -w * u2, -L11

    #: its formulas hold past the square: numeric lines of curvature may
    #: evaluate the fundamental forms there (``lgraph.families.fieldlines``)
    defined_past_domain = True

    # the cubic ray test costs about as much as the torus's quartic one
    hit_cost = 10.0
    hit_call_cost = 500.0

    def implicit(self, points: Any) -> np.ndarray:
        """``z - c (x^3 - 3 x y^2)``: zero on the surface."""
        p = np.asarray(points, dtype=float)
        x, y = p[..., 0], p[..., 1]
        return p[..., 2] - self.c * (x**3 - 3 * x * y * y)

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Exact ray test: along ``o + s v`` the implicit function is a cubic
        in ``s``; its real roots in ``(eps, smax)`` whose point lies over the
        square ``|x|, |y| <= extent`` are hits.  A point on the surface (``ON``)
        has the root ``s = 0`` divided out, a contour point (``CONTOUR``) twice."""
        o = np.asarray(origins, dtype=float).reshape(-1, 3)
        v = np.asarray(directions, dtype=float).reshape(-1, 3)
        n = len(o)
        smax = np.broadcast_to(np.asarray(smax, dtype=float), (n,))
        own = np.zeros(n, np.int8) if own is None else np.asarray(own)
        coef = ray_cubic(self.c, o, v)
        speed = np.sqrt(np.einsum("ij,ij->i", v, v))
        hit = np.zeros(n, dtype=bool)
        size = self.size
        e = self.extent * (1 + RIM_SLACK)
        for degree, rows in (
            (3, np.flatnonzero((own != ON) & (own != CONTOUR))),
            (2, np.flatnonzero(own == ON)),
            (1, np.flatnonzero(own == CONTOUR)),
        ):
            if not len(rows):
                continue
            scale = size / speed[rows]
            s = all_real_roots(coef[rows, : degree + 1], scale)
            x = o[rows, 0, None] + s * v[rows, 0, None]
            y = o[rows, 1, None] + s * v[rows, 1, None]
            with np.errstate(invalid="ignore"):
                ok = (s > SELF_HIT_RTOL * scale[:, None]) & (s < smax[rows, None])
                ok &= (np.abs(x) <= e) & (np.abs(y) <= e)
            hit[rows] = ok.any(axis=1)
        return hit

    def visibility_margins(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray,
        uv: np.ndarray | None = None,
        which: int | None = None,
    ) -> np.ndarray | None:
        """Its contour, its four rims and grazing rays as transition functions
        (:mod:`lgraph.surfaces.classical._saddle_margins`); ``uv`` is not needed."""
        return margins(self, origins, directions, smax, own, which)


@attrs.frozen
class Helicoid(Surface):
    """Helicoid ``(u1 cos u2, u1 sin u2, c u2)``, ``|u1| <= radius``, ``0 <= u2 <= 2 pi turns``.

    A minimal surface: its lines of curvature bisect the asymptotic lines
    (the rulings ``u2 = const`` and the helices ``u1 = const``).

    >>> Helicoid(turns=0)
    Traceback (most recent call last):
    ...
    ValueError: Helicoid: turns must be a positive finite number, got 0
    """

    radius: float = _positive("Helicoid", 1.0)
    c: float = _positive("Helicoid", 0.25)
    turns: float = _positive("Helicoid", 1.0)

    @property
    def domain(self) -> Domain:
        return Domain((-self.radius, self.radius), (0.0, _TWO_PI * self.turns))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = _uv(u1, u2)
        return _stack(u1 * np.cos(u2), u1 * np.sin(u2), self.c * u2)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        c2, s2 = np.cos(u2), np.sin(u2)
        return (
            _stack(c2, s2, np.zeros_like(u1)),
            _stack(-u1 * s2, u1 * c2, np.full_like(u1, self.c)),
        )

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        c2, s2, z = np.cos(u2), np.sin(u2), np.zeros_like(u1)
        return _stack(z, z, z), _stack(-s2, c2, z), _stack(-u1 * c2, -u1 * s2, z)


@attrs.frozen
class Catenoid(Surface):
    """Catenoid ``(c cosh(u2/c) cos u1, c cosh(u2/c) sin u1, u2)``, ``|u2| <= height``.

    ``u1`` is periodic.  Minimal; its lines of curvature are the meridians and
    parallels.  As a surface of revolution its contour is closed form per
    parallel and its ray test one root problem per ray
    (:class:`~lgraph.SurfaceOfRevolution` with the ``"catenoid"`` profile).

    >>> Catenoid(c="1")
    Traceback (most recent call last):
    ...
    ValueError: Catenoid: c must be a positive finite number, got '1'
    """

    c: float = _positive("Catenoid", 1.0)
    height: float = _positive("Catenoid", 1.2)

    @property
    def domain(self) -> Domain:
        return Domain((0.0, _TWO_PI), (-self.height, self.height), periodic=(True, False))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = _uv(u1, u2)
        rho = self.c * np.cosh(u2 / self.c)
        return _stack(rho * np.cos(u1), rho * np.sin(u1), u2)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u1, u2 = _uv(u1, u2)
        rho = self.c * np.cosh(u2 / self.c)
        sh = np.sinh(u2 / self.c)
        return (
            _stack(-rho * np.sin(u1), rho * np.cos(u1), np.zeros_like(u1)),
            _stack(sh * np.cos(u1), sh * np.sin(u1), np.ones_like(u1)),
        )

    # a surface of revolution: contour, hits and lines of curvature from
    # lgraph.surfaces.revolution (its u1 = t is our u2, its u2 = phi our u1)
    hit_cost = 12.0
    hit_call_cost = 800.0

    def _revolution(self) -> Any:
        return _catenoid_revolution(self.c, self.height)

    def contour(self, projector: Any) -> list:
        """Closed form per parallel (:class:`~lgraph.SurfaceOfRevolution`)."""
        out = []
        for b in self._revolution().contour(projector):

            def evaluate(idx: np.ndarray, t: np.ndarray, b: Any = b) -> tuple:
                xyz, uv = b.evaluate(idx, t)
                return xyz, uv[:, ::-1]

            out.append(attrs.evolve(b, evaluate=evaluate, surface=self))
        return out

    def hits(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        smax: np.ndarray,
        own: np.ndarray | None = None,
    ) -> np.ndarray:
        """Exact ray test of the surface of revolution (one root problem per ray)."""
        return self._revolution().hits(origins, directions, smax, own)

    def lines_of_curvature(self, n1: int, n2: int) -> list:
        """Meridians ``u1 = const`` and parallels ``u2 = const`` (exact)."""
        d = self.domain
        return parameter_line_batches(self, d.lines(0, n1), d.lines(1, n2))


@functools.lru_cache(maxsize=16)
def _catenoid_revolution(c: float, height: float) -> Any:
    from ..revolution import SurfaceOfRevolution
    from ..revolution.profiles import named_profile

    return SurfaceOfRevolution(named_profile("catenoid", c=c, height=height))


@attrs.frozen
class Enneper(Surface):
    """Enneper's minimal surface
    ``(u1 - u1^3/3 + u1 u2^2, u2 - u2^3/3 + u2 u1^2, u1^2 - u2^2)`` over
    ``[-extent, extent]^2`` (embedded for ``extent`` below about 1.2).

    Its lines of curvature are the parameter lines.

    >>> Enneper(extent=float("inf"))
    Traceback (most recent call last):
    ...
    ValueError: Enneper: extent must be a positive finite number, got inf
    """

    extent: float = _positive("Enneper", 1.2)

    @property
    def domain(self) -> Domain:
        return Domain((-self.extent, self.extent), (-self.extent, self.extent))

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u, v = _uv(u1, u2)
        return _stack(u - u**3 / 3 + u * v * v, v - v**3 / 3 + v * u * u, u * u - v * v)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        u, v = _uv(u1, u2)
        return (
            _stack(1 - u * u + v * v, 2 * u * v, 2 * u),
            _stack(2 * u * v, 1 - v * v + u * u, -2 * v),
        )

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u, v = _uv(u1, u2)
        two = np.full_like(u, 2.0)
        return (
            _stack(-2 * u, 2 * v, two),
            _stack(2 * v, 2 * u, np.zeros_like(u)),
            _stack(2 * u, -2 * v, -two),
        )
