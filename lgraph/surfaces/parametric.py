"""Surfaces given by a parametrization only, and classic examples.

:class:`ParametricSurface` wraps any function ``(u1, u2) -> (..., 3)``; the
contour, the ray hits and the lines of curvature then come from the numeric
defaults of :class:`~lgraph.surfaces._base.Surface`.  The built-in examples
(:class:`Torus`, :class:`DupinCyclide`, :class:`MonkeySaddle`, :class:`Helicoid`,
:class:`Catenoid`, :class:`Enneper`) add analytic derivatives.

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
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from .._tolerance import SELF_HIT_RTOL
from .._validate import as_number, at_most, finite_positive, interval
from ..families import parameter_line_batches
from ._base import CONTOUR, ON, Domain, Surface, _bool_pair, _pole_pairs
from ._polyroots import all_real_roots, has_root_in

__all__ = [
    "ParametricSurface",
    "Torus",
    "DupinCyclide",
    "MonkeySaddle",
    "Helicoid",
    "Catenoid",
    "Enneper",
]

_TWO_PI = 2 * np.pi


def _callable(owner: str) -> Callable[[Any, Any, Any], None]:
    def check(_i: Any, a: Any, v: Any) -> None:
        if v is not None and not callable(v):
            raise TypeError(f"{owner}: {a.name} must be callable, got {type(v).__name__}")

    return check


def _stack(*c: np.ndarray) -> np.ndarray:
    shapes = {np.shape(x) for x in c}
    shape = shapes.pop() if len(shapes) == 1 else np.broadcast_shapes(*shapes)
    out = np.empty(shape + (len(c),))
    for i, x in enumerate(c):
        out[..., i] = x
    return out


def _uv(u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    return np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))


@attrs.frozen(eq=False)
class ParametricSurface(Surface):
    """A surface ``x = func(u1, u2)`` over ``u1_range x u2_range``.

    Parameters
    ----------
    func : callable
        ``func(u1, u2)`` takes broadcastable arrays and returns an array of
        shape ``broadcast(u1, u2).shape + (3,)``.
    u1_range, u2_range : (lo, hi)
        The drawn parameter rectangle.
    periodic : bool or (bool, bool)
        Whether ``u1`` / ``u2`` wrap around (the two ends are the same curve).
    poles : bool, (bool, bool) or ((bool, bool), (bool, bool))
        Which ends of ``u1`` / ``u2`` collapse to single points: one flag for
        all, one per parameter, or ``(low, high)`` per parameter (a bowl with
        its vertex at ``u1 = 0`` and its rim at ``u1 = 1``:
        ``poles=((True, False), False)``).
    derivatives_func : callable, optional
        ``derivatives_func(u1, u2) -> (x1, x2)``; otherwise finite differences.

    Contour, hidden lines and lines of curvature are computed numerically.

    >>> import numpy as np
    >>> s = ParametricSurface(lambda u, v: np.stack(np.broadcast_arrays(u, v, u * v), -1),
    ...                       (-1, 1), (-1, 1))
    >>> s.point(0.5, 2.0).tolist()
    [0.5, 2.0, 1.0]
    >>> ParametricSurface(lambda u, v: u, (0, 1), (0, 1))
    Traceback (most recent call last):
    ...
    ValueError: ParametricSurface: func must map arrays of shape (2,) to shape (2, 3), ...
    >>> ParametricSurface(lambda u, v: u, (1, 0), (0, 1))
    Traceback (most recent call last):
    ...
    ValueError: ParametricSurface: u1_range must be a pair (lo, hi) ... got (1, 0)
    """

    func: Callable[[np.ndarray, np.ndarray], np.ndarray] = attrs.field(
        validator=_callable("ParametricSurface")
    )
    u1_range: tuple[float, float] = attrs.field(
        converter=lambda v: interval("ParametricSurface", "u1_range", v)
    )
    u2_range: tuple[float, float] = attrs.field(
        converter=lambda v: interval("ParametricSurface", "u2_range", v)
    )
    periodic: tuple[bool, bool] = attrs.field(default=(False, False), converter=_bool_pair)
    poles: tuple[tuple[bool, bool], tuple[bool, bool]] = attrs.field(
        default=False, converter=_pole_pairs
    )
    derivatives_func: Callable[..., tuple[np.ndarray, np.ndarray]] | None = attrs.field(
        default=None, kw_only=True, validator=_callable("ParametricSurface")
    )

    def __attrs_post_init__(self) -> None:
        if self.func is None:
            raise TypeError("ParametricSurface: func must be callable, got NoneType")
        if self.derivatives_func is not None:
            self._probe_derivatives()
        u1 = np.array([self.u1_range[0], sum(self.u1_range) / 2])
        u2 = np.array([self.u2_range[0], sum(self.u2_range) / 2])
        try:
            probe = np.asarray(self.func(u1, u2), dtype=float)
        except Exception as exc:  # noqa: BLE001 - report any failure of user code
            raise ValueError(f"ParametricSurface: func(u1, u2) failed: {exc!r}") from exc
        if probe.shape != (2, 3):
            raise ValueError(
                "ParametricSurface: func must map arrays of shape (2,) to shape (2, 3), "
                f"got shape {probe.shape}"
            )

    def _probe_derivatives(self) -> None:
        u1 = np.array([self.u1_range[0], sum(self.u1_range) / 2])
        u2 = np.array([self.u2_range[0], sum(self.u2_range) / 2])
        try:
            x1, x2 = self.derivatives_func(u1, u2)  # type: ignore[misc]
            shapes = [np.asarray(x, dtype=float).shape for x in (x1, x2)]
        except Exception as exc:  # noqa: BLE001 - report any failure of user code
            raise ValueError(
                "ParametricSurface: derivatives_func(u1, u2) must return two arrays "
                f"(x1, x2) of shape broadcast(u1, u2).shape + (3,); it failed: {exc!r}"
            ) from exc
        if shapes != [(2, 3), (2, 3)]:
            raise ValueError(
                "ParametricSurface: derivatives_func must map arrays of shape (2,) to two "
                f"arrays of shape (2, 3), got shapes {shapes}"
            )

    @property
    def domain(self) -> Domain:
        return Domain(self.u1_range, self.u2_range, periodic=self.periodic, poles=self.poles)

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        u1, u2 = _uv(u1, u2)
        return np.asarray(self.func(u1, u2), dtype=float)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        if self.derivatives_func is None:
            return super().derivatives(u1, u2)
        u1, u2 = _uv(u1, u2)
        x1, x2 = self.derivatives_func(u1, u2)
        return np.asarray(x1, dtype=float), np.asarray(x2, dtype=float)


#: largest length of a quartic surface: its equation's fourth powers must stay finite
_MAX_QUARTIC_LENGTH = 1e75


def _positive(owner: str, default: float | None = None) -> Any:
    check = [
        finite_positive(owner),
        at_most(owner, _MAX_QUARTIC_LENGTH, "fourth powers of the equation overflow beyond"),
    ]
    if default is None:
        return attrs.field(converter=as_number, validator=check)
    return attrs.field(default=default, converter=as_number, validator=check)


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
) -> np.ndarray:
    """Exact ray test for the surfaces :func:`_quartic_implicit` describes.

    Along ``o + s v`` the implicit function is a quartic in ``s``, solved for
    all rays at once (:func:`~lgraph.surfaces._polyroots.has_root_in`).  A
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
    hit = np.zeros(n, dtype=bool)
    for degree, rows in (
        (4, np.flatnonzero((own != ON) & (own != CONTOUR))),
        (3, np.flatnonzero(own == ON)),
        (2, np.flatnonzero(own == CONTOUR)),
    ):
        if len(rows):  # the last 4 - degree coefficients vanish: s = 0 divided out
            scale = size / speed[rows]
            hit[rows] = has_root_in(
                coef[rows, : degree + 1], SELF_HIT_RTOL * scale, smax[rows], scale
            )
    return hit


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
        ox, oy, oz = o.T
        vx, vy, vz = v.T
        c = self.c
        coef = np.stack(
            [-c * (vx**3 - 3 * vx * vy * vy),
             -c * (3 * ox * vx * vx - 3 * (ox * vy * vy + 2 * oy * vx * vy)),
             vz - c * (3 * ox * ox * vx - 3 * (2 * ox * oy * vy + vx * oy * oy)),
             oz - c * (ox**3 - 3 * ox * oy * oy)], axis=1,
        )  # fmt: skip
        speed = np.sqrt(np.einsum("ij,ij->i", v, v))
        hit = np.zeros(n, dtype=bool)
        size = self.size
        e = self.extent * (1 + 1e-12)
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
    from .profiles import named_profile
    from .revolution import SurfaceOfRevolution

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
