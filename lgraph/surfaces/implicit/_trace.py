"""Space curves ``F = 0, G = 0`` of implicit surfaces: seeds, tracing, batches.

The contour, the plane sections and the clip curve of an implicit surface
are all curves cut out of ``F = 0`` by a second equation ``G = 0``
(``grad F . v``, a plane ``x . d - c``, a face of the box, the sphere).
:func:`trace_curves` finds them in three steps:

1. **seeds**: on a grid of the clip box (cached per surface: ``F`` and
   ``grad F`` at its nodes), every cell whose eight corners give ``F`` both
   signs and ``G`` both signs is a candidate; its centre is moved onto the
   curve by Gauss-Newton steps (the least-norm step of the two equations);
2. **tracing**: from one seed per cluster, all curves at once in lockstep
   (a predictor step along the tangent ``grad F x grad G``, Gauss-Newton
   corrections to ``1e-12`` of the scene, the step halved where the
   correction fails or the tangent turns), both ways, until the curve
   closes, leaves the clip region (its last point is then solved exactly on
   ``F = G = 0`` and the clip boundary) or reaches a singular point
   (``grad F`` and ``grad G`` parallel); seeds near a traced curve are
   consumed, the others seed the next round;
3. **batches**: each curve becomes a cubic spline in arc length, and every
   evaluation is projected back onto ``F = G = 0`` by Gauss-Newton steps.

What can be missed: a component that crosses no grid cell whose corners
show both signs of ``F`` and of ``G`` -- a closed loop smaller than a cell
(``size / (grid - 1)`` of the clip box), or a piece that stays within a
cell of a tangency of the two surfaces ``F = 0`` and ``G = 0`` -- unless the
surface gives certain bounds per cell (``cells``: polynomials, by their
Bernstein coefficients), then every cell the curve may cross seeds.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from ..._tolerance import IMPLICIT_MIN_STEP as MIN_STEP
from ..._tolerance import IMPLICIT_STEP as STEP
from ..._tolerance import IMPLICIT_TRACE_TOL as TRACE_TOL
from ...curves import CurveBatch

__all__ = ["Clip", "trace_curves", "gauss_newton", "surface_grid"]

#: Gauss-Newton steps for seeds, and when evaluating a traced curve
SEED_STEPS = 12
EVAL_STEPS = 4
#: tracing: the most steps of one curve
MAX_TRACE_STEPS = 6000
#: rounds of seeding (each traces the curves of the seeds left)
MAX_ROUNDS = 8

Eq = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


@attrs.frozen
class Clip:
    """The clip region: the box ``lo <= x <= hi`` or the ball ``|x - centre| <= radius``."""

    lo: np.ndarray
    hi: np.ndarray
    radius: float | None = None
    centre: np.ndarray | None = None

    @property
    def size(self) -> float:
        return float(np.linalg.norm(self.hi - self.lo))

    def excess(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(value, gradient, which)``: how far ``x`` is outside (<= 0 inside)
        and the gradient of the active constraint (the sphere, or the face
        ``which`` of the box: 0..5 = x lo, x hi, y lo, ...)."""
        if self.radius is not None:
            d = x - self.centre
            r = np.linalg.norm(d, axis=-1)
            with np.errstate(invalid="ignore", divide="ignore"):
                g = d / r[..., None]
            return r - self.radius, g, np.zeros(len(x), int)
        faces = np.concatenate([self.lo - x, x - self.hi], axis=-1)[:, [0, 3, 1, 4, 2, 5]]
        which = np.argmax(faces, axis=1)
        g = np.zeros_like(x)
        g[np.arange(len(x)), which // 2] = np.where(which % 2, 1.0, -1.0)
        return faces[np.arange(len(x)), which], g, which

    def ray_interval(self, o: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(s_in, s_out)`` of the rays ``o + s v`` inside the region (``s_in >
        s_out`` where a ray misses it)."""
        if self.radius is not None:
            d = o - self.centre
            a = np.einsum("ij,ij->i", v, v)
            b = np.einsum("ij,ij->i", d, v)
            c = np.einsum("ij,ij->i", d, d) - self.radius**2
            disc = b * b - a * c
            root = np.sqrt(np.maximum(disc, 0.0))
            s_in, s_out = (-b - root) / a, (-b + root) / a
            return np.where(disc >= 0, s_in, np.inf), np.where(disc >= 0, s_out, -np.inf)
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = (self.lo - o) / v, (self.hi - o) / v
        near, far = np.fmin(t0, t1), np.fmax(t0, t1)
        inside = (o >= self.lo) & (o <= self.hi)
        near = np.where(v == 0, np.where(inside, -np.inf, np.inf), near)
        far = np.where(v == 0, np.where(inside, np.inf, -np.inf), far)
        return near.max(axis=1), far.min(axis=1)


def surface_grid(
    F: Callable[..., Any], grad: Callable[[np.ndarray], np.ndarray], clip: Clip, n: int
) -> dict[str, np.ndarray]:
    """``F`` and ``grad F`` on the ``n**3`` nodes of the clip box (the seeds' search)."""
    axes = [np.linspace(clip.lo[i], clip.hi[i], n) for i in range(3)]
    X = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    with np.errstate(all="ignore"):
        f = np.asarray(F(X[:, 0], X[:, 1], X[:, 2]), float)
        g = np.asarray(grad(X), float)
    return {"x": X, "f": f, "g": g, "n": np.array(n)}


def _straddles(values: np.ndarray, n: int) -> np.ndarray:
    """Per cell of an ``n**3`` grid (flattened ``(n-1)**3``): whether its
    corners' values take both signs (NaN corners never straddle)."""
    v = values.reshape(n, n, n)
    lo = np.full((n - 1,) * 3, np.inf)
    hi = np.full((n - 1,) * 3, -np.inf)
    for a in (0, 1):
        for b in (0, 1):
            for c in (0, 1):
                w = v[a : n - 1 + a, b : n - 1 + b, c : n - 1 + c]
                lo = np.fmin(lo, w)
                hi = np.fmax(hi, w)
    return ((lo <= 0) & (hi >= 0)).ravel()


def gauss_newton(
    fg: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    gg: Eq,
    x: np.ndarray,
    idx: np.ndarray,
    steps: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Least-norm Newton steps onto ``F = 0, G = 0`` for points ``x`` of curves
    ``idx``; returns the points and their residual as a distance
    (``max(|F|/|grad F|, |G|/|grad G|)``)."""
    x, res, _ = _newton(fg, gg, x, idx, steps, 0.0)
    return x, res


def _newton(fg: Any, gg: Eq, x: np.ndarray, idx: np.ndarray, steps: int, done: float) -> Any:
    """:func:`gauss_newton`, stopping early once every residual is below
    ``done``; also returns the unit tangents ``grad F x grad G`` at the points."""
    x = np.array(x, float, copy=True)
    act = np.arange(len(x))
    res = np.full(len(x), np.inf)
    tan = np.full(x.shape, np.nan)
    for k in range(steps + 1):
        f, gf = fg(x[act])
        g, g2 = gg(x[act], idx[act])
        a = np.einsum("ij,ij->i", gf, gf)
        b = np.einsum("ij,ij->i", gf, g2)
        c = np.einsum("ij,ij->i", g2, g2)
        with np.errstate(all="ignore"):
            r = np.maximum(np.abs(f) / np.sqrt(a), np.abs(g) / np.sqrt(c))
            res[act] = np.where(np.isfinite(r), r, np.inf)
            t = np.cross(gf, g2)
            tan[act] = t / np.linalg.norm(t, axis=1, keepdims=True)
        if k == steps:
            break
        keep = res[act] > done
        act, f, g, gf, g2, a, b, c = (v[keep] for v in (act, f, g, gf, g2, a, b, c))
        if not len(act):
            break
        with np.errstate(all="ignore"):
            det = a * c - b * b
            y1 = (c * f - b * g) / det
            y2 = (a * g - b * f) / det
            dx = y1[:, None] * gf + y2[:, None] * g2
        ok = np.isfinite(dx).all(axis=1) & (det > 1e-24 * a * c)
        x[act[ok]] -= dx[ok]
    return x, res, tan


def _tangent(fg: Any, gg: Eq, x: np.ndarray, idx: np.ndarray) -> np.ndarray:
    _, gf = fg(x)
    _, g2 = gg(x, idx)
    t = np.cross(gf, g2)
    with np.errstate(all="ignore"):
        return t / np.linalg.norm(t, axis=1, keepdims=True)


def _exit_point(fg: Any, gg: Eq, clip: Clip, x: np.ndarray, idx: np.ndarray) -> Any:
    """Newton on ``F = G = 0`` and the active clip constraint from ``x`` (just
    outside); returns the points and whether each converged."""
    x = np.array(x, float, copy=True)
    _, _, which = clip.excess(x)
    for _ in range(8):
        f, gf = fg(x)
        g, g2 = gg(x, idx)
        if clip.radius is not None:
            e, ge, _ = clip.excess(x)
        else:
            ax, up = which // 2, which % 2 == 1
            bound = np.where(up, clip.hi[ax], clip.lo[ax])
            e = x[np.arange(len(x)), ax] - bound
            ge = np.zeros_like(x)
            ge[np.arange(len(x)), ax] = 1.0
        J = np.stack([gf, g2, ge], axis=1)
        r = np.stack([f, g, e], axis=1)
        with np.errstate(all="ignore"):
            ok = np.abs(np.linalg.det(J)) > 1e-300
            dx = np.zeros_like(x)
            if ok.any():
                dx[ok] = np.linalg.solve(J[ok], r[ok][..., None])[..., 0]
        x -= np.where(np.isfinite(dx), dx, 0.0)
    _, res = gauss_newton(fg, gg, x, idx, 0)
    return x, res < 1e-9 * clip.size


def _trace(fg: Any, gg: Eq, clip: Clip, seeds: np.ndarray, idx: np.ndarray, h0: float) -> list:
    """Trace every seed both ways in lockstep; per seed ``(points (m, 3), closed)``."""
    m = len(seeds)
    x = np.concatenate([seeds, seeds])
    cid = np.concatenate([idx, idx])
    t = _tangent(fg, gg, x, cid)
    t[m:] *= -1
    h = np.full(2 * m, h0)
    active = np.isfinite(t).all(axis=1)
    closed = np.zeros(2 * m, bool)
    travelled = np.zeros(2 * m)
    paths: list[list[np.ndarray]] = [[] for _ in range(2 * m)]
    slack = 1e-9 * clip.size
    start, t_start = x.copy(), t.copy()
    for _ in range(MAX_TRACE_STEPS):
        a = np.flatnonzero(active)
        if not len(a):
            break
        xp = x[a] + h[a, None] * t[a]
        xn, res, tn = _newton(fg, gg, xp, cid[a], 5, 1e-3 * TRACE_TOL * clip.size)
        cos = np.einsum("ij,ij->i", tn, t[a])
        tn = np.where(cos[:, None] < 0, -tn, tn)
        moved = np.linalg.norm(xn - xp, axis=1)
        step = np.linalg.norm(xn - x[a], axis=1)
        good = (res < TRACE_TOL * clip.size) & (moved < 0.5 * h[a]) & (np.abs(cos) > 0.95)
        good &= np.isfinite(tn).all(axis=1) & (step > 0.2 * h[a])
        bad = a[~good]
        h[bad] *= 0.5
        active[bad[h[bad] < MIN_STEP * clip.size]] = False  # a singular point: stop
        ok, xn, tn = a[good], xn[good], tn[good]
        out = clip.excess(xn)[0] > slack
        if out.any():
            o = ok[out]
            xe, conv = _exit_point(fg, gg, clip, xn[out], cid[o])
            for k, p, c in zip(o.tolist(), xe, conv.tolist()):
                if c:
                    paths[k].append(p)
            active[o] = False
        inn = ~out
        ok, xn, tn = ok[inn], xn[inn], tn[inn]
        travelled[ok] += h[ok]
        back = (travelled[ok] > 3 * h[ok]) & (np.linalg.norm(xn - start[ok], axis=1) < 0.6 * h[ok])
        # a point that has passed the start again is left out: the curve closes there
        past = back & (np.einsum("ij,ij->i", xn - start[ok], t_start[ok]) >= 0)
        for k, p in zip(ok[~past].tolist(), xn[~past]):
            paths[k].append(p)
        closed[ok[back]] = True
        active[ok[back]] = False
        x[ok], t[ok] = xn, tn
        smooth = np.abs(np.einsum("ij,ij->i", tn, t[ok])) > 0.995
        h[ok[smooth]] = np.minimum(h[ok[smooth]] * 1.25, h0)
    out_curves = []
    for k in range(m):
        fwd = np.array(paths[k]).reshape(-1, 3)
        if closed[k] or closed[k + m]:
            pts = np.vstack([seeds[k][None], fwd if closed[k] else np.array(paths[k + m])[::-1]])
            out_curves.append((pts, True))
        else:
            back = np.array(paths[k + m]).reshape(-1, 3)[::-1]
            out_curves.append((np.vstack([back, seeds[k][None], fwd]), False))
    return out_curves


def trace_curves(
    fg: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    gg: Eq,
    clip: Clip,
    grid: dict[str, np.ndarray],
    g_on_grid: np.ndarray,
    clip_on_grid: np.ndarray | None = None,
    cells: Callable[[np.ndarray, int, np.ndarray], np.ndarray] | None = None,
) -> list[tuple[np.ndarray, bool, int]]:
    """The curves ``F = 0, G_k = 0`` (``k`` the rows of ``g_on_grid``: ``G_k``
    at the grid's nodes) inside ``clip``: ``(points, closed, k)`` each, the
    points on the curve to ``TRACE_TOL`` of the scene, about ``STEP`` of the
    clip box apart.  ``clip_on_grid`` (optional): per node, the clip
    function, restricting the seeds to cells near the region.  ``cells``
    (optional): ``cells(candidates, k, straddles)``, which of the candidate
    cells (flat indices) may hold a point of ``F = G_k = 0`` (certain
    bounds, for polynomials; ``straddles``, per cell, whether ``G_k``'s
    corners show both signs: exact for a plane); they seed too, besides the
    cells whose corners show both signs of both."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    n = int(grid["n"])
    cell = clip.size / np.sqrt(3) / (n - 1)
    centres = _cell_centres(grid["x"], n)
    fcells = _straddles(grid["f"], n)
    if clip_on_grid is not None:  # cells of the clip box near the region
        fcells &= _cell_min(clip_on_grid, n) <= 1.8 * cell
    seeds, idx = [], []
    near = None
    if cells is not None:  # every cell near the region: the bounds decide
        near = np.ones(len(fcells), bool)
        if clip_on_grid is not None:
            near = _cell_min(clip_on_grid, n) <= 1.8 * cell
    for k, gk in enumerate(np.atleast_2d(g_on_grid)):
        gs = _straddles(gk, n)
        c = np.flatnonzero(fcells & gs)
        if cells is not None and near is not None:
            c = np.union1d(c, cells(np.flatnonzero(near), k, gs))
        seeds.append(centres[c])
        idx.append(np.full(len(c), k))
    x = np.concatenate(seeds) if seeds else np.empty((0, 3))
    idx = np.concatenate(idx) if idx else np.empty(0, int)
    if not len(x):
        return []
    x, res = gauss_newton(fg, gg, x, idx, SEED_STEPS)
    d = np.linalg.norm(x - np.concatenate(seeds), axis=1)
    keep = (res < TRACE_TOL * clip.size) & (d < 2 * cell) & (clip.excess(x)[0] <= 0)
    x, idx = x[keep], idx[keep]
    h = STEP * clip.size
    curves: list[tuple[np.ndarray, bool, int]] = []
    for _ in range(MAX_ROUNDS):
        if not len(x):
            break
        # one seed per cluster of seeds (of one equation) within 1.5 cells
        pairs = cKDTree(x).query_pairs(1.5 * cell, output_type="ndarray")
        pairs = pairs[idx[pairs[:, 0]] == idx[pairs[:, 1]]]
        adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), (len(x), len(x)))
        _, label = connected_components(adj, directed=False)
        rep = np.unique(label, return_index=True)[1]
        traced = _trace(fg, gg, clip, x[rep], idx[rep], h)
        used = np.zeros(len(x), bool)
        for (pts, closed), r in zip(traced, rep.tolist()):
            if used[r] or len(pts) < 2:
                used[r] = True
                continue
            near = np.isfinite(cKDTree(pts).query(x, distance_upper_bound=0.6 * h)[0])
            used |= near & (idx == idx[r])
            used[r] = True
            curves.append((pts, closed, int(idx[r])))
        x, idx = x[~used], idx[~used]
    return curves


def _cell_centres(X: np.ndarray, n: int) -> np.ndarray:
    G = X.reshape(n, n, n, 3)
    return (0.5 * (G[:-1, :-1, :-1] + G[1:, 1:, 1:])).reshape(-1, 3)


def _cell_min(values: np.ndarray, n: int) -> np.ndarray:
    v = values.reshape(n, n, n)
    out = np.full((n - 1,) * 3, np.inf)
    for a in (0, 1):
        for b in (0, 1):
            for c in (0, 1):
                out = np.fmin(out, v[a : n - 1 + a, b : n - 1 + b, c : n - 1 + c])
    return out.ravel()


def curve_batch(
    surface: Any,
    family: str,
    curves: list[tuple[np.ndarray, bool, int]],
    fg: Any,
    gg: Eq,
) -> list[CurveBatch]:
    """One batch of the traced ``curves`` (points lie on ``surface``, no
    parameters): splines in arc length, projected back onto ``F = G = 0``
    by Gauss-Newton steps at every evaluation."""
    from scipy.interpolate import CubicSpline, make_interp_spline

    splines, lengths, closed, eqs = [], [], [], []
    for pts, is_closed, k in curves:
        if is_closed:
            pts = np.vstack([pts, pts[:1]])
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        keep = np.concatenate([[True], np.diff(s) > 1e-12 * max(s[-1], 1e-300)])
        pts, s = pts[keep], s[keep]
        if len(s) < 2 or s[-1] <= 0:
            continue
        if is_closed and len(s) >= 4:
            pts[-1] = pts[0]
            sp = CubicSpline(s, pts, bc_type="periodic")
        else:
            sp = make_interp_spline(s, pts, k=min(3, len(s) - 1))
            is_closed = False
        splines.append(sp)
        lengths.append(s[-1])
        closed.append(is_closed)
        eqs.append(k)
    if not splines:
        return []
    eq = np.array(eqs)

    def evaluate(ci: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, None]:
        ci = np.asarray(ci)
        x = np.empty((len(t), 3))
        for c in np.unique(ci).tolist():
            sel = ci == c
            x[sel] = splines[c](t[sel])
        x, _ = gauss_newton(fg, gg, x, eq[ci], EVAL_STEPS)
        return x, None

    return [
        CurveBatch(
            family,
            np.zeros(len(splines)),
            np.array(lengths),
            evaluate,
            closed=np.array(closed),
            surface=surface,
        )
    ]
