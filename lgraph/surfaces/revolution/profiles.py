"""Meridian profiles ``t -> (rho, z)`` for surfaces of revolution.

A :class:`Profile` is a plane curve given by its distance ``rho >= 0`` from
the axis and its height ``z``, optionally with analytic first and second
derivatives.  The named profiles (``PROFILES``: ``"pseudosphere"``,
``"catenoid"``, ``"egg"``, ``"vase"``, ``"circle"``) carry their derivatives
in closed form; :func:`profile_from_points` interpolates piecewise data (a
list of ``(rho, z)`` knots) by a cubic spline.  Scene files choose a profile by
name or give knots; they never evaluate code.

>>> import numpy as np
>>> p = named_profile("circle", center=(3.0, 0.0), radius=1.0)
>>> [np.round(x, 12).tolist() for x in p(np.array([0.0, np.pi / 2]))]
[[4.0, 3.0], [0.0, 1.0]]
>>> p.t_range
(0.0, 6.283185307179586)
>>> named_profile("spiral")
Traceback (most recent call last):
...
ValueError: named_profile: name must be one of 'catenoid', 'circle', 'egg', ... got 'spiral'
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import attrs
import numpy as np

from ..._validate import as_number

__all__ = ["Profile", "PROFILES", "named_profile", "profile_from_points"]

Pair = tuple[np.ndarray, np.ndarray]


def _callable_or_none(_i: Any, a: Any, v: Any) -> None:
    if v is not None and not callable(v):
        raise TypeError(f"Profile: {a.name} must be callable, got {type(v).__name__}")


@attrs.frozen(eq=False)
class Profile:
    """A meridian profile ``func(t) -> (rho, z)`` with optional analytic derivatives.

    ``derivative(t) -> (rho', z')`` and ``second_derivative(t) -> (rho'', z'')``
    follow the same convention; ``t_range`` is the profile's natural parameter
    range (used when a surface is built without one); ``name`` is for display.
    """

    func: Callable[[np.ndarray], Any] = attrs.field()
    derivative: Callable[[np.ndarray], Any] | None = attrs.field(
        default=None, validator=_callable_or_none
    )
    second_derivative: Callable[[np.ndarray], Any] | None = attrs.field(
        default=None, validator=_callable_or_none
    )
    t_range: tuple[float, float] | None = None
    name: str = "custom"
    #: An interval of ``t`` on which the profile is *proved* (not sampled) to
    #: bound a convex solid: ``z`` strictly monotone with ``sigma = sign z'``
    #: and ``sigma (rho' z'' - z' rho'') >= 0`` there.  A surface whose
    #: ``t_range`` lies inside it, with poles at both ends and a full turn, then
    #: decides the visibility of its own points without ray tests
    #: (:mod:`lgraph.surfaces.revolution._convex`).  None: no such claim.
    convex: tuple[float, float] | None = attrs.field(default=None, kw_only=True)

    @func.validator
    def _check_func(self, _a: Any, v: Any) -> None:
        if not callable(v):
            raise TypeError(f"Profile: func must be callable, got {type(v).__name__}")

    @classmethod
    def from_formulas(
        cls, rho: str, z: str, t: tuple[Any, Any], *, constants: Mapping[str, float] | None = None
    ) -> Profile:
        """The profile ``t -> (rho, z)`` of two formulas (:mod:`lgraph.formula`)
        over the range ``t``, with exact derivatives.

        >>> p = Profile.from_formulas("1 + 0.3*cos(2*t)", "sin(t)", ("-pi/2", "pi/2"))
        >>> [round(float(a), 12) for a in p(0.0)]
        [1.3, 0.0]
        """
        from ...formula.maps import constant_range, map_orders

        f, f1, f2 = map_orders((rho, z), ("t",), constants, stack=False)
        t_range = constant_range(t, f.constants, "Profile.from_formulas: t")
        return cls(f, f1, f2, t_range=t_range, name="formula")

    def __call__(self, t: Any) -> Any:
        return self.func(t)


def _pseudosphere(a: float = 1.0, extent: float = 3.0) -> Profile:
    """Tractrix ``rho = a sech t``, ``z = a (t - tanh t)``, ``0 <= t <= extent``
    (the rim ``t = 0`` is a cuspidal edge; constant curvature ``-1/a^2``)."""

    def f(t: np.ndarray) -> Pair:
        return a / np.cosh(t), a * (t - np.tanh(t))

    def d(t: np.ndarray) -> Pair:
        sech, th = 1 / np.cosh(t), np.tanh(t)
        return -a * sech * th, a * th * th

    def dd(t: np.ndarray) -> Pair:
        sech, th = 1 / np.cosh(t), np.tanh(t)
        return a * sech * (th * th - sech * sech), 2 * a * th * sech * sech

    return Profile(f, d, dd, (0.0, extent), "pseudosphere")


def _catenoid(c: float = 1.0, height: float = 1.2) -> Profile:
    """Catenary ``rho = c cosh(t / c)``, ``z = t``, ``|t| <= height`` (minimal)."""

    def f(t: np.ndarray) -> Pair:
        return c * np.cosh(t / c), np.asarray(t, float) * 1.0

    def d(t: np.ndarray) -> Pair:
        return np.sinh(t / c), np.ones_like(t, dtype=float)

    def dd(t: np.ndarray) -> Pair:
        return np.cosh(t / c) / c, np.zeros_like(t, dtype=float)

    return Profile(f, d, dd, (-height, height), "catenoid")


def _egg(a: float = 1.4, b: float = 1.0, e: float = 0.18) -> Profile:
    """Egg ``rho = b sin t (1 + e cos t)``, ``z = -a cos t``, ``0 <= t <= pi``
    (blunt end down for ``e > 0``; poles at both ends).

    Convex for ``a != 0``, ``b > 0``, ``|e| < 1/sqrt(2)``: ``z' = a sin t`` has
    the sign of ``a`` inside, and ``rho' z'' - z' rho'' = a b (1 + e cos t (1 + 2
    sin^2 t))``, where ``|cos t (1 + 2 sin^2 t)| = |c (3 - 2 c^2)| <= sqrt(2)``
    (its maximum, at ``c = 1/sqrt(2)``); so ``sign(a) (rho' z'' - z' rho'') >=
    |a| b (1 - sqrt(2) |e|) > 0``.
    """

    def f(t: np.ndarray) -> Pair:
        return b * np.sin(t) * (1 + e * np.cos(t)), -a * np.cos(t)

    def d(t: np.ndarray) -> Pair:
        return b * (np.cos(t) + e * np.cos(2 * t)), a * np.sin(t)

    def dd(t: np.ndarray) -> Pair:
        return b * (-np.sin(t) - 2 * e * np.sin(2 * t)), a * np.cos(t)

    convex = (0.0, math.pi) if a != 0 and b > 0 and abs(e) * math.sqrt(2) < 1 else None
    return Profile(f, d, dd, (0.0, math.pi), "egg", convex=convex)


def _vase(radius: float = 1.0, bulge: float = 0.42, height: float = 3.0) -> Profile:
    """Vase ``rho = radius (1 + bulge sin(2.2 t / height * 3 - 0.9))``, ``z = t``,
    ``0 <= t <= height``: a belly, a neck and a lip (open at both ends)."""
    w = 6.6 / height

    def f(t: np.ndarray) -> Pair:
        return radius * (1 + bulge * np.sin(w * t - 0.9)), np.asarray(t, float) * 1.0

    def d(t: np.ndarray) -> Pair:
        return radius * bulge * w * np.cos(w * t - 0.9), np.ones_like(t, dtype=float)

    def dd(t: np.ndarray) -> Pair:
        return -radius * bulge * w * w * np.sin(w * t - 0.9), np.zeros_like(t, dtype=float)

    return Profile(f, d, dd, (0.0, height), "vase")


def _circle(center: Any = (2.0, 0.0), radius: float = 1.0) -> Profile:
    """Circle ``(c_rho + radius cos t, c_z + radius sin t)``, ``0 <= t <= 2 pi``:
    a torus (``c_rho > radius``) or, with ``c_rho = 0`` and ``|t| <= pi/2``, a sphere
    (convex there: ``z' = radius cos t > 0`` and ``rho' z'' - z' rho'' = radius^2``)."""
    cr, cz = (float(as_number(x)) for x in center)

    def f(t: np.ndarray) -> Pair:
        return cr + radius * np.cos(t), cz + radius * np.sin(t)

    def d(t: np.ndarray) -> Pair:
        return -radius * np.sin(t), radius * np.cos(t)

    def dd(t: np.ndarray) -> Pair:
        return -radius * np.cos(t), -radius * np.sin(t)

    convex = (-math.pi / 2, math.pi / 2) if cr == 0 and radius > 0 else None
    return Profile(f, d, dd, (0.0, 2 * math.pi), "circle", convex=convex)


#: Named profiles: name -> factory taking keyword parameters.
PROFILES: dict[str, Callable[..., Profile]] = {
    "pseudosphere": _pseudosphere,
    "catenoid": _catenoid,
    "egg": _egg,
    "vase": _vase,
    "circle": _circle,
}


def named_profile(name: str = "", **params: Any) -> Profile:
    """The named profile ``name`` (a key of ``PROFILES``) with ``params``."""
    if name not in PROFILES:
        allowed = ", ".join(repr(k) for k in sorted(PROFILES))
        raise ValueError(f"named_profile: name must be one of {allowed}, got {name!r}")
    for key, value in params.items():
        if key == "center":
            continue
        if not (
            isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
        ):
            raise ValueError(f"named_profile: {name} {key} must be a finite number, got {value!r}")
    try:
        return PROFILES[name](**params)
    except TypeError as exc:
        raise ValueError(f"named_profile: bad parameters for {name!r}: {exc}") from None


def profile_from_points(points: Any) -> Profile:
    """A profile through the knots ``points`` (``(n, 2)`` of ``(rho, z)``, n >= 4),
    interpolated by a cubic spline in the chord length (``t_range`` = 0 to the
    polygon's length).  ``rho`` must be >= 0 at every knot.

    >>> p = profile_from_points([[0, 0], [1, 0.2], [1.2, 1], [0.8, 2]])
    >>> [round(float(x), 12) for x in np.ravel(p(np.array([0.0])))]
    [0.0, 0.0]
    >>> profile_from_points([[0, 0], [1, 1]])
    Traceback (most recent call last):
    ...
    ValueError: profile_from_points: points must be at least 4 pairs (rho, z), got shape (2, 2)
    """
    try:
        p = np.array(points, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"profile_from_points: points must be pairs (rho, z) of numbers, got {points!r}"
        ) from None
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 4:
        raise ValueError(
            f"profile_from_points: points must be at least 4 pairs (rho, z), got shape {p.shape}"
        )
    if not np.all(np.isfinite(p)):
        raise ValueError("profile_from_points: points must be finite numbers")
    if np.any(p[:, 0] < 0):
        k = int(np.argmax(p[:, 0] < 0))
        raise ValueError(
            f"profile_from_points: rho must be >= 0 at every knot, got rho={p[k, 0]} at knot {k}"
        )
    chord = np.linalg.norm(np.diff(p, axis=0), axis=1)
    if np.any(chord <= 0):
        raise ValueError("profile_from_points: consecutive knots must differ")
    t = np.concatenate([[0.0], np.cumsum(chord)])
    from scipy.interpolate import make_interp_spline

    spline = make_interp_spline(t, p, k=3)
    d1, d2 = spline.derivative(1), spline.derivative(2)

    def pair(s: Any) -> Callable[[np.ndarray], Pair]:
        def f(x: np.ndarray) -> Pair:
            v = s(np.asarray(x, float))
            return v[..., 0], v[..., 1]

        return f

    return Profile(pair(spline), pair(d1), pair(d2), (0.0, float(t[-1])), "points")
