"""Lines of curvature of implicit surfaces: the principal direction fields of
``F = 0`` from the Hessian restricted to the tangent plane, integrated in space.

At a regular point with ``g = grad F``, ``n = g / |g|`` and an orthonormal
basis ``t1, t2`` of the tangent plane, the shape operator in that basis is
``M_ij = t_i^T H t_j / |g|`` (``H`` the Hessian of ``F``; the second
fundamental form of the level set, up to the sign of ``n``).  Its
eigenvectors, ``e = cos(a) t1 + sin(a) t2`` with ``tan(2a) = 2 M_12 / (M_11
- M_22)`` and ``n x e``, are the principal directions; they are undefined
where ``M_11 = M_22, M_12 = 0`` (an umbilic).  Each line is integrated from a
seed both ways by classical Runge-Kutta steps on the unit field (its sign
kept from step to step), every step projected back onto ``F = 0`` by Newton
steps along ``grad F``, all lines in lockstep, until it leaves the clip
region, comes within ``UMBILIC_GAP`` of an umbilic, closes, or reaches
``MAX_STEPS``.  The seeds are points of ``F = 0`` from the search grid,
spread by farthest-point sampling: the lines are complete, not evenly
spaced.

>>> import lgraph as lg
>>> (b,) = lg.AlgebraicSurface("x^2/4 + y^2 + z^2/2.25 - 1", radius=3).lines_of_curvature(2, 2)
>>> len(b)
4
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._trace import _cell_centres, _cell_min, _straddles, curve_batch

__all__ = ["principal_fields", "implicit_lines_of_curvature"]

#: integration step, of the clip box's diagonal
STEP = 1 / 200
#: most steps of one half-line (a length of 6 clip box diagonals at full steps)
MAX_STEPS = 1200
#: the most a step may turn the field (radians), and the smallest step
TURN = 0.1
MIN_STEP = 1e-5
#: a point is an umbilic when the principal curvatures differ by less than
#: this, times the clip box's diagonal's inverse
UMBILIC_GAP = 1e-3


def principal_fields(surface: Any, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The unit principal directions ``e1, e2 = n x e1`` at points ``x`` of
    ``surface`` and the difference of the principal curvatures (``(n, 3)``,
    ``(n, 3)``, ``(n,)``; module docstring)."""
    g = surface.grad(x)
    H = surface.hess(x)
    gn = np.linalg.norm(g, axis=1)
    with np.errstate(all="ignore"):
        n = g / gn[:, None]
    k = np.argmin(np.abs(n), axis=1)
    a = np.zeros_like(n)
    a[np.arange(len(n)), k] = 1.0
    t1 = np.cross(n, a)
    t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
    t2 = np.cross(n, t1)
    with np.errstate(all="ignore"):
        m11 = np.einsum("ni,nij,nj->n", t1, H, t1) / gn
        m12 = np.einsum("ni,nij,nj->n", t1, H, t2) / gn
        m22 = np.einsum("ni,nij,nj->n", t2, H, t2) / gn
    ang = 0.5 * np.arctan2(2 * m12, m11 - m22)
    e1 = np.cos(ang)[:, None] * t1 + np.sin(ang)[:, None] * t2
    gap = np.hypot(m11 - m22, 2 * m12)
    return e1, np.cross(n, e1), gap


def _project(surface: Any, x: np.ndarray) -> np.ndarray:
    for _ in range(3):
        f, g = surface._fg(x)
        with np.errstate(all="ignore"):
            step = (f / np.einsum("ij,ij->i", g, g))[:, None] * g
        x = x - np.where(np.isfinite(step), step, 0.0)
    return x


def _candidates(surface: Any) -> np.ndarray:
    """Points of ``F = 0`` inside the clip region: the search grid's crossed
    cells, projected onto the surface."""
    grid = surface._search()
    m = int(grid["n"])
    cells = _straddles(grid["f"], m) & (_cell_min(grid["clip"], m) <= 0)
    c = _project(surface, _cell_centres(grid["x"], m)[cells])
    return c[np.isfinite(c).all(axis=1) & (surface.clip.excess(c)[0] <= 0)]


def _seeds(c: np.ndarray, n: int, dist: np.ndarray) -> np.ndarray:
    """``n`` of the candidate points ``c``, each the farthest from the lines
    drawn and the seeds chosen (``dist``: the candidates' distances to the
    lines drawn, inf if none)."""
    dist = dist.copy()
    chosen = []
    for _ in range(min(n, len(c))):  # one pass per seed: n at most MAX_FIELD_LINES
        k = int(np.argmax(dist)) if np.isfinite(dist).any() else 0
        chosen.append(k)
        dist = np.minimum(dist, np.linalg.norm(c - c[k], axis=1))
    return c[chosen]


def _field(surface: Any, which: int, x: np.ndarray, prev: np.ndarray) -> tuple[Any, Any]:
    e1, e2, gap = principal_fields(surface, x)
    e = e1 if which == 0 else e2
    s = np.sign(np.einsum("ij,ij->i", e, prev))
    return e * np.where(s == 0, 1.0, s)[:, None], gap


def _integrate(surface: Any, which: int, seeds: np.ndarray) -> list:
    """Both halves of the lines from ``seeds`` in lockstep; per seed ``(points, closed)``."""
    clip = surface.clip
    size = clip.size
    h0 = STEP * size
    m = len(seeds)
    h = np.full(2 * m, h0)
    x = np.concatenate([seeds, seeds])
    e1, e2, gap = principal_fields(surface, x)
    d = (e1 if which == 0 else e2).copy()
    d[m:] *= -1
    active = np.isfinite(d).all(axis=1) & (gap * size > UMBILIC_GAP)
    start, d0, travelled = x.copy(), d.copy(), np.zeros(2 * m)
    closed = np.zeros(2 * m, bool)
    paths: list[list[np.ndarray]] = [[] for _ in range(2 * m)]
    for _ in range(MAX_STEPS):
        a = np.flatnonzero(active)
        if not len(a):
            break
        xa, da, ha = x[a], d[a], h[a, None]
        k1, _ = _field(surface, which, xa, da)
        k2, _ = _field(surface, which, xa + 0.5 * ha * k1, k1)
        k3, _ = _field(surface, which, xa + 0.5 * ha * k2, k2)
        k4, _ = _field(surface, which, xa + ha * k3, k3)
        xn = _project(surface, xa + ha / 6 * (k1 + 2 * k2 + 2 * k3 + k4))
        dn, gap = _field(surface, which, xn, k4)
        # a step that turns the field by more than TURN is halved (near an
        # umbilic the field turns fast); below MIN_STEP the line ends there
        turn = np.einsum("ij,ij->i", dn, k1) < np.cos(TURN)
        retry = turn & (h[a] > MIN_STEP * size)
        h[a[retry]] *= 0.5
        ok = np.isfinite(xn).all(axis=1) & np.isfinite(dn).all(axis=1) & ~turn
        ok &= (clip.excess(xn)[0] <= 0) & (gap * size > UMBILIC_GAP)
        travelled[a[ok]] += h[a[ok]]
        h[a[ok]] = np.minimum(h[a[ok]] * 1.25, h0)
        # closed: back near the seed, running the same way (lines of one family
        # do not cross, so only the line itself comes back like that)
        back = ok & (travelled[a] > 4 * h0) & (np.linalg.norm(xn - start[a], axis=1) < 2 * h0)
        back &= np.einsum("ij,ij->i", dn, d0[a]) > 0.9
        for k, p in zip(a[ok & ~back].tolist(), xn[ok & ~back]):
            paths[k].append(p)
        closed[a[back]] = True
        active[a[(~ok & ~retry) | back]] = False
        x[a[ok]], d[a[ok]] = xn[ok], dn[ok]
    out = []
    for k in range(m):
        fwd = np.array(paths[k]).reshape(-1, 3)
        if closed[k]:
            out.append((np.vstack([seeds[k][None], fwd]), True))
        else:
            bwd = np.array(paths[k + m]).reshape(-1, 3)[::-1]
            out.append((np.vstack([bwd, seeds[k][None], fwd]), False))
    return out


def implicit_lines_of_curvature(surface: Any, n1: int, n2: int) -> list[Any]:
    """``n1`` lines of the first principal family and ``n2`` of the second
    (one batch, family ``"curvature"``), on ``F = 0`` to rounding error.

    Seeds are chosen in rounds: each the candidate point farthest from the
    lines of its family drawn so far; a line through the seed of one
    already drawn (closer than ``0.6`` of a step) is left out."""
    from scipy.spatial import cKDTree

    from ..._budget import check_field_lines

    check_field_lines("LinesOfCurvature", n1, n2)
    cand = _candidates(surface)
    h = STEP * surface.clip.size
    curves = []
    for which, n in ((0, n1), (1, n2)):
        drawn: list[np.ndarray] = []
        for _ in range(4):  # rounds: lines through one seed were drawn twice
            if len(drawn) >= n or not len(cand):
                break
            pts_all = np.concatenate(drawn) if drawn else np.empty((0, 3))
            dist = cKDTree(pts_all).query(cand)[0] if len(pts_all) else np.full(len(cand), np.inf)
            seeds = _seeds(cand, n - len(drawn), dist)
            for pts, closed in _integrate(surface, which, seeds):
                if len(drawn) >= n or len(pts) < 3:
                    continue
                seed_taken = any(
                    np.isfinite(cKDTree(q).query(pts[:1], distance_upper_bound=0.6 * h)[0][0])
                    for q in drawn
                )
                if not seed_taken:
                    drawn.append(pts)
                    curves.append((pts, closed, 0))
    if not curves:
        return []
    return curve_batch(surface, "curvature", curves, surface._fg, _Free(surface))


class _Free:
    """The "second equation" of a line of curvature for the evaluation's
    Gauss-Newton steps: ``G = 0`` along the step, so only ``F = 0`` is
    enforced (the step is along ``grad F``)."""

    def __init__(self, surface: Any) -> None:
        self.surface = surface

    def __call__(self, x: np.ndarray, _idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        _, g = self.surface._fg(x)
        # any direction perpendicular to grad F, with G = 0: the least-norm step
        # of (F, G) is then the step of F alone
        k = np.argmin(np.abs(g), axis=1)
        a = np.zeros_like(g)
        a[np.arange(len(g)), k] = 1.0
        t = np.cross(g, a)
        return np.zeros(len(x)), t
