"""Space curves, curves on surfaces, and the batches the renderer samples.

>>> import numpy as np
>>> helix = Curve(lambda t: np.stack([np.cos(t), np.sin(t), t / 5], axis=-1), 0, 6.0)
>>> helix(np.array([0.0])).round(12).tolist()
[[1.0, 0.0, 0.0]]
>>> helix.derivative(np.array([0.0])).round(6).tolist()
[[0.0, 1.0, 0.2]]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import attrs
import numpy as np

from ._own import ON
from ._validate import as_number

__all__ = ["Curve", "CurveOnSurface", "CurveBatch"]


def _finite_number(owner: str, name: str) -> Callable[[Any, Any, Any], None]:
    def check(_i: Any, _a: Any, v: Any) -> None:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{owner}: {name} must be a finite number, got {v!r}")

    return check


def _check_func(owner: str) -> Callable[[Any, Any, Any], None]:
    def check(_i: Any, a: Any, v: Any) -> None:
        if not callable(v):
            raise TypeError(f"{owner}: {a.name} must be callable, got {type(v).__name__}")

    return check


# eighth-order central difference weights for offsets 1..4
_W1 = (4 / 5, -1 / 5, 4 / 105, -1 / 280)
_W2 = (8 / 5, -1 / 5, 8 / 315, -1 / 560)


def _d1(f: Callable[[np.ndarray], np.ndarray], t: np.ndarray, h: float) -> np.ndarray:
    """First derivative of ``f`` at ``t`` by eighth-order central differences."""
    acc = 0.0
    for k, w in enumerate(_W1, start=1):
        acc = acc + w * (f(t + k * h) - f(t - k * h))
    return acc / h


def _d2(f: Callable[[np.ndarray], np.ndarray], t: np.ndarray, h: float) -> np.ndarray:
    """Second derivative of ``f`` at ``t`` by eighth-order central differences."""
    acc = -205 / 72 * f(t)
    for k, w in enumerate(_W2, start=1):
        acc = acc + w * (f(t + k * h) + f(t - k * h))
    return acc / (h * h)


@attrs.frozen(eq=False)
class Curve:
    """A space curve ``t -> func(t)`` for ``t0 <= t <= t1``.

    ``func`` takes an array of ``t`` and returns an array of shape ``t.shape + (3,)``.
    ``derivative`` (optional, same calling convention) gives ``dx/dt``; otherwise
    accurate central differences are used.
    """

    func: Callable[[np.ndarray], np.ndarray] = attrs.field(validator=_check_func("Curve"))
    t0: float = attrs.field(converter=as_number, validator=_finite_number("Curve", "t0"))
    t1: float = attrs.field(converter=as_number, validator=_finite_number("Curve", "t1"))
    derivative_func: Callable[[np.ndarray], np.ndarray] | None = attrs.field(
        default=None, kw_only=True
    )
    second_derivative_func: Callable[[np.ndarray], np.ndarray] | None = attrs.field(
        default=None, kw_only=True
    )
    closed: bool = attrs.field(default=False, kw_only=True)

    def __attrs_post_init__(self) -> None:
        if not self.t0 < self.t1:
            raise ValueError(f"Curve: t0 must be less than t1, got t0={self.t0}, t1={self.t1}")
        probe = np.asarray(self.func(np.array([self.t0, (self.t0 + self.t1) / 2])), float)
        if probe.shape != (2, 3):
            raise ValueError(
                "Curve: func must map an array of shape (n,) to shape (n, 3), "
                f"got shape {probe.shape} for n=2"
            )

    @classmethod
    def from_formulas(
        cls,
        x: str,
        y: str,
        z: str,
        t: tuple[Any, Any],
        *,
        constants: Mapping[str, float] | None = None,
        closed: bool = False,
    ) -> Curve:
        """The curve ``(x, y, z)(t)`` of three formulas (:mod:`lgraph.formula`:
        never evaluated as Python) over the range ``t`` (numbers or formulas of
        ``constants``), with exact derivatives.

        >>> c = Curve.from_formulas("cos(t)", "sin(t)", "t / (2*pi)", (0, "2*pi"))
        >>> c(np.array([np.pi])).round(12).tolist()
        [[-1.0, 0.0, 0.5]]
        """
        from .formula.maps import constant_range, map_orders

        f, f1, f2 = map_orders((x, y, z), ("t",), constants)
        t0, t1 = constant_range(t, f.constants, "Curve.from_formulas: t")
        return cls(f, t0, t1, derivative_func=f1, second_derivative_func=f2, closed=closed)

    def __call__(self, t: Any) -> np.ndarray:
        return np.asarray(self.func(np.asarray(t, dtype=float)), dtype=float)

    def derivative(self, t: Any) -> np.ndarray:
        """``dx/dt`` (analytic if given, else eighth-order central differences).

        The numeric step is ``2e-3`` of the parameter span: truncation and
        rounding errors are both about ``1e-12`` relative for curves that turn
        a few times over their span.
        """
        t = np.asarray(t, dtype=float)
        if self.derivative_func is not None:
            return np.asarray(self.derivative_func(t), dtype=float)
        return _d1(self.__call__, t, 2e-3 * (self.t1 - self.t0))

    def second_derivative(self, t: Any) -> np.ndarray:
        """``d^2x/dt^2`` (analytic if given, else eighth-order central differences,
        of the analytic first derivative when there is one)."""
        t = np.asarray(t, dtype=float)
        if self.second_derivative_func is not None:
            return np.asarray(self.second_derivative_func(t), dtype=float)
        if self.derivative_func is not None:
            return _d1(self.derivative, t, 2e-3 * (self.t1 - self.t0))
        return _d2(self.__call__, t, 3e-3 * (self.t1 - self.t0))

    def batch(self, family: str = "curve") -> CurveBatch:
        """This curve as a one-curve batch for the renderer."""
        return CurveBatch(
            family=family,
            t0=np.array([self.t0]),
            t1=np.array([self.t1]),
            evaluate=lambda _idx, t: (self(t), None),
            closed=np.array([self.closed]),
        )


@attrs.frozen(eq=False)
class CurveOnSurface:
    """A curve ``t -> surface.point(*uv(t))`` given in the parameter plane.

    ``uv`` maps an array of ``t`` to an array of shape ``t.shape + (2,)``.
    """

    surface: Any
    uv: Callable[[np.ndarray], np.ndarray] = attrs.field(validator=_check_func("CurveOnSurface"))
    t0: float = attrs.field(converter=as_number, validator=_finite_number("CurveOnSurface", "t0"))
    t1: float = attrs.field(converter=as_number, validator=_finite_number("CurveOnSurface", "t1"))
    closed: bool = attrs.field(default=False, kw_only=True)

    def __attrs_post_init__(self) -> None:
        if not self.t0 < self.t1:
            raise ValueError(
                f"CurveOnSurface: t0 must be less than t1, got t0={self.t0}, t1={self.t1}"
            )

    def __call__(self, t: Any) -> np.ndarray:
        return self.surface.points(self.uv(np.asarray(t, dtype=float)))

    def batch(self, family: str = "curve") -> CurveBatch:
        def evaluate(_idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            uv = np.asarray(self.uv(t), dtype=float)
            return self.surface.points(uv), uv

        return CurveBatch(
            family=family,
            t0=np.array([self.t0]),
            t1=np.array([self.t1]),
            evaluate=evaluate,
            closed=np.array([self.closed]),
            surface=self.surface,
        )


@attrs.frozen(eq=False)
class CurveBatch:
    """Many curves of one family, evaluated together (the renderer's unit of work).

    ``evaluate(idx, t)`` takes equal-length arrays of curve indices and
    parameters and returns ``(xyz, uv)``: local coordinates ``(n, 3)`` and
    surface parameters ``(n, 2)`` (or None for free curves).  Curve ``k`` runs
    over ``t0[k] <= t <= t1[k]``; ``closed[k]`` marks closed curves.  ``own`` is
    how points relate to ``surface`` for visibility (``ON`` or ``CONTOUR``).

    ``curve_family`` (optional) names the family of each curve, overriding
    ``family`` (one batch may hold both parameter-line families, say).

    ``ellipses`` (optional, ``(m, 3, 3)``) says that curve ``k`` is exactly
    ``x(t) = c + p cos t + q sin t`` with rows ``c, p, q`` (local
    coordinates), as the parameter lines of an ellipsoid are; the renderer
    then finds where it crosses its own surface's contour in closed form.

    ``kernel`` (optional, ``(f, params)``) says that ``evaluate(idx, t)`` is
    ``f(params[idx], t)``, with one row of ``params`` a curve: batches with
    the same ``f`` (one object) are evaluated in one call, their ``params``
    stacked (the contours of one surface in many views, say).
    """

    family: str
    t0: np.ndarray
    t1: np.ndarray
    evaluate: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray | None]]
    closed: np.ndarray = attrs.field(default=None)
    surface: Any = None
    own: int = ON
    style: Any = None
    curve_family: tuple[str, ...] | None = None
    ellipses: np.ndarray | None = None
    kernel: tuple[Callable[[np.ndarray, np.ndarray], Any], np.ndarray] | None = None

    def __attrs_post_init__(self) -> None:
        object.__setattr__(self, "t0", np.asarray(self.t0, dtype=float).ravel())
        object.__setattr__(self, "t1", np.asarray(self.t1, dtype=float).ravel())
        if self.ellipses is not None:
            e = np.asarray(self.ellipses, dtype=float)
            if e.shape != (len(self.t0), 3, 3):
                raise ValueError(
                    f"CurveBatch: ellipses must have shape ({len(self.t0)}, 3, 3), got {e.shape}"
                )
            object.__setattr__(self, "ellipses", e)
        if self.kernel is not None and len(self.kernel[1]) != len(self.t0):
            raise ValueError(
                f"CurveBatch: kernel parameters must have {len(self.t0)} rows (one a curve), "
                f"got {len(self.kernel[1])}"
            )
        if self.closed is None:
            object.__setattr__(self, "closed", np.zeros(len(self.t0), bool))
        else:
            object.__setattr__(
                self, "closed", np.broadcast_to(np.asarray(self.closed, bool), self.t0.shape)
            )

    def __len__(self) -> int:
        return len(self.t0)

    @classmethod
    def from_uv(
        cls,
        surface: Any,
        family: str,
        t0: Any,
        t1: Any,
        uv: Callable[[np.ndarray, np.ndarray], np.ndarray],
        closed: Any = False,
        **kw: Any,
    ) -> CurveBatch:
        """A batch of curves given in the parameter plane: ``uv(idx, t) -> (n, 2)``."""

        def evaluate(idx: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            p = np.asarray(uv(idx, t), dtype=float)
            return surface.point(p[:, 0], p[:, 1]), p

        return cls(family, t0, t1, evaluate, closed=closed, surface=surface, **kw)

    @classmethod
    def from_curves(
        cls,
        surface: Any,
        family: str,
        t0: Any,
        t1: Any,
        uv_of: Callable[[int, np.ndarray], np.ndarray],
        closed: Any = False,
        adjust: Callable[[np.ndarray], np.ndarray] | None = None,
        **kw: Any,
    ) -> CurveBatch:
        """A batch of curves each with its own parameter-plane function
        ``uv_of(k, t) -> (n, 2)`` (one call per curve present);
        ``adjust(uv)`` (optional) corrects all parameters at once before the
        periodic ones are wrapped and the others clipped to the domain
        (across a twisted seam ``adjust`` sees the parameters wrapped)."""
        domain = surface.domain
        twisted = any(getattr(domain, "twisted", (False, False)))

        def uv(idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            idx = np.asarray(idx)
            out = np.empty((len(idx), 2))
            for k in np.unique(idx).tolist():
                sel = idx == k
                out[sel] = uv_of(k, t[sel])
            if adjust is None:
                return domain.wrap(out)
            return domain.wrap(adjust(domain.wrap(out, clip=False) if twisted else out))

        return cls.from_uv(surface, family, t0, t1, uv, closed=closed, **kw)
