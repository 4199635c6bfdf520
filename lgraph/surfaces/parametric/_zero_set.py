"""Zero sets ``fun(u1, u2) = 0`` on a parameter grid: marching squares.

The numeric contour of a surface (:mod:`~lgraph.surfaces.parametric._contour`) and the level
and parabolic lines of :mod:`lgraph.families.level` are zero sets of a
function of the parameters (docs/mathematics.rst, "Level lines, parabolic
lines, self-intersections").  :func:`zero_set` samples the function on a
``grid x grid`` parameter grid (periodic parameters wrap), finds the grid edges
whose ends differ in sign, refines each crossing on its edge to the rounding
level of the function (:func:`lgraph._roots.bracketed_roots`), and joins the
crossings cell by cell into polylines (saddle cells decided by the centre
value), also across periodic seams; pieces that meet across a twisted seam
are joined by :mod:`~lgraph.surfaces.parametric._seams`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, depth_first_order

from ..._roots import bracketed_roots
from ._seams import join_pieces

if TYPE_CHECKING:
    from .._domain import Parametrized

__all__ = ["collapsed_ends", "grid_axis", "grid_parameters", "march", "zero_set"]

#: grid nodes per parameter for the contour scan
CONTOUR_GRID = 193
#: a crossing on a grid edge is refined to this fraction of the edge
EDGE_XTOL = 1e-15
#: ... or until ``|fun|`` is below this times the largest ``|fun|`` on the grid
#: (its rounding level: the zero set is not defined more closely)
EDGE_FTOL = 4 * np.finfo(float).eps
#: a refined crossing with ``|fun|`` above this times its largest ``|fun|`` on
#: the grid is a jump of ``fun``, not a zero (left out of the zero set)
JUMP_RTOL = 1e-6


def grid_axis(surface: Parametrized, i: int, n: int) -> np.ndarray:
    """The grid's values of ``u_i`` (``n`` of them; periodic parameters wrap,
    poles and collapsed ends are kept ``1e-7`` of the span away)."""
    d = surface.domain
    lo, hi = d.range(i)
    if d.periodic[i] is True:
        return lo + (hi - lo) * np.arange(n) / n
    inset = 1e-7 * (hi - lo)
    low, high = (a or b for a, b in zip(d.poles[i], collapsed_ends(surface)[i]))
    return np.linspace(lo + inset * low, hi - inset * high, n)


def collapsed_ends(surface: Parametrized) -> tuple[tuple[bool, bool], tuple[bool, bool]]:
    """Per parameter, which of its ends (not glued) the surface maps to one
    point, declared a pole or not (a sphere chart whose poles are not
    declared): the grid keeps ``1e-7`` of the span from them, as from poles,
    since the normal is undefined there (computed once per surface)."""
    from ..._tolerance import SINGULAR_COLLAPSED_RTOL
    from .._memo import per_surface

    def compute() -> tuple[tuple[bool, bool], tuple[bool, bool]]:
        d = surface.domain
        t = np.linspace(0.0, 1.0, 33)
        out = []
        for i in (0, 1):
            lo, hi = d.range(1 - i)
            along = lo + (hi - lo) * t
            ends = []
            for end in d.range(i):
                if d.glued[i]:
                    ends.append(False)
                    continue
                uv = (np.full_like(along, end), along)
                pts = surface.point(*(uv if i == 0 else uv[::-1]))
                ends.append(
                    bool(np.ptp(pts, axis=0).max() <= SINGULAR_COLLAPSED_RTOL * surface.size)
                )
            out.append(tuple(ends))
        return out[0], out[1]

    return per_surface(surface, "collapsed ends", compute)


def _edge_roots(
    fun: Any, a: np.ndarray, b: np.ndarray, fa: np.ndarray, fb: np.ndarray, ftol: float = 0.0
) -> Any:
    """Roots of ``fun`` on segments ``a -> b`` (points (n, 2)) with a sign change
    (:func:`lgraph._roots.bracketed_roots` in the segment parameter ``t`` in [0, 1]);
    a point where ``|fun| <= ftol`` (its rounding level) is a root."""
    d = b - a

    def f(t: np.ndarray, sel: np.ndarray) -> np.ndarray:
        return fun(a[sel] + t[:, None] * d[sel])

    n = len(a)
    t = bracketed_roots(f, np.zeros(n), np.ones(n), fa, fb, EDGE_XTOL, ftol)
    return a + t[:, None] * d


def grid_parameters(
    surface: Parametrized, grid: int = CONTOUR_GRID
) -> tuple[np.ndarray, np.ndarray]:
    """``U1, U2`` (``grid x grid``, ``indexing="ij"``): the nodes :func:`zero_set` marches on."""
    a1, a2 = grid_axis(surface, 0, grid), grid_axis(surface, 1, grid)
    return np.meshgrid(a1, a2, indexing="ij")


def zero_set(
    surface: Parametrized, fun: Any, grid: int = CONTOUR_GRID, values: np.ndarray | None = None
) -> list[tuple[np.ndarray, bool]]:
    """The curves ``fun(u1, u2) = 0`` on the surface's domain as ``(points, closed)``:
    marching squares on a ``grid x grid`` parameter grid (periodic parameters
    wrap), each crossing refined on its grid edge to machine precision, the
    crossings joined into polylines in the parameter plane.  ``values``, if
    given, is ``fun`` on the nodes of :func:`grid_parameters` (computed by
    the caller from what it keeps between calls)."""
    a1, a2 = grid_axis(surface, 0, grid), grid_axis(surface, 1, grid)
    F = fun(*np.meshgrid(a1, a2, indexing="ij")) if values is None else values
    F = np.where(np.isfinite(F), F, 0.0)
    pos = F >= 0

    def crossed(i0: np.ndarray, j0: np.ndarray, i1: np.ndarray, j1: np.ndarray) -> np.ndarray:
        return pos[i0, j0] != pos[i1, j1]

    def centre_like_corner(i: np.ndarray, j: np.ndarray, uc1: Any, uc2: Any) -> np.ndarray:
        return (fun(uc1, uc2) >= 0) == pos[i, j]

    def fun_p(p: np.ndarray) -> np.ndarray:
        return fun(p[:, 0], p[:, 1])

    # the rounding level of fun: a few units in the last place of its largest value
    ftol = EDGE_FTOL * float(np.abs(F).max())

    def crossings(pa: np.ndarray, pb: np.ndarray, ends: tuple) -> tuple[np.ndarray, np.ndarray]:
        i0, j0, i1, j1 = ends
        pts = _edge_roots(fun_p, pa, pb, F[i0, j0], F[i1, j1], ftol)
        # a sign change that is no zero: ``fun`` jumps there (the normal of a
        # parametrization that folds over a degenerate line, such as the edge of
        # Apery's Boy surface that collapses to a point, flips with the
        # orientation) or is undefined (NaN, counted as 0 on the grid).  The
        # root search ends at the jump with ``|fun|`` still of the order of its
        # values; a true zero is refined to the rounding level
        real = np.abs(fun_p(pts)) <= JUMP_RTOL * float(np.abs(F).max())
        return pts, real

    return march(surface.domain, a1, a2, crossed, centre_like_corner, crossings)


def march(d: Any, a1: np.ndarray, a2: np.ndarray, crossed: Any, centre_like_corner: Any,
          crossings: Any) -> list[tuple[np.ndarray, bool]]:  # fmt: skip
    """Marching squares on the grid ``a1 x a2`` of domain ``d`` (periodic
    parameters wrap): ``crossed(i0, j0, i1, j1)``, which grid edges between
    nodes ``(i0, j0)`` and ``(i1, j1)`` the curves cross;
    ``centre_like_corner(i, j, uc1, uc2)``, for cells crossed on all four
    edges, whether the centre ``(uc1, uc2)`` of the cell with bottom-left
    corner ``(i, j)`` lies on that corner's side; ``crossings(pa, pb, (i0,
    j0, i1, j1))``, the crossing points ``(n, 2)`` on the crossed edges ``pa
    -> pb`` and which are real (the others are left out with their segments).
    Returns the polylines ``(points, closed)`` joining the crossings cell by
    cell (pieces across a twisted seam joined by :mod:`~lgraph.surfaces.parametric._seams`)."""
    n1, n2 = len(a1), len(a2)
    per1, per2 = d.periodic[0] is True, d.periodic[1] is True  # twisted: joined below
    e1 = n1 if per1 else n1 - 1  # number of edges along u1 per row
    e2 = n2 if per2 else n2 - 1
    # horizontal edges (i, j)-(i+1, j): ids i * n2 + j ; vertical (i, j)-(i, j+1): n1 n2 + i n2 + j
    ih, jh = np.meshgrid(np.arange(e1), np.arange(n2), indexing="ij")
    iv, jv = np.meshgrid(np.arange(n1), np.arange(e2), indexing="ij")
    hcross = crossed(ih, jh, (ih + 1) % n1, jh)
    vcross = crossed(iv, jv, iv, (jv + 1) % n2)
    cross = np.zeros(2 * n1 * n2, bool)
    cross[(ih * n2 + jh)[hcross]] = True
    cross[(n1 * n2 + iv * n2 + jv)[vcross]] = True
    if not cross.any():
        return []
    # cells (i, j): bottom h(i, j), top h(i, j+1), left v(i, j), right v(i+1, j)
    ci, cj = np.meshgrid(np.arange(e1), np.arange(e2), indexing="ij")
    ci, cj = ci.ravel(), cj.ravel()
    ci1, cj1 = (ci + 1) % n1, (cj + 1) % n2
    bottom = ci * n2 + cj
    top = ci * n2 + cj1
    left = n1 * n2 + ci * n2 + cj
    right = n1 * n2 + ci1 * n2 + cj
    E = np.stack([bottom, right, top, left], axis=1)
    C = cross[E]
    k = C.sum(axis=1)
    seg_a, seg_b = [], []
    two = k == 2
    if two.any():
        Et, Ct = E[two], C[two]
        first = np.argmax(Ct, axis=1)
        second = 3 - np.argmax(Ct[:, ::-1], axis=1)
        rows = np.arange(len(Et))
        seg_a.append(Et[rows, first])
        seg_b.append(Et[rows, second])
    four = k == 4
    if four.any():
        i4, j4 = ci[four], cj[four]
        i41, j41 = ci1[four], cj1[four]
        uc1 = 0.5 * (a1[i4] + np.where(i41 == 0, a1[i4] + (a1[1] - a1[0]), a1[i41]))
        uc2 = 0.5 * (a2[j4] + np.where(j41 == 0, a2[j4] + (a2[1] - a2[0]), a2[j41]))
        same = centre_like_corner(i4, j4, uc1, uc2)
        Ef = E[four]
        # same: cut off BR (bottom,right) and TL (top,left); else BL (bottom,left), TR (top,right)
        seg_a += [Ef[:, 0], Ef[:, 2]]
        seg_b += [np.where(same, Ef[:, 1], Ef[:, 3]), np.where(same, Ef[:, 3], Ef[:, 1])]
    if not seg_a:
        return []
    sa, sb = np.concatenate(seg_a), np.concatenate(seg_b)
    ids = np.nonzero(cross)[0]
    index = np.full(len(cross), -1)
    index[ids] = np.arange(len(ids))
    # crossing points, refined on their edges
    is_h = ids < n1 * n2
    rem = np.where(is_h, ids, ids - n1 * n2)
    i0, j0 = rem // n2, rem % n2
    i1 = np.where(is_h, (i0 + 1) % n1, i0)
    j1 = np.where(is_h, j0, (j0 + 1) % n2)
    pa = np.stack([a1[i0], a2[j0]], axis=1)
    pb = np.stack([a1[i1], a2[j1]], axis=1)
    # unwrap the far end of seam edges
    if per1:
        pb[:, 0] = np.where(is_h & (i1 == 0), a1[i0] + (a1[1] - a1[0]), pb[:, 0])
    if per2:
        pb[:, 1] = np.where(~is_h & (j1 == 0), a2[j0] + (a2[1] - a2[0]), pb[:, 1])
    pts, real = crossings(pa, pb, (i0, j0, i1, j1))
    keep = real[index[sa]] & real[index[sb]]
    sa, sb = sa[keep], sb[keep]
    m = len(ids)
    A = coo_matrix((np.ones(len(sa)), (index[sa], index[sb])), shape=(m, m)).tocsr()
    A = A + A.T
    ncomp, labels = connected_components(A, directed=False)
    deg = np.asarray((A > 0).sum(axis=1)).ravel()
    curves = []
    for c in range(ncomp):
        members = np.nonzero(labels == c)[0]
        if len(members) < 2:
            continue
        ends = members[deg[members] == 1]
        start = int(ends[0]) if len(ends) else int(members[0])
        order = depth_first_order(A, start, directed=False, return_predecessors=False)
        if not np.ptp(pts[order], axis=0).any():
            continue  # crossings on the edges around one grid node where fun vanishes: a point
        curves.append((pts[order], len(ends) == 0))
    return join_pieces(d, curves) if any(d.twisted) else curves
