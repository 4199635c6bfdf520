"""Singular curves of a parametrization: cuspidal edges, drawn as edges.

Along a cuspidal edge -- Dini's surface at ``v = pi/2``, the pseudosphere's
rim, any surface ``x(u, v)`` whose ``x_v`` vanishes along a curve ``v =
v0(u)`` -- the normal ``n = x_1 x x_2`` has a factor that changes sign:
``n = (v - v0) m`` with ``m`` smooth and nonzero, so the unit normal flips
across the curve.  The curve is part of what the surface shows: a cuspidal
edge projects onto an outline of the image (both sheets leave it on the same
side, unless the view runs along the cusp's tangent), and it is where the
numeric contour's ``N . w`` jumps instead of vanishing (the contour of
:mod:`~lgraph.surfaces.parametric._contour` ends on it).  :func:`singular_curves` finds it
without knowing it:

1. the unit normals on a ``CONTOUR_GRID``-square grid of the domain
   (offset from the contour's grid by an irrational fraction of a cell, so
   that a singular curve on a round parameter value misses the nodes);
2. a grid edge whose ends' normals point apart (negative dot product)
   brackets a flip; the crossing ``p`` is refined on the edge to machine
   precision as the zero of ``n . (N_b - N_a)`` (``N_a``, ``N_b`` the ends'
   unit normals), and kept where ``|n(p)|`` is below ``SINGULAR_EDGE_RTOL``
   of the ends' (a zero of ``n``: a regular surface turning through more
   than 90 degrees within a cell has none);
3. the crossings are joined cell by cell into curves
   (:func:`~lgraph.surfaces.parametric._zero_set.march`); curves whose image is a
   point (an edge that collapses, such as ``v = pi/2`` of Apery's Boy
   surface) are left out.

Isolated singular points (a Whitney umbrella's pinch point, poles) are no
curves and give none.  Points of the drawn curves are the cubic spline
through the crossings: an error ``e`` of a parameter across a cuspidal edge
moves the image by ``O(e^2)`` only.  :func:`singular_edge_batches` gives
them as part of the surface's edges (family ``"boundary"``): drawn, and part
of the net of curves where visibility may change (docs/mathematics.rst,
"Singular edges and points").
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..._own import ON
from ..._roots import bracketed_roots
from ..._tolerance import SINGULAR_COLLAPSED_RTOL, SINGULAR_EDGE_RTOL
from ...geometry.vectors import cross as _cross
from .._memo import per_surface
from ._contour import grid_geometry, normal_floor, zero_set_batch
from ._zero_set import CONTOUR_GRID, EDGE_XTOL, march

if TYPE_CHECKING:
    from ...curves import CurveBatch
    from .._domain import Parametrized

__all__ = ["singular_curves", "singular_edge_batches"]

#: the grid's offset from the domain's edges, in cells (the golden section:
#: far from every ratio of small integers)
OFFSET = (3 - 5**0.5) / 2


def _axis(surface: Parametrized, i: int, n: int) -> np.ndarray:
    lo, hi = surface.domain.range(i)
    return lo + (hi - lo) * (np.arange(n) + OFFSET) / n


def _normals(surface: Parametrized, u1: Any, u2: Any) -> np.ndarray:
    x1, x2 = surface.derivatives(u1, u2)
    return _cross(x1, x2)


def _unit(n: np.ndarray, floor: float) -> np.ndarray:
    """Unit vectors of ``n`` (NaN where ``|n| <= floor``: no direction)."""
    length = np.linalg.norm(n, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(length > floor, n / length, np.nan)


def singular_curves(
    surface: Parametrized, grid: int = CONTOUR_GRID
) -> list[tuple[np.ndarray, bool]]:
    """The curves ``(points (k, 2), closed)`` in the parameter plane along which
    the normal of ``surface`` vanishes and flips (module docstring), computed
    once per surface.  The contour's grid (computed anyway, and kept) is
    searched first: where it shows no flip and no singular node, there is
    nothing to find."""
    return per_surface(surface, ("singular curves", grid), lambda: _find(surface, grid))


def _suspect(surface: Parametrized, grid: int, floor: float) -> bool:
    """Whether the contour's grid has neighbouring nodes with normals pointing
    apart, or a node inside the domain whose normal vanishes."""
    d = surface.domain
    N = _unit(grid_geometry(surface, grid)[0], floor)
    none = np.isnan(N[..., 0])
    for i in (0, 1):
        if not d.glued[i]:  # the ends of a parameter may be poles
            none[(slice(None),) * i + ([0, -1],)] = False
    if none.any():
        return True
    with np.errstate(invalid="ignore"):
        for i in (0, 1):
            nxt = np.roll(N, -1, axis=i) if d.periodic[i] is True else np.delete(N, 0, axis=i)
            if (np.einsum("...i,...i", N[: nxt.shape[0], : nxt.shape[1]], nxt) < 0).any():
                return True
    return False


def _refine(surface: Parametrized, pa: np.ndarray, pb: np.ndarray, na: np.ndarray, nb: np.ndarray,
            floor: float) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The flips of the normal on segments ``pa -> pb`` (normals ``na``, ``nb``
    at the ends pointing apart), refined, and which are zeros of the normal."""
    Na, Nb = _unit(na, floor), _unit(nb, floor)
    ref = Nb - Na  # n . ref < 0 at a, > 0 at b
    step = pb - pa

    def g(t: np.ndarray, sel: np.ndarray) -> np.ndarray:
        p = pa[sel] + t[:, None] * step[sel]
        return np.einsum("ij,ij->i", _normals(surface, p[:, 0], p[:, 1]), ref[sel])

    ga, gb = np.einsum("ij,ij->i", na, ref), np.einsum("ij,ij->i", nb, ref)
    t = bracketed_roots(g, np.zeros(len(pa)), np.ones(len(pa)), ga, gb, EDGE_XTOL)
    pts = pa + t[:, None] * step
    at = np.linalg.norm(_normals(surface, pts[:, 0], pts[:, 1]), axis=-1)
    ends = np.maximum(np.linalg.norm(na, axis=-1), np.linalg.norm(nb, axis=-1))
    with np.errstate(invalid="ignore"):
        apart = np.einsum("ij,ij->i", Na, Nb) < 0
    return pts, apart & (at <= SINGULAR_EDGE_RTOL * ends)


def _find(surface: Parametrized, grid: int) -> list[tuple[np.ndarray, bool]]:
    d = surface.domain
    floor = normal_floor(surface)
    if not _suspect(surface, grid, floor):
        return []
    a1, a2 = _axis(surface, 0, grid), _axis(surface, 1, grid)
    n = _normals(surface, *np.meshgrid(a1, a2, indexing="ij"))
    N = _unit(n, floor)

    def crossed(i0: np.ndarray, j0: np.ndarray, i1: np.ndarray, j1: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore"):
            return np.einsum("...i,...i", N[i0, j0], N[i1, j1]) < 0

    def centre_like_corner(i: np.ndarray, j: np.ndarray, uc1: Any, uc2: Any) -> np.ndarray:
        return np.einsum("...i,...i", _normals(surface, uc1, uc2), N[i, j]) > 0

    def crossings(pa: np.ndarray, pb: np.ndarray, ends: tuple) -> tuple[np.ndarray, np.ndarray]:
        i0, j0, i1, j1 = ends
        return _refine(surface, pa, pb, n[i0, j0], n[i1, j1], floor)

    curves = march(d, a1, a2, crossed, centre_like_corner, crossings)
    size = surface.size
    out = []
    for pts, closed in curves:  # a few curves
        image = surface.point(pts[:, 0], pts[:, 1])
        if np.ptp(image, axis=0).max() > SINGULAR_COLLAPSED_RTOL * size:
            out.append((pts, closed))
    return _to_edges(surface, out, np.array([a1[1] - a1[0], a2[1] - a2[0]]), floor)


def _to_edges(surface: Parametrized, curves: list, h: np.ndarray, floor: float) -> list:
    """The open ``curves`` continued to the edges of the domain that their
    ends lie within ``1.5`` grid cells ``h`` of (the grid is offset from
    them): each end's tangent meets the edge; the flip is refined on the edge
    within a cell of that point."""
    d = surface.domain
    rows = [(k, e) for k, (p, closed) in enumerate(curves) if not closed and len(p) > 1
            for e in (0, -1)]  # fmt: skip
    if not rows:
        return curves
    E = np.array([curves[k][0][e] for k, e in rows])
    D = E - np.array([curves[k][0][1 if e == 0 else -2] for k, e in rows])
    lam = np.full(len(E), np.inf)
    axis = np.zeros(len(E), int)
    for i in (0, 1):
        if d.glued[i]:
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            for bound in d.range(i):
                li = (bound - E[:, i]) / D[:, i]
                li = np.where(li >= 0, li, np.inf)
                axis = np.where(li < lam, i, axis)
                lam = np.minimum(lam, li)
    Q = E + np.where(np.isfinite(lam), lam, 0.0)[:, None] * D
    near = np.isfinite(lam) & (np.abs(Q - E) / h <= 1.5).all(axis=1)
    if not near.any():
        return curves
    Q, axis, idx = d.clip(Q[near]), axis[near], np.flatnonzero(near)
    other = 1 - axis
    off = np.zeros_like(Q)
    off[np.arange(len(Q)), other] = h[other]
    pa, pb = d.clip(Q - off), d.clip(Q + off)
    pts, real = _refine(
        surface, pa, pb, _normals(surface, pa[:, 0], pa[:, 1]),
        _normals(surface, pb[:, 0], pb[:, 1]), floor,
    )  # fmt: skip
    out = [p for p, _ in curves]
    for r, q, ok in zip(idx.tolist(), pts, real.tolist()):
        if ok:
            k, e = rows[r]
            out[k] = np.vstack([q[None], out[k]]) if e == 0 else np.vstack([out[k], q[None]])
    return [(p, c) for p, (_, c) in zip(out, curves)]


def singular_edge_batches(surface: Parametrized) -> list[CurveBatch]:
    """The singular curves of ``surface`` (:func:`singular_curves`) as one
    batch of family ``"boundary"`` (empty where there are none)."""
    curves = singular_curves(surface)
    if not curves:
        return []
    return [zero_set_batch(surface, curves, None, "boundary", ON)]
