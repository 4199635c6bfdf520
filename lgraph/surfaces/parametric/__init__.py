"""Surfaces given by a parametrization only.

:class:`ParametricSurface` wraps any function ``(u1, u2) -> (..., 3)``; the
contour, the ray hits and the lines of curvature then come from the numeric
defaults of :class:`~lgraph.surfaces._base.Surface`.  Classic examples with
analytic derivatives are in :mod:`lgraph.surfaces.classical.quartic` (torus, Dupin
cyclide) and :mod:`lgraph.surfaces.classical` (monkey saddle, helicoid,
catenoid, Enneper's surface).

>>> import numpy as np
>>> s = ParametricSurface(lambda u, v: np.stack(np.broadcast_arrays(u, v, u * v), -1),
...                       (-1, 1), (-1, 1))
>>> s.point(np.array([0.5]), np.array([2.0])).tolist()
[[0.5, 2.0, 1.0]]
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import attrs
import numpy as np

from ..._validate import as_number, at_most, finite_positive, interval
from .._base import Domain, Surface, domain_flags

__all__ = ["ParametricSurface"]

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


def _takes_scalars(func: Callable[..., Any], u1: float, u2: float) -> bool:
    """Whether ``func`` works on two numbers (and so failed on arrays only)."""
    try:
        return np.shape(np.asarray(func(float(u1), float(u2)), dtype=float)) == (3,)
    except Exception:  # noqa: BLE001 - user code, any failure means no
        return False


def _uv(u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
    return np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))


_FLAGS = domain_flags("ParametricSurface")


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
    second_derivatives_func : callable, optional
        ``second_derivatives_func(u1, u2) -> (x11, x12, x22)``; otherwise
        finite differences.

    The class method ``from_formulas`` builds one from three formulas (exact
    derivatives, no Python needed: the form scene files use).

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
    periodic: tuple[bool, bool] = _FLAGS[0]
    poles: tuple[tuple[bool, bool], tuple[bool, bool]] = _FLAGS[1]
    derivatives_func: Callable[..., tuple[np.ndarray, np.ndarray]] | None = attrs.field(
        default=None, kw_only=True, validator=_callable("ParametricSurface")
    )
    second_derivatives_func: Callable[..., tuple[np.ndarray, np.ndarray, np.ndarray]] | None = (
        attrs.field(default=None, kw_only=True, validator=_callable("ParametricSurface"))
    )
    #: the Domain of the ranges, periodic and poles, built once (asked for
    #: in every inner loop of the numeric searches)
    _domain: Domain = attrs.field(init=False, repr=False, eq=False)

    @classmethod
    def from_formulas(
        cls,
        x: str,
        y: str,
        z: str,
        u: tuple[Any, Any],
        v: tuple[Any, Any],
        *,
        constants: Mapping[str, float] | None = None,
        periodic: Any = (False, False),
        poles: Any = False,
    ) -> ParametricSurface:
        """The surface ``(x, y, z)(u, v)`` of three formulas
        (:mod:`lgraph.formula`: never evaluated as Python), with exact first
        and second derivatives; ``u`` and ``v`` are the parameter ranges,
        numbers or formulas of ``constants`` (``"2*pi"``).

        >>> s = ParametricSurface.from_formulas(
        ...     "(1 + v/2*cos(u/2)) * cos(u)", "(1 + v/2*cos(u/2)) * sin(u)", "v/2*sin(u/2)",
        ...     (0, "2*pi"), (-0.5, 0.5))
        >>> s.point(0.0, 0.5).tolist()
        [1.25, 0.0, 0.0]
        """
        from ...formula.maps import constant_range, map_orders

        f, f1, f2 = map_orders((x, y, z), ("u", "v"), constants)
        return cls(
            f,
            constant_range(u, f.constants, "ParametricSurface.from_formulas: u"),
            constant_range(v, f.constants, "ParametricSurface.from_formulas: v"),
            periodic=periodic,
            poles=poles,
            derivatives_func=f1,
            second_derivatives_func=f2,
        )

    def __attrs_post_init__(self) -> None:
        if self.func is None:
            raise TypeError("ParametricSurface: func must be callable, got NoneType")
        object.__setattr__(
            self,
            "_domain",
            Domain(self.u1_range, self.u2_range, periodic=self.periodic, poles=self.poles),
        )
        if self.derivatives_func is not None or self.second_derivatives_func is not None:
            self._probe_derivatives()
        u1 = np.array([self.u1_range[0], sum(self.u1_range) / 2])
        u2 = np.array([self.u2_range[0], sum(self.u2_range) / 2])
        try:
            probe = np.asarray(self.func(u1, u2), dtype=float)
        except Exception as exc:  # noqa: BLE001 - report any failure of user code
            if _takes_scalars(self.func, u1[1], u2[1]):
                raise ValueError(
                    "ParametricSurface: func works on single numbers only, but it is called "
                    "with arrays of many parameters at once: write it with numpy (np.cos, not "
                    "math.cos; np.where, not if), or wrap it (slow): np.vectorize(lambda u, v: "
                    "np.array(func(u, v)), signature='(),()->(3)')"
                ) from exc
            raise ValueError(f"ParametricSurface: func(u1, u2) failed: {exc!r}") from exc
        if probe.shape != (2, 3):
            raise ValueError(
                "ParametricSurface: func must map arrays of shape (2,) to shape (2, 3), "
                f"got shape {probe.shape}"
            )

    def _probe_derivatives(self) -> None:
        u1 = np.array([self.u1_range[0], sum(self.u1_range) / 2])
        u2 = np.array([self.u2_range[0], sum(self.u2_range) / 2])
        probes = (("derivatives_func", "two", "(x1, x2)", 2),
                  ("second_derivatives_func", "three", "(x11, x12, x22)", 3))  # fmt: skip
        for name, count, what, n in probes:
            func = getattr(self, name)
            if func is None:
                continue
            try:
                parts = func(u1, u2)
                shapes = [np.asarray(x, dtype=float).shape for x in parts]
            except Exception as exc:  # noqa: BLE001 - report any failure of user code
                raise ValueError(
                    f"ParametricSurface: {name}(u1, u2) must return {count} arrays {what} "
                    f"of shape broadcast(u1, u2).shape + (3,); it failed: {exc!r}"
                ) from exc
            if shapes != [(2, 3)] * n:
                raise ValueError(
                    f"ParametricSurface: {name} must map arrays of shape (2,) to {count} "
                    f"arrays of shape (2, 3), got shapes {shapes}"
                )

    @property
    def domain(self) -> Domain:
        return self._domain

    def _base(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        """The parameters mapped into the rectangle across glued edges
        (:meth:`Domain.cells`), and the signs of that map per parameter (None
        when nothing is glued): the user's functions are only called there."""
        u1, u2 = _uv(u1, u2)
        per = self.periodic
        past = False  # a glued parameter past its range (inner loops: checked cheaply)
        for g, u, (lo, hi) in ((per[0], u1, self.u1_range), (per[1], u2, self.u2_range)):
            if g is not False and u.size:
                past = past or bool((u < lo).any()) or bool((u > hi).any())
        if not past:
            return u1, u2, None
        base, _, sign = self.domain.cells(np.stack([u1, u2], axis=-1))
        return base[..., 0], base[..., 1], sign

    def _checked(self, name: str, value: Any, u1: np.ndarray, u2: np.ndarray) -> np.ndarray:
        """``value`` as floats; NaN or inf (where the user's function failed
        inside the domain) is an error naming the surface and the parameters."""
        out = np.asarray(value, dtype=float)
        if not np.isfinite(out).all():
            # NaN parameters (a caller's failed search) may give NaN points
            bad = ~np.isfinite(out).reshape(np.shape(u1) + (-1,)).all(axis=-1)
            bad &= np.isfinite(u1) & np.isfinite(u2)
            i = np.flatnonzero(bad)
            if not len(i):
                return out
            a = np.broadcast_to(u1, bad.shape).ravel()[i]
            b = np.broadcast_to(u2, bad.shape).ravel()[i]
            raise ValueError(
                f"ParametricSurface: {name} returned NaN or inf at {len(i)} of {bad.size} "
                f"parameter pairs, first at (u1, u2) = ({float(a[0])!r}, {float(b[0])!r}) "
                f"(u1_range {self.u1_range}, u2_range {self.u2_range}): the function must be "
                "finite on the whole closed parameter rectangle; shrink the ranges to avoid "
                "singular edges"
            )
        return out

    def point(self, u1: Any, u2: Any) -> np.ndarray:
        b1, b2, _ = self._base(u1, u2)
        return self._checked("func", self.func(b1, b2), b1, b2)

    def derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray]:
        if self.derivatives_func is None:
            return super().derivatives(u1, u2)
        b1, b2, sign = self._base(u1, u2)
        x1, x2 = self.derivatives_func(b1, b2)
        x1 = self._checked("derivatives_func", x1, b1, b2)
        x2 = self._checked("derivatives_func", x2, b1, b2)
        if sign is not None:  # d/du_i of x(S u + t) is S_i x_i
            x1, x2 = x1 * sign[..., 0:1], x2 * sign[..., 1:2]
        return x1, x2

    def second_derivatives(self, u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if self.second_derivatives_func is None:
            return super().second_derivatives(u1, u2)
        b1, b2, sign = self._base(u1, u2)
        parts = self.second_derivatives_func(b1, b2)
        x11, x12, x22 = (self._checked("second_derivatives_func", x, b1, b2) for x in parts)
        if sign is not None:
            x12 = x12 * (sign[..., 0:1] * sign[..., 1:2])
        return x11, x12, x22


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
