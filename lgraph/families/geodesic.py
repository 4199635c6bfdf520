"""Geodesics: one geodesic from a point and a direction, as a curve on the
surface (:func:`geodesic`) or a family (:class:`Geodesic`).

>>> import numpy as np
>>> import lgraph as lg
>>> g = geodesic(lg.Torus(3, 1), (0.0, 0.0), (1.0, 0.0), 2.0)
>>> bool(np.allclose(g(np.array([2.0]))[0, 2], 0.0, atol=1e-9))  # the outer equator
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import attrs
import numpy as np

from .. import _tolerance as tol
from .._budget import check_geodesic
from .._validate import as_number, finite_positive
from ..curves import CurveBatch, CurveOnSurface
from ..surfaces._base import Surface
from . import Family

if TYPE_CHECKING:
    from ..scene.projectors import Projector

__all__ = ["Geodesic", "geodesic"]


# ---------------------------------------------------------------------------
# geodesics
# ---------------------------------------------------------------------------
def _geodesic_rhs(surface: Any) -> Any:
    d = surface.domain
    twisted = any(d.twisted)

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        # trial stages past an edge that is not glued: the nearest edge point
        # (the event `leave` ends the geodesic on the edge)
        (u1, u2), (a, b) = d.clip(y[:2]), y[2:]
        u1a, u2a = np.array([u1]), np.array([u2])
        sign = np.ones(2)
        if twisted:  # the cover point's derivatives, from the rectangle's point
            base, _, sg = d.cells(np.array([[u1, u2]]))
            u1a, u2a, sign = base[:, 0], base[:, 1], sg[0]
        x1, x2 = surface.derivatives(u1a, u2a)
        x11, x12, x22 = surface.second_derivatives(u1a, u2a)
        x1, x2, x12 = x1 * sign[0], x2 * sign[1], x12 * (sign[0] * sign[1])
        acc = (x11 * a * a + 2 * x12 * a * b + x22 * b * b)[0]
        x1, x2 = x1[0], x2[0]
        g11, g12, g22 = x1 @ x1, x1 @ x2, x2 @ x2
        r1, r2 = -(x1 @ acc), -(x2 @ acc)
        det = g11 * g22 - g12 * g12
        return np.array([a, b, (g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det])

    return rhs


def _geodesic_solution(surface: Any, uv0: Any, direction: Any, length: float) -> Any:
    from scipy.integrate import solve_ivp

    uv0 = np.asarray(uv0, float)
    du = np.asarray(direction, float)
    x1, x2 = surface.derivatives(uv0[0], uv0[1])
    speed = np.linalg.norm(du[0] * x1 + du[1] * x2)
    if not speed > 0:
        raise ValueError("Geodesic: direction must be a non-zero tangent direction (du1, du2)")
    du = du / speed
    d = surface.domain

    def leave(_t: float, y: np.ndarray) -> float:
        out = 1.0
        for i in (0, 1):
            if not d.periodic[i]:
                lo, hi = d.range(i)
                out = min(out, (y[i] - lo) / d.span(i), (hi - y[i]) / d.span(i))
        return out

    leave.terminal = True  # type: ignore[attr-defined]
    sol = solve_ivp(
        _geodesic_rhs(surface),
        (0.0, length),
        np.concatenate([uv0, du]),
        method="DOP853",
        dense_output=True,
        rtol=1e-10,
        atol=1e-12 * max(d.span(0), d.span(1)),
        events=leave,
    )
    return sol.sol, float(sol.t[-1])


def geodesic(surface: Any, uv0: Any, direction: Any, length: float) -> CurveOnSurface:
    """The geodesic from parameters ``uv0`` in the parameter direction
    ``direction = (du1, du2)``, ``length`` long in 3-D arc length (shorter if
    it leaves the domain), as a :class:`CurveOnSurface` with ``t`` = arc length.

    Integrates ``G u'' = -J^T (x11 u1'^2 + 2 x12 u1' u2' + x22 u2'^2)``: the
    acceleration of a geodesic is normal to the surface.
    """
    length = check_geodesic("geodesic", surface, uv0, direction, length)
    sol, t1 = _geodesic_solution(surface, uv0, direction, length)
    return CurveOnSurface(
        surface, lambda t: surface.domain.wrap(np.asarray(sol(t))[:2].T), 0.0, max(t1, 1e-12)
    )


def _pair(owner: str, name: str, value: Any) -> tuple[float, float]:
    """Converter: a pair of finite numbers (ValueError naming ``name`` otherwise)."""
    try:
        a, b = (float(as_number(x)) for x in value)
    except (TypeError, ValueError):
        raise ValueError(
            f"{owner}: {name} must be a pair of finite numbers, got {value!r}"
        ) from None
    if not (np.isfinite(a) and np.isfinite(b)):
        raise ValueError(f"{owner}: {name} must be a pair of finite numbers, got {value!r}")
    return a, b


@attrs.frozen(eq=False)
class Geodesic(Family):
    """One geodesic of the node's surface (family ``"geodesic"``): from the
    parameters ``uv0`` in the parameter direction ``direction = (du1, du2)``,
    ``length`` long (3-D arc length); ``both_ways`` also runs it backward.
    The length run in all (twice ``length`` both ways) is at most
    ``MAX_GEODESIC_TURNS`` times the surface's size, checked when drawn.

    >>> Geodesic((0, 0), (1, 0), length=0)
    Traceback (most recent call last):
    ...
    ValueError: Geodesic: length must be a positive finite number, got 0
    """

    view_dependent: ClassVar[bool] = False

    uv0: tuple[float, float] = attrs.field(converter=lambda v: _pair("Geodesic", "uv0", v))
    direction: tuple[float, float] = attrs.field(
        converter=lambda v: _pair("Geodesic", "direction", v)
    )
    length: float = attrs.field(
        default=10.0, converter=as_number, validator=finite_positive("Geodesic")
    )
    both_ways: bool = attrs.field(default=False, kw_only=True)

    def batches(self, surface: Surface, projector: Projector | None) -> list[CurveBatch]:
        length = check_geodesic("Geodesic", surface, self.uv0, self.direction, self.length)
        limit = tol.MAX_GEODESIC_TURNS * surface.size
        if self.both_ways and 2 * length > limit:  # both halves integrated: the work doubles
            raise ValueError(
                f"Geodesic: length {length:g} run both ways ({2 * length:g} in all) exceeds the "
                f"limit of {tol.MAX_GEODESIC_TURNS} times the surface's size ({limit:g})"
            )
        fwd, t1 = _geodesic_solution(surface, self.uv0, self.direction, self.length)
        t0 = 0.0
        bwd = None
        if self.both_ways:
            bwd, tb = _geodesic_solution(
                surface, self.uv0, tuple(-x for x in self.direction), self.length
            )
            t0 = -tb

        def uv(_idx: np.ndarray, t: np.ndarray) -> np.ndarray:
            out = np.empty((len(t), 2))
            pos = t >= 0
            if pos.any():
                out[pos] = np.asarray(fwd(t[pos]))[:2].T
            if (~pos).any() and bwd is not None:
                out[~pos] = np.asarray(bwd(-t[~pos]))[:2].T
            return surface.domain.wrap(out)

        return [CurveBatch.from_uv(surface, "geodesic", [t0], [t1], uv)]
