"""Isolated singular points of a parametrization (the pinch points of a
Whitney umbrella, a cross-cap, Steiner's Roman surface): the numeric
contour's pieces that stop beside one are carried on to it.

At a pinch point ``u*`` the normal ``n = x_1 x x_2`` vanishes, to first
order ``n = J (u - u*)`` with ``J`` of rank 2, so the unit normal takes
every direction of a great circle around the point, and the contour of every
view passes through it: its branches leave ``u*`` along the rays of the
parameter plane where ``N . w = 0``.  The contour's grid
(:mod:`~lgraph.surfaces.parametric._zero_set`) follows them only up to the
cell that holds ``u*`` (``N . w`` is undefined there), so the pieces stop
up to a cell short: a gap in the drawn outline at every pinch point.

:func:`to_singular_points` takes every open piece that ends in the interior
of the domain (not within ``EDGE_CELLS`` cells of an edge that is not
glued), looks for a zero of ``n`` next to the end (Gauss-Newton on ``n(u) =
0``, the Jacobian of ``n`` by central differences), and appends it to the
piece where it lies within ``END_CELLS`` cells and ``|n|`` there is below
:func:`~lgraph.surfaces.parametric._contour.normal_floor` (a true zero,
not a small normal).  The contour's projection onto ``N . w = 0`` leaves
that end where it is (no step where the cosine is undefined), so the drawn
outline reaches the pinch point from both sides.

An edge that collapses to a point (a declared pole, or an end found
collapsed by :func:`~lgraph.surfaces.parametric._zero_set.collapsed_ends`)
stops the grid the same way, a cell short of the point its pieces reach
(the cross-cap's poles): a piece ending within ``EDGE_CELLS`` of such an
edge is carried onto it (the grid's own line beside the pole, which maps to
the pole's point).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...geometry.vectors import cross
from ._zero_set import collapsed_ends, grid_axis

if TYPE_CHECKING:
    from .._domain import Parametrized

__all__ = ["to_singular_points"]

#: a piece's end within this many grid cells of its singular point is carried to it
END_CELLS = 3.0
#: ends this close (in cells) to an edge that is not glued end there
EDGE_CELLS = 2.0
#: an end this close (in cells) to its point is moved onto it, not joined to it
SAME_CELLS = 0.01
#: Gauss-Newton steps (the zero of ``n`` is simple: quadratic convergence)
STEPS = 8


def _normal(surface: Parametrized, u: np.ndarray) -> np.ndarray:
    x1, x2 = surface.derivatives(u[:, 0], u[:, 1])
    return cross(x1, x2)


def _zero_of_normal(surface: Parametrized, u: np.ndarray) -> np.ndarray:
    """Gauss-Newton from ``u (m, 2)`` toward zeros of ``n(u)``, iterates
    clipped to the rectangle."""
    d = surface.domain
    h = 1e-6 * np.array([d.span(0), d.span(1)])
    u = d.clip(np.array(u, dtype=float, copy=True))
    for _ in range(STEPS):
        n = _normal(surface, u)
        cols = []
        for i in (0, 1):
            a, b = u.copy(), u.copy()
            a[:, i] -= h[i]
            b[:, i] += h[i]
            cols.append((_normal(surface, b) - _normal(surface, a)) / (2 * h[i]))
        J = np.stack(cols, axis=-1)  # (m, 3, 2)
        JtJ = np.einsum("mki,mkj->mij", J, J)
        Jtn = np.einsum("mki,mk->mi", J, n)
        det = JtJ[:, 0, 0] * JtJ[:, 1, 1] - JtJ[:, 0, 1] ** 2
        with np.errstate(divide="ignore", invalid="ignore"):
            step = (
                np.stack(
                    [
                        JtJ[:, 1, 1] * Jtn[:, 0] - JtJ[:, 0, 1] * Jtn[:, 1],
                        JtJ[:, 0, 0] * Jtn[:, 1] - JtJ[:, 0, 1] * Jtn[:, 0],
                    ],
                    axis=1,
                )
                / det[:, None]
            )
        step = np.where(np.isfinite(step), step, 0.0)
        u = d.clip(u - step)
    return u


def to_singular_points(
    surface: Parametrized, curves: list[tuple[np.ndarray, bool]], grid: int, floor: float
) -> list[tuple[np.ndarray, bool]]:
    """The zero-set ``curves`` (polylines in the parameter plane, closed or
    not) with every open end that stops beside an isolated singular point
    carried on to it (module docstring); ``grid``: the zero set's grid,
    ``floor``: the length of ``n`` below which a point is singular."""
    d = surface.domain
    span = np.array([d.span(0), d.span(1)])
    cell = span / (grid - 1)
    lo = np.array([d.range(0)[0], d.range(1)[0]])
    # per parameter: the grid's first and last values, and which ends
    # collapse to a point (a piece ending beside one goes on to it)
    axes = [grid_axis(surface, i, grid) for i in (0, 1)]
    shut = collapsed_ends(surface)
    collapsed = [[a or b for a, b in zip(d.poles[i], shut[i])] for i in (0, 1)]
    out = [pts for pts, _ in curves]
    ends, where = [], []
    for k, (pts, closed) in enumerate(curves):
        if closed or len(pts) < 2:
            continue
        for side in (0, -1):
            p = pts[side]
            inner, pole = True, None
            for i in (0, 1):
                if d.periodic[i] is not False:
                    continue
                off = (p[i] - lo[i]) / cell[i]
                beside = (off <= EDGE_CELLS, off >= span[i] / cell[i] - EDGE_CELLS)
                for end in (0, 1):
                    if beside[end]:
                        inner = False
                        if collapsed[i][end]:
                            pole = p.copy()
                            pole[i] = axes[i][-end]
            if pole is not None:
                out[k] = _appended(out[k], side, pole, cell)
            elif inner:
                ends.append(p)
                where.append((k, side))
    if ends:
        start = np.array(ends)
        u = _zero_of_normal(surface, start)
        near = np.hypot(*((u - start) / cell).T) <= END_CELLS
        singular = np.linalg.norm(_normal(surface, u), axis=1) <= floor
        for (k, side), ok, point in zip(where, near & singular, u):
            if ok:
                out[k] = _appended(out[k], side, point, cell)
    return [(pts, closed) for pts, (_, closed) in zip(out, curves)]


def _appended(pts: np.ndarray, side: int, point: np.ndarray, cell: np.ndarray) -> np.ndarray:
    """The polyline ``pts`` with ``point`` at its start (``side`` 0) or end:
    added, or in place of that end when it lies within ``SAME_CELLS`` cells
    (the grid met the point already, to rounding)."""
    if np.hypot(*((pts[side] - point) / cell)) <= SAME_CELLS:
        pts = pts.copy()
        pts[side] = point
        return pts
    return np.vstack([point, pts]) if side == 0 else np.vstack([pts, point])
