"""Numeric defaults of :class:`~lgraph.surfaces._base.Surface`: contour and ray hits.

Both need nothing but ``point`` (and ``derivatives``, which has a
finite-difference default), so any parametrized surface can be drawn with
hidden lines removed.

* :func:`contour`: the zero set of ``f(u) = N(u) . w(u) / |w(u)|`` (``w`` the
  view vector) is found by marching squares on a parameter grid, each crossing
  refined on its grid edge to machine precision, the pieces joined into curves
  (also across periodic seams) and interpolated by splines whose values are
  projected back onto the zero set by Newton's method at evaluation time.
* :func:`hits`: a bounding-volume hierarchy of padded boxes over a parameter
  grid (cached per surface) selects candidate patches; Newton's method on
  ``x(u1, u2) - (o + s v) = 0`` starts in each; patches where it fails are
  subdivided.  A ray from a point on the surface (``own == ON``) never counts
  its own root ``s = 0``; a second root close to it (near the surface's own
  contour) is found from the local quadratic approximation of the surface.

>>> import numpy as np
>>> import lgraph as lg
>>> e = lg.Ellipsoid(3, 2, 1)
>>> s = lg.ParametricSurface(e.point, (-np.pi / 2, np.pi / 2), (0, 2 * np.pi),
...                          periodic=(False, True), poles=(True, False))
>>> o = np.array([[0.0, 0.0, -5.0], [5.0, 5.0, 5.0]])
>>> hits(s, o, np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]), np.array([np.inf, np.inf])).tolist()
[True, False]
"""

from __future__ import annotations

import weakref
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.interpolate import CubicSpline, make_interp_spline
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, depth_first_order

from .._own import CONTOUR, OFF, ON
from .._roots import bracketed_roots
from .._tolerance import HIT_CHUNK_RAYS, HIT_MAX_CANDIDATES, SELF_HIT_RTOL

if TYPE_CHECKING:
    from ..curves import CurveBatch
    from ..projectors import Projector
    from ._base import Surface

__all__ = ["contour", "hits", "view_cosine", "project_to_contour", "zero_set", "zero_set_batch"]
__all__ += ["project_to_zero"]

#: grid nodes per parameter for the contour scan
CONTOUR_GRID = 193
#: leaves per parameter of the hit hierarchy (a power of two)
HIT_LEAVES = 64
#: extra subdivision levels where Newton's method fails in a leaf
HIT_MAX_DEPTH = 3
#: Newton iterations per candidate patch
HIT_NEWTON_STEPS = 30
#: a contour point's ray counts a root within this distance (relative to the
#: surface size) of its origin as its own (double) root
CONTOUR_SELF_RTOL = 1e-5
#: a crossing on a grid edge is refined to this fraction of the edge
EDGE_XTOL = 1e-15
#: ... or until ``|fun|`` is below this times the largest ``|fun|`` on the grid
#: (its rounding level: the zero set is not defined more closely)
EDGE_FTOL = 4 * np.finfo(float).eps


# ---------------------------------------------------------------------------
# contour
# ---------------------------------------------------------------------------
def _is_central(projector: Any) -> bool:
    from ..projectors import CentralProjector

    return isinstance(projector, CentralProjector)


def view_cosine(surface: Surface, projector: Projector, u1: Any, u2: Any) -> np.ndarray:
    """``N . w / |w|`` (``N`` unit normal, ``w`` toward the viewer); zero on the contour."""
    u1, u2 = np.broadcast_arrays(np.asarray(u1, float), np.asarray(u2, float))
    x1, x2 = surface.derivatives(u1, u2)
    n = _cross(x1, x2)
    if _is_central(projector):
        w = projector.eye - surface.point(u1, u2)
    else:
        w = np.broadcast_to(projector.frame[2], n.shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.einsum("...i,...i", n, w) / (
            np.linalg.norm(n, axis=-1) * np.linalg.norm(w, axis=-1)
        )


def project_to_contour(
    surface: Surface, projector: Projector, uv: np.ndarray, steps: int = 4
) -> np.ndarray:
    """Newton projection of parameters ``uv (n, 2)`` onto the contour ``f = 0``."""

    def fun(u1: Any, u2: Any) -> np.ndarray:
        return view_cosine(surface, projector, u1, u2)

    return project_to_zero(surface, fun, uv, steps, 1e-14)


def project_to_zero(
    surface: Surface, fun: Any, uv: np.ndarray, steps: int = 4, ftol: float = 1e-14
) -> np.ndarray:
    """Newton projection of parameters ``uv (n, 2)`` onto ``fun(u1, u2) = 0``
    (minimal steps in parameters scaled by the spans, central-difference
    gradients); points with ``|fun| <= ftol`` stop early."""
    d = surface.domain
    scale = np.array([d.span(0), d.span(1)])
    uv = np.array(uv, dtype=float, copy=True)
    h = 1e-6 * scale
    active = np.arange(len(uv))
    for _ in range(steps):
        if not len(active):
            break
        p = uv[active]
        f = fun(p[:, 0], p[:, 1])
        g1 = (fun(p[:, 0] + h[0], p[:, 1]) - fun(p[:, 0] - h[0], p[:, 1])) / (2 * h[0])
        g2 = (fun(p[:, 0], p[:, 1] + h[1]) - fun(p[:, 0], p[:, 1] - h[1])) / (2 * h[1])
        # minimal step in coordinates scaled by the spans
        g1s, g2s = g1 * scale[0], g2 * scale[1]
        gg = g1s * g1s + g2s * g2s
        ok = np.isfinite(f) & (gg > 0)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.where(ok, f / gg, 0.0)
        uv[active, 0] -= step * g1s * scale[0]
        uv[active, 1] -= step * g2s * scale[1]
        active = active[ok & (np.abs(f) > ftol)]
    return uv


def _grid_axis(surface: Surface, i: int, n: int) -> np.ndarray:
    d = surface.domain
    lo, hi = d.range(i)
    if d.periodic[i]:
        return lo + (hi - lo) * np.arange(n) / n
    inset = 1e-7 * (hi - lo)
    return np.linspace(lo + inset * d.poles[i][0], hi - inset * d.poles[i][1], n)


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


def contour(surface: Surface, projector: Projector, grid: int = CONTOUR_GRID) -> list[CurveBatch]:
    """Numeric contour of ``surface`` for ``projector`` (local frame), as one batch."""

    def fun(u1: Any, u2: Any) -> np.ndarray:
        return view_cosine(surface, projector, u1, u2)

    curves = zero_set(surface, fun, grid)
    return [_contour_batch(surface, projector, curves)] if curves else []


def zero_set(surface: Surface, fun: Any, grid: int = CONTOUR_GRID) -> list[tuple[np.ndarray, bool]]:
    """The curves ``fun(u1, u2) = 0`` on the surface's domain as ``(points, closed)``:
    marching squares on a ``grid x grid`` parameter grid (periodic parameters
    wrap), each crossing refined on its grid edge to machine precision, the
    crossings joined into polylines in the parameter plane."""
    d = surface.domain
    n1, n2 = grid, grid
    a1, a2 = _grid_axis(surface, 0, n1), _grid_axis(surface, 1, n2)
    U1, U2 = np.meshgrid(a1, a2, indexing="ij")
    F = fun(U1, U2)
    F = np.where(np.isfinite(F), F, 0.0)
    pos = F >= 0
    per1, per2 = d.periodic
    e1 = n1 if per1 else n1 - 1  # number of edges along u1 per row
    e2 = n2 if per2 else n2 - 1
    # horizontal edges (i, j)-(i+1, j): ids i * n2 + j ; vertical (i, j)-(i, j+1): n1 n2 + i n2 + j
    ih, jh = np.meshgrid(np.arange(e1), np.arange(n2), indexing="ij")
    iv, jv = np.meshgrid(np.arange(n1), np.arange(e2), indexing="ij")
    hcross = pos[ih, jh] != pos[(ih + 1) % n1, jh]
    vcross = pos[iv, jv] != pos[iv, (jv + 1) % n2]
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
        fc = fun(uc1, uc2) >= 0
        same = fc == pos[i4, j4]  # centre like the bottom-left corner
        Ef = E[four]
        # same: cut off BR (bottom,right) and TL (top,left); else BL (bottom,left), TR (top,right)
        seg_a += [Ef[:, 0], Ef[:, 2]]
        seg_b += [np.where(same, Ef[:, 1], Ef[:, 3]), np.where(same, Ef[:, 3], Ef[:, 1])]
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

    def fun_p(p: np.ndarray) -> np.ndarray:
        return fun(p[:, 0], p[:, 1])

    # the rounding level of fun: a few units in the last place of its largest value
    ftol = EDGE_FTOL * float(np.abs(F).max())
    pts = _edge_roots(fun_p, pa, pb, F[i0, j0], F[i1, j1], ftol)
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
    return curves


def _unwrap(surface: Surface, p: np.ndarray) -> np.ndarray:
    d = surface.domain
    p = p.copy()
    for i in (0, 1):
        if d.periodic[i]:
            span = d.span(i)
            dp = np.diff(p[:, i])
            jumps = -span * np.round(dp / span)
            p[1:, i] += np.cumsum(jumps)
    return p


class _ContourCurve:
    """One contour curve: spline in the parameter plane + Newton projection."""

    def __init__(self, surface: Surface, pts: np.ndarray, closed: bool) -> None:
        d = surface.domain
        scale = np.array([d.span(0), d.span(1)])
        p = _unwrap(surface, pts)
        if closed:
            p = np.vstack([p, p[:1]])
            if d.periodic[0] or d.periodic[1]:
                # the closing step may cross a seam: unwrap it too
                p[-1] = _unwrap(surface, p[-2:])[-1]
        chord = np.linalg.norm(np.diff(p / scale, axis=0), axis=1)
        keep = np.concatenate([[True], chord > 1e-3 * np.median(chord)])
        if closed:
            keep[-1] = True
            keep[-2] = keep[-2] and chord[-1] > 1e-3 * np.median(chord)
        p = p[keep]
        t = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p / scale, axis=0), axis=1))])
        self.length = float(t[-1])
        self.closed = closed
        if closed and len(p) >= 4:
            self.drift = p[-1] - p[0]
            self.spline = CubicSpline(t, p - np.outer(t / t[-1], self.drift), bc_type="periodic")
        else:
            self.drift = np.zeros(2)
            self.spline = make_interp_spline(t, p, k=min(3, len(p) - 1))

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return self.spline(t) + np.outer(t / self.length, self.drift)


def _contour_batch(surface: Surface, projector: Projector, curves: list) -> CurveBatch:
    return zero_set_batch(
        surface, curves, lambda uv: project_to_contour(surface, projector, uv), "contour", CONTOUR
    )


def zero_set_batch(
    surface: Surface, curves: list, adjust: Any, family: str, own: int = ON
) -> CurveBatch:
    """One batch of the :func:`zero_set` curves: splines in the parameter plane
    (periodic for closed curves) whose points ``adjust(uv)`` projects back onto
    the zero set at evaluation time."""
    from ..curves import CurveBatch

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


# ---------------------------------------------------------------------------
# hits
# ---------------------------------------------------------------------------
def _cell_pad(S: np.ndarray) -> np.ndarray:
    """Padding of the box of each patch sampled by a 3x3 grid ``S (..., 3, 3, 3)``:
    a bound on how far the surface strays from the samples' hull."""
    d1 = np.linalg.norm(S[..., 0, :, :] - 2 * S[..., 1, :, :] + S[..., 2, :, :], axis=-1).max(-1)
    d2 = np.linalg.norm(S[..., :, 0, :] - 2 * S[..., :, 1, :] + S[..., :, 2, :], axis=-1).max(-1)
    d12 = np.linalg.norm(
        S[..., 0, 0, :] - S[..., 2, 0, :] - S[..., 0, 2, :] + S[..., 2, 2, :], axis=-1
    )
    return 0.5 * (d1 + d2) + 0.25 * d12


class _Hierarchy:
    """Boxes of a ``HIT_LEAVES x HIT_LEAVES`` parameter grid and their ancestors."""

    def __init__(self, surface: Surface) -> None:
        d = surface.domain
        n = HIT_LEAVES
        self.n = n
        self.name = type(surface).__name__
        self.lo1, self.lo2 = d.u1[0], d.u2[0]
        self.h1, self.h2 = d.span(0) / n, d.span(1) / n
        u1 = np.linspace(*d.u1, 2 * n + 1)
        u2 = np.linspace(*d.u2, 2 * n + 1)
        P = surface.point(*np.meshgrid(u1, u2, indexing="ij"))
        P = np.where(np.isfinite(P), P, 0.0)
        lo, hi = surface.bounds()
        self.size = float(np.linalg.norm(np.asarray(hi) - np.asarray(lo)))
        # leaf samples (n, n, 3, 3, 3)
        ia = 2 * np.arange(n)[:, None] + np.arange(3)[None, :]
        S = P[ia[:, None, :, None], ia[None, :, None, :]]
        _check_regular(surface, P, S)
        pad = _cell_pad(S)[..., None] + 1e-9 * self.size
        blo = S.min(axis=(2, 3)) - pad
        bhi = S.max(axis=(2, 3)) + pad
        self.levels = [(blo, bhi)]
        while blo.shape[0] > 1:
            blo = np.minimum.reduce(
                [blo[0::2, 0::2], blo[1::2, 0::2], blo[0::2, 1::2], blo[1::2, 1::2]]
            )
            bhi = np.maximum.reduce(
                [bhi[0::2, 0::2], bhi[1::2, 0::2], bhi[0::2, 1::2], bhi[1::2, 1::2]]
            )
            self.levels.append((blo, bhi))
        self.levels.reverse()  # root first
        self.flat = [(a.reshape(-1, 3), b.reshape(-1, 3)) for a, b in self.levels]


def _check_regular(surface: Surface, P: np.ndarray, S: np.ndarray) -> None:
    """Refuse a degenerate surface before any ray is cast at it.

    ``P`` is the sample grid over the whole domain and ``S`` the 3x3 samples of
    every leaf patch.  All points equal, or a leaf patch whose nine samples
    span no area (collapsed to a point or a curve: not a regular patch), make
    every ray meet every such patch (the hit test would subdivide without
    end).  Poles are fine: a patch touching a pole still spans an area.
    """
    name = type(surface).__name__
    ext = float(np.ptp(P.reshape(-1, 3), axis=0).max())
    if not ext > 0:
        raise ValueError(
            f"{name}: the surface is degenerate: all its points are equal "
            f"({P.reshape(-1, 3)[0].tolist()}); it has no area to draw"
        )
    a = S[..., 2, 2, :] - S[..., 0, 0, :]
    b = S[..., 2, 0, :] - S[..., 0, 2, :]
    c = S[..., 2, 1, :] - S[..., 0, 1, :]
    e = S[..., 1, 2, :] - S[..., 1, 0, :]
    area = np.maximum(
        np.linalg.norm(np.cross(a, b), axis=-1), np.linalg.norm(np.cross(c, e), axis=-1)
    )
    flat = area <= 1e-12 * ext * ext
    if flat.any():
        i, j = np.argwhere(flat)[0]
        d = surface.domain
        h1, h2 = d.span(0) / flat.shape[0], d.span(1) / flat.shape[1]
        u1, u2 = d.u1[0] + i * h1, d.u2[0] + j * h2
        raise ValueError(
            f"{name}: the surface is not regular on part of its domain: the patch "
            f"u1 in [{u1:.6g}, {u1 + h1:.6g}], u2 in [{u2:.6g}, {u2 + h2:.6g}] "
            f"({int(flat.sum())} of {flat.size} patches) collapses to a point or a curve; "
            "restrict u1_range/u2_range to where the surface is regular"
        )


_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_ID_CACHE: dict[int, tuple[Any, _Hierarchy]] = {}


def _hierarchy(surface: Surface) -> _Hierarchy:
    try:
        h = _CACHE.get(surface)
        if h is None:
            h = _CACHE[surface] = _Hierarchy(surface)
        return h
    except TypeError:  # unhashable or not weak-referenceable: cache by identity
        entry = _ID_CACHE.get(id(surface))
        if entry is None or entry[0] is not surface:
            if len(_ID_CACHE) > 64:
                _ID_CACHE.clear()
            entry = _ID_CACHE[id(surface)] = (surface, _Hierarchy(surface))
        return entry[1]


def _inverse(v: np.ndarray) -> np.ndarray:
    """``1 / v`` with zero components replaced by a huge finite value."""
    with np.errstate(divide="ignore"):
        return np.where(v == 0, 1e300, 1.0 / np.where(v == 0, 1.0, v))


def _slab(o: np.ndarray, inv: np.ndarray, lo: np.ndarray, hi: np.ndarray, smax: np.ndarray) -> Any:
    """Ray/box test for ``0 <= s <= smax`` (``inv = _inverse(v)``); returns
    (hit, s_enter, s_exit)."""
    with np.errstate(invalid="ignore", over="ignore"):
        t1 = (lo - o) * inv
        t2 = (hi - o) * inv
    a = np.minimum(t1, t2)
    b = np.maximum(t1, t2)
    tmin = np.maximum(np.maximum(a[:, 0], a[:, 1]), np.maximum(a[:, 2], 0.0))
    tmax = np.minimum(np.minimum(b[:, 0], b[:, 1]), np.minimum(b[:, 2], smax))
    return tmax >= tmin, tmin, tmax


def _candidates(H: _Hierarchy, o: np.ndarray, v: np.ndarray, smax: np.ndarray) -> Any:
    """(ray, i, j, s_enter, s_exit) of leaves whose boxes the rays meet."""
    inv = _inverse(v)
    r = np.arange(len(o))
    k = np.zeros(len(o), int)  # flat box index at the current level
    s0 = s1 = None
    di = np.array([0, 1, 0, 1])
    dj = np.array([0, 0, 1, 1])
    for lvl, (blo, bhi) in enumerate(H.flat):
        ok, s0, s1 = _slab(o[r], inv[r], blo[k], bhi[k], smax[r])
        r, k, s0, s1 = r[ok], k[ok], s0[ok], s1[ok]
        if len(r) > HIT_MAX_CANDIDATES * max(1.0, len(o) / HIT_CHUNK_RAYS):
            raise ValueError(
                f"{H.name}: rays meet more than {HIT_MAX_CANDIDATES // HIT_CHUNK_RAYS} patch "
                "boxes each on average (the limit): the surface winds over itself too many "
                "times or is nearly degenerate; draw one turn (narrow u1_range/u2_range) "
                "and repeat it with transforms"
            )
        if lvl + 1 < len(H.flat):
            m = 1 << lvl  # boxes per row at this level
            i, j = k // m, k % m
            r = np.repeat(r, 4)
            k = ((2 * i)[:, None] + di).ravel() * (2 * m) + ((2 * j)[:, None] + dj).ravel()
    n = H.n
    return r, k // n, k % n, s0, s1


def _analytic_derivatives(surface: Surface) -> bool:
    # the base class marks its finite-difference default (no import of _base here)
    if getattr(type(surface).derivatives, "finite_differences", False):
        return False
    return getattr(surface, "derivatives_func", True) is not None


def _fast_derivatives(surface: Surface, u1: np.ndarray, u2: np.ndarray, x: np.ndarray) -> Any:
    """Derivatives for Newton's method: analytic if the class has them, else
    forward differences (accurate enough for Newton, 3 times cheaper)."""
    if _analytic_derivatives(surface):
        return surface.derivatives(u1, u2)
    d = surface.domain
    h1, h2 = 1e-7 * d.span(0), 1e-7 * d.span(1)
    lo1, hi1 = d.u1
    lo2, hi2 = d.u2
    # step inward at the upper end of non-periodic parameters
    s1 = np.where(~d.periodic[0] & (u1 + h1 > hi1), -h1, h1)
    s2 = np.where(~d.periodic[1] & (u2 + h2 > hi2), -h2, h2)
    x1 = (surface.point(u1 + s1, u2) - x) / s1[:, None]
    x2 = (surface.point(u1, u2 + s2) - x) / s2[:, None]
    return x1, x2


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a x b`` for ``(..., 3)`` arrays (several times faster than ``np.cross``
    on the small arrays of a Newton step)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _newton(
    surface: Surface,
    o: np.ndarray,
    v: np.ndarray,
    uv: np.ndarray,
    s: np.ndarray,
    maxstep: np.ndarray,
    tol: float,
    steps: int = HIT_NEWTON_STEPS,
    cell: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newton on ``x(u) - o - s v = 0``; returns (uv, s, converged).

    With ``cell = (c0, c1)``, iterates that wander more than 1.5 patch widths
    from the patch ``[c0, c1]`` are given up (the caller subdivides)."""
    d = surface.domain
    uv = uv.copy()
    s = s.copy()
    conv = np.zeros(len(s), bool)
    act = np.arange(len(s))
    prev = np.full(len(s), np.inf)
    for _ in range(steps):
        if not len(act):
            break
        p = uv[act]
        x = surface.point(p[:, 0], p[:, 1])
        F = x - o[act] - s[act, None] * v[act]
        res = np.linalg.norm(F, axis=1)
        # polish to rounding level: stop when tiny, or when close and stagnating
        ok = res <= tol
        conv[act] = ok
        done = (res <= 1e-4 * tol) | (ok & (res > 0.5 * prev[act]))
        prev[act] = res
        keep = ~done & np.isfinite(res)
        act, p, F = act[keep], p[keep], F[keep]
        if not len(act):
            break
        x1, x2 = _fast_derivatives(surface, p[:, 0], p[:, 1], x[keep])
        w = -v[act]
        # solve [x1 x2 w] dz = -F by Cramer's rule
        c23 = _cross(x2, w)
        det = np.einsum("ij,ij->i", x1, c23)
        good = np.abs(det) > 1e-300
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            d1 = -np.einsum("ij,ij->i", F, c23) * inv
            d2 = -np.einsum("ij,ij->i", x1, _cross(F, w)) * inv
            d3 = -np.einsum("ij,ij->i", x1, _cross(x2, F)) * inv
        # limit the parameter step
        lim = maxstep[act]
        big = np.maximum(np.abs(d1) / lim[:, 0], np.abs(d2) / lim[:, 1])
        f = np.where(big > 1, 1.0 / np.where(big > 1, big, 1.0), 1.0)
        good &= np.isfinite(d1) & np.isfinite(d2) & np.isfinite(d3)
        act = act[good]
        uv[act, 0] += (f * d1)[good]
        uv[act, 1] += (f * d2)[good]
        s[act] += (f * d3)[good]
        uv[act] = d.wrap(uv[act])
        if cell is not None:
            act = act[_in_cell(surface, uv[act], cell[0][act], cell[1][act], 1.5)]
    return uv, s, conv


def _in_cell(
    surface: Surface, uv: np.ndarray, c0: np.ndarray, c1: np.ndarray, margin: float = 0.05
) -> np.ndarray:
    d = surface.domain
    inside = np.ones(len(uv), bool)
    for i in (0, 1):
        w = c1[:, i] - c0[:, i]
        lo, hi = c0[:, i] - margin * w, c1[:, i] + margin * w
        x = uv[:, i]
        if d.periodic[i]:
            span = d.span(i)
            x = lo + np.mod(x - lo, span)
        inside &= (x >= lo) & (x <= hi)
    return inside


def _sub_boxes(surface: Surface, c0: np.ndarray, c1: np.ndarray, size: float) -> Any:
    """Padded boxes of parameter rectangles ``[c0, c1]`` (n, 2)."""
    f = np.array([0.0, 0.5, 1.0])
    u1 = c0[:, 0, None] + (c1[:, 0] - c0[:, 0])[:, None] * f
    u2 = c0[:, 1, None] + (c1[:, 1] - c0[:, 1])[:, None] * f
    S = surface.point(u1[:, :, None], u2[:, None, :])
    pad = _cell_pad(S)[:, None] + 1e-9 * size
    return S.min(axis=(1, 2)) - pad, S.max(axis=(1, 2)) + pad


def _local_second_root(
    surface: Surface, o: np.ndarray, v: np.ndarray, uv0: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Start of Newton for the root next to the own root ``(uv0, 0)``: the local
    quadratic approximation gives ``s = 2 (v . N) / II(a)`` with ``J a`` the
    tangential part of ``v``."""
    x1, x2 = surface.derivatives(uv0[:, 0], uv0[:, 1])
    x11, x12, x22 = surface.second_derivatives(uv0[:, 0], uv0[:, 1])
    n = _cross(x1, x2)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    vn = np.einsum("ij,ij->i", v, n)
    g11 = np.einsum("ij,ij->i", x1, x1)
    g12 = np.einsum("ij,ij->i", x1, x2)
    g22 = np.einsum("ij,ij->i", x2, x2)
    b1 = np.einsum("ij,ij->i", x1, v)
    b2 = np.einsum("ij,ij->i", x2, v)
    g = g11 * g22 - g12 * g12
    a1 = (g22 * b1 - g12 * b2) / g
    a2 = (g11 * b2 - g12 * b1) / g
    L11 = np.einsum("ij,ij->i", n, x11)
    L12 = np.einsum("ij,ij->i", n, x12)
    L22 = np.einsum("ij,ij->i", n, x22)
    II = L11 * a1 * a1 + 2 * L12 * a1 * a2 + L22 * a2 * a2
    with np.errstate(divide="ignore", invalid="ignore"):
        s = 2 * vn / II
    return uv0 + s[:, None] * np.stack([a1, a2], axis=1), s


def hits(
    surface: Surface,
    origins: np.ndarray,
    directions: np.ndarray,
    smax: np.ndarray,
    own: np.ndarray | None = None,
) -> np.ndarray:
    """Numeric :meth:`Surface.hits` (see there).

    Rays are tested in chunks of ``HIT_CHUNK_RAYS`` so that memory stays
    bounded; a chunk whose rays meet more than ``HIT_MAX_CANDIDATES`` patch
    boxes in all (a surface winding over itself very many times) is refused
    with a ValueError before any Newton step.
    """
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    v = np.asarray(directions, dtype=float).reshape(-1, 3)
    nray = len(o)
    smax = np.broadcast_to(np.asarray(smax, dtype=float), (nray,)).copy()
    own = np.zeros(nray, np.int8) if own is None else np.asarray(own).reshape(-1)
    out = np.zeros(nray, bool)
    if not nray:
        return out
    H = _hierarchy(surface)
    for a in range(0, nray, HIT_CHUNK_RAYS):
        b = slice(a, a + HIT_CHUNK_RAYS)
        out[b] = _hits_chunk(surface, H, o[b], v[b], smax[b], own[b])
    return out


def _hits_chunk(
    surface: Surface, H: _Hierarchy, o: np.ndarray, v: np.ndarray, smax: np.ndarray, own: Any
) -> np.ndarray:
    nray = len(o)
    out = np.zeros(nray, bool)
    d = surface.domain
    size = H.size
    vnorm = np.linalg.norm(v, axis=1)
    vnorm = np.where(vnorm > 0, vnorm, 1.0)
    s_eps = SELF_HIT_RTOL * size / vnorm
    s_self = np.where(own == CONTOUR, CONTOUR_SELF_RTOL * size / vnorm, s_eps)
    tol = 1e-10 * size
    r, i, j, s0, s1 = _candidates(H, o, v, smax)
    c0 = np.stack([H.lo1 + i * H.h1, H.lo2 + j * H.h2], axis=1)
    c1 = c0 + np.array([H.h1, H.h2])
    own_uv = np.full((nray, 2), np.nan)
    for depth in range(HIT_MAX_DEPTH + 1):
        keep = ~out[r]
        r, c0, c1, s0, s1 = r[keep], c0[keep], c1[keep], s0[keep], s1[keep]
        if not len(r):
            break
        uv = 0.5 * (c0 + c1)
        s = 0.5 * (s0 + s1)
        s = np.where(np.isfinite(s), s, s0)
        maxstep = 2.0 * (c1 - c0)
        uv, s, conv = _newton(surface, o[r], v[r], uv, s, maxstep, tol, cell=(c0, c1))
        x_off = np.linalg.norm(surface.point(uv[:, 0], uv[:, 1]) - o[r], axis=1)
        selfroot = conv & (own[r] != OFF) & ((s < s_self[r]) | (x_off < s_self[r] * vnorm[r]))
        valid = conv & ~selfroot & (s > s_eps[r]) & (s < smax[r])
        out[r[valid]] = True
        m = selfroot & (own[r] == ON)
        own_uv[r[m]] = uv[m]
        if depth == HIT_MAX_DEPTH:
            break
        # subdivide patches where Newton failed or left the patch
        redo = ~valid & ~out[r] & ~(conv & _in_cell(surface, uv, c0, c1, 1.5))
        if not redo.any():
            break
        r, c0, c1 = r[redo], c0[redo], c1[redo]
        mid = 0.5 * (c0 + c1)
        nr = np.repeat(r, 4)
        q0 = np.repeat(c0, 4, axis=0)
        q1 = np.repeat(c1, 4, axis=0)
        m4 = np.repeat(mid, 4, axis=0)
        a = np.tile([0, 1, 0, 1], len(r)).astype(bool)
        b = np.tile([0, 0, 1, 1], len(r)).astype(bool)
        n0 = np.stack([np.where(a, m4[:, 0], q0[:, 0]), np.where(b, m4[:, 1], q0[:, 1])], 1)
        n1 = np.stack([np.where(a, q1[:, 0], m4[:, 0]), np.where(b, q1[:, 1], m4[:, 1])], 1)
        blo, bhi = _sub_boxes(surface, n0, n1, size)
        ok, t0, t1 = _slab(o[nr], _inverse(v[nr]), blo, bhi, smax[nr])
        r, c0, c1, s0, s1 = nr[ok], n0[ok], n1[ok], t0[ok], t1[ok]
    # rays from points on the surface: the root next to the own root
    cand = np.nonzero((own == ON) & ~out & np.isfinite(own_uv[:, 0]))[0]
    if len(cand):
        uv, s = _local_second_root(surface, o[cand], v[cand], own_uv[cand])
        ok = np.isfinite(s) & (s > 0) & np.isfinite(uv).all(axis=1)
        cand, uv, s = cand[ok], uv[ok], s[ok]
        if len(cand):
            uv = surface.domain.wrap(uv)
            step = np.tile([[d.span(0) / 8, d.span(1) / 8]], (len(cand), 1))
            uv, s, conv = _newton(surface, o[cand], v[cand], uv, s, step, tol)
            out[cand[conv & (s > s_eps[cand]) & (s < smax[cand])]] = True
    return out
