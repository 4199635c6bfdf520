"""The numeric contour of a parametrized surface: the default of
:meth:`Surface.contour <lgraph.surfaces._base.Surface.contour>`.

The contour is the zero set of ``f(u) = N(u) . w(u) / |w(u)|`` (``N`` the unit
normal, ``w`` the view vector toward the viewer; :func:`view_cosine`), found
by :func:`~lgraph.surfaces.parametric._zero_set.zero_set`.  Each curve of a zero set is
interpolated by a spline in the parameter plane (periodic for closed curves,
unwrapped across periodic seams) whose points are projected back onto the
zero set by Newton's method when the renderer evaluates them
(:func:`project_to_zero`), so drawn contour points satisfy ``f = 0`` to
rounding (docs/mathematics.rst, "Level lines, parabolic lines,
self-intersections").
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.interpolate import CubicSpline, make_interp_spline

from ..._own import CONTOUR, ON
from ..._tolerance import SINGULAR_NORMAL_RTOL
from ...geometry.vectors import cross as _cross
from .._memo import per_surface
from ._seams import unjump
from ._singular_points import to_singular_points
from ._zero_set import CONTOUR_GRID, grid_parameters, zero_set

if TYPE_CHECKING:
    from ...curves import CurveBatch
    from ...scene.projectors import Projector
    from .._domain import Parametrized

__all__ = [
    "contour",
    "grid_geometry",
    "normal_floor",
    "project_to_contour",
    "project_to_zero",
    "view_cosine",
    "view_cosine_gradient",
    "zero_set_batch",
]


def _is_central(projector: Any) -> bool:
    from ...scene.projectors import CentralProjector

    return isinstance(projector, CentralProjector)


def view_cosine(surface: Parametrized, projector: Projector, u1: Any, u2: Any) -> np.ndarray:
    """``N . w / |w|`` (``N`` unit normal, ``w`` toward the viewer); zero on the
    contour, NaN at singular points of the parametrization (:func:`normal_floor`)."""
    u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
    x1, x2 = surface.derivatives(u1, u2)
    n = _cross(x1, x2)
    p = surface.point(u1, u2) if _is_central(projector) else None
    return _cosine(n, p, projector, normal_floor(surface))


def normal_floor(surface: Parametrized) -> float:
    """The length of ``x_1 x x_2`` below which a point is singular: its normal
    is undefined, the computed one noise (``SINGULAR_NORMAL_RTOL`` of the
    surface's typical ``|x_1| |x_2|``, ``size^2 / (span_1 span_2)``)."""
    d = surface.domain
    return SINGULAR_NORMAL_RTOL * surface.size**2 / (d.span(0) * d.span(1))


def _cosine(
    n: np.ndarray, p: np.ndarray | None, projector: Projector, floor: float = 0.0
) -> np.ndarray:
    """``N . w / |w|`` from the normal ``n`` (any length) and, for a central
    view, the point ``p``; NaN where ``|n| <= floor`` (a singular point)."""
    if _is_central(projector):
        w = projector.eye - p
    else:
        w = np.broadcast_to(projector.frame[2], n.shape)
    nn = np.linalg.norm(n, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.einsum("...i,...i", n, w) / (nn * np.linalg.norm(w, axis=-1))
    return np.where(nn > floor, f, np.nan)


def _analytic_second_derivatives(surface: Parametrized) -> bool:
    """Whether the surface's class overrides the numeric default of
    ``second_derivatives`` (defined by the base class: the last of the MRO),
    and, for a :class:`~lgraph.ParametricSurface`, was given them."""
    if getattr(surface, "second_derivatives_func", True) is None:
        return False
    owners = [c for c in type(surface).__mro__ if "second_derivatives" in vars(c)]
    return len(owners) > 1


def view_cosine_gradient(
    surface: Parametrized, projector: Projector, u1: Any, u2: Any
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``f = N . w / |w|`` and its partial derivatives ``f_1, f_2`` from the
    second derivatives: with ``n = x_1 x x_2``, ``n_i = x_1i x x_2 + x_1 x x_2i``
    and ``w_i = 0`` (parallel view) or ``-x_i`` (central view),
    ``f_i = (n_i . w + n . w_i) / (|n| |w|) - f (n . n_i / |n|^2 + w . w_i / |w|^2)``."""
    u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
    x1, x2 = surface.derivatives(u1, u2)
    x11, x12, x22 = surface.second_derivatives(u1, u2)
    n = _cross(x1, x2)
    n1 = _cross(x11, x2) + _cross(x1, x12)
    n2 = _cross(x12, x2) + _cross(x1, x22)
    central = _is_central(projector)
    w = projector.eye - surface.point(u1, u2) if central else projector.frame[2]

    def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.einsum("...i,...i", a, np.broadcast_to(b, a.shape))

    nn = dot(n, n)
    ww = dot(w, w) if central else float(w @ w)
    nw = dot(n, w)
    with np.errstate(invalid="ignore", divide="ignore"):
        norm = np.sqrt(nn) * np.sqrt(ww)
        f = np.where(np.sqrt(nn) > normal_floor(surface), nw / norm, np.nan)
        grads = []
        for ni, xi in ((n1, x1), (n2, x2)):
            a = dot(ni, w) - (dot(n, xi) if central else 0.0)
            b = dot(n, ni) / nn - (dot(w, xi) / ww if central else 0.0)
            grads.append(a / norm - f * b)
    return f, grads[0], grads[1]


def project_to_contour(
    surface: Parametrized, projector: Projector, uv: np.ndarray, steps: int = 4
) -> np.ndarray:
    """Newton projection of parameters ``uv (n, 2)`` onto the contour ``f = 0``
    (with the analytic gradient :func:`view_cosine_gradient` where the surface
    has analytic second derivatives)."""

    def fun(u1: Any, u2: Any) -> np.ndarray:
        return view_cosine(surface, projector, u1, u2)

    def fun_grad(u1: Any, u2: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return view_cosine_gradient(surface, projector, u1, u2)

    analytic = _analytic_second_derivatives(surface)
    return project_to_zero(surface, fun, uv, steps, 1e-14, fun_grad if analytic else None)


def project_to_zero(
    surface: Parametrized,
    fun: Any,
    uv: np.ndarray,
    steps: int = 4,
    ftol: float = 1e-14,
    fun_grad: Any = None,
) -> np.ndarray:
    """Newton projection of parameters ``uv (n, 2)`` onto ``fun(u1, u2) = 0``
    (minimal steps in parameters scaled by the spans, central-difference
    gradients, or ``fun_grad(u1, u2) -> (f, f_1, f_2)`` when given); points
    with ``|fun| <= ftol`` stop early."""
    d = surface.domain
    scale = np.array([d.span(0), d.span(1)])
    uv = np.array(uv, dtype=float, copy=True)
    h = 1e-6 * scale
    active = np.arange(len(uv))
    for _ in range(steps):
        if not len(active):
            break
        p = uv[active]
        if fun_grad is not None:
            f, g1, g2 = fun_grad(p[:, 0], p[:, 1])
        else:
            f = fun(p[:, 0], p[:, 1])
            g1, g2 = (_difference(d, fun, p, i, h[i]) for i in (0, 1))
        # minimal step in coordinates scaled by the spans
        g1s, g2s = g1 * scale[0], g2 * scale[1]
        gg = g1s * g1s + g2s * g2s
        ok = np.isfinite(f) & (gg > 0)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.where(ok, f / gg, 0.0)
        # no step where f or its gradient is undefined (a singular point)
        uv[active, 0] -= np.where(ok, step * g1s, 0.0) * scale[0]
        uv[active, 1] -= np.where(ok, step * g2s, 0.0) * scale[1]
        uv[active] = d.clip(uv[active])  # Newton iterates stay in the rectangle
        active = active[ok & (np.abs(f) > ftol)]
    return uv


def _difference(d: Any, fun: Any, p: np.ndarray, i: int, h: float) -> np.ndarray:
    """Central difference of ``fun`` along ``u_i`` at ``p (n, 2)``, one-sided
    where a step would leave the rectangle (not across glued edges)."""
    a, b = p.copy(), p.copy()
    a[:, i] -= h
    b[:, i] += h
    a, b = d.clip(a), d.clip(b)
    with np.errstate(invalid="ignore", divide="ignore"):
        return (fun(b[:, 0], b[:, 1]) - fun(a[:, 0], a[:, 1])) / (b[:, i] - a[:, i])


def grid_geometry(surface: Parametrized, grid: int = CONTOUR_GRID) -> tuple[np.ndarray, np.ndarray]:
    """The normals ``x_1 x x_2`` and the points on the nodes of
    :func:`~lgraph.surfaces.parametric._zero_set.grid_parameters`: the same for every
    view, computed once per surface."""

    def compute() -> tuple[np.ndarray, np.ndarray]:
        U1, U2 = grid_parameters(surface, grid)
        x1, x2 = surface.derivatives(U1, U2)
        return _cross(x1, x2), surface.point(U1, U2)

    return per_surface(surface, ("contour grid", grid), compute)


def contour(
    surface: Parametrized, projector: Projector, grid: int = CONTOUR_GRID
) -> list[CurveBatch]:
    """Numeric contour of ``surface`` for ``projector`` (local frame), as one batch."""

    def fun(u1: Any, u2: Any) -> np.ndarray:
        return view_cosine(surface, projector, u1, u2)

    n, p = grid_geometry(surface, grid)
    values = _cosine(n, p, projector, normal_floor(surface))
    curves = zero_set(surface, fun, grid, values=values)
    # pieces that stop a cell short of a pinch point go on to it
    curves = to_singular_points(surface, curves, grid, normal_floor(surface))
    return [_contour_batch(surface, projector, curves)] if curves else []


class _ContourCurve:
    """One contour curve: spline in the parameter plane + Newton projection.

    Points are unwrapped into the cover (:mod:`~lgraph.surfaces.parametric._seams`); a closed curve
    whose closing step crosses a twisted seam comes back mirrored, so its
    spline runs over two laps (a translation apart) of which one is drawn."""

    def __init__(self, surface: Parametrized, pts: np.ndarray, closed: bool) -> None:
        d = surface.domain
        scale = np.array([d.span(0), d.span(1)])
        p = unjump(d, pts)
        if closed:
            p = np.vstack([p, d.nearest_image(p[-1], p[0])])
        chord = np.linalg.norm(np.diff(p / scale, axis=0), axis=1)
        keep = np.concatenate([[True], chord > 1e-3 * np.median(chord)])
        if closed:
            keep[-1] = True
            keep[-2] = keep[-2] and chord[-1] > 1e-3 * np.median(chord)
        p = p[keep]
        laps = 1
        if closed and any(d.twisted):
            S, t = d.deck(p[-1], p[0])
            if (S < 0).any():  # mirrored: the second lap closes it in the cover
                p = np.vstack([p, S * p[1:] + t])
                laps = 2
        t = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p / scale, axis=0), axis=1))])
        self.period = float(t[-1])
        self.length = float(t[-1]) / laps
        self.closed = closed
        if closed and len(p) >= 4:
            self.drift = p[-1] - p[0]
            self.spline = CubicSpline(t, p - np.outer(t / t[-1], self.drift), bc_type="periodic")
        else:
            self.drift = np.zeros(2)
            self.spline = make_interp_spline(t, p, k=min(3, len(p) - 1))

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return self.spline(t) + np.outer(t / self.period, self.drift)


def _contour_batch(surface: Parametrized, projector: Projector, curves: list) -> CurveBatch:
    return zero_set_batch(
        surface, curves, lambda uv: project_to_contour(surface, projector, uv), "contour", CONTOUR
    )


def zero_set_batch(
    surface: Parametrized, curves: list, adjust: Any, family: str, own: int = ON
) -> CurveBatch:
    """One batch of the :func:`zero_set` curves: splines in the parameter plane
    (periodic for closed curves) whose points ``adjust(uv)`` projects back onto
    the zero set at evaluation time."""
    from ...curves import CurveBatch

    objs = [_ContourCurve(surface, p, closed) for p, closed in curves]
    return CurveBatch.from_curves(
        surface,
        family,
        np.zeros(len(objs)),
        [o.length for o in objs],
        lambda k, t: objs[k](t),
        closed=[o.closed for o in objs],
        adjust=adjust,
        own=own,
    )
