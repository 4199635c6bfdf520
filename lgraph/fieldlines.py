"""Lines of a line field on a surface: numeric lines of curvature and asymptotic lines.

A *line field* (:func:`lgraph.curvature.principal_field`,
:func:`lgraph.curvature.asymptotic_field`) gives two unoriented directions at
every point of the parameter plane.  Its lines are traced here, all lines of a
family at once (derivation and guarantees: ``docs/mathematics.rst``, "Numeric
line families"):

* The curve parameter is 3-D arc length.  Every line advances in lockstep with
  its own step size (Dormand and Prince's embedded 5(4) pair, error per step below
  :data:`~lgraph._tolerance.FIELD_RTOL` of the parameter spans,
  :data:`~lgraph._tolerance.ASYMPTOTIC_RTOL` for asymptotic lines), so one
  field evaluation serves every line.
* At every stage a line takes the branch of the field nearest (in the
  surface's metric) to its current direction, with that direction's sign:
  it never switches branch, also next to umbilics and flat umbilics, where it
  either goes straight on (tangent continuity) or stops.  Nothing depends on
  the last bits of floating point.
* A line stops at the patch boundary (located on the step's cubic Hermite
  interpolant), where the field degenerates (an umbilic, a parabolic line, a
  pole: the step would have to shrink below
  :data:`~lgraph._tolerance.FIELD_MIN_STEP`), when it returns to its seed
  (closed), or after :data:`~lgraph._tolerance.FIELD_MAX_LENGTH` sizes.
* Lines are complete by default: seeds are spread evenly along a transversal
  line through the middle of the patch, and a line that retraces one already
  drawn is replaced by one through the point farthest from the drawn lines.
  ``spacing="even"`` instead trims lines where they come closer than half the
  spacing to another (evenly spaced streamlines, Jobard and Lefer 1997).
* Where the parameter lines are the field's lines (``g12 = L12 = 0`` for lines
  of curvature, the paper's Proposition 4.1; ``L11 = L22 = 0`` for asymptotic
  lines) the parameter lines are drawn: exact.

>>> import lgraph as lg
>>> from lgraph.curvature import principal_field
>>> batches = field_line_batches(lg.MonkeySaddle(), principal_field, 3, 3)
>>> sum(len(b) for b in batches)
6
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._tolerance import (
    ASYMPTOTIC_RTOL,
    FIELD_CLOSE_RTOL,
    FIELD_DUPLICATE_RTOL,
    FIELD_FIRST_STEP,
    FIELD_MAX_ITERATIONS,
    FIELD_MAX_LENGTH,
    FIELD_MAX_STEP,
    FIELD_MIN_STEP,
    FIELD_RTOL,
    FIELD_SINGULAR_RTOL,
    PARABOLIC_STOP,
    PARAMETER_LINES_RTOL,
    UMBILIC_STOP,
)
from .curves import CurveBatch
from .families import SPACINGS, parameter_line_batches

__all__ = ["FieldLines", "trace", "field_line_batches"]


# Dormand-Prince 5(4): nodes, stage coefficients, 5th-order weights, and the
# difference of the 5th- and 4th-order weights (7 stages, the last one is the
# field at the new point and starts the next step).
_A = (
    (),
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
)
_B = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84)
_E = (71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40)
# the quartic term of the continuous extension (Hairer, Norsett and Wanner's DOPRI5)
#: a step ends on an edge or the seed when that lies within this fraction of its end
_END_RTOL = 1e-7
_D = (-12715105075 / 11282082432, 0.0, 87487479700 / 32700410799,
      -10690763975 / 1880347072, 701980252875 / 199316789632,
      -1453857185 / 822651844, 69997945 / 29380423)  # fmt: skip


def _stop_of(field: Any) -> float:
    from .curvature import asymptotic_field

    return PARABOLIC_STOP if field is asymptotic_field else UMBILIC_STOP


def _rtol_of(field: Any) -> float:
    from .curvature import asymptotic_field

    return ASYMPTOTIC_RTOL if field is asymptotic_field else FIELD_RTOL


def _cubic(y0: np.ndarray, k0: np.ndarray, y1: np.ndarray, k1: np.ndarray,
           h: np.ndarray) -> np.ndarray:  # fmt: skip
    """Coefficients ``(n, 4, 2)`` (constant first) of the cubic Hermite
    interpolants of steps ``y0 -> y1`` with arc-length tangents ``k0, k1``,
    in the step fraction ``0..1``."""
    hk0, hk1 = h[:, None] * k0, h[:, None] * k1
    return np.stack([y0, hk0, 3 * (y1 - y0) - 2 * hk0 - hk1, 2 * (y0 - y1) + hk0 + hk1], axis=1)


def _at(C: np.ndarray, th: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Point and arc-length derivative of cubics ``C`` at fractions ``th``."""
    t = th[:, None]
    p = ((C[:, 3] * t + C[:, 2]) * t + C[:, 1]) * t + C[:, 0]
    dp = ((3 * C[:, 3] * t + 2 * C[:, 2]) * t + C[:, 1]) / h[:, None]
    return p, dp


def _dense_at(y0: np.ndarray, k0: np.ndarray, y1: np.ndarray, k1: np.ndarray,
              r5: np.ndarray, h: np.ndarray, th: np.ndarray) -> np.ndarray:  # fmt: skip
    """Dormand and Prince's continuous extension of steps (rows) at fractions
    ``th``: the cubic Hermite interpolant plus ``th^2 (1 - th)^2 r5``."""
    t = th[:, None]
    ydiff = y1 - y0
    bspl = h[:, None] * k0 - ydiff
    r4 = ydiff - h[:, None] * k1 - bspl
    return y0 + t * (ydiff + (1 - t) * (bspl + t * (r4 + (1 - t) * r5)))


def _exit(C: np.ndarray, lo: np.ndarray, hi: np.ndarray, per: np.ndarray) -> np.ndarray:
    """The fraction where each cubic (which starts inside the box ``lo..hi``
    and ends outside it) first leaves it: the first of 16 parts that ends
    outside, then safeguarded Newton steps on the excess over the box."""
    grid = np.linspace(0.0, 1.0, 17)
    t = grid[None, :, None]
    p = ((C[:, None, 3] * t + C[:, None, 2]) * t + C[:, None, 1]) * t + C[:, None, 0]
    first = np.argmax((((p < lo) | (p > hi)) & ~per).any(axis=2), axis=1)
    a, b = grid[first - 1], grid[first]
    lo_, hi_ = np.where(per, -np.inf, lo), np.where(per, np.inf, hi)
    one = np.ones(len(C))
    rows = np.arange(len(C))
    c = 0.5 * (a + b)
    for _ in range(6):
        p, dp = _at(C, c, one)
        excess = np.maximum(lo_ - p, p - hi_)  # > 0 outside
        i = np.argmax(excess, axis=1)
        f = excess[rows, i]
        df = np.where(p[rows, i] > hi_[i], dp[rows, i], -dp[rows, i])
        a, b = np.where(f > 0, a, c), np.where(f > 0, c, b)
        with np.errstate(invalid="ignore", divide="ignore"):
            c = c - f / df
        c = np.where((c > a) & (c < b), c, 0.5 * (a + b))
    return c


def _chord_gap(y0: np.ndarray, y1: np.ndarray, target: np.ndarray, span: np.ndarray,
               per: np.ndarray) -> np.ndarray:  # fmt: skip
    """Distance (scaled parameters, max norm) of ``target`` to the chords ``y0 -> y1``."""
    r0 = _rel(y0, target, span, per)
    dr = (y1 - y0) / span
    with np.errstate(invalid="ignore", divide="ignore"):
        tc = np.clip(-np.einsum("ij,ij->i", r0, dr) / np.einsum("ij,ij->i", dr, dr), 0, 1)
    return np.abs(r0 + np.nan_to_num(tc)[:, None] * dr).max(axis=1)


def _rel(p: np.ndarray, seed: np.ndarray, span: np.ndarray, per: np.ndarray) -> np.ndarray:
    """Parameters relative to ``seed`` in spans (periodic ones to the nearest copy)."""
    q = (p - seed) / span
    return np.where(per, q - np.round(q), q)


def _closest(C: np.ndarray, upto: np.ndarray, h: np.ndarray, seed: np.ndarray,
             span: np.ndarray, per: np.ndarray) -> tuple[np.ndarray, ...]:  # fmt: skip
    """The fraction (at most ``upto``) where each cubic passes closest to its
    seed (scaled parameters): the best of 33 samples, then Newton on
    ``(p - seed) . p' = 0``; with the point and tangent there."""
    grid = np.linspace(0.0, 1.0, 33)
    t = grid[None, :, None]
    p = ((C[:, None, 3] * t + C[:, None, 2]) * t + C[:, None, 1]) * t + C[:, None, 0]
    q = (p - seed[:, None]) / span
    q = np.where(per, q - np.round(q), q)
    th = np.minimum(grid[np.argmin((q * q).sum(axis=2), axis=1)], upto)
    for _ in range(6):
        p, dp = _at(C, th, h)
        r = _rel(p, seed, span, per) / span  # gradient of the scaled distance
        w = dp * h[:, None]
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.einsum("ij,ij->i", r, w) / np.einsum("ij,ij->i", w / span, w / span)
        th = np.clip(th - np.nan_to_num(step), 0.0, upto)
    p, dp = _at(C, th, h)
    return th, p, dp


class FieldLines:
    """Lines traced by :func:`trace`: line ``k`` runs over arc lengths
    ``-ends[1, k] .. ends[0, k]`` (0 at its seed); ``closed[k]`` lines are loops
    over ``0 .. ends[0, k]``.

    Stored as the integrator's nodes (parameters, unit tangents, and the
    quartic term of each step's continuous extension) and evaluated with the
    method's own 4th-order interpolant, all lines at once (:meth:`uv`).
    """

    def __init__(self, surface: Any, s: list, y: list, k: list, r5: list,
                 closed: np.ndarray) -> None:  # fmt: skip
        self.surface = surface
        self.domain = surface.domain
        self.m = len(s)
        self.closed = np.asarray(closed, bool)
        self.ends = np.array([[float(si[-1]) for si in s], [float(-si[0]) for si in s]])
        self.ends = self.ends.reshape(2, self.m)
        counts = np.array([len(si) for si in s], int)
        self._start = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(int)
        self._count = counts
        lengths = self.ends[0] + self.ends[1]
        # a global increasing key: line k's arc lengths shifted past all before it
        self._shift = np.concatenate([[0.0], np.cumsum(lengths + 1.0)[:-1]]) + self.ends[1]
        self._s = np.concatenate(s) if s else np.empty(0)
        self._key = self._s + np.repeat(self._shift, counts)
        self._y = np.concatenate(y) if y else np.empty((0, 2))
        self._k = np.concatenate(k) if k else np.empty((0, 2))
        self._r5 = np.concatenate(r5) if r5 else np.empty((0, 2))

    def uv(self, idx: Any, t: Any) -> np.ndarray:
        """Parameters ``(n, 2)`` of lines ``idx`` at signed arc lengths ``t``
        (unwrapped: periodic parameters may leave their range)."""
        idx = np.asarray(idx, int)
        t = np.clip(np.asarray(t, float), -self.ends[1, idx], self.ends[0, idx])
        lo = self._start[idx]
        hi = lo + np.maximum(self._count[idx] - 2, 0)
        j = np.clip(np.searchsorted(self._key, t + self._shift[idx], "right") - 1, lo, hi)
        if not len(j):
            return np.empty((0, 2))
        j1 = np.minimum(j + 1, len(self._s) - 1)
        h = self._s[j1] - self._s[j]
        single = h <= 0  # a line of one node
        hs = np.where(single, 1.0, h)
        th = np.where(single, 0.0, (t - self._s[j]) / hs)
        return _dense_at(self._y[j], self._k[j], self._y[j1], self._k[j1], self._r5[j], hs, th)

    def uv_line(self, k: int, t: np.ndarray) -> np.ndarray:
        """:meth:`uv` of one line."""
        return self.uv(np.full(len(t), k), t)

    def points(self, k: int, t: np.ndarray) -> np.ndarray:
        """3-D points of line ``k`` at arc lengths ``t``."""
        uv = self.domain.wrap(self.uv_line(k, np.asarray(t, float)), clip=False)
        return self.surface.point(uv[:, 0], uv[:, 1])

    def batch(self, family: str, keep: Any = None) -> CurveBatch | None:
        """The lines ``keep`` (default all, those of zero length left out) as one batch."""
        ks = np.arange(self.m) if keep is None else np.asarray(keep, int)
        ks = ks[(self.ends[0, ks] + self.ends[1, ks]) > 0]
        if not len(ks):
            return None
        domain = self.domain
        return CurveBatch.from_uv(
            self.surface,
            family,
            -self.ends[1, ks],
            self.ends[0, ks],
            lambda c, t: domain.wrap(self.uv(ks[np.asarray(c, int)], t)),
            closed=self.closed[ks],
        )


def _finish(ends: tuple, rows: np.ndarray, th: np.ndarray, target: np.ndarray) -> None:
    """End the steps ``rows`` on ``target`` (a patch edge or the seed) where
    the step ends there (``th`` ~ 1); where it would end a tiny step
    (about ``FIELD_MIN_STEP``) after its start, the line ends at the start
    instead.  ``ends`` holds the step's arrays, changed in place."""
    y1, stop_here, drop = ends
    full = th >= 1 - _END_RTOL
    y1[rows[full]] = target[full]
    drop[rows[~full]] = True
    stop_here[rows] = True


def trace(
    surface: Any,
    field: Any,
    seeds: Any,
    directions: Any,
    *,
    length: float | None = None,
    stop: float | None = None,
    rtol: float | None = None,
    singular: Any = (),
) -> FieldLines:
    """Trace the lines of ``field`` through ``seeds`` ``(m, 2)``, each starting
    along the branch nearest to ``directions[k]`` (parameter directions),
    forward and backward, all at once.  Lines end where they pass within
    :data:`~lgraph._tolerance.FIELD_SINGULAR_RTOL` of a point of ``singular``
    (parameters of umbilics).  See the module docstring.

    >>> import numpy as np
    >>> import lgraph as lg
    >>> from lgraph.curvature import principal_field
    >>> L = trace(lg.MonkeySaddle(), principal_field, [[0.5, 0.2]], [[1.0, 0.0]])
    >>> bool(L.ends[0, 0] > 0 and L.ends[1, 0] > 0), bool(L.closed[0])
    (True, False)
    """
    seeds = np.asarray(seeds, float).reshape(-1, 2)
    m = len(seeds)
    if m == 0:
        return FieldLines(surface, [], [], [], [], np.zeros(0, bool))
    d = surface.domain
    size = float(surface.size)
    length = FIELD_MAX_LENGTH * size if length is None else float(length)
    stop = _stop_of(field) if stop is None else float(stop)
    rtol = _rtol_of(field) if rtol is None else float(rtol)
    singular = np.asarray(singular, float).reshape(-1, 2)
    span = np.array([d.span(0), d.span(1)])
    lo = np.array([d.u1[0], d.u2[0]])
    hi = np.array([d.u1[1], d.u2[1]])
    per = np.array(d.periodic)

    def oriented(uv: np.ndarray, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The field's direction at ``uv`` nearest to ``ref`` (same sign), and
        whether it is valid (finite, strong, at most 60 degrees from ``ref``)."""
        D, strength, G = field(surface, d.wrap(uv, clip=False))
        Gr = np.stack([G[:, 0] * ref[:, 0] + G[:, 1] * ref[:, 1],
                       G[:, 1] * ref[:, 0] + G[:, 2] * ref[:, 1]], axis=1)  # fmt: skip
        c = np.einsum("ibj,ij->ib", D, Gr)  # cosines with ref, per branch
        b = (np.abs(c[:, 1]) > np.abs(c[:, 0])).astype(int)
        rows = np.arange(len(uv))
        cb = c[rows, b]
        out = D[rows, b] * np.where(cb < 0, -1.0, 1.0)[:, None]
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(out).all(axis=1) & (strength > stop) & (np.abs(cb) > 0.5)
        return np.where(ok[:, None], out, 0.0), ok

    # rays 0..m-1 run forward, m..2m-1 backward from the same seeds
    Y = np.concatenate([seeds, seeds])
    ref = np.asarray(directions, float).reshape(-1, 2)
    ref = np.concatenate([ref, -ref])
    _, _, G0 = field(surface, d.wrap(seeds, clip=False))
    G0 = np.concatenate([G0, G0])
    nref = np.sqrt(G0[:, 0] * ref[:, 0] ** 2 + 2 * G0[:, 1] * ref[:, 0] * ref[:, 1]
                   + G0[:, 2] * ref[:, 1] ** 2)  # fmt: skip
    with np.errstate(invalid="ignore", divide="ignore"):
        ref = ref / nref[:, None]
    K, alive = oriented(Y, np.where(np.isfinite(ref), ref, 0.0))
    R = 2 * m
    S = np.zeros(R)
    H = np.full(R, FIELD_FIRST_STEP * size)
    hmin, hmax = FIELD_MIN_STEP * size, FIELD_MAX_STEP * size
    closed = np.zeros(R, bool)
    left = np.zeros(R, bool)  # has been far from its seed (closing test)
    zero = np.zeros((R, 2))
    rec_i, rec_s, rec_y, rec_k, rec_r = [np.arange(R)], [S.copy()], [Y.copy()], [K.copy()], [zero]

    for _iteration in range(FIELD_MAX_ITERATIONS):
        act = np.flatnonzero(alive)
        if not len(act):
            break
        y, k1 = Y[act], K[act]
        h = np.minimum(H[act], length - S[act])
        ks = [k1]
        ok = np.ones(len(act), bool)
        for a in _A[1:]:
            yi = y + h[:, None] * sum(c * kj for c, kj in zip(a, ks) if c)
            ki, oki = oriented(yi, ks[-1])
            ok &= oki
            ks.append(ki)
        y5 = y + h[:, None] * sum(c * kj for c, kj in zip(_B, ks) if c)
        k7, ok7 = oriented(y5, ks[-1])
        ok &= ok7
        ks.append(k7)
        err = np.abs(h[:, None] * sum(c * kj for c, kj in zip(_E, ks) if c)) / span
        err = err.max(axis=1)
        good = ok & (err <= rtol)
        with np.errstate(divide="ignore"):
            fac = np.clip(0.9 * (rtol / np.maximum(err, 1e-300)) ** 0.2, 0.2, 5.0)
        newh = np.where(ok, h * np.where(good, fac, np.minimum(fac, 0.5)), 0.1 * h)
        # a step that cannot shrink further: a singular point (or the field's edge)
        dead = ~good & (newh < hmin)
        H[act] = np.minimum(newh, hmax)
        alive[act[dead]] = False
        g = np.flatnonzero(good)
        if not len(g):
            continue
        hg = h[g]
        C = _cubic(y[g], k1[g], y5[g], k7[g], hg)
        y1, k1n = y5[g].copy(), k7[g].copy()
        r5 = hg[:, None] * sum(c * kj[g] for c, kj in zip(_D, ks) if c)
        stop_here = np.zeros(len(g), bool)
        redo = np.full(len(g), np.nan)  # retry with this step (ends on an edge or the seed)

        drop = np.zeros(len(g), bool)  # ends where it starts: no new node
        ends = (y1, stop_here, drop)
        # leaving the patch across a non-periodic side: end exactly on it
        out = np.flatnonzero((((y1 < lo) | (y1 > hi)) & ~per).any(axis=1))
        if len(out):
            th = _exit(C[out], lo, hi, per)
            last = (th >= 1 - _END_RTOL) | (th * hg[out] <= 10 * hmin)
            box = (np.where(per, -np.inf, lo), np.where(per, np.inf, hi))
            _finish(ends, out[last], th[last], np.clip(y1[out[last]], *box))
            # retry with a step that ends just past the edge
            redo[out[~last]] = np.minimum(th[~last] * (1 + 0.1 * _END_RTOL), 1) * hg[out[~last]]
        # closing: a forward line passing its seed again after leaving it
        f = np.flatnonzero((act[g] < m) & np.isnan(redo) & ~stop_here)
        if len(f):
            gap = _chord_gap(y[g[f]], y1[f], seeds[act[g[f]]], span, per)
            near = f[(gap <= 0.05) & left[act[g[f]]]]
            left[act[g[f[gap > 0.05]]]] = True
            if len(near):
                seed = seeds[act[g[near]]]
                th, p, _ = _closest(C[near], np.ones(len(near)), hg[near], seed, span, per)
                hit = np.abs(_rel(p, seed, span, per)).max(axis=1) < FIELD_CLOSE_RTOL
                last = hit & ((th >= 1 - _END_RTOL) | (th * hg[near] <= 10 * hmin))
                # the loop ends exactly on its seed (shifted by whole periods)
                shift = _rel(p[last], seed[last], span, per) * span
                _finish(ends, near[last], th[last], p[last] - shift)
                closed[act[g[near[last]]]] = True
                alive[act[g[near[last]]] + m] = False  # the backward half is not needed
                redo[near[hit & ~last]] = th[hit & ~last] * hg[near[hit & ~last]]
        # reaching a singular point (an umbilic): the line ends where it passes it
        for point in singular:
            f = np.flatnonzero(np.isnan(redo) & ~stop_here)
            gap = _chord_gap(y[g[f]], y1[f], np.broadcast_to(point, (len(f), 2)), span, per)
            near = f[gap <= FIELD_SINGULAR_RTOL]
            if len(near):
                target = np.broadcast_to(point, (len(near), 2))
                th, p, _ = _closest(C[near], np.ones(len(near)), hg[near], target, span, per)
                last = (th >= 1 - _END_RTOL) | (th * hg[near] <= 10 * hmin)
                _finish(ends, near[last], th[last], y1[near[last]])
                redo[near[~last]] = th[~last] * hg[near[~last]]
        again = ~np.isnan(redo)
        H[act[g[again]]] = redo[again]
        sel = ~again & ~drop
        acc = act[g[sel]]
        Y[acc], K[acc] = y1[sel], k1n[sel]
        S[acc] += hg[sel]
        alive[act[g[stop_here]]] = False  # after their last node
        alive[acc[S[acc] >= length * (1 - 1e-12)]] = False
        rec_i.append(acc)
        rec_s.append(S[acc].copy())
        rec_y.append(y1[sel])
        rec_k.append(k1n[sel])
        rec_r.append(r5[sel])

    ri = np.concatenate(rec_i)
    order = np.lexsort((np.concatenate(rec_s), ri))
    ri = ri[order]
    rs, ry, rk, rr = (np.concatenate(x)[order] for x in (rec_s, rec_y, rec_k, rec_r))
    bounds = np.searchsorted(ri, np.arange(R + 1))
    s_out, y_out, k_out, r_out = [], [], [], []
    for j in range(m):
        fa, fb = bounds[j], bounds[j + 1]
        ba, bb = bounds[j + m] + 1, bounds[j + m + 1]  # the seed is the forward half's
        if closed[j]:
            ba = bb  # a loop is its forward half
        s_out.append(np.concatenate([-rs[ba:bb][::-1], rs[fa:fb]]))
        y_out.append(np.concatenate([ry[ba:bb][::-1], ry[fa:fb]]))
        k_out.append(np.concatenate([-rk[ba:bb][::-1], rk[fa:fb]]))
        # each node carries the quartic term of the step that leaves it
        r_out.append(np.concatenate([rr[ba:bb][::-1], rr[fa + 1 : fb], np.zeros((1, 2))]))
    return FieldLines(surface, s_out, y_out, k_out, r_out, closed[:m])


# ---------------------------------------------------------------------------
# families: which lines to draw
# ---------------------------------------------------------------------------
def _parameter_lines_are_field_lines(surface: Any, field: Any) -> bool:
    """Whether the parameter lines are the field's lines, checked on a grid:
    ``g12 = L12 = 0`` (lines of curvature, the paper's Proposition 4.1) or
    ``L11 = L22 = 0`` (asymptotic lines)."""
    from .curvature import _frame, asymptotic_field

    d = surface.domain
    f = (np.arange(24) + 0.5) / 24
    g = np.stack(np.meshgrid(d.u1[0] + d.span(0) * f, d.u2[0] + d.span(1) * f,
                             indexing="ij"), -1).reshape(-1, 2)  # fmt: skip
    _x1, _x2, (g11, g12, g22), (L11, L12, L22) = _frame(surface, g)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = np.sqrt(g11 * g22)
        kappa = (np.abs(L11) / g11 + np.abs(L22) / g22 + 2 * np.abs(L12) / scale).max()
        if field is asymptotic_field:
            small = (np.abs(L11) / g11 + np.abs(L22) / g22) / kappa
            return bool(np.all(small <= PARAMETER_LINES_RTOL)) and bool(kappa > 0)
        small = np.maximum(np.abs(g12) / scale, np.abs(L12) / scale / kappa)
    return bool(np.all(small <= PARAMETER_LINES_RTOL))


def _umbilic_residual(surface: Any, uv: np.ndarray, kappa: float) -> np.ndarray:
    """``(A, B, C)`` of equation (3.3) (``A du1^2 + B du1 du2 + C du2^2 = 0``),
    scaled: all three vanish exactly at umbilics (flat ones included)."""
    from .curvature import _frame

    _x1, _x2, (g11, g12, g22), (L11, L12, L22) = _frame(surface, uv)
    scale = (g11 * g22 * kappa)[:, None]
    return np.stack([L11 * g12 - L12 * g11, L11 * g22 - L22 * g11, L12 * g22 - L22 * g12],
                    axis=1) / scale  # fmt: skip


def umbilics(surface: Any, n: int = 24) -> np.ndarray:
    """Parameters ``(k, 2)`` of the umbilics of the drawn patch (flat ones
    included): local minima of the residual of (3.3) on an ``n x n`` grid,
    refined by Gauss-Newton steps (finite-difference Jacobian), kept where
    the residual vanishes to 1e-9.

    >>> import lgraph as lg
    >>> umbilics(lg.MonkeySaddle()).round(9).tolist()
    [[0.0, 0.0]]
    """
    from scipy.ndimage import minimum_filter

    from .curvature import _frame

    d = surface.domain
    span = np.array([d.span(0), d.span(1)])
    lo = np.array([d.u1[0], d.u2[0]])
    axes = [lo[i] + span[i] * (np.arange(n) + 0.5) / n for i in (0, 1)]
    G = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 2)
    _x1, _x2, (g11, _g12, g22), (L11, L12, L22) = _frame(surface, G)
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.abs(L11) / g11 + np.abs(L22) / g22 + 2 * np.abs(L12) / np.sqrt(g11 * g22)
    kappa = float(np.nanmax(k)) if np.isfinite(k).any() else 0.0
    if not kappa > 0:
        return np.empty((0, 2))
    r = np.linalg.norm(_umbilic_residual(surface, G, kappa), axis=1)
    r = np.where(np.isfinite(r), r, np.inf).reshape(n, n)
    mode = ["wrap" if p else "nearest" for p in d.periodic]
    low = np.flatnonzero(((r == minimum_filter(r, size=3, mode=mode)) & (r < 0.5)).ravel())
    u = G[low[np.argsort(r.ravel()[low])][:64]]
    h = 1e-6 * span
    for _ in range(12):  # Gauss-Newton on the three residuals
        f = _umbilic_residual(surface, d.wrap(u, clip=False), kappa)
        J = np.stack([(_umbilic_residual(surface, d.wrap(u + e, clip=False), kappa) - f) / e.sum()
                      for e in (np.array([h[0], 0.0]), np.array([0.0, h[1]]))], axis=2)  # fmt: skip
        M = np.einsum("kia,kib->kab", J, J)  # normal equations, solved by hand (2 x 2)
        b = -np.einsum("kia,ki->ka", J, f)
        det = M[:, 0, 0] * M[:, 1, 1] - M[:, 0, 1] * M[:, 1, 0]
        with np.errstate(invalid="ignore", divide="ignore"):
            adj_b = np.stack([M[:, 1, 1] * b[:, 0] - M[:, 0, 1] * b[:, 1],
                              M[:, 0, 0] * b[:, 1] - M[:, 1, 0] * b[:, 0]], axis=1)  # fmt: skip
            step = adj_b / det[:, None]
        u = u + np.clip(np.nan_to_num(step), -0.1 * span, 0.1 * span)
    f = np.linalg.norm(_umbilic_residual(surface, d.wrap(u, clip=False), kappa), axis=1)
    u = d.wrap(u, clip=False)
    inside = np.all((u >= lo) & (u <= lo + span), axis=1)
    u = u[(f < 1e-9) & inside]
    keep: list[np.ndarray] = []
    for p in u[np.lexsort((u[:, 1], u[:, 0]))]:
        if all(np.abs(_rel(p[None], q[None], span, np.array(d.periodic))).max() > 1e-6
               for q in keep):  # fmt: skip
            keep.append(p)
    return np.array(keep).reshape(-1, 2)


def _center_seed(surface: Any, field: Any, stop: float) -> np.ndarray:
    """A seed near the middle of the domain where the field is well defined."""
    d = surface.domain
    f = np.array([0.5, 0.42, 0.58, 0.35, 0.65, 0.3, 0.7, 0.2, 0.8])
    c1 = d.u1[0] + d.span(0) * f
    c2 = d.u2[0] + d.span(1) * f[[0, 2, 1, 4, 3, 6, 5, 8, 7]]
    U = np.stack(np.meshgrid(c1, c2, indexing="ij"), -1).reshape(-1, 2)
    D, a, _ = field(surface, U)
    a = np.where(np.isfinite(a) & _stable(surface, field, U, D[:, 0])
                 & _stable(surface, field, U, D[:, 1]), a, -1.0)  # fmt: skip
    good = np.flatnonzero(a > 20 * stop)
    return U[good[0] if len(good) else int(np.argmax(a))]


def _stable(surface: Any, field: Any, seeds: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """Whether the field's branch along ``dirs`` at ``seeds`` is resolved: the
    nearest branch a small step (1e-3 of the spans) away in each of four
    directions is within 20 degrees.  A seed on (or next to) a singular point
    fails: its direction would hang on rounding."""
    d = surface.domain
    m = len(seeds)
    step = 1e-3 * np.array([d.span(0), d.span(1)])
    offsets = np.array([[1, 0], [-1, 0], [0, 1], [0, -1]]) * step
    around = (seeds[None] + offsets[:, None]).reshape(-1, 2)
    D, strength, G = field(surface, d.wrap(np.concatenate([seeds, around]), clip=False))
    ref = np.tile(dirs, (5, 1))
    Gr = np.stack([G[:, 0] * ref[:, 0] + G[:, 1] * ref[:, 1],
                   G[:, 1] * ref[:, 0] + G[:, 2] * ref[:, 1]], axis=1)  # fmt: skip
    nr = np.sqrt(np.einsum("ij,ij->i", ref, Gr))
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.abs(np.einsum("ibj,ij->ib", D, Gr)).max(axis=1) / nr
        ok = (c > np.cos(np.radians(20))) & np.isfinite(strength)
    return ok.reshape(5, m).all(axis=0)


def _spread(lines: FieldLines, k: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n`` parameters evenly spread in arc length along line ``k``, and the
    line's tangents there."""
    a, b = -lines.ends[1, k], lines.ends[0, k]
    frac = np.arange(n) / n if lines.closed[k] else (np.arange(n) + 0.5) / n
    t = a + (b - a) * frac
    uv = lines.uv_line(k, t)
    eps = 1e-6 * max(b - a, 1e-300)
    tangent = lines.uv_line(k, np.minimum(t + eps, b)) - lines.uv_line(k, np.maximum(t - eps, a))
    return uv, tangent


def _crossing(field: Any, surface: Any, uv: np.ndarray, tangent: np.ndarray) -> np.ndarray:
    """The field's branch at ``uv`` most transversal to ``tangent`` (both in
    the parameter plane): the lines that cross a transversal line."""
    D, _, G = field(surface, surface.domain.wrap(uv, clip=False))
    Gt = np.stack([G[:, 0] * tangent[:, 0] + G[:, 1] * tangent[:, 1],
                   G[:, 1] * tangent[:, 0] + G[:, 2] * tangent[:, 1]], axis=1)  # fmt: skip
    c = np.abs(np.einsum("ibj,ij->ib", D, Gt))
    return D[np.arange(len(uv)), (c[:, 1] < c[:, 0]).astype(int)]


def _dense(lines: FieldLines, ks: Any, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Points about ``step`` apart along lines ``ks`` and the line of each
    (all lines evaluated in one call)."""
    ks = np.asarray(ks, int)
    if not len(ks):
        return np.empty((0, 3)), np.empty(0, int)
    a, b = -lines.ends[1, ks], lines.ends[0, ks]
    counts = np.maximum(np.ceil((b - a) / step).astype(int) + 1, 2)
    ids = np.repeat(ks, counts)
    first = np.repeat(np.cumsum(counts) - counts, counts)
    frac = (np.arange(len(ids)) - first) / np.repeat(counts - 1, counts)
    t = np.repeat(a, counts) + frac * np.repeat(b - a, counts)
    uv = lines.domain.wrap(lines.uv(ids, t), clip=False)
    return lines.surface.point(uv[:, 0], uv[:, 1]), ids


def _select(surface: Any, lines: FieldLines, cand: np.ndarray, n: int, grid: tuple) -> list[int]:
    """``n`` of the traced lines ``cand`` spread as evenly over the patch as
    they allow, none retracing another.

    Greedy: each pick is the candidate line that minimizes the area-weighted
    mean squared distance of the patch (grid points) to the lines picked so
    far (the first pick is the most central line).  Energies are compared
    rounded to 1e-9, ties go to the earlier candidate: the choice does not
    hang on the last bits of floating point.
    """
    size = float(surface.size)
    _G, GP, weight = grid
    coarse = 2e-2 * size
    cand = [int(k) for k in cand if lines.ends[0, k] + lines.ends[1, k] > 0]
    if not cand:
        return []
    p, ids = _dense(lines, cand, coarse)
    # squared distance of every grid point to every candidate (chunks of ~4M)
    bounds = np.flatnonzero(np.r_[True, ids[1:] != ids[:-1]])
    sq = np.empty((len(cand), len(GP)))
    g2 = np.einsum("ij,ij->i", GP, GP)
    p2 = np.einsum("ij,ij->i", p, p)
    per_chunk = max(1, int(4e6 // max(len(GP) * len(p) / len(cand), 1)))
    for c0 in range(0, len(cand), per_chunk):
        c1 = min(c0 + per_chunk, len(cand))
        lo_, hi_ = bounds[c0], (bounds[c1] if c1 < len(cand) else len(p))
        d2 = g2[None, :] + p2[lo_:hi_, None] - 2 * (p[lo_:hi_] @ GP.T)
        sq[c0:c1] = np.minimum.reduceat(d2, bounds[c0:c1] - lo_, axis=0)
    sq = np.maximum(sq, 0.0)
    seed3 = surface.points(surface.domain.wrap(lines.uv(cand, np.zeros(len(cand))), clip=False))
    # which candidate seeds lie on which other candidate line (it would be
    # drawn twice): segments of the fine polylines next to each seed
    from scipy.spatial import cKDTree

    tol = FIELD_DUPLICATE_RTOL * size
    fine = 2e-3 * size
    q, qid = _dense(lines, cand, fine)
    row_of = {k: r for r, k in enumerate(cand)}
    on_line = np.zeros((len(cand), len(cand)), bool)
    for j, near in enumerate(cKDTree(q).query_ball_point(seed3, r=fine + tol)):
        near = np.asarray(near, int)
        near = near[qid[near] != cand[j]]
        if not len(near):
            continue
        a = np.concatenate([near, near])
        b = np.concatenate([np.maximum(near - 1, 0), np.minimum(near + 1, len(q) - 1)])
        a, b = a[qid[a] == qid[b]], b[qid[a] == qid[b]]
        ab = q[b] - q[a]
        with np.errstate(invalid="ignore", divide="ignore"):
            tt = np.clip(np.einsum("ij,ij->i", seed3[j] - q[a], ab)
                         / np.einsum("ij,ij->i", ab, ab), 0, 1)  # fmt: skip
        dist = np.linalg.norm(q[a] + np.nan_to_num(tt)[:, None] * ab - seed3[j], axis=1)
        for k in np.unique(qid[a][dist <= tol]):
            on_line[j, row_of[int(k)]] = True
    best = np.full(len(GP), np.inf)
    usable = np.ones(len(cand), bool)
    picked: list[int] = []
    while len(picked) < n and usable.any():
        energy = np.minimum(best, sq) @ weight
        energy = np.round(energy / max(float(energy[usable].max()), 1e-300), 9)
        row = int(np.flatnonzero(usable)[np.argmin(energy[usable])])
        picked.append(cand[row])
        best = np.minimum(best, sq[row])
        usable[row] = False
        usable[on_line[:, row] | on_line[row]] = False  # the same line again
    return sorted(picked)


def _grid(surface: Any, field: Any, stop: float, n: int = 24) -> tuple:
    """Grid points of the patch where the field is well defined: parameters,
    points and area weights (zero where the field is not)."""
    d = surface.domain
    axes = []
    for i in (0, 1):
        lo, hi = d.range(i)
        if d.periodic[i]:
            axes.append(lo + (hi - lo) * (np.arange(n) + 0.5) / n)
        else:
            axes.append(lo + (hi - lo) * (np.arange(n) + 0.5) / n)
    G = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 2)
    _, strength, g = field(surface, G)
    with np.errstate(invalid="ignore"):
        area = np.sqrt(np.maximum(g[:, 0] * g[:, 2] - g[:, 1] ** 2, 0.0))
        good = np.isfinite(strength) & (strength > 20 * stop) & np.isfinite(area)
    weight = np.where(good, area, 0.0)
    return G, surface.points(G), weight / max(weight.sum(), 1e-300)


def field_line_batches(
    surface: Any,
    field: Any,
    n1: int,
    n2: int,
    stop: float | None = None,
    family: str = "curvature",
    spacing: str = "complete",
) -> list[CurveBatch]:
    """Batches of ``n1`` lines of the branch that runs like the ``u1 = const``
    lines at the centre of the domain and ``n2`` of the other (see the module
    docstring for ``spacing``)."""
    if spacing not in SPACINGS:
        choices = ", ".join(map(repr, SPACINGS))
        raise ValueError(f"spacing must be one of {choices}, got {spacing!r}")
    if n1 + n2 <= 0:
        return []

    d = surface.domain
    if _parameter_lines_are_field_lines(surface, field):
        return parameter_line_batches(surface, d.lines(0, n1), d.lines(1, n2), family, family)
    stop = _stop_of(field) if stop is None else stop
    from .curvature import principal_field

    singular = umbilics(surface) if field is principal_field else np.empty((0, 2))
    c = _center_seed(surface, field, stop)
    D, _, G = field(surface, np.array([c]))
    # the lines through the centre place seeds only: a loose tolerance will do
    both = trace(surface, field, [c, c], D[0], stop=stop, rtol=1e-6, singular=singular)
    # the branch running like the u1 = const lines (along x2) at the centre
    x1, x2 = surface.derivatives(c[0], c[1])
    e = D[0, :, :1] * x1 + D[0, :, 1:] * x2
    a = 0 if abs(e[0] @ x2) >= abs(e[1] @ x2) else 1
    if spacing == "even":
        from ._even_spacing import even_batches

        return even_batches(surface, field, both, a, n1, n2, stop, family, singular)
    grid = _grid(surface, field, stop)
    G, _, weight = grid
    # candidate seeds of both families, traced together: many along the
    # transversal (regular spacing where the lines cross it) and a coarse
    # grid over the patch (the parts they miss)
    coarse = np.flatnonzero(weight > 0)[:: max(len(G) // 25, 1)]
    seeds, dirs, fam = [], [], []
    for which, n in ((a, n1), (1 - a, n2)):
        if n <= 0:
            continue
        transversal = 1 - which  # the line of the other branch through the centre
        s_f, d_f = np.array([c]), D[0, which][None]
        if both.ends[0, transversal] + both.ends[1, transversal] > 0:
            s_t, tangent = _spread(both, transversal, 2 * n + 1)
            s_f = np.concatenate([s_f, s_t])
            d_f = np.concatenate([d_f, _crossing(field, surface, s_t, tangent)])
        s_f = np.concatenate([s_f, G[coarse]])
        d_f = np.concatenate([d_f, field(surface, G[coarse])[0][:, which]])
        keep = _stable(surface, field, s_f, d_f)
        seeds.append(s_f[keep])
        dirs.append(d_f[keep])
        fam.append(np.full(int(keep.sum()), n))
    lines = trace(
        surface, field, np.concatenate(seeds), np.concatenate(dirs), stop=stop, singular=singular
    )
    out, start = [], 0
    for f in fam:
        cand = np.arange(start, start + len(f))
        start += len(f)
        b = lines.batch(family, _select(surface, lines, cand, int(f[0]) if len(f) else 0, grid))
        if b is not None:
            out.append(b)
    return out
